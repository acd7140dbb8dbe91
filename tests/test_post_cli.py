"""``leathercut post`` and ``leathercut send`` end to end on a real drawing
(import, recognition and planning run for real), streaming into the built-in
fake controller."""

import json
import math

import ezdxf
import pytest

from LeatherCutWorkbench import cli
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.gcode_reader import interpreter_for, traced_cuts
from LeatherCutWorkbench.post.link import GrblLink, Journal, job_from_file, load_journal
from LeatherCutWorkbench.post.profiles import load_profile


@pytest.fixture
def main(monkeypatch):
    # only this verbs: the other verbs are tested by their own suites
    monkeypatch.setattr(cli, "VERB_MODULES", ["post", "send"])
    return cli.main


def drawing(tmp_path, x0=100.0):
    doc = ezdxf.new("R2010", units=4)        # millimetres
    msp = doc.modelspace()
    msp.add_lwpolyline([(x0, 100), (x0 + 300, 100), (x0 + 300, 250), (x0, 250)], close=True)
    msp.add_circle((x0 + 80, 170), 25)
    msp.add_lwpolyline([(x0 + 400, 100), (x0 + 550, 100), (x0 + 550, 200)], close=False)
    path = tmp_path / "parts.dxf"
    doc.saveas(str(path))
    return str(path)


FASTPLAN = ["--plan-method", "nn"]


def test_post_all_formats(tmp_path, main, capsys):
    dxf = drawing(tmp_path)
    for fmt, machine in (("gcode", "grblhal_tangential"), ("gcode", "linuxcnc_tangential"),
                         ("hpgl", "hpgl_plotter"), ("dxf", "grblhal_tangential")):
        out = tmp_path / f"out_{machine}.{fmt}"
        assert main(["post", dxf, "--machine", machine, "--format", fmt, "-o", str(out),
                     "--json"] + FASTPLAN) == 0
        data = json.loads(capsys.readouterr().out)
        assert data["output"] == str(out) and out.exists() and data["items"] == 3
    text = (tmp_path / "out_grblhal_tangential.gcode").read_text()
    prof = load_profile("grblhal_tangential")
    it = interpreter_for(prof)
    for n, line in enumerate(text.splitlines(), 1):
        it.execute(line, n)
    cuts, bad = traced_cuts(it.moves, prof)
    assert not bad
    length = sum(((m.end["X"] - m.start["X"]) ** 2 + (m.end["Y"] - m.start["Y"]) ** 2) ** 0.5
                 for m in cuts if m.kind == "line")
    arcs = [m for m in cuts if m.kind == "arc"]
    assert length == pytest.approx(2 * (300 + 150) + 150 + 100, abs=0.01)
    sweep = 0.0
    for m in arcs:                 # the circle: arcs of at most 90 degrees, 360 in all
        a0 = math.atan2(m.start["Y"] - m.center[1], m.start["X"] - m.center[0])
        a1 = math.atan2(m.end["Y"] - m.center[1], m.end["X"] - m.center[0])
        sw = math.degrees((a1 - a0) % (2 * math.pi) if m.ccw else (a0 - a1) % (2 * math.pi))
        assert sw <= 90.0 + 1e-6
        sweep += sw
    assert sweep == pytest.approx(360.0, abs=1e-3)


def test_post_refusal_writes_nothing(tmp_path, main, capsys):
    dxf = drawing(tmp_path, x0=2300.0)        # sticks out past x = 2500
    out = tmp_path / "job.nc"
    assert main(["post", dxf, "--machine", "grblhal_tangential", "-o", str(out)] + FASTPLAN) == 2
    err = capsys.readouterr().err
    assert "outside the table" in err and "item" in err
    assert not out.exists() and not (tmp_path / "job.nc.part").exists()
    # stock GRBL cannot take the C axis job: refused by word, nothing written
    bad = tmp_path / "bad.json"
    prof = json.load(open(load_profile("grbl11_knife_z_servo").source))
    prof.update(axes="XYZC", rotary_axis="C", name="bad")
    bad.write_text(json.dumps(prof))
    assert main(["post", drawing(tmp_path), "--machine", str(bad), "-o", str(out)] + FASTPLAN) == 2
    assert "word C" in capsys.readouterr().err and not out.exists()


