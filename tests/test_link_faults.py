"""Every fault the emulator injects: a real job streamed through pyserial into
the fake controller stops safely, and resuming from the journal cuts every
segment exactly once (none lost, none repeated).

Two sets of cases: the shipped profiles (a ``G4 P0`` sync after each item:
after a fault that loses the position, completed segments of the interrupted
item may be cut again) and the same profiles with ``sync_every_segment`` (a
sync after every segment: after *any* fault the resume starts at the
interrupted segment -- the only segment that may be cut twice)."""


import pytest

from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.link import (GrblLink, Journal, job_from_lines, job_from_program,
                                           load_journal, resume_job)
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from post_helpers import sample_plan

# short, but not so short that a loaded test machine looks like a lost link
FAST = dict(status_interval=0.05, link_timeout=1.0, greet_timeout=3.0, hold_timeout=2.0,
            reset_timeout=2.0, command_timeout=3.0, min_poll_interval=0.005)


def make_job(profile):
    plan = sample_plan()
    plan.items += sample_plan(dx=0, dy=400).items      # two parts: 8 items
    prog = gcode.build_program(plan, profile)
    return job_from_program("job.nc", prog)


def line_outcomes(results, blocks, start):
    """Align the controller's processed lines (from ``start``) 1:1 with the blocks
    the host sent; returns {position in blocks: executed?} (the machine made
    the move, not only acknowledged it)."""
    out = {}
    for k, (_, block, reply, executed) in enumerate(results[start:start + len(blocks)]):
        assert block == blocks[k] or block.startswith("#"), (k, block, blocks[k])
        out[k] = executed
    return out


def complete_segments(job, outcomes, ignore=()):
    """Segments whose every job line the machine executed (blocks in ``ignore``,
    e.g. the closing ``G4P0`` sync that cuts nothing, are not required)."""
    lines = {}
    for k, s in enumerate(job.segs):
        if s and job.index[k] is not None and job.blocks[k] not in ignore:
            lines.setdefault(s, []).append(k)
    return {s for s, ks in lines.items() if all(outcomes.get(k) for k in ks)}


def segment_sync_profile(flavour):
    """The shipped profile of ``flavour`` with a sync after every segment (through
    the profile validation, like a user's JSON file)."""
    name = "grbl11_knife_z_servo" if flavour == "grbl" else "grblhal_tangential"
    return profile_from_dict({**load_profile(name).to_json(), "sync_every_segment": True})


def line_of(job, seg, n):
    """Emulator line number (1-based G-code lines received) of the ``n``-th
    block of segment ``seg`` (1-based; -1 = its last block, the sync)."""
    ks = [k for k, s in enumerate(job.segs) if s == seg]
    assert job.blocks[ks[-1]] == "G4P0", "segment does not end with its sync"
    return (ks[n - 1] if n > 0 else ks[n]) + 1


def connect(emu, profile):
    link = GrblLink(emu.port, **FAST).open()
    link.use_profile(profile)
    link.greet()
    return link


