"""The failures found by the fault and hostile runs of issue #16 (the live
link and job files), each reproduced against the fake controller."""

import errno
import json
import os
import time

import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.post import jobfile
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.gcode_reader import GcodeError, read_program
from LeatherCutWorkbench.post.link import (GrblLink, LinkError, SendSession, job_from_file,
                                           load_journal)
from LeatherCutWorkbench.post.link.feeds import linear_feed_only

from link_helpers import FAST, cutting_lines, make_job, profile_for, send_until_done
from test_post_cli import FASTPLAN, drawing


@pytest.fixture
def main():
    from LeatherCutWorkbench import cli
    return cli.main


def line_in(job, seg, n=1):
    """Emulator line number (1-based G-code lines) of the n-th block of ``seg``."""
    return [k for k, s in enumerate(job.segs) if s == seg][n - 1] + 1


# ---------------------------------------------------------------- journal per run

def test_a_fresh_run_never_inherits_an_old_runs_progress(tmp_path):
    """Issue #16, 1: hide 1 stops in segment 15:3 (13:3 in the issue's job);
    hide 2, a fresh run of the
    same job.nc with the same journal, power-resets in item 1.  The resume must
    cut everything of hide 2 (before: it proposed 13:3 and left 132 of 247
    cutting lines uncut)."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=4)
    assert "15:3" in job.segment_ids
    jpath = str(tmp_path / "job.journal")
    # hide 1: stops in 13:3 (error), not resumed
    emu = FakeController(flavour="grblhal", axes="XYZC", homing=True,
                         faults=[Fault("error", line_in(job, "15:3", 1), code=33)]).start()
    try:
        out1 = SendSession(job, profile, emu.port, jpath, mode="char-count", **FAST).run()
    finally:
        emu.close()
    assert out1.result.status == "error" and out1.resume_from == "15:3"
    # hide 2: a fresh send, power cycle in item 1, then --resume-from auto
    emu = FakeController(flavour="grblhal", axes="XYZC", homing=True,
                         faults=[Fault("reset", line_in(job, "1:1", 4))]).start()
    counts, outs, emus, stray = send_until_done(emu, job, profile, jpath, "char-count")
    assert outs[0].result.status == "reset" and outs[0].resume_from.startswith("1:")
    assert outs[-1].ok and outs[1].resumed_from == outs[0].resume_from
    lost = [i for i in cutting_lines(job) if not counts.get(i)]
    assert lost == [] and not stray and emus[0].misplaced == 0
    st = load_journal(jpath)
    assert st.passes == 2 and set(st.done_segments()) == set(job.segment_ids)


def test_a_completed_job_then_a_new_stop_resumes_correctly(tmp_path):
    """After a job once completed, a later fresh run that stops suggests its
    own resume point (before: ``--resume-from None``)."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    jpath = str(tmp_path / "job.journal")
    with FakeController(flavour="grblhal", axes="XYZC", homing=True) as emu:
        assert SendSession(job, profile, emu.port, jpath, **FAST).run().ok
    with FakeController(flavour="grblhal", axes="XYZC", homing=True,
                        faults=[Fault("error", line_in(job, "3:5", 4), code=33)]) as emu:
        out = SendSession(job, profile, emu.port, jpath, **FAST).run()
    assert out.result.status == "error" and out.resume_from == "3:5"
    assert load_journal(jpath).first_incomplete() == "3:5"


