"""Multi-tool jobs (post/tools.py, tool_jobs.py, tool_export.py) on the real AAMA
sample GMX1016S18_AAMA.DXF: every drill hole one punch at its position (+ the
punch offset), every notch one slit, all before the knife cuts the part free;
the written G-code is traced back through the project's G-code interpreter."""

import json
import math
import os
from dataclasses import replace

import ezdxf
import pytest

from LeatherCutWorkbench import cli
from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.job import JobOptions, run_job
from LeatherCutWorkbench.core.pathplan import PlanOptions
from LeatherCutWorkbench.post import hpgl, tool_export
from LeatherCutWorkbench.post.gcode_reader import interpreter_for
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict
from LeatherCutWorkbench.post.tools import declared_tools, tool_map

from conftest import SAMPLES_DIR

AAMA = os.path.join(SAMPLES_DIR, "GMX1016S18_AAMA.DXF")
MACHINE = "linuxcnc_leather_multitool"


def one_size(tmp_path, size="50"):
    """The real AAMA file with only the pieces of one size (10 pieces)."""
    doc = ezdxf.readfile(AAMA)
    msp = doc.modelspace()
    for ins in list(msp.query("INSERT")):
        if not ins.dxf.name.endswith("_" + size):
            msp.delete_entity(ins)
    path = tmp_path / f"gmx_{size}.dxf"
    doc.saveas(str(path))
    return str(path)


@pytest.fixture(scope="module")
def aama_job():
    res = run_job(AAMA, JobOptions(plan=PlanOptions(method="nn"), move_to_origin=80.0,
                                  sizes=["all"]))
    return res


def trace(text, profile):
    """Per line of the program: the tool active (from T words) and the
    interpreter's moves; returns a list of (tool number, event, x, y, item)
    where event is 'strike' (the punch output), 'down' (knife: Z below 0, pen:
    its output) or 'cut' (a knife move in the material)."""
    it = interpreter_for(profile)
    tool = None
    item = None
    events = []
    down = False
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if s.startswith("(item "):
            item = s[1:-1].split(" ", 2)[2]
        for m in it.execute(line, n):
            if m.kind in ("rapid", "line") and m.end.get("Z", 0) != m.start.get("Z", 0):
                down = m.end["Z"] < 0
                if down:
                    events.append((tool, "down", m.end["X"], m.end["Y"], item))
            elif m.kind in ("line", "arc") and down:
                events.append((tool, "cut", m.end["X"], m.end["Y"], item))
        tool = it.state.tool
        if s.startswith("M64 P4"):                      # the punch strikes
            events.append((tool, "strike", it.pos["X"], it.pos["Y"], item))
        if s.startswith("M64 P5"):                      # the pen goes down (its output)
            events.append((tool, "down", it.pos["X"], it.pos["Y"], item))
    return events


