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


def _square_loop(x, y, s, cluster=None):
    from LeatherCutWorkbench.core.geometry import LineSeg
    from LeatherCutWorkbench.core.recognition.loops import Loop

    pts = [(x, y), (x + s, y), (x + s, y + s), (x, y + s)]
    segs = [LineSeg(pts[k], pts[(k + 1) % 4]) for k in range(4)]
    lp = Loop(segs, set(), set(), cluster=cluster)
    lp.chord_tol = 0.01
    return lp


def _parents_one_by_one(loops, tol):
    """The containment search of every loop (no bulk box pass): the reference."""
    from LeatherCutWorkbench.core.recognition import nesting_depth as N

    order = sorted(range(len(loops)), key=lambda i: -loops[i].area)
    index = N.LoopIndex(loops)
    parent = [None] * len(loops)
    for i in order:
        lp = loops[i]
        p = lp.sample_point()
        cands = [j for j in index.at(p)
                 if loops[j].area > lp.area and N._box_in(lp.bbox, loops[j].bbox, tol)
                 and (lp.cluster is None or loops[j].cluster != lp.cluster)]
        cands.sort(key=lambda j: loops[j].area)
        parent[i] = next((j for j in cands if N.contains(loops[j], lp, p, tol)), None)
        index.add(i, lp.bbox)
    return parent


def test_bulk_box_pass_of_containment_gives_the_parents_of_the_full_search():
    from LeatherCutWorkbench.core.recognition.nesting_depth import parents

    rng = random.Random(16)
    tol = 0.01
    for trial in range(25):
        loops = []
        for _ in range(rng.randrange(1, 120)):
            s = rng.choice((1.0, 2.0, 2.0, 5.0, 10.0, 40.0))
            x, y = rng.randrange(0, 20) * 2.5, rng.randrange(0, 20) * 2.5
            cluster = rng.choice((None, None, 0, 1))
            loops.append(_square_loop(x, y, s, cluster))
            if rng.random() < 0.3:                          # a hole, an island, a near twin
                d = rng.choice((0.5, tol * 0.5, tol * 2))
                loops.append(_square_loop(x + d, y + d, s - 2 * d))
        expected = _parents_one_by_one(loops, tol)
        assert parents(loops, tol) == expected
        assert any(p is not None for p in expected) or len(loops) < 10


def test_recognition_of_nested_touching_and_shared_squares():
    """Parts, holes and islands of a grid of nests, corner-touching squares and
    common-edge squares: the same counts whatever the bulk pass skips."""
    from LeatherCutWorkbench.core.recognition import recognise

    import recognise_shapes as S

    edges = []
    for k in range(12):
        x = k * 100.0
        edges += S.rect(x, 0, 80, 80) + S.rect(x + 10, 10, 60, 60) + S.rect(x + 20, 20, 40, 40)
        edges += S.rect(x, 100, 40, 40) + S.rect(x + 40, 140, 40, 40)        # corners touch
        edges += S.rect(x, 200, 40, 40) + S.rect(x + 40, 200, 40, 40)        # a common edge
    rec = recognise(S.drawing(edges))
    from collections import Counter

    def box(c):
        pts = c.points()
        return (min(x for x, _ in pts), min(y for _, y in pts))

    got = Counter((round(p.net_area, 6), tuple(box(h) for h in p.holes)) for p in rec.active_parts())
    assert sum(got.values()) == 12 * 6
    assert sum(n for (a, hs), n in got.items() if a == 6400.0 - 3600.0 and len(hs) == 1) == 12
    assert got[(1600.0, ())] == 12 * 5                  # islands, touching and common-edge squares
    islands = [p for p in rec.active_parts() if box(p.outer)[1] == 20.0]
    assert len(islands) == 12 and all(not p.holes for p in islands)