def test_a_resume_of_an_earlier_pass_does_not_count_for_the_last(tmp_path):
    """Resume records name the pass they continue; one of an earlier pass is
    history, not progress of the last one."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    jpath = str(tmp_path / "job.journal")
    from LeatherCutWorkbench.post.link import Journal
    j = Journal.open(jpath, job, "send-response", profile)
    first_pass = j.pass_id
    j.close()
    Journal.open(jpath, job, "send-response", profile).close()          # pass 2
    with open(jpath, "a") as fh:
        fh.write(json.dumps({"e": "resume", "seg": "2:1", "run": "x", "of": first_pass}) + "\n")
        fh.write(json.dumps({"e": "ack", "i": 3, "s": "1:1"}) + "\n")
    st = load_journal(jpath)
    assert st.passes == 2 and len(st.runs) == 1 and st.pass_id != first_pass


# ------------------------------------------------------------ job files: atomic + seal

def sealed_job(tmp_path, main):
    nc = tmp_path / "job.nc"
    assert main(["post", drawing(tmp_path), "--machine", "grblhal_tangential", "-o", str(nc)]
                + FASTPLAN) == 0
    return nc


def test_a_truncated_or_edited_job_file_is_refused_before_the_first_byte(tmp_path, main,
                                                                           capsys):
    nc = sealed_job(tmp_path, main)
    data = nc.read_bytes()
    assert data.rstrip().splitlines()[-1].startswith(b"(LEATHERCUT END lines=")
    job_from_file(str(nc))                                  # intact: accepted
    for name, bad in (("cut.nc", data[:len(data) * 4 // 5]),
                      ("edited.nc", data.replace(b"F12000", b"F24000", 1)),
                      ("tail.nc", data + b"G0 X0 Y0\n")):
        p = tmp_path / name
        p.write_bytes(bad)
        with pytest.raises(InputError, match="end marker"):
            job_from_file(str(p))
        # even the override for hand-written files never streams a LeatherCut job
        with pytest.raises(InputError, match="end marker"):
            job_from_file(str(p), allow_unsealed=True)
        capsys.readouterr()
        with FakeController(flavour="grblhal", axes="XYZC") as emu:
            code = main(["send", str(p), "--port", emu.port, "--allow-unsealed"])
            assert emu.log == []                         # not a byte streamed
        assert code == 2 and "end marker" in capsys.readouterr().err


def test_a_hand_written_file_streams_only_with_the_override(tmp_path, data_dir):
    src = os.path.join(data_dir, "post", "foreign_grbl.nc")
    with pytest.raises(InputError, match="--allow-unsealed"):
        job_from_file(src)
    assert job_from_file(src, allow_unsealed=True).blocks


def full_disk_after(monkeypatch, limit):
    """os.write fails with ENOSPC once ``limit`` bytes were written (a full disk)."""
    real = os.write
    written = [0]

    def write(fd, data):
        room = limit - written[0]
        if room <= 0:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        n = real(fd, bytes(data[:room]))
        written[0] += n
        return n
    monkeypatch.setattr(os, "write", write)


def test_a_full_disk_leaves_no_truncated_job_file(tmp_path, main, capsys, monkeypatch):
    """Issue #16, 2: ``run`` on a full disk left job.nc cut mid-item, which
    ``send`` streamed as complete.  Now nothing truncated is left as job.nc
    (the previous one stays intact) and no ``.part`` file remains."""
    dxf = drawing(tmp_path)
    out = tmp_path / "out"
    assert main(["run", dxf, "-o", str(out), "--machine", "grblhal_tangential"] + FASTPLAN) == 0
    before = (out / "job.nc").read_bytes()
    job_from_file(str(out / "job.nc"))
    (out / "job.nc").unlink()
    capsys.readouterr()
    full_disk_after(monkeypatch, len(before) // 2)        # the disk fills mid-job.nc
    code = main(["run", dxf, "-o", str(out), "--machine", "grblhal_tangential"] + FASTPLAN)
    monkeypatch.undo()
    assert code == 2 and "No space left" in capsys.readouterr().err
    assert not (out / "job.nc").exists()
    assert [p.name for p in out.iterdir() if p.name.endswith(".part")] == []
    # an existing job.nc survives a failed rewrite untouched
    (out / "job.nc").write_bytes(before)
    full_disk_after(monkeypatch, 4096)
    with pytest.raises(InputError, match="No space left"):
        jobfile.write_job_file(str(out / "job.nc"), "G0 X1\n" * 5000, gcode=True)
    monkeypatch.undo()
    assert (out / "job.nc").read_bytes() == before
    assert [p.name for p in out.iterdir() if p.name.endswith(".part")] == []


def test_writers_refuse_a_fifo_a_device_or_a_folder(tmp_path, main, capsys):
    fifo = tmp_path / "pipe.nc"
    os.mkfifo(fifo)
    for target in (str(fifo), "/dev/null", str(tmp_path)):
        with pytest.raises(InputError, match="not a regular file|folder"):
            jobfile.write_file(target, "G0 X0\n")
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")
    assert not os.path.isfile(fifo)                  # still a FIFO
    capsys.readouterr()
    code = main(["post", drawing(tmp_path), "--machine", "grblhal_tangential", "-o", str(fifo)]
                + FASTPLAN)
    assert code == 2 and "FIFO" in capsys.readouterr().err


# -------------------------------------------------------------- acks and replies

def stream_with(emu, job, profile, mode="char-count", **opts):
    link = GrblLink(emu.port, **{**FAST, **opts}).open()
    try:
        link.use_profile(profile)
        link.greet()
        link.ready_for_job(profile)
        return link.stream(job, None, mode)
    finally:
        link.close()


@pytest.mark.parametrize("mode", ["send-response", "char-count"])
def test_a_garbled_ok_stops_safely_instead_of_hanging(mode):
    """Issue #16, 4: a reply ``o\\xffk`` was collected and never acted on; the
    sender hung with the knife in the leather.  Now: a safe stop, verified."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    with FakeController(flavour="grblhal", axes="XYZC", homing=True,
                        faults=[Fault("garble_reply", line_in(job, "3:5", 3))]) as emu:
        t0 = time.monotonic()
        res = stream_with(emu, job, profile, mode)
        assert time.monotonic() - t0 < 10
        assert res.status == "garbled" and res.message.startswith("garbled reply 'o")
        assert res.stopped_safely and emu.state == "Idle"
        assert emu.position["Z"] == profile.z_up and emu.spindle == "M5"


