"""The live link against the fake controller: identify, stream modes, check
mode, pause/resume/abort, lost link, journal; and reply parsing."""

import math
import os
import threading
import time

import pytest

from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.link import (GrblLink, Journal, LinkError, job_from_lines,
                                           job_from_program, load_journal)
from LeatherCutWorkbench.post.link.protocol import parse_reply
from LeatherCutWorkbench.post.profiles import load_profile

from post_helpers import sample_plan

FAST = dict(status_interval=0.05, link_timeout=1.0, greet_timeout=1.5, hold_timeout=2.0,
            reset_timeout=2.0, command_timeout=3.0, min_poll_interval=0.005)


def job_for(name="grblhal_tangential"):
    prof = load_profile(name)
    return prof, job_from_program("job.nc", gcode.build_program(sample_plan(), prof))


def test_parse_replies():
    assert parse_reply("ok").kind == "ok"
    e = parse_reply("error:20")
    assert (e.kind, e.code) == ("error", 20) and "unsupported" in e.text
    a = parse_reply("ALARM:1")
    assert (a.kind, a.code) == ("alarm", 1) and "hard limit" in a.text
    s = parse_reply("<Hold:0|MPos:1.000,2.000,3.000|Bf:15,128|FS:0,0>")
    assert s.kind == "status" and s.state == "Hold:0" and s.fields["MPos"] == "1.000,2.000,3.000"
    assert parse_reply("Grbl 1.1h ['$' for help]").kind == "banner"
    assert parse_reply("GrblHAL 1.1f ['$' or '$HELP' for help]").text == "GrblHAL 1.1f"
    assert parse_reply("[MSG:Enabled]").text == "Enabled"
    assert parse_reply("[OPT:V,15,128]").fields == {"OPT": "V,15,128"}


@pytest.mark.parametrize("flavour,rx,axes", [("grbl", 128, "XYZ"), ("grblhal", 1024, "XYZC")])
def test_greet_identifies_controller(flavour, rx, axes):
    with FakeController(flavour=flavour, axes=axes) as emu:
        with GrblLink(emu.port, **FAST) as link:
            info = link.greet()
    assert info.flavour == flavour and info.rx_size == rx and info.axes == axes
    assert info.state == "Idle" and info.version.startswith("1.1")


def test_no_controller_is_a_clear_error():
    with GrblLink("loop://", **FAST) as link:       # loop:// only echoes
        with pytest.raises(LinkError, match="no controller answers"):
            link.greet()
    with pytest.raises(LinkError, match="cannot open"):
        GrblLink("/dev/does-not-exist", **FAST).open()


def test_char_counting_fills_but_never_overflows_the_buffer(tmp_path):
    prof, job = job_for()
    with FakeController(flavour="grbl", axes="XYZC", line_time=0.002) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.greet()
            seen = []
            orig = emu._process_one

            def spy():
                seen.append(len(emu._rx))
                orig()
            emu._process_one = spy
            res = link.stream(job, Journal.open(str(tmp_path / "j"), job, "char-count"),
                              "char-count")
    assert res.status == "done" and emu.overflows == 0
    assert max(seen) > 64            # the host really kept the 128-byte buffer busy
    assert max(seen) <= 127
    assert emu.executed == job.blocks
    st = load_journal(str(tmp_path / "j"))
    last_sync = max(i for i, l in enumerate(job.source) if l == "G4 P0")
    assert st.last_sync == last_sync and st.events[-1]["e"] == "done"


def test_send_response_has_one_line_in_flight(tmp_path):
    prof, job = job_for()
    with FakeController(flavour="grblhal", axes="XYZC", line_time=0.001) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.greet()
            seen = []
            orig = emu._process_one

            def spy():
                seen.append(emu._rx.count(b"\n"))
                orig()
            emu._process_one = spy
            res = link.stream(job, None, "send-response")
    assert res.status == "done" and max(seen) == 1
    assert emu.executed == job.blocks


def test_check_mode_finds_a_bad_line_and_nothing_moves():
    prof, job = job_for()
    lines = list(job.source)
    bad = next(i for i, l in enumerate(lines) if l.startswith("G2 "))
    lines[bad] = lines[bad].replace("I", "Q", 1)            # Q is unused by G2: error:36
    bad_job = job_from_lines("bad.nc", lines)
    with FakeController(flavour="grblhal", axes="XYZC") as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.greet()
            res = link.run_check(bad_job, "char-count")
            assert res.status == "check-failed" and res.line == bad + 1
            assert res.message.startswith("error:")
            assert emu.executed == [] and emu.state == "Idle"
            ok = link.run_check(job, "char-count")
            assert ok.status == "check-ok" and emu.executed == []
            assert emu.position["X"] == 0.0          # check mode moved nothing