CASES = [
    # id, flavour, mode, fault, planner blocks (0 = a controller that acknowledges
    # a line once executed; > 0 = GRBL's look-ahead: acknowledged is not executed).
    # The planner faults hit the curve of the outline (line 38 / 41) right after
    # three short segments whose lines are then acknowledged but still queued.
    ("error-grbl-send-response", "grbl", "send-response", Fault("error", 45, code=20), 0),
    ("error-grbl-char-count", "grbl", "char-count", Fault("error", 45, code=33), 0),
    ("error-grblhal-latched", "grblhal", "char-count", Fault("error", 45, code=36), 0),
    ("alarm", "grblhal", "char-count", Fault("alarm", 60, code=2), 0),
    ("reset-banner", "grblhal", "char-count", Fault("reset", 70), 0),
    ("stall", "grblhal", "send-response", Fault("stall", 50, seconds=2.0), 0),
    ("disconnect", "grblhal", "char-count", Fault("disconnect", 55), 0),
    ("garbled-line", "grbl", "char-count", Fault("garble", 38), 0),
    ("planner-error-grbl", "grbl", "char-count", Fault("error", 41, code=33), 6),
    ("planner-error-grblhal", "grblhal", "char-count", Fault("error", 38, code=36), 6),
    ("planner-alarm", "grblhal", "char-count", Fault("alarm", 38, code=2), 6),
    ("planner-reset-banner", "grblhal", "char-count", Fault("reset", 77), 6),
    ("planner-stall", "grblhal", "char-count", Fault("stall", 38, seconds=2.0), 6),
    ("planner-disconnect", "grblhal", "char-count", Fault("disconnect", 55), 6),
    ("planner-garbled-line", "grbl", "char-count", Fault("garble", 41), 6),
]


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_fault_stops_safely_and_resume_loses_nothing(case, tmp_path):
    name, flavour, mode, fault, planner = case
    run_fault_case(tmp_path, flavour, mode, fault, planner=planner)


SEGMENT_SYNC_CASES = [
    # id, flavour, mode, fault kind, fault options, planner blocks, (segment,
    # n-th block of it; -1 = its closing G4 P0).  3:5 and 7:5 are the 18-line
    # curve of the outlines: a fault in it interrupts a segment half cut, with
    # the planner holding acknowledged, unexecuted lines of it.
    ("error-grbl-send-response", "grbl", "send-response", "error", dict(code=20), 0, ("3:5", 8)),
    ("error-grbl-char-count", "grbl", "char-count", "error", dict(code=33), 0, ("3:5", 8)),
    ("error-grblhal-latched", "grblhal", "char-count", "error", dict(code=36), 0, ("3:5", 8)),
    ("alarm", "grblhal", "char-count", "alarm", dict(code=2), 0, ("7:5", 5)),
    ("reset-banner", "grblhal", "char-count", "reset", {}, 0, ("3:5", 10)),
    ("stall", "grblhal", "send-response", "stall", dict(seconds=2.0), 0, ("3:5", 3)),
    ("disconnect", "grblhal", "char-count", "disconnect", {}, 0, ("3:5", 10)),
    ("garbled-line", "grbl", "char-count", "garble", {}, 0, ("3:5", 6)),
    ("planner-error-grbl", "grbl", "char-count", "error", dict(code=33), 6, ("3:5", 10)),
    ("planner-error-grblhal", "grblhal", "char-count", "error", dict(code=36), 6, ("3:5", 10)),
    ("planner-alarm", "grblhal", "char-count", "alarm", dict(code=2), 6, ("3:5", 10)),
    ("planner-reset-banner", "grblhal", "char-count", "reset", {}, 6, ("7:5", 12)),
    ("planner-stall", "grblhal", "char-count", "stall", dict(seconds=2.0), 6, ("3:5", 10)),
    ("planner-disconnect", "grblhal", "char-count", "disconnect", {}, 6, ("3:5", 12)),
    ("planner-garbled-line", "grbl", "char-count", "garble", {}, 6, ("3:5", 10)),
    # edges of a segment for the faults that lose the position
    ("reset-at-sync", "grblhal", "char-count", "reset", {}, 6, ("3:4", -1)),
    ("reset-at-segment-start", "grbl", "char-count", "reset", {}, 6, ("3:6", 1)),
    ("reset-in-first-segment", "grbl", "send-response", "reset", {}, 0, ("1:1", 5)),
    ("disconnect-at-sync", "grblhal", "char-count", "disconnect", {}, 0, ("2:2", -1)),
    ("disconnect-at-segment-start", "grbl", "char-count", "disconnect", {}, 6, ("7:6", 1)),
]