def test_a_lost_ok_is_a_fault_when_the_controller_sits_idle():
    """An answer that never arrives: Idle with lines outstanding = fault."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    with FakeController(flavour="grblhal", axes="XYZC", homing=True,
                        faults=[Fault("drop_ack", line_in(job, "3:5", 3))]) as emu:
        t0 = time.monotonic()
        res = stream_with(emu, job, profile, "send-response")
        assert time.monotonic() - t0 < 10
    assert res.status == "unanswered" and res.stopped_safely


def test_one_unanswered_status_poll_is_polled_again_not_a_lost_link():
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    with FakeController(flavour="grblhal", axes="XYZC", homing=True, line_time=0.002,
                        faults=[Fault("drop_status", 20)]) as emu:
        res = stream_with(emu, job, profile, "send-response", status_interval=0.2,
                          link_timeout=0.6)
    assert res.status == "done"


def test_a_spurious_ok_never_overflows_the_buffer_and_a_reset_after_it_loses_nothing(
        tmp_path):
    """Issue #16, 6: one spurious ok pushed character counting 31 bytes past
    GRBL's 127; a spurious ok followed by a power reset 20 ms later lost 5
    cutting lines of segment 1:2."""
    profile = profile_for("grbl")
    job = make_job(profile, copies=1)
    for at in range(2, 40, 6):
        emu = FakeController(flavour="grbl", axes="XYZ", line_time=0.002,
                             faults=[Fault("spurious", at), Fault("reset", at, after=0.02)])
        counts, outs, emus, stray = send_until_done(emu.start(), job, profile,
                                                    str(tmp_path / f"j{at}"), "char-count")
        assert outs[-1].ok and not stray
        assert [i for i in cutting_lines(job) if not counts.get(i)] == [], at
        assert max(e.max_rx for e in emus) <= 127 and emus[0].overflows == 0
        assert sum(e.misplaced for e in emus) == 0


# ------------------------------------------------------------------ verified stop

@pytest.mark.parametrize("code", [1, 2])
def test_after_a_limit_alarm_the_report_never_says_stopped_safely(code, tmp_path, capsys,
                                                                  main):
    """Issue #16, 5: after ALARM:1/2 the report said "Stopped safely" with the
    knife still at Z -1.2.  Now it says what the status after the stop shows."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    line = line_in(job, "3:5", 5)
    with FakeController(flavour="grblhal", axes="XYZC", homing=True,
                        faults=[Fault("alarm", line, code=code)]) as emu:
        out = SendSession(job, profile, emu.port, str(tmp_path / "j"), **FAST).run()
        z = emu.position["Z"]
    res = out.result
    assert z < profile.z_up and not res.stopped_safely
    assert res.verified["state"] == "Alarm" and res.verified["knife"] == "down"
    text = res.stop_summary()
    assert "NOT stopped safely" in text and "locked in Alarm" in text and "Z -1.200" in text
    assert res.position_lost == (code == 1)
    ev = [e for e in load_journal(str(tmp_path / "j")).events if e["e"] == "alarm"][0]
    assert ev["stopped_safely"] is False and ev["verified"]["knife"] == "down"


