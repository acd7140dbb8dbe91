"""HP-GL and DXF writers, safety refusals and machine profiles."""

import json
import math

import ezdxf
import pytest

from LeatherCutWorkbench.core.errors import InputError, SafetyError
from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg
from LeatherCutWorkbench.core.model import CutItem, CutPlan
from LeatherCutWorkbench.post import dxf_out, gcode, hpgl
from LeatherCutWorkbench.post.profiles import list_profiles, load_profile

from post_helpers import dist_to_segment, sample_plan

ALL = ["grblhal_tangential", "grbl11_knife_z_servo", "linuxcnc_tangential", "flame_plasma",
       "hpgl_plotter"]


def rect_plan(x0, y0, w, h):
    pts = [(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h), (x0, y0)]
    return CutPlan([CutItem("C1", "P1", "outer", (x0, y0),
                            [LineSeg(a, b) for a, b in zip(pts, pts[1:])])])


def test_shipped_profiles_load_and_list():
    names = {p["name"] for p in list_profiles()}
    assert set(ALL) <= names
    p = load_profile("grblhal_tangential")
    assert p.table_size == (2500.0, 1600.0) and p.rotary_axis == "C" and not p.rotary_wrap
    assert load_profile("linuxcnc_tangential").rotary_wrap
    g = load_profile("grbl11_knife_z_servo")
    assert g.axes == "XYZ" and g.rotary_axis == "Z" and g.units_per_turn == 3.6


def test_user_profile_folder_and_bad_profiles(tmp_path, monkeypatch):
    monkeypatch.setenv("LEATHERCUT_MACHINES", str(tmp_path))
    base = json.load(open(load_profile("grblhal_tangential").source))
    base["name"] = "my_table"
    base["table_size"] = [3000, 2000]
    (tmp_path / "my_table.json").write_text(json.dumps(base))
    assert load_profile("my_table").table_size == (3000.0, 2000.0)
    assert any(p["name"] == "my_table" and p["origin"] == "user" for p in list_profiles())
    bad = dict(base, cut_feed=90000)
    (tmp_path / "bad.json").write_text(json.dumps(bad))
    with pytest.raises(InputError, match="cut_feed"):
        load_profile(str(tmp_path / "bad.json"))
    (tmp_path / "typo.json").write_text(json.dumps(dict(base, lift_angel=10)))
    with pytest.raises(InputError, match="lift_angel"):
        load_profile(str(tmp_path / "typo.json"))
    with pytest.raises(InputError, match="no machine profile"):
        load_profile("no_such_machine")


def test_hpgl_units_commands_and_overcut():
    profile = load_profile("hpgl_plotter")
    text = hpgl.export(rect_plan(10, 10, 20, 10), profile)
    assert text.splitlines()[:4] == ["IN;", "VS20;", "FS80;", "SP1;"]
    assert "PU400,400;" in text
    assert "PD1200,400,1200,800,400,800,400,400,440,400;" in text    # 1 mm overcut
    assert "PE" not in text and text.rstrip().endswith("SP0;")
    no_oc = hpgl.export(rect_plan(10, 10, 20, 10), profile, gcode.ExportOptions(overcut=0))
    assert "PD1200,400,1200,800,400,800,400,400;" in no_oc


def test_hpgl_traced_path_equals_plan():
    profile = load_profile("hpgl_plotter")
    plan = sample_plan()
    strokes = hpgl.read_hpgl(hpgl.export(plan, profile, gcode.ExportOptions(overcut=0)))
    assert len(strokes) == len(plan.items)
    for stroke, item in zip(strokes, plan.items):
        assert math.dist(stroke[0], item.start) < 0.0125 + 1e-9      # 1 unit = 0.025 mm
        assert math.dist(stroke[-1], item.end) < 0.0125 + 1e-9
        for p in stroke:
            d = min(dist_to_segment(p, s) for s in item.segments)
            assert d < 0.018 + profile.chord_tol        # rounding to 0.025 mm grid


