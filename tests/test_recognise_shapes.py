"""Recognition on generated drawings with known answers (no DXF import involved)."""

import math

import FreeCAD
import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.geometry import ArcSeg, CurveSeg, LineSeg, dist
from LeatherCutWorkbench.core.model import (ArcEdge, EdgeSource, LineEdge, Mark, PieceInfo,
                                            SplineEdge)
from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise
from LeatherCutWorkbench.core.recognition.from_part import signed_path_area
from LeatherCutWorkbench.core.recognition.to_part import to_segment

import recognise_shapes as S


def run(edges, **kw):
    return recognise(S.drawing(edges), RecogniseOptions(**kw))


def closed(contour, tol=1e-6):
    segs = contour.segments
    joints = all(dist(a.end, b.start) <= tol for a, b in zip(segs, segs[1:]))
    return joints and dist(segs[-1].end, segs[0].start) <= tol


def areas(rec):
    return sorted(round(p.net_area, 3) for p in rec.active_parts())


# ---------------------------------------------------------------- basics
def test_part_with_hole_and_line_lead_in():
    rec = run(S.part_with_hole(0, 0, lead_in="line"))
    assert len(rec.parts) == 1 and not rec.open_chains and not rec.flags
    p = rec.parts[0]
    assert p.id == "P1" and p.outer.id == "C1"
    assert p.outer.area == pytest.approx(1200.0)            # outer CCW
    assert len(p.holes) == 1 and p.holes[0].area == pytest.approx(-math.pi * 25, rel=5e-3)
    assert isinstance(p.holes[0].segments[0], ArcSeg)       # circle kept exact
    assert p.net_area == pytest.approx(1200 - math.pi * 25, rel=1e-3)
    assert closed(p.outer, 1e-9) and closed(p.holes[0], 1e-9)
    (li,) = p.lead_ins
    assert li.id == "L1" and li.contour_id == "C1" and li.role == "lead_in"
    assert li.start == pytest.approx((5.0, -3.0)) and li.end == pytest.approx((5.0, 0.0))
    assert li.length == pytest.approx(3.0)
    # the contour got a vertex where the lead-in enters (T-junction split)
    assert any(dist(s.start, (5.0, 0.0)) < 1e-9 for s in p.outer.segments)


def test_arc_lead_in_runs_from_free_end_to_contour():
    rec = run(S.part_with_hole(10, 20, lead_in="arc"))
    (li,) = rec.parts[0].lead_ins
    assert li.start == pytest.approx((12.0, 17.0)) and li.end == pytest.approx((15.0, 20.0))
    assert isinstance(li.segments[0], ArcSeg)
    assert li.length == pytest.approx(math.pi * 3 / 2)


def test_lead_in_touching_a_corner_is_not_swallowed():
    edges = S.rect(0, 0, 20, 10) + [S.line_lead_in(0, 0, 4.0, 225.0)]
    rec = run(edges)
    (p,) = rec.parts
    assert p.outer.area == pytest.approx(200.0) and len(p.outer.segments) == 4
    assert len(p.lead_ins) == 1 and p.lead_ins[0].end == pytest.approx((0.0, 0.0))


def test_lead_in_and_lead_out_pair():
    # lead-in arrives along +X into the bottom edge's direction (CCW outer),
    # lead-out leaves along +X too: from the same contact point
    edges = S.rect(0, 0, 20, 10) + [LineEdge((2.0, -3.0), (5.0, 0.0), S.src()),
                                    LineEdge((5.0, 0.0), (8.0, -3.0), S.src())]
    rec = run(edges)
    (p,) = rec.parts
    roles = sorted((li.role, li.start, li.end) for li in p.lead_ins)
    assert [r[0] for r in roles] == ["lead_in", "lead_out"]
    assert roles[0][1] == pytest.approx((2.0, -3.0)) and roles[0][2] == pytest.approx((5.0, 0.0))
    assert roles[1][1] == pytest.approx((5.0, 0.0)) and roles[1][2] == pytest.approx((8.0, -3.0))


def test_hole_lead_in_and_orientation_of_holes():
    edges = S.rect(0, 0, 50, 50) + S.rect(20, 20, 10, 10) + [S.line_lead_in(25, 20, 4, 90)]
    rec = run(edges)
    (p,) = rec.parts
    (h,) = p.holes
    assert h.area == pytest.approx(-100.0)                  # hole CW
    (li,) = p.lead_ins
    assert li.contour_id == h.id and li.start == pytest.approx((25.0, 24.0))