def test_the_stop_report_names_where_the_tool_is(tmp_path):
    """Issue #16, 9: the report named the oldest unacknowledged line; the tool
    was elsewhere (the planner held acknowledged, unexecuted lines)."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    fault = Fault("error", line_in(job, "3:5", 12), code=33, long_move=True)
    with FakeController(flavour="grblhal", axes="XYZC", homing=True, planner_blocks=6,
                        block_time=0.005, faults=[fault]) as emu:
        out = SendSession(job, profile, emu.port, str(tmp_path / "j"), mode="char-count",
                          **FAST).run()
        session = emu.results[0][0]
        executed = [r[1] for r in emu.results if r[3] and r[0] == session]
    tool = out.tool_at
    assert out.basis == "position" and tool["how"] == "after"   # whole blocks, this emulator
    assert tool["line"] < out.result.line                  # not the refused line
    k = job.index.index(tool["line"] - 1)
    last_move = [b for b in executed if "X" in b or "Y" in b][-1]
    assert job.blocks[k] == last_move                      # where the machine really is


# ------------------------------------------------------------ lost position, port lock

def test_a_resume_after_a_power_reset_needs_homing_or_a_confirmed_zero(tmp_path):
    """Issue #16, 7: stock GRBL (no homing) power-reset; resuming without
    re-zeroing cut 78 lines in the wrong place."""
    profile = profile_for("grbl")
    job = make_job(profile, copies=1)
    jpath = str(tmp_path / "j")
    with FakeController(flavour="grbl", axes="XYZ",
                        faults=[Fault("reset", line_in(job, "3:5", 6))]) as emu:
        out = SendSession(job, profile, emu.port, jpath, **FAST).run()
        assert out.result.status == "reset" and out.result.position_lost
        with pytest.raises(LinkError, match="position was lost.*--confirm-work-zero"):
            SendSession(job, profile, emu.port, jpath, resume_from="auto", **FAST).run()
        assert emu.misplaced == 0
        emu.rezero()                                   # the operator re-zeroes
        out2 = SendSession(job, profile, emu.port, jpath, resume_from="auto",
                           confirm_work_zero=True, **FAST).run()
        assert out2.ok and out2.zero == "confirmed" and emu.misplaced == 0
    assert any(e["e"] == "zero" and e["how"] == "confirmed" for e in load_journal(jpath).events)


def test_two_senders_cannot_open_one_port():
    with FakeController(flavour="grbl") as emu:
        a = GrblLink(emu.port, **FAST).open()
        try:
            with pytest.raises(LinkError, match="in use"):
                GrblLink(emu.port, **FAST).open()
        finally:
            a.close()
        GrblLink(emu.port, **FAST).open().close()      # free again once closed


def test_a_disconnect_that_swallows_an_items_sync_repeats_at_most_one_segment(tmp_path):
    """Issue #16, 7: a disconnect swallowing an item's sync ok repeated up to
    105 lines.  A homing controller found Idle on reconnect kept its power; its
    position tells where the tool stopped."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    last3 = max(k for k, s in enumerate(job.segs) if s.startswith("3:"))
    sync = job.blocks.index("G4P0", last3) + 1          # item 3's sync, after the lift
    # the sync is executed, its ok is lost on the wire, then the cable goes
    emu = FakeController(flavour="grblhal", axes="XYZC", homing=True,
                         faults=[Fault("drop_ack", sync),
                                 Fault("disconnect", sync, after=0.05)]).start()
    counts, outs, emus, stray = send_until_done(emu, job, profile, str(tmp_path / "j"),
                                                "char-count", power_lost=False)
    assert outs[0].result.status == "lost" and outs[-1].ok
    cut = cutting_lines(job)
    repeated = [i for i in cut if counts.get(i, 0) > 1]
    assert [i for i in cut if not counts.get(i)] == []
    segs = {job.segs[job.index.index(i)] for i in repeated}
    assert len(segs) <= 1, segs
    assert outs[1].zero == ""                          # kept its position: no homing needed
    st = load_journal(str(tmp_path / "j"))
    st.executed()
    assert st.bases[0] == "position" and any(e["e"] == "reconnect" for e in st.events)


# ------------------------------------------------------------------ item 9

def test_grbls_absolute_arc_radius_limit():
    """GRBL refuses (error:33) an arc whose end radius differs by more than
    0.5 mm, even when that is under 0.1 % of the radius."""
    with pytest.raises(GcodeError) as exc:
        read_program("G21 G90\nG0 X100 Y100\nG2 X1100 Y1100.6 I1000 J0 F1000\n")
    assert exc.value.code == 33
    read_program("G21 G90\nG0 X100 Y100\nG2 X1100 Y1100.4 I1000 J0 F1000\n")