def test_pause_resume_and_abort(tmp_path):
    prof, job = job_for()
    with FakeController(flavour="grblhal", axes="XYZC", line_time=0.01) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.use_profile(prof)
            link.greet()
            out = {}
            th = threading.Thread(target=lambda: out.setdefault(
                "r", link.stream(job, Journal.open(str(tmp_path / "j"), job, "char-count"),
                                 "char-count")))
            th.start()
            time.sleep(0.15)
            link.pause()
            end = time.monotonic() + 3.0
            while emu.state != "Hold:0" and time.monotonic() < end:
                time.sleep(0.01)
            assert emu.state == "Hold:0"
            n_paused = len(emu.executed)
            time.sleep(0.2)
            assert len(emu.executed) == n_paused       # nothing runs during the hold
            link.resume()
            end = time.monotonic() + 3.0
            while len(emu.executed) == n_paused and time.monotonic() < end:
                time.sleep(0.01)
            assert len(emu.executed) > n_paused
            link.abort()
            th.join(5)
    res = out["r"]
    assert res.status == "aborted" and res.stopped_safely
    assert 0 < res.acked < len(job.blocks)
    assert emu.position["Z"] == prof.z_up               # knife lifted after the stop
    st = load_journal(str(tmp_path / "j"))
    assert len(st.acked_set) == res.acked and st.events[-1]["e"] == "aborted"


def test_lost_link_when_status_goes_unanswered(tmp_path):
    prof, job = job_for()
    emu = FakeController(flavour="grblhal", axes="XYZC",
                         faults=[Fault("stall", 20, seconds=30)]).start()
    try:
        link = GrblLink(emu.port, **{**FAST, "reset_timeout": 0.2}).open()
        link.greet()
        t0 = time.monotonic()
        res = link.stream(job, None)
        assert res.status == "lost" and "no status reply" in res.message
        assert time.monotonic() - t0 < 6.0      # link_timeout + the stop attempt
        link.close()
    finally:
        emu._stall_until = 0
        emu.close()


def test_journal_refuses_another_job_and_survives_torn_write(tmp_path):
    prof, job = job_for()
    p = str(tmp_path / "j")
    j = Journal.open(p, job, "send-response")
    j.ack(job.index[0], job.segs[0])
    j.close()
    with open(p, "a") as fh:
        fh.write('{"e":"ack","i":')          # crash mid-write
    st = load_journal(p)
    assert st.acked == [job.index[0]]
    other = job_from_lines("other.nc", job.source + ["G0 X1"])
    with pytest.raises(Exception, match="another job"):
        Journal.open(p, other, "send-response")


def test_foreign_gcode_file_is_checked_and_journaled_per_line(data_dir, tmp_path):
    from LeatherCutWorkbench.core.errors import InputError, SafetyError
    from LeatherCutWorkbench.post import safety
    from LeatherCutWorkbench.post.link import job_from_file

    path = os.path.join(data_dir, "post", "foreign_grbl.nc")
    prof = load_profile("grbl11_knife_z_servo")
    with pytest.raises(InputError, match="no LeatherCut end marker"):
        job_from_file(path)                    # hand-written: only when asked
    job = job_from_file(path, allow_unsealed=True)
    safety.check_program(job.source, prof, path)
    assert job.segment_ids[0] == "L3" and len(job.blocks) == 13
    with FakeController(flavour="grbl", axes="XYZ") as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.greet()
            link.check_axes(job)
            res = link.stream(job, Journal.open(str(tmp_path / "j"), job, "char-count"),
                              "char-count")
    assert res.status == "done" and emu.position["X"] == 0.0
    st = load_journal(str(tmp_path / "j"))
    assert set(st.done_segments()) == set(job.segment_ids)
    # the same program moved 300 mm over: the arc leaves the 1300 x 900 table
    moved = [l.replace("X60", "X1310") if l.startswith("G3") else l for l in job.source]
    with pytest.raises(SafetyError, match="line 9"):
        safety.check_program(moved, prof, "moved.nc")


def test_send_session_runs_off_the_calling_thread(tmp_path):
    from LeatherCutWorkbench.post.link import SendSession

    prof, job = job_for()
    with FakeController(flavour="grblhal", axes="XYZC", homing=True) as emu:
        done = threading.Event()
        seen = []
        s = SendSession(job, prof, emu.port, str(tmp_path / "j"), mode="char-count",
                        check=True, progress=seen.append, **FAST)
        th = s.start(lambda sess: done.set())
        assert th is not threading.current_thread()
        assert done.wait(10)
    assert s.error is None and s.outcome.ok and s.outcome.check.ok
    assert seen[-1]["percent"] == 100.0 and emu.executed == job.blocks