def test_stray_open_chain_and_edges_of_other_roles():
    stray = S.polyline([(100, 0), (110, 5), (120, 0)], closed=False)
    engraved = S.rect(0, 0, 5, 5, role="mark")
    rec = run(S.rect(0, 0, 30, 30) + stray + engraved)
    assert len(rec.parts) == 1 and rec.parts[0].outer.area == pytest.approx(900.0)
    (oc,) = rec.open_chains
    assert oc.id == "O1" and oc.length == pytest.approx(2 * math.hypot(10, 5))
    assert {oc.start, oc.end} == {(100, 0), (120, 0)}


# ---------------------------------------------------------------- join tolerance
@pytest.mark.parametrize("gap, joined", [(0.009, True), (0.011, False)])
def test_join_tolerance_boundary(gap, joined):
    rec = run(S.square_with_gap(gap), join_tol=0.01)
    if joined:
        assert len(rec.parts) == 1 and not rec.flags and not rec.open_chains
        assert rec.parts[0].outer.area == pytest.approx(400.0, abs=0.01)
        assert closed(rec.parts[0].outer, 0.01)
    else:
        assert not rec.parts and len(rec.open_chains) == 1
        (f,) = rec.flags
        assert f.kind == "under" and f.gap == pytest.approx(gap) and f.ids == ["O1"]


# ---------------------------------------------------------------- gaps (under)
@pytest.mark.parametrize("gap, flagged", [(0.49, True), (0.51, False)])
def test_gap_tolerance_boundary(gap, flagged):
    rec = run(S.square_with_gap(gap), gap_tol=0.5)
    assert not rec.parts and len(rec.open_chains) == 1
    if flagged:
        (f,) = rec.flags
        assert f.kind == "under" and f.gap == pytest.approx(gap) and f.accepted is None
        (bridge,) = f.fix
        assert isinstance(bridge, LineSeg) and bridge.length == pytest.approx(gap)
        assert {bridge.start, bridge.end} == {(0.0, 0.0), (0.0, gap)}
    else:
        assert rec.flags == []


def test_close_gaps_applies_the_bridge():
    rec = run(S.square_with_gap(0.3), close_gaps=True)
    assert not rec.open_chains
    (p,) = rec.parts
    assert p.outer.area == pytest.approx(400.0) and closed(p.outer, 1e-9)
    assert any(isinstance(s, LineSeg) and s.length == pytest.approx(0.3) for s in p.outer.segments)
    (f,) = rec.flags
    assert f.kind == "under" and f.accepted is True and f.ids == [p.outer.id]


def test_two_chains_with_two_gaps_close_together():
    rec = run(S.square_two_gaps(0.2))
    (f,) = rec.flags
    assert f.ids == ["O1", "O2"] and len(f.fix) == 2 and f.gap == pytest.approx(0.2)
    rec2 = run(S.square_two_gaps(0.2), close_gaps=True)
    assert [round(a) for a in areas(rec2)] == [400]


def test_missing_short_segment_between_chains_is_bridged():
    # square with its right side missing 0.4 mm in the middle
    edges = S.polyline([(0, 10), (0, 0), (20, 0), (20, 4.8)], closed=False) + \
        S.polyline([(20, 5.2), (20, 10), (0, 10)], closed=False)
    rec = run(edges, close_gaps=True)
    assert areas(rec) == [pytest.approx(200.0)]


def test_overshoot_stub_is_flagged_not_a_lead_in():
    rec = run(S.square_overshoot(0.3))
    (p,) = rec.parts
    assert p.outer.area == pytest.approx(400.0) and not p.lead_ins
    (f,) = rec.flags
    assert f.kind == "under" and f.gap == pytest.approx(0.3) and "stub" in f.reason
    rec2 = run(S.square_overshoot(0.3), close_gaps=True)
    assert not rec2.open_chains and rec2.flags[0].accepted is True


def test_crossing_overshoots_at_every_corner():
    rec = run(S.square_cross_overshoot(0.25))
    (p,) = rec.parts
    assert p.outer.area == pytest.approx(400.0) and len(p.outer.segments) == 4
    assert not p.lead_ins and len(rec.open_chains) == 8
    assert all(f.kind == "under" and f.gap == pytest.approx(0.25) for f in rec.flags)