def test_grblhal_feed_on_linear_axes_only_takes_back_the_rotary_raise(tmp_path):
    """grblHAL $701=1 applies F to X Y Z only: the raised F of knife-turning
    cuts would drive XY up to 40000/12000 of the cut feed."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    raised = [b for b in job.blocks if "C" in b and "F" in b
              and float(b.split("F")[1]) > profile.cut_feed]
    assert raised
    with FakeController(flavour="grblhal", axes="XYZC", homing=True,
                        settings={"701": "1"}) as emu:
        s = SendSession(job, profile, emu.port, str(tmp_path / "j"), **FAST)
        out = s.run()
    assert out.ok and out.feeds_adjusted >= len(raised)
    feeds = [float(b.split("F")[1]) for b in s.streamed.blocks if "F" in b and b[:2] != "G0"]
    assert max(feeds) <= profile.cut_feed
    same, n = linear_feed_only(job, profile)
    assert n == out.feeds_adjusted


def test_the_end_marker_is_a_comment_to_the_real_linuxcnc_interpreter(tmp_path):
    """The seal is one parenthesised comment after the program end: LinuxCNC
    2.9's interpreter accepts the sealed file and makes the same moves."""
    import test_post_rs274 as rs
    if not os.path.isfile(rs.RS274):
        pytest.skip("real LinuxCNC interpreter not unpacked (bash tools/get_rs274.sh)")
    from LeatherCutWorkbench.post import gcode
    from LeatherCutWorkbench.post.profiles import load_profile
    from post_helpers import sample_plan
    text = gcode.export(sample_plan(dx=10, dy=20), load_profile("linuxcnc_tangential"))
    rc0, _, plain = rs.run_rs274(tmp_path, text)
    rc, out, canon = rs.run_rs274(tmp_path, jobfile.seal(text))
    assert rc0 == 0 and rc == 0, out
    assert rs.canon_moves(canon) == rs.canon_moves(plain)


def test_a_garbled_reply_in_check_mode_fails_the_check_and_leaves_check_mode():
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    with FakeController(flavour="grblhal", axes="XYZC",
                        faults=[Fault("garble_reply", 30)]) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.use_profile(profile)
            link.greet()
            res = link.run_check(job, "char-count")
            assert res.status == "check-failed" and "garbled reply" in res.message
            assert link.status().state == "Idle"           # out of check mode
            assert not [b for b in emu.executed if "X" in b or "Y" in b]   # only the lift


def test_tool_location_mid_move_from_the_reported_position(tmp_path):
    """A position reported half-way along an acknowledged move names that move."""
    from LeatherCutWorkbench.post.link import Journal, job_from_lines
    lines = ["G21 G90 G17 G94", "(seg 1:1)", "G1 X10 Y0 F1000", "G1 X10 Y10", "G1 X0 Y10",
             "G4 P0", "(end item 1)", "M2"]
    job = job_from_lines("mid.nc", lines)
    p = str(tmp_path / "j")
    with Journal.open(p, job, "char-count") as j:
        for i in (0, 2, 3, 4):
            j.ack(i, job.job_segs[i])
        j.event("error", position={"X": 10.0, "Y": 4.0, "Z": 0.0}, position_trusted=True,
                position_lost=False)
    st = load_journal(p)
    assert st.tool_at() == {"line": 4, "block": "G1 X10 Y10", "segment": "1:1", "how": "on"}
    assert st.first_incomplete() == "1:1"


# ------------------------------------------- swallowed sync ok, several spurious oks

def segments_of(job, lines):
    return {job.segs[job.index.index(i)] for i in lines}