def test_resume_program_rebuilds_state_before_the_segment():
    from LeatherCutWorkbench.post.link import resume_job

    prof, job = job_for()
    r = resume_job(job, "3:3", prof)         # mid-outline, knife down, vacuum and oscillator on
    head = r.blocks[:7]
    assert head[0] == "G21G90G17G94" and head[1] == "M8" and head[2] == "G0Z5"
    assert head[3].startswith("G0X280Y50C")   # start of 3:3 (the rounded corner), pre-turned
    assert head[4] == "M3S18000" and head[5] == "G1Z-1.2F1500" and head[6] == "F12000"
    assert r.index[:7] == [None] * 7 and r.segs[7] == "3:3"
    # servo-lifted knife on stock GRBL: knife down is the servo line, after the move
    sprof = load_profile("grbl11_knife_z_servo")
    sjob = job_from_program("s.nc", gcode.build_program(sample_plan(), sprof))
    s = resume_job(sjob, "3:3", sprof)
    assert s.blocks[2:4] == ["M5", "G4P0.25"] and s.blocks[4].startswith("G0X280Y50Z")
    assert s.blocks[5:7] == ["M3S1000", "G4P0.25"]
    # skipping complete segments re-positions before the next one
    k = resume_job(job, "3:2", prof, skip=["3:3"])
    at = k.segs.index("3:4")
    assert k.index[at] is None and k.blocks[at] == "G21G90G17G94"


def test_locate_position_on_lines_and_arcs():
    from LeatherCutWorkbench.post.gcode_reader import read_program
    from LeatherCutWorkbench.post.link.recovery import locate

    it = read_program("G21 G90\nG1 X10 Y0 C0 F100\nG3 X20 Y10 I0 J10 C90\n")
    line, arc = it.moves
    tol = {"X": 0.02, "Y": 0.02, "Z": 0.02, "C": 0.05}
    assert locate(line, {"X": 5.0, "Y": 0.0, "Z": 0.0, "C": 0.0}, tol) == pytest.approx(0.5)
    assert locate(line, {"X": 5.0, "Y": 0.5, "Z": 0.0, "C": 0.0}, tol) is None
    mid = (10 + 10 * math.cos(math.radians(-45)), 10 + 10 * math.sin(math.radians(-45)))
    assert locate(arc, {"X": mid[0], "Y": mid[1], "Z": 0.0, "C": 45.0}, tol) == pytest.approx(0.5)
    assert locate(arc, {"X": mid[0], "Y": mid[1], "Z": 0.0, "C": 10.0}, tol) is None  # wrong knife angle
    assert locate(arc, {"X": 0.0, "Y": 10.0, "Z": 0.0, "C": 45.0}, tol) is None      # off the sweep


@pytest.mark.parametrize("report_buffer", [True, False])
def test_the_link_knows_whether_the_reports_carry_the_buffer_state(report_buffer):
    """The hard receive-buffer bound needs ``Bf:`` (GRBL ``$10`` bit 1): the
    link says whether it has it, and streams either way."""
    from LeatherCutWorkbench.post.link import job_from_program
    from post_helpers import sample_plan
    profile = load_profile("grbl11_knife_z_servo")
    job = job_from_program("j.nc", gcode.build_program(sample_plan(), profile))
    with FakeController(flavour="grbl", report_buffer=report_buffer) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.use_profile(profile)
            info = link.greet()
            assert info.buffer_reported == report_buffer
            assert link.stream(job, None, "char-count").status == "done"
        assert emu.overflows == 0


def test_without_a_spurious_ok_the_count_runs_on_the_oks_not_on_the_reports(tmp_path):
    """The lead's benchmark (5 ms lines): a bound that ignores every ``ok``
    until the next status report starved the planner -- GRBL's 128 bytes
    drain faster than reports come.  With genuine ``ok``s the count trusts
    them: far more than RX - 1 bytes go out between two polls, the ``Bf:``
    resync never fires (no false spurious-ok alarm), the buffer never
    overflows.  (Failed before: at most RX - 1 bytes per report.)"""
    from LeatherCutWorkbench.post.link import job_from_program
    from post_helpers import sample_plan
    profile = load_profile("grbl11_knife_z_servo")
    job = job_from_program("j.nc", gcode.build_program(sample_plan(), profile))
    with FakeController(flavour="grbl", planner_blocks=15, block_time=0.002) as emu:
        with GrblLink(emu.port, **FAST) as link:
            link.use_profile(profile)
            assert link.greet().buffer_reported
            at_poll = []
            real = link._poll

            def counted():
                at_poll.append(link._written)
                real()
            link._poll = counted
            res = link.stream(job, Journal.open(str(tmp_path / "j"), job, "char-count"),
                              "char-count")
    assert res.status == "done" and emu.overflows == 0 and emu.max_rx <= 127
    assert res.buffer_resyncs == 0 and not res.strict_buffer
    assert max(b - a for a, b in zip(at_poll, at_poll[1:])) > 127