def test_every_drill_hole_is_one_punch_before_its_part_is_cut(aama_job):
    prof = load_profile(MACHINE)
    parts = aama_job.parts_to_cut
    drills = [(p.id, m.position) for p in parts for m in p.marks if m.kind == "drill"]
    notches = [(p.id, m.position) for p in parts for m in p.marks if m.kind == "notch"]
    assert len(drills) == 30 and len(notches) == 39     # 15 + 31 drawn, unfolded halves mirrored
    job = tool_export.job_for(aama_job.plan, parts, prof)
    text = tool_export.render(aama_job.plan, parts, prof, "gcode", job=job)
    events = trace(text, prof)
    punch = declared_tools(prof)["punch4"]
    strikes = [(x + punch.offset[0], y + punch.offset[1]) for t, e, x, y, _ in events
               if e == "strike"]
    assert all(t == 2 for t, e, *_ in events if e == "strike")       # punched with T2 active
    assert len(strikes) == len(drills)
    for _, pos in drills:                                  # exactly one punch per hole
        assert sum(1 for s in strikes if math.dist(s, pos) < 1e-3) == 1
    # knife: one slit per notch, from the outline 3 mm into the part, each cut
    # before the outer contour of its part
    order = [it for it in job.main.items]
    slits = [k for k, it in enumerate(order) if it.contour_id.endswith("/notch")]
    assert len(slits) == len(notches)
    for k in slits:
        it = order[k]
        assert it.length == pytest.approx(3.0, abs=1e-6)
        outer = next(j for j, o in enumerate(order) if o.kind == "outer" and o.part_id == it.part_id)
        assert k < outer
    for pid, pos in notches:              # one slit per notch mark (some marks coincide)
        same = sum(1 for q, p2 in notches if q == pid and math.dist(p2, pos) < 0.05)
        assert sum(1 for k in slits if order[k].part_id == pid
                   and min(math.dist(order[k].start, pos), math.dist(order[k].end, pos)) < 0.05) \
            == same
    # all strikes (T2) and pen lines (T3) happen before the first knife plunge (T1)
    first_knife = next(i for i, ev in enumerate(events) if ev[0] == 1 and ev[1] == "down")
    assert all(i < first_knife for i, ev in enumerate(events) if ev[0] in (2, 3))
    # tool changes: each tool selected once
    assert [ln for ln in text.splitlines() if ln.endswith("M6")] == ["T3 M6", "T2 M6", "T1 M6"]
    # the pen draws the internal lines at their place (+ pen offset)
    pen = declared_tools(prof)["pen"]
    pen_cut = sum(1 for t, e, *_ in events if t == 3 and e == "down")
    assert pen_cut == sum(len(p.lines) for p in parts) == 765
    first_line = job.passes[0].items[0]
    x, y = next((x, y) for t, e, x, y, _ in events if t == 3 and e == "down")
    assert (x + pen.offset[0], y + pen.offset[1]) == pytest.approx(first_line.start, abs=1e-3)
    report = {r["tool"]: r for r in tool_export.tool_report(job, prof)}
    assert report["punch4"]["count"] == 30 and report["knife"]["roles"] == {"notch": 39}
    assert report["pen"]["length_mm"] == pytest.approx(
        sum(ln.length for p in parts for ln in p.lines), rel=1e-6)


def test_hpgl_pens_and_dxf_layers(aama_job):
    base = json.load(open(load_profile("hpgl_drag_knife").source))
    base.update(name="plotter_pen", tools=[
        {"name": "pen", "kind": "pen", "number": 2, "offset": [0, 0]},
        {"name": "punch", "kind": "punch", "number": 3, "diameter": 3}],
        tool_map={"drill": "punch", "internal": "pen"}, table_size=[3000, 20000])
    prof = profile_from_dict(base, source="plotter_pen.json")
    text = tool_export.render(aama_job.plan, aama_job.parts_to_cut, prof, "hpgl")
    sps = [s for s in text.replace("\n", "").split(";") if s.startswith("SP")]
    assert sps == ["SP2", "SP3", "SP1", "SP0"]
    body3 = text.split("SP3;")[1].split("SP1;")[0]
    assert body3.count("PD;PU;") == 30
    dxf = tool_export.render(aama_job.plan, aama_job.parts_to_cut, prof, "dxf")
    doc = ezdxf.read(__import__("io").StringIO(dxf))
    msp = doc.modelspace()
    assert len(msp.query('POINT[layer=="TOOL_PUNCH"]')) == 30
    assert len(msp.query('CIRCLE[layer=="TOOL_PUNCH"]')) == 30
    assert len(msp.query('*[layer=="TOOL_PEN"]')) >= 765
    # the knife pass is drag-knife compensated, the pen pass is not
    strokes = hpgl.read_hpgl("IN;" + text.split("SP1;")[1], 40)
    assert strokes


def test_bad_tool_input_names_the_field(tmp_path, monkeypatch, capsys):
    prof = load_profile(MACHINE)
    with pytest.raises(InputError, match="--tool-map.*scissors"):
        tool_map(prof, {"stitch": "scissors"})
    with pytest.raises(InputError, match="only strikes points"):
        tool_map(prof, {"stitch": "punch4"})
    with pytest.raises(InputError, match="unknown role"):
        tool_map(prof, {"buttonhole": "pen"})
    base = json.load(open(prof.source))
    with pytest.raises(InputError, match=r"tools\[0\].*diameter"):
        profile_from_dict(dict(base, tools=[{"name": "p", "kind": "punch"}]), source="x.json")
    with pytest.raises(InputError, match="field tool_map.*laser"):
        profile_from_dict(dict(base, tool_map={"drill": "laser"}), source="x.json")
    grbl = json.load(open(load_profile("grblhal_tangential").source))
    with pytest.raises(InputError, match=r"tools\[0\].*'select' is required"):
        profile_from_dict(dict(grbl, tools=[{"name": "pen", "kind": "pen"}]), source="g.json")
    monkeypatch.setattr(cli, "VERB_MODULES", ["post", "run"])
    dxf = one_size(tmp_path)
    out = tmp_path / "job.nc"
    assert cli.main(["post", dxf, "--machine", MACHINE, "--tool-map", "stitch=laser",
                     "-o", str(out), "--plan-method", "nn", "--move-to-origin", "50"]) == 2
    err = capsys.readouterr().err
    assert "laser" in err and "--tool-map" in err and "Traceback" not in err
    assert not out.exists()