# ---------------------------------------------------------------- common edges
def _cells_ok(rec, n, size=10.0):
    act = rec.active_parts()
    assert len(act) == n
    for p in act:
        assert p.outer.area == pytest.approx(size * size)
        assert closed(p.outer, 1e-6)


@pytest.mark.parametrize("maker", [S.grid_separate, S.grid_lines, S.grid_segments])
def test_common_edge_grid_each_cell_once(maker):
    rec = run(maker(4, 3))
    _cells_ok(rec, 12)
    assert not rec.flags and not rec.open_chains
    # shared edges are known: interior cell (1,1) shares all four sides
    shared = sorted(len(p.outer.shared) for p in rec.parts)
    assert shared.count(4) == 2 and shared.count(2) == 4 and shared.count(3) == 6
    # every shared segment has a geometric twin in another contour
    keys = {}
    for p in rec.parts:
        for i in p.outer.shared:
            s = p.outer.segments[i]
            k = tuple(sorted([tuple(round(v, 6) for v in s.start), tuple(round(v, 6) for v in s.end)]))
            keys.setdefault(k, []).append(p.id)
    assert all(len(v) == 2 for v in keys.values()) and len(keys) == 17


def test_two_squares_shared_edge_drawn_once_is_not_one_big_contour():
    rec = run(S.grid_segments(2, 1))
    assert areas(rec) == [100.0, 100.0]
    assert [p.outer.shared for p in rec.parts] != [[], []]


@pytest.mark.parametrize("maker", [S.pinwheel_separate, S.pinwheel_lines])
def test_pinwheel_scrap_square_is_flagged_and_excluded(maker):
    rec = run(maker())
    assert areas(rec) == [200.0] * 4
    (f,) = rec.flags
    assert f.kind == "over" and f.accepted is None
    scrap = next(p for p in rec.parts if p.excluded)
    assert f.ids == [scrap.outer.id] and scrap.outer.area == pytest.approx(100.0)
    assert scrap.outer.bbox == pytest.approx((10, 10, 20, 20))
    # a person includes it: it becomes a part to cut, the flag records the decision
    rec2 = recognise(S.drawing(maker()), RecogniseOptions(include=frozenset({scrap.outer.id})))
    assert len(rec2.active_parts()) == 5 and rec2.flags[0].accepted is False


def test_pinwheel_flag_comes_with_evidence():
    f_sep = run(S.pinwheel_separate()).flags[0]
    f_lin = run(S.pinwheel_lines()).flags[0]
    assert "drawn" in f_sep.reason and "shared" in f_sep.reason
    assert "T-junction" in f_lin.reason


def test_exclude_by_contour_and_part_id():
    rec = recognise(S.drawing(S.grid_separate(2, 1)), RecogniseOptions(exclude=frozenset({"C1"})))
    assert [p.excluded for p in rec.parts] == [True, False]
    rec = recognise(S.drawing(S.grid_separate(2, 1)), RecogniseOptions(exclude=frozenset({"P2"})))
    assert [p.excluded for p in rec.parts] == [False, True]
    rec = recognise(S.drawing(S.grid_separate(2, 1)), RecogniseOptions(exclude=frozenset({"C9"})))
    assert any(f.code == "unknown-id" for f in rec.findings)
    with pytest.raises(InputError):
        recognise(S.drawing(S.rect(0, 0, 1, 1)),
                  RecogniseOptions(include=frozenset({"C1"}), exclude=frozenset({"C1"})))


def test_grid_of_cells_inside_a_part_are_its_holes():
    edges = S.rect(-10, -10, 60, 50) + S.grid_lines(3, 2)
    rec = run(edges)
    (big,) = rec.parts
    assert len(big.holes) == 6 and all(h.area == pytest.approx(-100.0) for h in big.holes)
    assert big.net_area == pytest.approx(3000 - 600)


# ---------------------------------------------------------------- nesting depth
def test_islands_in_holes_become_parts():
    edges = (S.rect(0, 0, 100, 100) + S.rect(10, 10, 80, 80)       # part with a big hole
             + S.rect(20, 20, 60, 60) + [S.circle(50, 50, 5)]      # island with a hole
             + S.rect(49, 49, 2, 2))                               # island in the island's hole
    rec = run(edges)
    assert len(rec.parts) == 3
    outer, island, inner = sorted(rec.parts, key=lambda p: -abs(p.outer.area))
    assert outer.net_area == pytest.approx(10000 - 6400)
    assert island.parent_id == outer.id and island.outer.area > 0
    assert island.holes[0].area < 0 and inner.parent_id == island.id
    assert inner.outer.area == pytest.approx(4.0)


