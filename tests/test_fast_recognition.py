"""The fast paths of recognition give the same result as the step-by-step code:
bulk end-point snapping (``NodeGrid.nodes``) makes the same nodes, in the same
order, as snapping one point at a time, on clouds with clusters closer than
the tolerance, bit-identical repeats, -0.0 and points on cell borders."""

import random

from LeatherCutWorkbench.core.recognition.graph import NodeGrid


def _clouds():
    rng = random.Random(16)
    tol = 0.01
    for trial in range(30):
        pts = []
        for _ in range(rng.randrange(1, 400)):
            x, y = rng.uniform(-5, 5), rng.uniform(-5, 5)
            pts.append((x, y))
            for _ in range(rng.randrange(0, 3)):     # a near neighbour or an exact repeat
                d = rng.choice((0.0, tol * 0.5, tol * 0.99, tol * 1.01, tol * 2.5))
                pts.append((x + d, y - d * rng.random()))
        pts += [(0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (tol, 0.0), (tol * 2, tol * 3)]
        rng.shuffle(pts)
        yield tol, pts
    yield 1.0, [(float(i % 7), float(i // 7)) for i in range(200)]   # grid at the cell size


def test_bulk_snapping_makes_the_same_nodes_as_one_point_at_a_time():
    for tol, pts in _clouds():
        one, bulk = NodeGrid(tol), NodeGrid(tol)
        expected = [one.node(p) for p in pts]
        assert bulk.nodes(pts) == expected
        assert bulk.pos == one.pos and bulk.cells == one.cells and bulk.exact == one.exact
        for p in pts[:50]:                                  # later queries agree too
            q = (p[0] + tol * 0.3, p[1])
            assert bulk.find(q) == one.find(q) and bulk.node(q) == one.node(q)


def test_bulk_snapping_of_coordinates_too_far_apart_for_one_key_falls_back():
    pts = [(-1e9, -1e9), (1e9, 1e9), (1e9, 1e9 + 0.001), (0.5, 0.5)]
    one, bulk = NodeGrid(0.01), NodeGrid(0.01)
    assert bulk.nodes(pts) == [one.node(p) for p in pts] == [0, 1, 1, 2]


def test_part_choices_copy_parts_and_lists_but_share_the_geometry():
    from LeatherCutWorkbench.core.geometry import LineSeg
    from LeatherCutWorkbench.core.model import Contour, Part, Recognition
    from LeatherCutWorkbench.core.part_choice import PartChoice, apply_choices

    segs = [LineSeg((0.0, 0.0), (1.0, 0.0)), LineSeg((1.0, 0.0), (0.0, 1.0)),
            LineSeg((0.0, 1.0), (0.0, 0.0))]
    part = Part("P1", Contour("C1", segs, "CUT"), holes=[Contour("C2", segs, "CUT")],
                rotations=[0.0, 180.0])
    rec = Recognition(parts=[part])
    out = apply_choices(rec, {"P1": PartChoice(False, 3)})
    copy = out.parts[0]
    assert copy is not part and (copy.excluded, copy.quantity) == (True, 3)
    assert (part.excluded, part.quantity) == (False, 1)
    assert copy.outer is part.outer and copy.holes == part.holes
    copy.holes.append(part.outer)
    copy.rotations.append(90.0)
    out.parts.append(copy)
    assert len(part.holes) == 1 and part.rotations == [0.0, 180.0] and len(rec.parts) == 1