def hide_dxf(tmp_path):
    doc = ezdxf.new("R2010", units=4)
    msp = doc.modelspace()
    # kept 100 mm off the table edges: the pen and punch sit up to 60 mm from the knife
    msp.add_lwpolyline([(150, 100), (2200, 160), (2350, 800), (2200, 1450), (200, 1400),
                        (100, 700)], close=True, dxfattribs={"layer": "HIDE"})
    msp.add_lwpolyline([(1100, 700), (1160, 700), (1160, 760), (1100, 760)], close=True,
                       dxfattribs={"layer": "DEFECT"})
    path = tmp_path / "hide.dxf"
    doc.saveas(str(path))
    return str(path)


def test_cli_multitool_leather_job_nested_on_a_hide(tmp_path, monkeypatch, capsys):
    """End to end: knife + punch + pen on one size of the AAMA pattern nested on a hide."""
    monkeypatch.setattr(cli, "VERB_MODULES", ["run"])
    dxf = one_size(tmp_path)
    outdir = tmp_path / "out"
    assert cli.main(["run", dxf, "--machine", MACHINE, "--hide", hide_dxf(tmp_path),
                     "--nest-time", "0", "--plan-method", "nn", "--tool-map", "stitch=pen",
                     "-o", str(outdir), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    tools = {t["tool"]: t for t in data["tools"]}
    assert data["nesting"]["placed"] == 10 and not data["nesting"]["unplaced"]
    parts = run_job(dxf, JobOptions(plan=PlanOptions(method="nn"))).parts_to_cut
    n_drill = sum(1 for p in parts for m in p.marks if m.kind == "drill")
    n_notch = sum(1 for p in parts for m in p.marks if m.kind == "notch")
    assert n_drill == 2 and n_notch == 39
    assert tools["punch4"]["count"] == n_drill and tools["knife"]["roles"] == {"notch": n_notch}
    assert tools["pen"]["count"] > 0 and tools["pen"]["time_s"] > 0
    text = (outdir / "job.nc").read_text()
    prof = load_profile(MACHINE)
    events = trace(text, prof)
    assert sum(1 for ev in events if ev[1] == "strike") == n_drill
    svg = (outdir / "preview.svg").read_text()
    assert 'id="tool-punch4"' in svg and 'id="tool-pen"' in svg


def test_profiles_without_tools_write_what_they_wrote_before(aama_job):
    from LeatherCutWorkbench.post import gcode
    prof = load_profile("linuxcnc_tangential")
    assert tool_export.render(aama_job.plan, aama_job.parts_to_cut, prof, "gcode") == \
        gcode.export(aama_job.plan, prof)
    multi = load_profile(MACHINE)
    plain = replace(multi, tool_map={})
    assert tool_export.render(aama_job.plan, aama_job.parts_to_cut, plain, "gcode") == \
        gcode.export(aama_job.plan, plain)


def test_a_punch_first_job_still_starts_with_the_vacuum(aama_job):
    prof = replace(load_profile(MACHINE), tool_map={"drill": "punch4"})
    text = tool_export.render(aama_job.plan, aama_job.parts_to_cut, prof, "gcode")
    lines = [ln for ln in text.splitlines() if not ln.startswith("(")]
    assert lines.index("T2 M6") < lines.index("M64 P0") < lines.index("M64 P4")
    assert lines.index("M65 P0") > max(i for i, ln in enumerate(lines) if ln == "T1 M6")
    assert lines.count("M64 P0") == 1 and lines.count("M65 P0") == 1


def test_multitool_profile_round_trips_through_the_user_folder(tmp_path, monkeypatch):
    """Machine profiles -> Copy to user folder keeps tools, tool_map and the
    drag-knife fields (what the profile editor shows and saves)."""
    from LeatherCutWorkbench.post.profiles import save_user_profile
    monkeypatch.setenv("LEATHERCUT_MACHINES", str(tmp_path))
    prof = load_profile(MACHINE)
    path = save_user_profile(replace(prof, name="mine"))
    back = load_profile("mine")
    assert back.source == path
    for key in ("tools", "tool_map", "tool_select", "notch_length", "blade_offset", "swivel_angle"):
        assert getattr(back, key) == getattr(prof, key)
    assert declared_tools(back)["punch4"].diameter == 4.0


def test_one_tool_drawing_lines_and_dotting_holes(aama_job):
    """The pen draws the internal lines and dots the drill holes in one pass."""
    prof = replace(load_profile(MACHINE), tool_map={"drill": "pen", "internal": "pen"})
    parts = aama_job.parts_to_cut
    text = tool_export.render(aama_job.plan, parts, prof, "gcode")
    events = trace(text, prof)
    downs = [(x - 40.0, y + 25.0) for t, e, x, y, _ in events if t == 3 and e == "down"]
    assert len(downs) == 765 + 30
    for p in parts:
        for m in p.marks:
            if m.kind == "drill":
                assert min(math.dist(d, m.position) for d in downs) < 1e-3
    hp = replace(load_profile("hpgl_drag_knife"), tools=[{"name": "pen", "kind": "pen"}],
                 tool_map={"drill": "pen", "internal": "pen"}, table_size=(3000.0, 20000.0))
    text = tool_export.render(aama_job.plan, parts, hp, "hpgl")
    pen = text.split("SP2;")[1].split("SP1;")[0]
    assert pen.count("PD;PU;") == 30 and pen.count("PD") > 765


def test_line_numbers_run_through_the_whole_multi_tool_program(aama_job):
    from LeatherCutWorkbench.post.gcode import ExportOptions
    prof = load_profile(MACHINE)
    text = tool_export.render(aama_job.plan, aama_job.parts_to_cut, prof, "gcode",
                              ExportOptions(line_numbers=True))
    blocks = [ln for ln in text.splitlines() if not ln.startswith("(")]
    assert [int(b.split()[0][1:]) for b in blocks] == list(range(1, len(blocks) + 1))
    assert "N" not in "".join(ln for ln in text.splitlines() if ln.startswith("(LeatherCut"))


def test_layer_keys_and_none_in_the_tool_map(aama_job):
    prof = load_profile(MACHINE)
    parts = aama_job.parts_to_cut
    job = tool_export.job_for(aama_job.plan, parts, prof, {"layer:8": "crease", "notch": "none"})
    passes = {p.tool.name: p for p in job.passes}
    assert set(passes) == {"crease", "punch4", "knife"}          # layer 8 = the internal lines
    assert passes["crease"].roles == {"internal": 765} and passes["knife"].roles == {}
    assert len(passes["knife"].items) == len(aama_job.plan.items)   # no slits: notch unmapped
    assert any(f.code == "role-not-mapped" and "39 notch" in f.message for f in job.findings)


def test_notch_slits_run_into_the_part(aama_job):
    from shapely.geometry import Point as SPoint, Polygon
    prof = load_profile(MACHINE)
    job = tool_export.job_for(aama_job.plan, aama_job.parts_to_cut, prof)
    parts = {p.id: p for p in aama_job.parts_to_cut}
    slits = [it for it in job.main.items if it.contour_id.endswith("/notch")]
    assert len(slits) == 39
    for it in slits:
        poly = Polygon(parts[it.part_id].outer.points(0.01))
        ends = [SPoint(it.start), SPoint(it.end)]
        on = [e.distance(poly.exterior) < 0.05 for e in ends]
        assert sum(on) == 1                                  # one end on the outline
        inner = ends[on.index(False)]
        assert poly.contains(inner) and inner.distance(poly.exterior) > 2.0


def test_multi_tool_program_keeps_segment_ids_for_the_live_link(aama_job):
    """``send`` streams tool_export.program: one id per segment through the
    whole job, and the (seg I:S) comments of the file give the same ids back
    (what the link journals and resumes from)."""
    from LeatherCutWorkbench.post.gcode import segment_map
    prof = load_profile(MACHINE)
    prog = tool_export.program(aama_job.plan, aama_job.parts_to_cut, prof)
    assert len(prog.lines) == len(prog.segs)
    job = tool_export.job_for(aama_job.plan, aama_job.parts_to_cut, prof)
    assert len(set(prog.segment_ids)) == len(prog.segment_ids) == sum(
        len(it.segments) for p in job.passes for it in p.items) + 30
    segs, order = segment_map(prog.lines)
    assert order == prog.segment_ids
    assert all(a == b for a, b, ln in zip(segs, prog.segs, prog.lines) if not ln.startswith("("))