def test_group_outline_around_parts_is_flagged():
    parts = S.part_with_hole(10, 10, lead_in=None) + S.part_with_hole(60, 10, lead_in=None)
    rec = run(S.rect(0, 0, 120, 60) + parts)
    (f,) = rec.flags
    frame = next(p for p in rec.parts if p.excluded)
    assert f.kind == "over" and f.ids == [frame.outer.id] and "sheet border" in f.reason
    act = rec.active_parts()
    assert len(act) == 2 and all(len(p.holes) == 1 and p.parent_id is None for p in act)


# ---------------------------------------------------------------- curves, mirroring
def test_mirrored_geometry_keeps_orientation_and_area():
    a = run(S.rounded_rect(0, 0, 30, 20, 4)).parts[0]
    b = run(S.mirrored(S.rounded_rect(0, 0, 30, 20, 4))).parts[0]
    expect = 30 * 20 - (4 - math.pi) * 16
    assert signed_path_area(a.outer.segments) == pytest.approx(expect)
    assert signed_path_area(b.outer.segments) == pytest.approx(expect)
    assert b.outer.bbox == pytest.approx((-30, 0, 0, 20))
    assert sum(isinstance(s, ArcSeg) for s in b.outer.segments) == 4


def test_ellipse_and_spline_contours():
    rec = run([S.ellipse(100, 0, 20, 10, 30)] + S.open_spline_with_line())
    e = next(p for p in rec.parts if p.outer.bbox[0] > 50)
    assert e.outer.area == pytest.approx(math.pi * 200, rel=1e-3)
    assert all(isinstance(s, CurveSeg) for s in e.outer.segments)
    s = next(p for p in rec.parts if p.outer.bbox[0] < 50)
    kinds = {type(x) for x in s.outer.segments}
    assert kinds == {CurveSeg, LineSeg} and s.outer.area > 0 and closed(s.outer, 1e-6)


def test_rational_and_bad_splines():
    # a quarter circle as a rational quadratic B-spline + two lines = quarter disc
    w = math.sqrt(0.5)
    arc = SplineEdge([(10, 0), (10, 10), (0, 10)], [0, 0, 0, 1, 1, 1], [1, w, 1], 2, src=S.src())
    rec = run([arc, LineEdge((0, 10), (0, 0), S.src()), LineEdge((0, 0), (10, 0), S.src())])
    assert signed_path_area(rec.parts[0].outer.segments) == pytest.approx(math.pi * 25, rel=2e-3)
    bad = SplineEdge([(0, 0), (1, 1)], [0, 1], [], 3, src=S.src())
    rec = run([bad] + S.rect(0, 0, 1, 1))
    assert len(rec.parts) == 1 and any(f.code == "bad-edge" for f in rec.findings)


def test_arcs_with_jittered_ends_join():
    r = 10.0
    edges = [ArcEdge((0, 0), r, 0, 90, S.src()), ArcEdge((0.00001, 0), r, 90, 90, S.src()),
             ArcEdge((0, 0.00001), r, 180, 90, S.src()), ArcEdge((0, 0), r, 270, 90, S.src())]
    rec = run(edges)
    assert signed_path_area(rec.parts[0].outer.segments) == pytest.approx(math.pi * 100, rel=1e-4)


def test_duplicated_edges_and_zero_length_edges_are_dropped():
    edges = S.rect(0, 0, 10, 10) * 2 + [LineEdge((5, 5), (5, 5.001), S.src())]
    rec = run(edges)
    assert areas(rec) == [100.0] and not rec.open_chains
    codes = {f.code for f in rec.findings}
    assert {"duplicate-edges-dropped", "short-edges-dropped"} <= codes


