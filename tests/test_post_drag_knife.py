"""Drag-knife compensation (post/drag_knife.py), checked by simulating the blade
tip from the written HP-GL / G-code (tests/drag_sim.py) on real geometry."""

import json
import math
import os
from dataclasses import replace

import pytest

from LeatherCutWorkbench import cli
from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.job import JobOptions, run_job
from LeatherCutWorkbench.core.model import CutItem, CutPlan
from LeatherCutWorkbench.core.pathplan import PlanOptions
from LeatherCutWorkbench.post import gcode, hpgl
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from conftest import SAMPLES_DIR
from drag_sim import drawn_lines, gcode_strokes, simulate, split_deviation, swivel_corners

TOL = 0.05          # mm, the limit for the blade tip


@pytest.fixture(scope="module")
def deepnest_plan():
    """Real parts with arcs, circles and sharp corners, cut where they lie."""
    res = run_job(os.path.join(SAMPLES_DIR, "deepnest_ReadMeExampleSmall.dxf"),
                  JobOptions(plan=PlanOptions(method="nn"), move_to_origin=10.0))
    assert len(res.plan.items) > 20
    return res.plan


def tip_deviation(plan, strokes, r, swivel):
    tips = simulate(strokes, r)
    return split_deviation(tips, drawn_lines(plan), swivel_corners(plan, swivel), 1.5 * r)


def test_hpgl_blade_tip_follows_the_drawing(deepnest_plan):
    prof = load_profile("hpgl_drag_knife")
    assert prof.blade_offset == 0.25
    text = hpgl.export(deepnest_plan, prof)
    away, at_swivel = tip_deviation(deepnest_plan, hpgl.read_hpgl(text, 40), 0.25,
                                    prof.swivel_angle)
    assert away <= TOL and at_swivel <= TOL
    # the check can fail: the same job uncompensated, same blade, is 0.25 mm out
    plain = hpgl.export(deepnest_plan, replace(prof, blade_offset=0.0))
    away0, _ = tip_deviation(deepnest_plan, hpgl.read_hpgl(plain, 40), 0.25, prof.swivel_angle)
    assert away0 > 0.2


def test_gcode_drag_knife_swivel_arcs_are_g2_g3(deepnest_plan):
    plan = CutPlan(deepnest_plan.items[:12], home=deepnest_plan.home)      # keeps it quick
    prof = replace(load_profile("flame_plasma"), name="drag", tool="drag_knife", lift_axis="Z",
                   knife_up=[], knife_down=[], pierce_delay=0.0, cooling_delay=0.0,
                   blade_offset=1.0, swivel_angle=10.0, overcut=1.0)
    text = gcode.export(plan, prof)
    away, at_swivel = tip_deviation(plan, gcode_strokes(text, prof), 1.0, 10.0)
    assert away <= 0.01 and at_swivel <= 0.01          # exact arcs: only float noise
    # swivel arcs: radius 1 mm about a drawn corner or entry
    corners = swivel_corners(plan, 10.0)
    swivels = 0
    for line in text.splitlines():
        if line.startswith(("G2 ", "G3 ")):
            w = dict((t[0], float(t[1:])) for t in line.split()[1:] if t[0] in "IJ")
            if abs(math.hypot(w["I"], w["J"]) - 1.0) < 2e-3:
                swivels += 1
    assert len(corners) * 0.5 < swivels <= len(corners) * 2


def test_lines_extended_by_the_offset_and_corner_swivel():
    # an L: the axis runs 2 mm past each drawn end, circles the corner at r = 2
    plan = CutPlan([CutItem("O1", "", "open", (10, 10),
                            [LineSeg((10, 10), (50, 10)), LineSeg((50, 10), (50, 40))])])
    prof = replace(load_profile("hpgl_drag_knife"), blade_offset=2.0, overcut=0.0)
    strokes = hpgl.read_hpgl(hpgl.export(plan, prof), 40)
    assert len(strokes) == 1
    s = strokes[0]
    assert s[0] == pytest.approx((12.0, 10.0))           # plunge: tip on (10, 10), blade +X
    assert (52.0, 10.0) in [pytest.approx(p) for p in s]  # line extended by 2 mm
    assert s[-1] == pytest.approx((50.0, 42.0))          # end extended by 2 mm
    swivel = [p for p in s if abs(math.dist(p, (50.0, 10.0)) - 2.0) < 0.03]
    assert len(swivel) > 10                               # the 90 degree swivel arc


def test_blade_offset_refused_on_tangential_knife(tmp_path, monkeypatch, capsys):
    base = json.load(open(load_profile("grblhal_tangential").source))
    with pytest.raises(InputError, match="blade_offset"):
        profile_from_dict(dict(base, blade_offset=0.3), source="x.json")
    torch = json.load(open(load_profile("flame_plasma").source))
    with pytest.raises(InputError, match="blade_offset.*torch"):
        profile_from_dict(dict(torch, blade_offset=0.3), source="t.json")
    with pytest.raises(InputError, match="swivel_angle"):
        profile_from_dict(dict(base, swivel_angle=200), source="x.json")
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(dict(base, name="bad", blade_offset=0.3)))
    import ezdxf
    doc = ezdxf.new("R2010", units=4)
    doc.modelspace().add_lwpolyline([(10, 10), (60, 10), (60, 40)], close=True)
    dxf = tmp_path / "t.dxf"
    doc.saveas(str(dxf))
    monkeypatch.setattr(cli, "VERB_MODULES", ["post"])
    out = tmp_path / "job.nc"
    assert cli.main(["post", str(dxf), "--machine", str(bad), "-o", str(out),
                     "--plan-method", "nn"]) == 2
    err = capsys.readouterr().err
    assert "blade_offset" in err and "tangential_knife" in err and "Traceback" not in err
    assert not out.exists()


def test_no_offset_keeps_output_unchanged(deepnest_plan):
    prof = load_profile("hpgl_plotter")
    assert prof.blade_offset == 0.0
    assert hpgl.export(deepnest_plan, prof) == hpgl.export(deepnest_plan, replace(prof, swivel_angle=30))


def test_cli_drag_knife_hpgl_job(tmp_path, monkeypatch, capsys, deepnest_plan):
    """End to end from the command line: a real drawing to a compensated .plt
    (the CLI plans the same way as the fixture: nearest neighbour, moved 10 mm)."""
    monkeypatch.setattr(cli, "VERB_MODULES", ["post"])
    out = tmp_path / "job.plt"
    assert cli.main(["post", os.path.join(SAMPLES_DIR, "deepnest_ReadMeExampleSmall.dxf"),
                     "--machine", "hpgl_drag_knife", "--format", "hpgl", "-o", str(out),
                     "--plan-method", "nn", "--move-to-origin", "10", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["machine"] == "hpgl_drag_knife" and out.exists()
    assert data["items"] == len(deepnest_plan.items)
    away, at_swivel = tip_deviation(deepnest_plan, hpgl.read_hpgl(out.read_text(), 40), 0.25, 10.0)
    assert away <= TOL and at_swivel <= TOL
