"""Every fault the emulator injects: a real job streamed through pyserial into
the fake controller stops safely, and resuming from the journal cuts every
segment exactly once (none lost, none repeated)."""


import pytest

from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.link import (GrblLink, Journal, job_from_program, load_journal,
                                           resume_job)
from LeatherCutWorkbench.post.profiles import load_profile

from post_helpers import sample_plan

# short, but not so short that a loaded test machine looks like a lost link
FAST = dict(status_interval=0.05, link_timeout=1.0, greet_timeout=3.0, hold_timeout=2.0,
            reset_timeout=2.0, command_timeout=3.0)


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


def complete_segments(job, outcomes):
    """Segments whose every job line the machine executed."""
    lines = {}
    for k, s in enumerate(job.segs):
        if s and job.index[k] is not None:
            lines.setdefault(s, []).append(k)
    return {s for s, ks in lines.items() if all(outcomes.get(k) for k in ks)}


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


def test_lines_executed_after_an_error_are_not_cut_again(tmp_path):
    """Stock GRBL keeps executing what is in its buffer after an error: with
    character counting a whole later segment can be cut before the hold lands.
    The journal records those acks and the resume skips that segment."""
    profile = load_profile("grbl11_knife_z_servo")
    job = make_job(profile)
    last_of_first = max(k for k, s in enumerate(job.segs) if s == "1:1")
    fault = Fault("error", last_of_first + 1, code=33, wait_full=True)
    done1, done2 = run_fault_case(tmp_path, "grbl", "char-count", fault, line_time=0.0)
    assert "1:1" not in done1 and "2:1" in done1    # 2:1 was cut from the buffer
    assert "1:1" in done2 and "2:1" not in done2    # ... and is not cut again


def run_fault_case(tmp_path, flavour, mode, fault, line_time=0.001, planner=0):
    """Stream a job into a controller that faults, check the stop, the journal's
    account of what was cut, then resume and check every segment was cut.

    Faults after which the controller reports where it stopped (error, alarm 2,
    stall, garbled line) must be resumed exactly: no segment lost, none cut
    twice.  After a reset we did not ask for or a disconnect the position is
    lost; then nothing may be lost and only segments after the last point the
    journal knows was executed (a synchronising line) may be cut again."""
    # stock GRBL: knife on Z, servo lift, no homing; grblHAL: C axis, Z lift, homing
    profile = load_profile("grbl11_knife_z_servo" if flavour == "grbl" else "grblhal_tangential")
    axes = "XYZ" if flavour == "grbl" else "XYZC"
    exact = fault.kind not in ("reset", "disconnect")
    fault.long_move = bool(planner)      # queued, acknowledged moves wait behind a long one
    job = make_job(profile)
    jpath = str(tmp_path / "job.journal")
    emu = FakeController(flavour=flavour, axes=axes, homing=profile.homing, line_time=line_time,
                         planner_blocks=planner, block_time=0.005, faults=[fault]).start()
    emu2 = None
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
            assert res.stopped_safely and "ALARM:2" in res.message
        assert res.position_trusted == exact
        session_of_job = emu.results[mark1][0]
        run1 = [r for r in emu.results[mark1:] if r[0] == session_of_job]
        outcomes1 = line_outcomes(run1, job.blocks, 0)
        done1 = complete_segments(job, outcomes1)
        if planner:     # the controller really held acknowledged, unexecuted moves
            assert any(r[2] == "ok" and not r[3] for r in run1)
        # ---- the journal's account of what was cut
        state = load_journal(jpath)
        claimed = set(state.done_segments())
        assert claimed <= done1                  # never claims an uncut segment
        recut = done1 - claimed
        if exact:
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
        journal = Journal.open(jpath, job, mode, profile)
        journal.event("resume", seg=resume_from)
        mark2 = len(target.results)
        res2 = link.stream(rjob, journal, mode)
        journal.close()
        link.close()
        assert res2.status == "done", res2
        outcomes2 = line_outcomes(target.results, rjob.blocks, mark2)
        done2 = complete_segments(rjob, outcomes2)
        # ---- nothing lost; nothing repeated beyond what the journal could not know
        assert done1 | done2 == set(job.segment_ids)
        assert done1 & done2 == recut
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
        emu.close()
        if emu2 is not None:
            emu2.close()