# ---------------------------------------------------------------- pieces and marks
def test_pattern_pieces_are_recognised_separately():
    a = S.rect(0, 0, 50, 40)
    b = S.rect(0, 0, 50, 40)                 # the same outline stacked (another size)
    grain = LineEdge((10, 20), (40, 20), EdgeSource(layer="7", role="grain"))
    edges = a + b + [grain]
    pieces = {"FRONT": PieceInfo(key="FRONT", name="Front", size="M", quantity=2,
                                 edges=[0, 1, 2, 3, 8], grain_angle=0.0),
              "BACK": PieceInfo(key="BACK", name="Back", edges=[4, 5, 6, 7])}
    marks = [Mark((25, 20), "drill")]
    pieces["FRONT"].marks = [0]
    rec = recognise(S.drawing(edges, marks=marks, pieces=pieces))
    assert len(rec.parts) == 2 and not rec.flags
    front, back = rec.parts
    assert front.name == "Front size M" and front.quantity == 2 and front.rotations == [0.0, 180.0]
    assert back.name == "Back" and back.quantity == 1 and back.rotations is None
    assert len(front.marks) == 1 and back.marks == []


def test_marks_go_to_the_part_containing_them():
    edges = S.rect(0, 0, 40, 40) + S.rect(10, 10, 20, 20) + S.rect(100, 0, 10, 10)
    marks = [Mark((5, 5), "drill"), Mark((20, 20), "drill"), Mark((105, 5), "notch"),
             Mark((0, 20), "notch")]
    rec = recognise(S.drawing(edges, marks=marks))
    big, small = rec.parts
    assert [m.position for m in big.marks] == [(5, 5), (0, 20)]   # notch on the outline counts
    assert [m.position for m in small.marks] == [(105, 5)]
    assert any(f.code == "mark-outside-parts" for f in rec.findings)  # (20,20) is in the hole


def test_ids_are_stable_and_progress_is_reported():
    edges = S.grid_lines(3, 3) + S.part_with_hole(100, 0)
    calls = []
    r1 = recognise(S.drawing(edges), progress=lambda f, m: calls.append(f) or True)
    r2 = recognise(S.drawing(edges))
    assert [(p.id, p.outer.id, round(p.net_area, 6)) for p in r1.parts] == \
        [(p.id, p.outer.id, round(p.net_area, 6)) for p in r2.parts]
    assert calls and calls[-1] == 1.0


def test_sliver_between_nearly_coincident_lines_is_flagged():
    s = S.src()
    edges = [LineEdge((0, 0), (20.1, 0), s), LineEdge((20.1, 0), (20.1, 10), s),
             LineEdge((20.1, 10), (0, 10), s), LineEdge((0, 10), (0, 0), s),
             LineEdge((10, 0), (10, 10), s), LineEdge((10.1, 0), (10.1, 10), s)]
    rec = run(edges)
    assert areas(rec) == [100.0, 100.0]
    (f,) = rec.flags
    sliver = next(p for p in rec.parts if p.excluded)
    assert f.ids == [sliver.outer.id] and "sliver" in f.reason
    assert sliver.outer.area == pytest.approx(1.0)


def test_cancel_through_progress():
    from LeatherCutWorkbench.core.errors import CancelledError
    with pytest.raises(CancelledError):
        recognise(S.drawing(S.grid_lines(3, 3)), progress=lambda f, m: f < 0.3)


def test_self_intersecting_outline_is_reported():
    rec = run(S.polyline([(0, 0), (10, 10), (10, 0), (0, 10)]) + S.rect(20, 0, 5, 5))
    (f,) = [f for f in rec.findings if f.code == "self-intersecting-contour"]
    assert "C1" in f.message and "5 5" in f.message
    assert len(rec.parts) == 2


def test_crossing_contours_are_reported():
    rec = run([S.circle(0, 0, 5), S.circle(3, 0, 5), S.circle(30, 0, 5)])
    (f,) = [f for f in rec.findings if f.code == "crossing-contours"]
    assert "C1" in f.message and "C2" in f.message and "C3" not in f.message
    # common edges touch but do not cross
    assert not [f for f in run(S.grid_lines(2, 2)).findings if f.code == "crossing-contours"]


def test_marks_without_any_part_are_reported():
    rec = recognise(S.drawing([], marks=[Mark((1, 1), "drill")]))
    assert not rec.parts and [f.code for f in rec.findings] == ["mark-outside-parts"]


