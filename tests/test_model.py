"""core.model: transformed copies keep the invariants later stages rely on."""

import pytest

from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg, Transform2D
from LeatherCutWorkbench.core.model import Contour, LeadIn, Mark, Part


def loop(pts):
    return [LineSeg(a, b) for a, b in zip(pts, pts[1:] + pts[:1])]


@pytest.fixture
def part():
    outer = Contour("C1", loop([(0, 0), (40, 0), (40, 20), (0, 20)]), shared=[0])   # CCW
    hole = Contour("C2", [ArcSeg((10, 10), 3, 0, -360)])                           # CW
    lead = LeadIn("L1", "C1", [LineSeg((-5, -5), (0, 0))])
    return Part("P1", outer, [hole], [lead], [Mark((30, 10), "drill")])


@pytest.mark.parametrize("mirrored", [False, True])
def test_transformed_part_keeps_orientation_and_shared_edge(part, mirrored):
    xf = Transform2D(dx=100, dy=50, angle=90, mirrored=mirrored)
    moved = part.transformed(xf, new_id="P1#3")
    assert moved.outer.area == pytest.approx(800) and moved.holes[0].area < 0
    # the shared edge is still the one that came from the original bottom edge
    (k,) = moved.outer.shared
    seg, orig = moved.outer.segments[k], part.outer.segments[0]

    def ends(a, b):
        return sorted((round(x, 6), round(y, 6)) for x, y in (a, b))
    assert ends(seg.start, seg.end) == ends(xf.apply(orig.start), xf.apply(orig.end))
    assert moved.id == "P1#3" and moved.outer.id == "P1#3/C1"
    assert moved.lead_ins[0].contour_id == "P1#3/C1" and moved.lead_ins[0].end == pytest.approx(
        xf.apply((0, 0)))
    assert moved.marks[0].position == pytest.approx(xf.apply((30, 10)))
    assert part.outer.segments[0].start == (0, 0)          # the original is untouched


def test_transformed_without_new_id_keeps_ids(part):
    moved = part.transformed(Transform2D(dx=1))
    assert (moved.id, moved.outer.id, moved.lead_ins[0].id) == ("P1", "C1", "L1")