def test_send_nc_with_check_mode_to_emulator(tmp_path, main, capsys):
    dxf = drawing(tmp_path)
    nc = tmp_path / "job.nc"
    assert main(["post", dxf, "--machine", "grblhal_tangential", "-o", str(nc)] + FASTPLAN) == 0
    capsys.readouterr()
    code = main(["send", str(nc), "--port", "emulator:grblhal", "--check", "--mode",
                 "char-count", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0, data
    assert data["check"]["status"] == "check-ok"
    assert data["result"]["status"] == "done"
    assert data["controller"]["rx_size"] == 1024 and data["controller"]["axes"] == "XYZC"
    st = load_journal(data["journal"])
    assert set(st.done_segments()) == set(st.segments) and st.segments


def test_send_resume_from_journal_via_cli(tmp_path, main, capsys):
    """A job stopped by an alarm, resumed with --resume-from auto on the same
    controller port (socket-free: the pty of the fake controller)."""
    dxf = drawing(tmp_path)
    nc = tmp_path / "job.nc"
    assert main(["post", dxf, "--machine", "grblhal_tangential", "-o", str(nc)] + FASTPLAN) == 0
    profile = load_profile("grblhal_tangential")
    job = job_from_file(str(nc))
    jpath = str(tmp_path / "job.journal")
    emu = FakeController(flavour="grblhal", axes="XYZC", homing=True,
                         faults=[Fault("alarm", 30, code=2)]).start()
    try:
        link = GrblLink(emu.port, status_interval=0.05, link_timeout=0.5, hold_timeout=1,
                        reset_timeout=1).open()
        link.use_profile(profile)
        link.greet()
        link.ready_for_job(profile)
        j = Journal.open(jpath, job, "send-response")
        res = link.stream(job, j)
        j.close()
        link.close()
        assert res.status == "alarm"
        first = load_journal(jpath).first_incomplete()
        mark = len(emu.executed)
        capsys.readouterr()
        code = main(["send", str(nc), "--port", emu.port, "--resume-from", "auto",
                     "--journal", jpath, "--json"])
        data = json.loads(capsys.readouterr().out)
        assert code == 0, data
        assert data["resumed_from"] == first
        st = load_journal(jpath)
        assert set(st.done_segments()) == set(st.segments)
        assert emu.executed[mark:][0] == "G21G90G17G94"       # modal state restored first
    finally:
        emu.close()


def test_send_refuses_missing_axis(tmp_path, main, capsys):
    dxf = drawing(tmp_path)
    nc = tmp_path / "job.nc"
    assert main(["post", dxf, "--machine", "grblhal_tangential", "-o", str(nc)] + FASTPLAN) == 0
    capsys.readouterr()
    emu = FakeController(flavour="grblhal", axes="XYZ").start()     # no C axis
    try:
        assert main(["send", str(nc), "--port", emu.port, "--machine", "grblhal_tangential",
                     "--no-home"]) == 2
        assert "uses axis C" in capsys.readouterr().err
        assert emu.executed == []
    finally:
        emu.close()


def test_send_stops_on_error_and_names_line_and_resume_point(tmp_path, main, capsys):
    dxf = drawing(tmp_path)
    nc = tmp_path / "job.nc"
    assert main(["post", dxf, "--machine", "grblhal_tangential", "-o", str(nc)] + FASTPLAN) == 0
    capsys.readouterr()
    emu = FakeController(flavour="grblhal", axes="XYZC", planner_blocks=4, block_time=0.003,
                         faults=[Fault("error", 25, code=33)]).start()
    try:
        code = main(["send", str(nc), "--port", emu.port, "--mode", "char-count", "--json"])
        data = json.loads(capsys.readouterr().out)
    finally:
        emu.close()
    assert code == 1
    res = data["result"]
    assert res["status"] == "error" and res["message"].startswith("error:33")
    assert res["stopped_safely"] and res["position_trusted"]
    lines = nc.read_text().splitlines()
    assert lines[res["line"] - 1].replace(" ", "") == res["block"]
    # the planner still held moves before the refused line: the machine stopped
    # at or before the refused line's segment, and the resume starts there
    key = lambda sid: tuple(int(v) for v in sid.split(":"))
    assert data["resume_basis"] == "position"
    assert key(data["resume_from"]) <= key(res["segment"])