@pytest.mark.parametrize("flavour,mode,window,then", [
    ("grbl", "char-count", 1, "reset"), ("grblhal", "send-response", 1, "reset"),
    ("grbl", "send-response", 2, "reset"), ("grblhal", "char-count", 2, "reset"),
    ("grbl", "char-count", 1, "disconnect-power"), ("grblhal", "char-count", 2, "disconnect"),
])
def test_a_swallowed_item_sync_ok_repeats_at_most_the_interrupted_segment(
        flavour, mode, window, then, tmp_path):
    """Issue #16, 7: when an item's sync ``ok`` is lost and the power fails (on
    the same port, or with the cable), the resume re-cut the whole item from
    the last verified sync (up to 105 lines).  The status reports received
    while streaming prove what was executed: the re-cut is the interrupted
    segment -- with cut window 2 at most the segment before it too (when
    the tool crossed into the last segment after the last report)."""
    profile = profile_for(flavour)
    job = make_job(profile, copies=1)
    last3 = max(k for k, s in enumerate(job.segs) if s.startswith("3:"))
    sync = job.blocks.index("G4P0", last3) + 1          # item 3's sync, after the lift
    follow = (Fault("reset", sync, after=0.02) if then == "reset"
              else Fault("disconnect", sync, after=0.02))
    emu = FakeController(flavour=flavour, axes="XYZ" if flavour == "grbl" else "XYZC",
                         homing=profile.homing, planner_blocks=6, block_time=0.002,
                         faults=[Fault("drop_ack", sync), follow]).start()
    streams = []
    counts, outs, emus, stray = send_until_done(
        emu, job, profile, str(tmp_path / "j"), mode, power_lost=then != "disconnect",
        streams=streams, link_options={"cut_window": window})
    assert outs[0].result.status in ("reset", "lost") and outs[-1].ok and not stray
    cut = cutting_lines(job)
    assert [i for i in cut if not counts.get(i)] == []
    repeated = [i for i in cut if counts.get(i, 0) > 1]
    last_cut = [i for i in streams[0] if i in cut][-1]
    interrupted = job.segs[job.index.index(last_cut)]
    order = job.segment_ids
    allowed = {interrupted} if window == 1 else {interrupted,
                                                 order[order.index(interrupted) - 1]}
    assert segments_of(job, repeated) <= allowed, (segments_of(job, repeated), interrupted)
    assert sum(e.misplaced for e in emus) == 0


@pytest.mark.parametrize("mode", ["char-count", "send-response"])
def test_several_spurious_oks_never_overfill_the_receive_buffer(mode, tmp_path):
    """Issue #16, 6 (closing note): the margin covered one spurious ``ok``
    between resynchronisations; several in one item overfilled GRBL's 127
    bytes.  Every status report's ``Bf:`` is compared with the count: the
    first report after a spurious ``ok`` shows more unread bytes than counted,
    the excess is counted in flight again and the stream keeps the strict
    bound (no ``ok`` enters it) from then on -- so the later ones, even
    several on one line, cannot overfill it.  (A burst inside one report
    interval before any is detected is the documented limit, docs/LINK.md.)"""
    profile = profile_for("grbl")
    job = make_job(profile, copies=1)
    at = line_in(job, "3:5", 2)
    lines = (at - 30, at, at, at + 1, at + 1, at + 2, at + 3, at + 5)
    spurious = [Fault("spurious", a) for a in lines]
    emu = FakeController(flavour="grbl", axes="XYZ", line_time=0.003, faults=spurious).start()
    jpath = str(tmp_path / "j")
    counts, outs, emus, stray = send_until_done(emu, job, profile, jpath, mode)
    assert all(f.fired for f in spurious)
    assert emus[0].max_rx <= 127 and emus[0].overflows == 0, emus[0].max_rx
    assert outs[-1].ok and not stray
    assert [i for i in cutting_lines(job) if counts.get(i, 0) != 1] == []
    assert outs[0].result.strict_buffer              # detected: strict from then on
    with open(jpath) as f:
        assert '"strict"' in f.read()


def test_the_lines_the_link_makes_pass_the_safety_check_before_the_first_byte(tmp_path):
    """Issue #16, 3: every line the link streams passes the safety check --
    the job as sent, and the link's own lines (resume preamble, feeds taken
    back; every resume in these tests passes it).  A job that leaves the
    profile's table is refused before anything is streamed (before, a
    SendSession -- the workbench's path -- streamed it unchecked)."""
    from LeatherCutWorkbench.core.errors import SafetyError
    from LeatherCutWorkbench.post.profiles import profile_from_dict
    profile = profile_for("grblhal")
    job = make_job(profile, copies=4)                  # parts up to y = 400 + ...
    small = profile_from_dict({**profile.to_json(), "table_size": [600, 300]})
    with FakeController(flavour="grblhal", axes="XYZC", homing=True) as emu:
        with pytest.raises(SafetyError, match="outside the table"):
            SendSession(job, small, emu.port, str(tmp_path / "j"), **FAST).run()
        assert [b for b in emu.log if not b.startswith("$")] == []    # nothing streamed
