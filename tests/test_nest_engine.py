"""The own nesting engine on real geometry: sheets, strips, hides, holes,
rotations, mirroring, spacing, determinism, progress and cancel.  Every
layout is also re-checked here with the independent checker."""

import math
import os

import ezdxf
import pytest
from shapely.geometry import Polygon

from LeatherCutWorkbench.core.errors import CancelledError, InputError
from LeatherCutWorkbench.core.nesting import (ContainerSpec, NestOptions, check_layout, nest,
                                              placed_parts, read_hide_dxf)
from LeatherCutWorkbench.core.nesting.esicup import read_esicup

from nest_shapes import disc, frame, l_shape, rect, ring

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def valid(parts, layout, opts):
    return check_layout(parts, layout, spacing=opts.spacing, margin=opts.margin,
                        rotations_override=opts.rotations_override,
                        mirror_override=opts.mirror_override, free_rotation=opts.free_rotation)


def test_sheets_open_as_needed_and_fixed_count_reports_unplaced():
    parts = [rect("a", 60, 40, q=7)]          # 4 fit one 130 x 90 sheet
    # the budget covers preparing the shapes too: evaluations, not a short time,
    # bound this search so a loaded machine gives the same result
    opts = NestOptions(container=ContainerSpec.sheet(130, 90), time_budget=5, max_evaluations=300,
                       workers=1)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    assert lay.unplaced == []
    assert [c.id for c in lay.containers] == ["sheet1", "sheet2"]
    assert lay.metrics["sheets"] == 2
    per = {c["id"]: c for c in lay.metrics["per_container"]}
    assert per["sheet1"]["parts"] + per["sheet2"]["parts"] == 7
    assert max(per["sheet1"]["parts"], per["sheet2"]["parts"]) == 4     # 4 is all a sheet holds
    assert lay.metrics["utilisation"] == pytest.approx(7 * 2400 / (2 * 130 * 90), abs=1e-6)

    opts1 = NestOptions(container=ContainerSpec.sheet(130, 90, count=1), time_budget=5,
                        max_evaluations=300, workers=1)
    lay1 = nest(parts, opts1)
    assert len(lay1.placements) == 4 and len(lay1.unplaced) == 3
    assert any(f.code == "unplaced-parts" for f in lay1.findings)


def test_part_too_big_for_every_sheet_is_unplaced_not_an_error():
    parts = [rect("big", 300, 10), rect("ok", 10, 10)]
    opts = NestOptions(container=ContainerSpec.sheet(100, 100), time_budget=0, workers=1)
    lay = nest(parts, opts)
    assert lay.unplaced == [("big", 0)]
    assert [p.part_id for p in lay.placements] == ["ok"]


def test_small_parts_go_into_holes_of_big_ones():
    # a 100 x 100 sheet holds the frame only; 8 squares must go into its hole
    parts = [frame("F", 100, 100, 10), rect("s", 19, 19, q=16)]
    opts = NestOptions(container=ContainerSpec.sheet(100, 100, count=1), time_budget=1, workers=1)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    assert lay.unplaced == []
    hole = Polygon([(10, 10), (90, 10), (90, 90), (10, 90)])
    f = [p for p in lay.placements if p.part_id == "F"][0]
    assert (f.x, f.y) == pytest.approx((0, 0), abs=1e-3)
    for pp in placed_parts(parts, lay):
        if pp.id.startswith("s#"):
            assert hole.buffer(1e-6).contains(Polygon(pp.outer.points()))


def test_rings_take_discs_with_spacing_and_margin():
    parts = [ring("R", 50, 35, q=2), disc("d", 15, q=6)]
    opts = NestOptions(container=ContainerSpec.sheet(215, 110), spacing=2, margin=3,
                       time_budget=1, workers=1)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    assert lay.unplaced == []
    placed = placed_parts(parts, lay)
    # spacing and margin measured on the placed true shapes
    polys = [Polygon(p.outer.points(0.01), [h.points(0.01) for h in p.holes]) for p in placed]
    for i in range(len(polys)):
        b = polys[i].bounds
        assert b[0] >= 3 - 1e-3 and b[1] >= 3 - 1e-3 and b[2] <= 212 + 1e-3 and b[3] <= 107 + 1e-3
        for j in range(i):
            if lay.placements[i].container == lay.placements[j].container:
                assert polys[i].distance(polys[j]) >= 2 - 1e-2
    # at least some discs sit in ring holes (the sheet is too small otherwise)
    holes = [Polygon(h.points(0.01)) for p in placed if p.id.startswith("R#") for h in p.holes]
    assert sum(any(hh.contains(pg) for hh in holes) for pg in polys) >= 1


