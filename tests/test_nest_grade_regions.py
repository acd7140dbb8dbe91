"""Part regions with their own grade: from a DXF (an inner contour on a
GRADE_<g> layer) and from the Baldacci item zones (Test8 item i_3: a frame
whose window, quality 0, may lie anywhere); the engine places them only
where every region lies on good enough material, the independent checker
rejects layouts where a region or the rest of the part does not, and the
report says on which grade each region lies."""

import os

import ezdxf
import pytest

from LeatherCutWorkbench.core.model import Container, Layout, Placement
from LeatherCutWorkbench.core.nesting import check_layout
from LeatherCutWorkbench.core.nesting.esicup import read_esicup

from nest_shapes import write_hide_dxf
from test_nest_cli import run_json

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def _shoe_dxf(path):
    """A 200 x 120 part of grade B (its outer contour's layer) with a real hole
    and an 80 x 60 visible zone of grade A drawn on layer GRADE_A."""
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    for name in ("GRADE_B", "GRADE_A"):
        doc.layers.add(name)
    msp.add_lwpolyline([(0, 0), (200, 0), (200, 120), (0, 120)], close=True,
                       dxfattribs={"layer": "GRADE_B"})
    msp.add_lwpolyline([(20, 50), (40, 50), (40, 70), (20, 70)], close=True)       # a hole
    msp.add_lwpolyline([(100, 30), (180, 30), (180, 90), (100, 90)], close=True,
                       dxfattribs={"layer": "GRADE_A"})                              # the region
    doc.saveas(path)


def _hide_dxf(path):
    """A 600 x 300 hide of base grade B with one 120 x 100 grade-A zone."""
    write_hide_dxf(path, (600, 300), "HIDE_B", "ZONE_A", (420, 150, 540, 250))


def test_dxf_region_lies_on_grade_a_and_is_not_cut(capsys, tmp_path):
    src, hide = str(tmp_path / "shoe.dxf"), str(tmp_path / "hide.dxf")
    _shoe_dxf(src)
    _hide_dxf(hide)
    d = run_json(capsys, src, "--hide", hide, "--time", "3", "--workers", "1")
    msgs = [f["message"] for f in d["findings"] if f["code"] == "part-region"]
    assert len(msgs) == 1 and "region of grade 4" in msgs[0]
    m = d["metrics"]
    assert m["checked"] and m["placed_count"] == 1
    row = m["grades"][0]
    assert row["part_grade"] == 3
    regions = {r["piece"]: r for r in row["regions"]}
    # the visible zone needs A and lies on the only A zone; the rest lies on B or better
    assert regions["region 0"]["grade"] == 4 and regions["region 0"]["material_grade"] == 4
    assert regions["rest"]["grade"] == 3 and regions["rest"]["material_grade"] >= 3
    # the part keeps its real hole only: the region is a marking, not a cut
    assert d["containers"][0]["part_area_mm2"] == pytest.approx(200 * 120 - 20 * 20)


def test_checker_rejects_a_region_on_too_low_a_grade(tmp_path):
    from LeatherCutWorkbench.core.nesting import read_hide_dxf
    from LeatherCutWorkbench.core.dxfimport.grades import assign_grades
    from LeatherCutWorkbench.core.model import Contour
    from LeatherCutWorkbench.core.geometry import LineSeg

    def contour(cid, pts, layer=""):
        return Contour(id=cid, segments=[LineSeg(pts[i], pts[(i + 1) % len(pts)])
                                         for i in range(len(pts))], layer=layer)

    from LeatherCutWorkbench.core.model import Part
    part = Part(id="P1", outer=contour("o", [(0, 0), (200, 0), (200, 120), (0, 120)]),
                holes=[contour("r", [(100, 30), (100, 90), (180, 90), (180, 30)], "GRADE_A")],
                grade=3)
    assign_grades([part], [])
    assert part.holes == [] and [g for g, _ in part.grade_regions] == [4]
    hide = str(tmp_path / "hide.dxf")
    _hide_dxf(hide)
    h = read_hide_dxf(hide)[0]

    def layout(x, y):
        return Layout(containers=[h], placements=[Placement("P1", 0, h.id, x, y, 0.0, False)],
                      unplaced=[], metrics={}, findings=[])

    # region (100..180, 30..90) moved into the A zone (420..540, 150..250)
    assert check_layout([part], layout(330, 150)) == []
    bad = check_layout([part], layout(10, 10))                     # region on B material
    assert len(bad) == 1 and "region 0" in bad[0] and "below grade 4" in bad[0]
    # the whole part on A material would do for the region but not fit: the rest on B is fine
    part.grade = 4                                                    # now the rest needs A too
    assert any("rest" in p for p in check_layout([part], layout(330, 150)))


def test_baldacci_item_zone_quality_0_may_cover_a_hole():
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    frame = next(p for p in inst.parts if p.grade_regions)
    assert frame.id == "3" and frame.grade == 3 and [g for g, _ in frame.grade_regions] == [0]
    # a clean 1000 x 1000 hide with a 100 x 100 hole
    hole = [(500, 500), (600, 500), (600, 600), (500, 600)]
    h = Container(id="h", kind="hide", outline=[(0, 0), (1000, 0), (1000, 1000), (0, 1000)],
                  defects=[hole], base_grade=3)

    def at(x, y):
        return Layout(containers=[h], placements=[Placement("3", 0, "h", x, y, 0.0, False)],
                      unplaced=[], metrics={}, findings=[])

    # window (40..220, 30..240) over the hole: allowed; the frame over it: not
    assert check_layout([frame], at(420, 400)) == []
    bad = check_layout([frame], at(300, 400))
    assert bad and "covers defect" in bad[0]


def test_baldacci_test8_graded_nest_keeps_every_region_on_its_grade():
    from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, nest
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    angles = [0.0, 90.0, 180.0, 270.0]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=0, workers=1,
                       rotations_override=angles)
    lay = nest(inst.parts, opts)
    assert check_layout(inst.parts, lay, rotations_override=angles) == []
    rows = [r for r in lay.metrics["grades"] if r["part"] == "3"]
    assert rows and all("regions" in r for r in rows)
    for r in lay.metrics["grades"]:
        for piece in r.get("regions", []):
            assert piece["material_grade"] >= piece["grade"]