def test_dxf_layers_entities_and_order_numbers(tmp_path):
    plan = sample_plan()
    text = dxf_out.export(plan, load_profile("grblhal_tangential"))
    path = tmp_path / "job.dxf"
    path.write_text(text)
    doc = ezdxf.readfile(str(path))
    assert doc.dxfversion == "AC1009"
    msp = doc.modelspace()
    layers = {e.dxf.layer for e in msp}
    assert {"CUT", "LEAD_IN", "IDLE", "ORDER"} <= layers
    assert len(msp.query('CIRCLE[layer=="CUT"]')) == 1
    assert len(msp.query('ARC[layer=="CUT"]')) == 3
    assert len(msp.query('LINE[layer=="LEAD_IN"]')) == 1
    texts = sorted(int(t.dxf.text) for t in msp.query("TEXT"))
    assert texts == [1, 2, 3, 4]
    assert len(msp.query('LINE[layer=="IDLE"]')) == len(plan.items) + 1
    # a CW arc keeps its geometry: its midpoint lies on the planned arc
    arc_seg = plan.items[1].segments[1]
    arcs = [a for a in msp.query('ARC[layer=="CUT"]')
            if math.dist((a.dxf.center.x, a.dxf.center.y), arc_seg.center) < 1e-9]
    a = arcs[0]
    mid_ang = math.radians((a.dxf.start_angle + ((a.dxf.end_angle - a.dxf.start_angle) % 360) / 2))
    mid = (a.dxf.center[0] + a.dxf.radius * math.cos(mid_ang),
           a.dxf.center[1] + a.dxf.radius * math.sin(mid_ang))
    assert dist_to_segment(mid, arc_seg) < 1e-9


@pytest.mark.parametrize("name", ALL)
def test_safety_refuses_job_outside_table(name, tmp_path):
    profile = load_profile(name)
    w, h = profile.table_size
    plan = rect_plan(w - 50, 10, 100, 20)           # sticks out 50 mm on +X
    writer = hpgl if profile.dialect == "hpgl" else gcode
    with pytest.raises(SafetyError) as e:
        writer.export(plan, profile)
    assert "item 1" in str(e.value) and "outside the table" in str(e.value)
    plan_arc = CutPlan([CutItem("C", "P", "hole", (30, 25),
                                [ArcSeg((20, 25), 10.0, 0, 360)])], home=(0, 0))
    plan_arc.items[0].segments[0] = ArcSeg((20, 5), 10.0, 0, 360)    # dips to y = -5
    with pytest.raises(SafetyError, match="outside the table"):
        writer.export(plan_arc, profile)


def test_safety_refuses_bad_feed_and_unknown_words(tmp_path):
    plan = rect_plan(10, 10, 50, 50)
    p = load_profile("grblhal_tangential")
    p.cut_feed = p.max_feed * 2
    with pytest.raises(SafetyError, match="feed"):
        gcode.export(plan, p)
    # stock GRBL has no C axis: a profile asking for one is refused
    g = load_profile("grbl11_knife_z_servo")
    g.axes, g.rotary_axis = "XYZC", "C"
    with pytest.raises(SafetyError, match="word C"):
        gcode.export(plan, g)
    g = load_profile("grbl11_knife_z_servo")
    g.vacuum_on = ["M64 P0"]                      # grblHAL / LinuxCNC only
    with pytest.raises(SafetyError, match="M64"):
        gcode.export(plan, g)
    h = load_profile("grblhal_tangential")
    h.header = ["G21 G90 Q7"]
    with pytest.raises(SafetyError, match="word Q|Q"):
        gcode.export(plan, load_profile("grbl11_knife_z_servo").__class__(
            **{**load_profile("grbl11_knife_z_servo").__dict__, "header": ["G21 G90 Q7"]}))




def test_origin_offsets_output_and_home_is_machine_zero():
    p = load_profile("grblhal_tangential")
    p.origin = (100.0, 50.0)
    plan = rect_plan(10, 10, 50, 50)
    plan.home = (-100.0, -50.0)             # machine zero, outside the table
    lines = gcode.export(plan, p).splitlines()
    assert "G0 X110 Y60 C0" in lines and "G0 X0 Y0" in lines


def test_table_edge_tolerance_is_the_output_resolution():
    p = load_profile("grblhal_tangential")
    gcode.export(rect_plan(-0.0004, 0, 100, 50), p)          # float noise from nesting: fine
    with pytest.raises(SafetyError):
        gcode.export(rect_plan(-0.01, 0, 100, 50), p)        # 10 um off the table: refused


def test_dxf_marks_layer():
    from LeatherCutWorkbench.core.model import Mark
    text = dxf_out.export(sample_plan(), None,
                          dxf_out.DxfOptions(marks=[Mark((120.0, 60.0), "drill")]))
    import io
    doc = ezdxf.read(io.StringIO(text))
    pts = doc.modelspace().query('POINT[layer=="MARKS"]')
    assert len(pts) == 1 and tuple(pts[0].dxf.location)[:2] == (120.0, 60.0)