def test_strip_esicup_fu_is_dense_and_valid():
    inst = read_esicup(os.path.join(DATA, "fu.json"))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=60,
                       max_evaluations=600, workers=1, seed=5)
    lay = nest(inst.parts, opts)
    assert valid(inst.parts, lay, opts) == []
    m = lay.metrics
    assert m["placed_count"] == 12 and lay.unplaced == []
    assert m["strip_length_mm"] >= inst.item_area / inst.strip_height
    assert m["density"] == pytest.approx(inst.item_area / (m["strip_length_mm"] * inst.strip_height))
    assert m["density"] > 0.80          # bottom-left fill alone reaches ~0.76
    for p in lay.placements:
        assert p.angle in (0.0, 90.0, 180.0, 270.0) and not p.mirrored


def test_rotation_rules_are_kept():
    parts = [l_shape("grain", 60, 30, 8, q=4, rotations=[0, 180]),
             l_shape("free", 50, 25, 8, q=3, rotations=None)]
    opts = NestOptions(container=ContainerSpec.strip(70), time_budget=1, workers=1,
                       rotation_step=45)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    for p in lay.placements:
        if p.part_id == "grain":
            assert p.angle in (0.0, 180.0)
        else:
            assert p.angle % 45 == pytest.approx(0, abs=1e-9)
    # a global override replaces the parts' own rules
    opts2 = NestOptions(container=ContainerSpec.strip(70), time_budget=0.5, workers=1,
                        rotations_override=[90.0])
    lay2 = nest(parts, opts2)
    assert {p.angle for p in lay2.placements} == {90.0}
    assert valid(parts, lay2, opts2) == []


def test_mirroring_only_when_allowed():
    # L-shapes pair up best when one is mirrored; without permission none is
    parts = [l_shape("L", 60, 60, 10, q=6, rotations=[0], mirror=False)]
    opts = NestOptions(container=ContainerSpec.strip(80), time_budget=0.5, workers=1)
    lay = nest(parts, opts)
    assert not any(p.mirrored for p in lay.placements)
    parts_m = [l_shape("L", 60, 60, 10, q=6, rotations=[0], mirror=True)]
    lay_m = nest(parts_m, opts)
    assert valid(parts_m, lay_m, opts) == []
    assert lay_m.unplaced == []


def _hide_dxf(path):
    doc = ezdxf.new(units=4)          # mm
    msp = doc.modelspace()
    pts = []
    for i in range(36):
        a = 2 * math.pi * i / 36
        r = 300 + 40 * math.sin(3 * a)
        pts.append((400 + 1.3 * r * math.cos(a), 300 + r * math.sin(a)))
    msp.add_lwpolyline(pts, close=True, dxfattribs={"layer": "HIDE"})
    msp.add_circle((400, 300), 30, dxfattribs={"layer": "DEFECT"})
    msp.add_lwpolyline([(250, 150), (300, 160), (280, 200)], close=True, dxfattribs={"layer": "DEFECT"})
    msp.add_lwpolyline([(300, 200), (600, 200), (600, 450), (300, 450)], close=True,
                       dxfattribs={"layer": "ZONE_3"})
    msp.add_line((0, 0), (10, 10), dxfattribs={"layer": "NOTES"})     # ignored layer
    doc.saveas(path)