@pytest.mark.parametrize("case", SEGMENT_SYNC_CASES, ids=[c[0] for c in SEGMENT_SYNC_CASES])
def test_segment_sync_resumes_exactly_after_every_fault(case, tmp_path):
    """With a sync after every segment, every fault -- including a reset we did
    not ask for and a disconnect, which lose the position -- resumes at the
    interrupted segment: executed-before-fault | executed-after-resume is
    every segment, and they share at most that one segment."""
    name, flavour, mode, kind, kw, planner, (seg, n) = case
    profile = segment_sync_profile(flavour)
    job = make_job(profile)
    fault = Fault(kind, line_of(job, seg, n), **kw)
    # a disconnect loses the answers still in transit: when it strikes as the
    # next segment starts, the previous segment's sync ok may be among them
    # (that segment is then the one cut twice; the next one never started)
    order = job.segment_ids
    unconfirmed = order[order.index(seg) - 1] if kind == "disconnect" and n == 1 else None
    run_fault_case(tmp_path, flavour, mode, fault, planner=planner, profile=profile,
                   fault_seg=seg, queued=bool(planner) and n > planner, unconfirmed=unconfirmed)


def test_lines_executed_after_an_error_are_not_cut_again(tmp_path):
    """Stock GRBL keeps executing what is in its buffer after an error: with
    character counting a whole later segment can be cut before the hold lands.
    The journal records those acks and the resume skips that segment."""
    profile = load_profile("grbl11_knife_z_servo")
    job = make_job(profile)
    # within an item (nothing is sent past an item's sync until it is verified)
    last_of = max(k for k, s in enumerate(job.segs) if s == "3:5")
    fault = Fault("error", last_of + 1, code=33, wait_full=True)
    done1, done2 = run_fault_case(tmp_path, "grbl", "char-count", fault, line_time=0.0)
    assert "3:5" not in done1 and "3:6" in done1    # 3:6 was cut from the buffer
    assert "3:5" in done2 and "3:6" not in done2    # ... and is not cut again