def test_spline_in_a_common_edge_layout_with_loose_ends():
    # a spline arch over a 40 mm base, split in two cells by a vertical line
    # ending on the arch (a T-junction on a curve); the spline's first end misses
    # the base line's end by 5 um (inside the join tolerance)
    arch = S.open_spline_with_line()
    sp = arch[0]
    sp.poles[0] = (0.005, 0.0)
    top = to_segment(sp, 0.001)[1]
    apex = top.valueAt(top.Curve.parameter(FreeCAD.Vector(20, 40, 0)))
    assert apex.x == pytest.approx(20.0, abs=0.01)
    mid = LineEdge((20.0, 0.0), (20.0, apex.y), S.src())
    rec = run([sp, arch[1], mid])
    act = rec.active_parts()
    assert len(act) == 2 and not rec.flags
    total = sum(signed_path_area(p.outer.segments) for p in act)
    whole = signed_path_area(run(arch).parts[0].outer.segments)
    assert total == pytest.approx(whole, rel=1e-3)
    assert all(p.outer.shared for p in act)


def test_outline_drawn_twice_is_kept_once_but_same_box_shapes_are_not():
    twice = S.polyline([(0, 0), (10, 0), (10, 10), (0, 10)]) + \
        S.polyline([(0, 0), (0, 10), (10, 10), (10, 0)])          # reversed copy
    rec = run(twice + [S.circle(40, 5, 5)] + S.rect(35, 0, 10, 10))
    assert len(rec.parts) == 2
    square = next(p for p in rec.parts if p.outer.bbox[0] < 20)
    assert not square.holes
    framed = next(p for p in rec.parts if p.outer.bbox[0] > 20)
    assert len(framed.holes) == 1      # the inscribed circle touches the box on all sides


def test_lead_in_stopping_short_of_the_contour():
    edges = S.rect(0, 0, 20, 10) + [LineEdge((5.0, -4.0), (5.0, -0.3), S.src())]
    rec = run(edges)
    (p,) = rec.parts
    assert not p.lead_ins and len(rec.open_chains) == 1
    (f,) = rec.flags
    assert f.kind == "under" and f.gap == pytest.approx(0.3) and f.ids == ["O1"]
    (b,) = f.fix
    assert b.start == pytest.approx((5.0, -0.3)) and b.end == pytest.approx((5.0, 0.0))
    fixed = run(edges, close_gaps=True)
    (li,) = fixed.parts[0].lead_ins
    assert li.start == pytest.approx((5.0, -4.0)) and li.end == pytest.approx((5.0, 0.0))
    assert li.length == pytest.approx(4.0) and not fixed.open_chains
    assert fixed.flags[0].accepted is True and fixed.flags[0].ids == [li.id]
    # farther than the gap tolerance: stays an open chain without a flag
    far = run(S.rect(0, 0, 20, 10) + [LineEdge((5.0, -4.0), (5.0, -0.6), S.src())])
    assert len(far.open_chains) == 1 and not far.flags


def test_under_flags_say_what_accepting_does():
    edges = (S.square_with_gap(0.2) + S.shifted(S.square_overshoot(0.3), 50, 0)
             + S.shifted(S.rect(0, 0, 20, 10), 100, 0)
             + [LineEdge((105.0, -4.0), (105.0, -0.3), S.src())])
    rec = run(edges)
    actions = sorted(f.action for f in rec.flags)
    assert actions == ["close", "join", "trim"]
    assert all(f.kind == "under" for f in rec.flags)
    assert next(f for f in rec.flags if f.action == "trim").fix == []


def test_open_lines_in_pattern_pieces_are_slits_not_lead_ins():
    edges = S.rect(0, 0, 50, 40) + [LineEdge((10, 0), (10, 5), S.src())]
    pieces = {"P": PieceInfo(key="P", name="Piece", edges=list(range(5)))}
    rec = recognise(S.drawing(edges, pieces=pieces))
    (p,) = rec.parts
    assert not p.lead_ins and len(rec.open_chains) == 1
    assert rec.open_chains[0].length == pytest.approx(5.0)


def test_line_running_into_the_part_is_a_slit_not_a_lead_in():
    edges = S.rect(0, 0, 50, 40) + [LineEdge((10, 0), (10, 5), S.src()),      # into the part
                                     LineEdge((30, -5), (30, 0), S.src())]     # from outside
    edges += S.rect(20, 15, 10, 10) + [LineEdge((22, 20), (20, 20), S.src()),  # from inside hole
                                       LineEdge((30, 20), (33, 20), S.src())]  # hole into material
    rec = run(edges)
    (p,) = rec.parts
    starts = sorted(tuple(li.start) for li in p.lead_ins)
    assert starts == [(22.0, 20.0), (30.0, -5.0)]
    assert sorted(round(c.length, 6) for c in rec.open_chains) == [3.0, 5.0]