def test_hide_with_defects_and_quality_zone(tmp_path):
    path = str(tmp_path / "hide.dxf")
    _hide_dxf(path)
    hides = read_hide_dxf(path)
    assert len(hides) == 1
    h = hides[0]
    assert len(h.defects) == 2 and h.zones[0][0] == 3 and h.base_grade == 1
    parts = [rect("top", 60, 40, q=10, grade=3, rotations=[0, 90]), rect("any", 80, 50, q=12),
             disc("d", 20, q=10)]
    opts = NestOptions(container=ContainerSpec.hide(*hides), spacing=2, margin=4, time_budget=2,
                       workers=1)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    assert lay.unplaced == []
    zone = Polygon([(300, 200), (600, 200), (600, 450), (300, 450)])
    defect = Polygon(h.defects[0])
    for pp in placed_parts(parts, lay):
        pg = Polygon(pp.outer.points(0.01))
        if pp.id.startswith("top#"):
            assert zone.buffer(1e-3).contains(pg)
        assert pg.distance(defect) >= 4 - 1e-3
    m = lay.metrics
    assert 0 < m["utilisation"] <= 1 and m["utilisation_gross"] < m["utilisation"]


def test_hide_dxf_errors_name_the_problem(tmp_path):
    path = str(tmp_path / "nohide.dxf")
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (10, 0), (10, 10)], close=True,
                                    dxfattribs={"layer": "DEFECT"})
    doc.saveas(path)
    with pytest.raises(InputError, match="no hide outline"):
        read_hide_dxf(path)
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (10, 0), (10, 10)], close=False,
                                    dxfattribs={"layer": "HIDE"})
    doc.saveas(path)
    with pytest.raises(InputError, match="not closed"):
        read_hide_dxf(path)


def test_same_seed_same_result_with_two_workers():
    inst = read_esicup(os.path.join(DATA, "shapes0.json"))
    runs = []
    for _ in range(2):
        opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=60,
                           max_evaluations=25, workers=2, seed=11)
        lay = nest(inst.parts, opts)
        runs.append([(p.part_id, p.copy, p.x, p.y, p.angle) for p in lay.placements])
        assert lay.metrics["workers"] == 2
    assert runs[0] == runs[1]


def test_progress_reported_and_cancel_raises():
    parts = [rect("a", 30, 20, q=10), l_shape("L", 40, 30, 8, q=5)]
    calls = []

    def progress(f, msg):
        calls.append(f)
        return True

    nest(parts, NestOptions(container=ContainerSpec.strip(60), time_budget=0.5, workers=1), progress)
    assert calls[-1] == 1.0 and len(calls) > 3
    assert all(0 <= f <= 1 for f in calls)
    for workers in (1, 2):
        with pytest.raises(CancelledError):
            nest(parts, NestOptions(container=ContainerSpec.strip(60), time_budget=5, workers=workers),
                 lambda f, m: f < 0.1)


def test_placed_parts_are_transformed_copies():
    parts = [l_shape("L", 40, 30, 8, q=2, rotations=[90], mirror=True), ring("R", 20, 10)]
    opts = NestOptions(container=ContainerSpec.sheet(200, 200), time_budget=0.3, workers=1)
    lay = nest(parts, opts)
    out = placed_parts(parts, lay)
    assert sorted(p.id for p in out) == ["L#0", "L#1", "R#0"]
    for pl, pp in zip(lay.placements, out):
        assert pp.quantity == 1
        assert pp.outer.area > 0                      # still counter-clockwise
        assert all(h.area < 0 for h in pp.holes)      # holes clockwise
        src = [p for p in parts if p.id == pl.part_id][0]
        assert abs(pp.outer.area) == pytest.approx(abs(src.outer.area), rel=1e-6)
    r = [p for p in out if p.id == "R#0"][0]
    assert type(r.outer.segments[0]).__name__ == "ArcSeg"   # arcs stay arcs
    assert parts[0].id == "L" and parts[0].quantity == 2     # sources untouched


def test_bad_options_are_input_errors():
    parts = [rect("a", 10, 10)]
    with pytest.raises(InputError):
        nest(parts, NestOptions(container=ContainerSpec.sheet(0, 10)))
    with pytest.raises(InputError):
        nest(parts, NestOptions(container=ContainerSpec.strip(10), spacing=-1))
    with pytest.raises(InputError, match="unique"):
        nest([rect("a", 1, 1), rect("a", 2, 2)], NestOptions(container=ContainerSpec.strip(10)))
    with pytest.raises(InputError, match="sparrow engine only nests on a strip"):
        nest(parts, NestOptions(container=ContainerSpec.sheet(10, 10), engine="sparrow"))


