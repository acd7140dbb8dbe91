"""core.geometry: the segment maths every later stage relies on."""

import math

import pytest

from LeatherCutWorkbench.core.geometry import (ArcSeg, CurveSeg, LineSeg, Transform2D,
                                               path_length, path_points, rotate_closed_path,
                                               signed_area, turn_angle)


def square(s=10.0):
    p = [(0, 0), (s, 0), (s, s), (0, s)]
    return [LineSeg(a, b) for a, b in zip(p, p[1:] + p[:1])]


def test_arc_flattening_respects_chord_tolerance():
    arc = ArcSeg((5.0, -3.0), 40.0, 10.0, 250.0)
    tol = 0.01
    pts = arc.points(tol)
    for a, b in zip(pts, pts[1:]):
        mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        sagitta = 40.0 - math.hypot(mid[0] - 5.0, mid[1] + 3.0)
        assert 0 <= sagitta <= tol + 1e-9
    assert pts[0] == pytest.approx(arc.start) and pts[-1] == pytest.approx(arc.end)


def test_arc_reversed_and_headings():
    arc = ArcSeg((0, 0), 10, 0, 90)
    assert arc.start == pytest.approx((10, 0)) and arc.end == pytest.approx((0, 10))
    assert arc.start_heading() == pytest.approx(90)
    r = arc.reversed()
    assert r.start == pytest.approx(arc.end) and r.end == pytest.approx(arc.start)
    assert r.start_heading() % 360 == pytest.approx(0)  # clockwise from (0, 10) heads +X


@pytest.mark.parametrize("mirrored", [False, True])
def test_transform_keeps_arcs_on_transformed_points(mirrored):
    xf = Transform2D(dx=100, dy=-20, angle=33, mirrored=mirrored)
    arc = ArcSeg((3, 4), 7, 20, -130)
    moved = arc.transformed(xf)
    for s in (0.0, 3.0, arc.length):
        assert moved.point_at(s) == pytest.approx(xf.apply(arc.point_at(s)), abs=1e-9)


def test_rotate_closed_path_keeps_loop_and_length():
    sq = square()
    rot = rotate_closed_path(sq, 15.0)
    assert rot[0].start == pytest.approx((10, 5))
    assert rot[-1].end == pytest.approx((10, 5))
    assert path_length(rot) == pytest.approx(40.0)
    for a, b in zip(rot, rot[1:]):
        assert a.end == pytest.approx(b.start)


def test_signed_area_orientation():
    pts = path_points(square())[:-1]
    assert signed_area(pts) == pytest.approx(100.0)
    assert signed_area(pts[::-1]) == pytest.approx(-100.0)


def test_curve_split_and_turn_angle():
    c = CurveSeg(((0, 0), (10, 0), (10, 10)), "spline")
    a, b = c.split_at(15.0)
    assert a.end == pytest.approx((10, 5)) and b.start == pytest.approx((10, 5))
    assert a.length + b.length == pytest.approx(c.length)
    assert turn_angle(170, -170) == pytest.approx(20)
    assert turn_angle(0, 180) == pytest.approx(180)