def run_fault_case(tmp_path, flavour, mode, fault, line_time=0.001, planner=0, profile=None,
                   fault_seg=None, queued=None, unconfirmed=None):
    """Stream a job into a controller that faults, check the stop, the journal's
    account of what was cut, then resume and check every segment was cut.

    Faults after which the controller reports where it stopped (error, alarm 2,
    stall, garbled line) must be resumed exactly: no segment lost, none cut
    twice.  After a reset we did not ask for or a disconnect the position is
    lost; then nothing may be lost and only segments after the last point the
    journal knows was executed (a synchronising line) may be cut again.

    With ``fault_seg`` (a profile with ``sync_every_segment``) the check is
    strict for every fault: the resume starts at ``fault_seg``, the segment the
    fault interrupted, and it is the only segment that may be cut twice (when
    its moves were all made but its sync was never acknowledged).  When the
    link was lost, ``unconfirmed`` names the segment before it whose sync
    answer may have been lost in transit; the resume may start there, and then
    ``fault_seg`` must not have been started."""
    # stock GRBL: knife on Z, servo lift, no homing; grblHAL: C axis, Z lift, homing
    if profile is None:
        profile = load_profile("grbl11_knife_z_servo" if flavour == "grbl"
                               else "grblhal_tangential")
    strict = fault_seg is not None
    case_seg = fault_seg
    axes = "XYZ" if flavour == "grbl" else "XYZC"
    exact = fault.kind not in ("reset", "disconnect")
    fault.long_move = bool(planner)      # queued, acknowledged moves wait behind a long one
    queued = bool(planner) if queued is None else queued
    # what cutting a segment means: every line made, except the closing sync
    # (it moves nothing; a segment cut but not synced is re-cut, and counted)
    ignore = ("G4P0",) if strict else ()
    job = make_job(profile)
    jpath = str(tmp_path / "job.journal")
    emu = FakeController(flavour=flavour, axes=axes, homing=profile.homing, line_time=line_time,
                         planner_blocks=planner, block_time=0.005, faults=[fault]).start()
    emu2 = link = None
    try:
        link = connect(emu, profile)
        link.check_axes(job)
        link.ready_for_job(profile)
        journal = Journal.open(jpath, job, mode, profile)
        mark1 = len(emu.results)
        res = link.stream(job, journal, mode)
        journal.close()
        # ---- the job stopped, and safely
        assert res.status != "done"
        assert fault.fired
        expected_status = {"error": "error", "garble": "error", "alarm": "alarm",
                           "reset": "reset", "stall": "stalled", "disconnect": "lost"}
        assert res.status == expected_status[fault.kind], res
        if fault.kind in ("error", "garble"):
            assert res.stopped_safely and res.message.startswith("error:")
            assert res.line is not None and job.source[res.line - 1].strip()
            assert emu.state == "Idle"
            if profile.lift_axis:                               # knife lifted
                assert emu.position[profile.lift_axis] == profile.z_up
            else:
                assert emu.spindle == "M5"
        if fault.kind == "alarm":
            # locked in Alarm: the knife-up lines cannot run -- never "stopped safely"
            assert "ALARM:2" in res.message and not res.stopped_safely
            lift = profile.lift_axis
            assert res.verified["state"] == "Alarm"
            assert res.verified["knife"] == ("up" if emu.position[lift] >= profile.z_up
                                             else "down")
            assert "NOT stopped safely" in res.stop_summary()
        if res.stopped_safely:       # verified, not intended: the machine agrees
            assert emu.state == "Idle" and emu.spindle == "M5"
            if profile.lift_axis:
                assert emu.position[profile.lift_axis] == profile.z_up
        assert res.position_trusted == exact
        session_of_job = emu.results[mark1][0]
        run1 = [r for r in emu.results[mark1:] if r[0] == session_of_job]
        # after the fault the controller made no move of the job (only the
        # knife-up lines of the safe stop)
        after = [r[1] for r in emu.results[mark1:] if r[0] != session_of_job and r[3]]
        assert not [b for b in after if "X" in b or "Y" in b], after
        outcomes1 = line_outcomes(run1, job.blocks, 0)
        done1 = complete_segments(job, outcomes1, ignore)
        if queued:      # the controller really held acknowledged, unexecuted moves
            assert any(r[2] == "ok" and not r[3] for r in run1)
        # ---- the journal's account of what was cut
        state = load_journal(jpath)
        claimed = set(state.done_segments())
        assert claimed <= done1                  # never claims an uncut segment
        recut = done1 - claimed
        if strict:
            # the journal knows every completed segment but, at most, the
            # interrupted one; the resume starts exactly there
            if state.first_incomplete() == unconfirmed is not None:
                fault_seg = unconfirmed
                assert not any(outcomes1.get(k) for k, s in enumerate(job.segs)
                               if s == case_seg), "the next segment was started"
            assert state.first_incomplete() == fault_seg, (state.bases, fault_seg)
            assert recut <= {fault_seg}, (state.bases, recut)
            if exact:
                assert recut == set(), (state.bases, recut)
        elif exact:
            assert recut == set(), (state.bases, recut)
        else:
            # position lost: only what follows the last synchronised point is cut again
            order = job.segment_ids
            assert all(order.index(r) > order.index(c) for r in recut for c in claimed), recut
        assert len(done1) < len(job.segment_ids)
        resume_from = state.first_incomplete()
        assert resume_from is not None and resume_from not in claimed
        # ---- reconnect (a new controller after a disconnect) and resume
        link.close()
        target = emu
        if fault.kind == "disconnect":
            emu2 = FakeController(flavour=flavour, axes=axes, homing=profile.homing,
                                  planner_blocks=planner).start()
            target = emu2
        link = connect(target, profile)
        link.ready_for_job(profile)              # re-homes when locked in Alarm
        assert target.state == "Idle"
        rjob = resume_job(job, resume_from, profile, skip=state.later_done())
        journal = Journal.open(jpath, job, mode, profile, resume_seg=resume_from)
        mark2 = len(target.results)
        res2 = link.stream(rjob, journal, mode)
        journal.close()
        link.close()
        assert res2.status == "done", res2
        outcomes2 = line_outcomes(target.results, rjob.blocks, mark2)
        done2 = complete_segments(rjob, outcomes2, ignore)
        # ---- nothing lost; nothing repeated beyond what the journal could not know
        assert done1 | done2 == set(job.segment_ids)
        assert done1 & done2 == recut
        if strict:
            assert done1 & done2 <= {fault_seg}
            assert fault_seg in done2 and fault_seg == resume_from
        lines_of = {}
        for k, s in enumerate(job.segs):
            if s:
                lines_of.setdefault(s, set()).add(job.index[k])
        for s in done2:    # each resumed segment is cut from its start, whole
            assert {rjob.index[k] for k, x in enumerate(rjob.segs)
                    if x == s and rjob.index[k] is not None} == lines_of[s]
        assert set(load_journal(jpath).done_segments()) == set(job.segment_ids)
        assert emu.overflows == 0
        return done1, done2
    finally:
        if link is not None:
            link.close()
        emu.close()
        if emu2 is not None:
            emu2.close()