def test_two_hides_in_one_dxf_fill_in_order(tmp_path):
    path = str(tmp_path / "hides.dxf")
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    msp.add_lwpolyline([(500, 0), (700, 0), (700, 150), (500, 150)], close=True,
                       dxfattribs={"layer": "HIDE"})
    msp.add_lwpolyline([(0, 0), (200, 0), (220, 80), (200, 150), (0, 150)], close=True,
                       dxfattribs={"layer": "HIDE_2"})
    msp.add_circle((600, 75), 10, dxfattribs={"layer": "DEFECT"})
    doc.saveas(path)
    hides = read_hide_dxf(path)
    assert [h.id for h in hides] == ["hide1", "hide2"]
    assert hides[0].base_grade == 2 and hides[1].base_grade == 1      # leftmost first
    assert hides[0].defects == [] and len(hides[1].defects) == 1
    parts = [rect("p", 90, 70, q=6, rotations=[0])]   # 4 fit the left hide, 2 go right
    opts = NestOptions(container=ContainerSpec.hide(*hides), time_budget=0, workers=1)
    lay = nest(parts, opts)
    assert valid(parts, lay, opts) == []
    by = {}
    for p in lay.placements:
        by[p.container] = by.get(p.container, 0) + 1
    assert by["hide1"] == 4 and by["hide2"] == 2 and lay.unplaced == []


def test_nfp_of_discs_covers_every_overlapping_position():
    # regression: rounding left a degenerate island inside the NFP of two discs, and a
    # small disc was placed inside a big one (the checker caught it)
    from LeatherCutWorkbench.core.nesting.nfp import solid_nfp
    from LeatherCutWorkbench.core.nesting.shapes import make_variants, piece_from_part
    import pyclipper
    scale = 1e4
    big, small = (piece_from_part(disc(n, r), 0.05, 30, [0]) for n, r in (("D", 18), ("d", 12)))
    vb, vs = make_variants([big, small], scale, 1.0, 0.05)[:2]
    for a, b, ra, rb in ((vb, vs, 18, 12), (vs, vb, 12, 18)):
        nfp = solid_nfp(a.outer, b.outer)
        assert len(nfp) == 1 and pyclipper.Orientation(nfp[0])
        # centre of a at (ra, ra), of b at (rb, rb) relative to their origins
        for k in range(200):
            ang = 2 * math.pi * k / 200
            for frac in (0.0, 0.2, 0.5, 0.9, 0.99):
                d = frac * (ra + rb) * scale
                t = (int(ra * scale + d * math.cos(ang) - rb * scale),
                     int(ra * scale + d * math.sin(ang) - rb * scale))
                assert pyclipper.PointInPolygon(t, nfp[0]) == 1


def test_convex_fast_path_matches_general_minkowski_sum():
    from LeatherCutWorkbench.core.nesting import nfp
    import pyclipper
    a = [[0, 0], [100, 0], [130, 60], [20, 90]]
    b = [[0, 0], [40, 10], [10, 50]]
    assert nfp.is_convex(a) and nfp.is_convex(b)
    assert not nfp.is_convex([[0, 0], [10, 0], [10, 10], [5, 3], [0, 10]])
    fast = nfp.solid_nfp(a, b)
    nb = [[-x, -y] for x, y in b]
    general = nfp.union(list(pyclipper.MinkowskiSum(nb, a, True)) +
                        [[[x + nb[0][0], y + nb[0][1]] for x, y in a]])
    assert len(fast) == 1
    assert pyclipper.Area(fast[0]) == pytest.approx(sum(pyclipper.Area(p) for p in general))
    diff = nfp.difference(general, fast) + nfp.difference(fast, general)
    assert sum(abs(pyclipper.Area(p)) for p in diff) < 1.0