class BurstPort:
    """A port that answers every line with ``ok`` and every ``?`` with an Idle
    report at once, until the host writes its ``burst_after``-th line: that
    one's ``ok`` arrives, then a reset banner (or the loss of the port) before
    any status report -- as when a controller resets or a cable is pulled
    just after answering a segment's sync.  Replies go through the link's own
    parser (``_handle``)."""

    def __init__(self, link, burst_after, then):
        self.link, self.burst_after, self.then, self.lines = link, burst_after, then, 0
        self.dead = False

    def write(self, data):
        if self.dead:
            return len(data)
        if data == b"?":
            self.link._handle("<Idle|MPos:0.000,0.000,0.000|FS:0,0>")
        elif data.endswith(b"\n"):
            self.lines += 1
            self.link._handle("ok")
            if self.lines == self.burst_after:
                self.dead = True
                if self.then == "reset":
                    self.link._handle("Grbl 1.1h ['$' for help]")
                else:
                    self.link._lost = "port closed or unplugged"
        return len(data)

    def close(self):
        pass


@pytest.mark.parametrize("then", ["reset", "lost"])
def test_a_sync_ok_proves_nothing_until_an_idle_report_follows(then, tmp_path):
    """Answers that arrived before the banner (or before the port died) are
    journaled as acknowledgements, but a sync's ``ok`` proves its segment
    executed only once a status report received after it shows Idle: a
    spurious or early ``ok`` cannot fake that.  1:1's sync was verified, 1:2's
    ``ok`` came just before the reset: the resume starts at 1:2."""
    lines = ["G21 G90 G17 G94", "(seg 1:1)", "G1 X10 Y0 F1000", "G4 P0",
             "(seg 1:2)", "G1 X10 Y10", "G4 P0", "(seg 1:3)", "G1 X0 Y10", "G4 P0",
             "(end item 1)", "M2"]
    job = job_from_lines("burst.nc", lines)
    link = GrblLink("burst://", **dict(FAST, link_timeout=0.3, reset_timeout=0.3))
    link.ser = BurstPort(link, 5, then)            # answers lines 1..5 (through 1:2's sync)
    link.info.rx_size = 1024
    jpath = str(tmp_path / "burst.journal")
    journal = Journal.open(jpath, job, "char-count")
    res = link.stream(job, journal, "char-count")
    journal.close()
    assert res.status == ("reset" if then == "reset" else "lost")
    assert res.position_lost
    state = load_journal(jpath)
    assert sorted(state.acked) == [0, 2, 3, 5, 6]
    assert [e["i"] for e in state.events if e["e"] == "sync"] == [3]
    assert state.done_segments() == ["1:1"] and state.first_incomplete() == "1:2"
    assert link.ser.lines == 5                     # nothing sent after an unverified sync
