"""Accepting any subset of gap fixes yields each part once (issue 12, item 1).

The reference is independent of recognition: the drawing's cut edges are read
with ezdxf (``recover``) or taken from the generated edges, flattened, the
accepted fixes' bridges added, and shapely's ``unary_union`` + ``polygonize``
gives every bounded face.  Recognition must find one closed outline per face
(outer contours and holes) and, with containment depth taken over the faces
whose outline recognition did not exclude, the same number of parts and the
same net part area (outer minus holes, mm²).
"""

import itertools
import math
import os

import pytest
import shapely
from shapely.geometry import LineString, Polygon
from shapely.ops import polygonize, unary_union

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing
from LeatherCutWorkbench.core.geometry import path_points
from LeatherCutWorkbench.core.model import ArcEdge, LineEdge
from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise

import recognise_shapes as S

DEEPNEST = os.path.join(os.path.dirname(__file__), "data", "samples",
                        "deepnest_ReadMeExampleSmall.dxf")


# -- independent reference ----------------------------------------------------------

def dxf_lines(path):
    """Flattened cut lines of a plain DXF, read by ezdxf alone (no LeatherCut code)."""
    from ezdxf import path as ezpath, recover
    doc, _audit = recover.readfile(path)
    out = []
    for e in doc.modelspace():
        pts = [(v.x, v.y) for v in ezpath.make_path(e).flattening(0.005)]
        if len(pts) >= 2:
            out.append(LineString(pts))
    return out


def edge_lines(edges):
    """Flattened lines of generated LineEdge / ArcEdge values."""
    out = []
    for e in edges:
        if isinstance(e, LineEdge):
            out.append(LineString([e.start, e.end]))
        elif isinstance(e, ArcEdge):
            a0 = math.radians(e.start_angle)
            a1 = a0 + math.radians(e.sweep)
            n = 720
            out.append(LineString([(e.center[0] + e.radius * math.cos(a0 + (a1 - a0) * k / n),
                                    e.center[1] + e.radius * math.sin(a0 + (a1 - a0) * k / n))
                                   for k in range(n + 1)]))
    return out


def faces(lines, bridges, grid=1e-3):
    """Bounded faces of the lines noded together, end points snapped to ``grid`` mm."""
    lines = list(lines) + [LineString([b.start, b.end]) for b in bridges]
    snapped = shapely.set_precision(unary_union(lines), grid)
    return [f for f in polygonize(unary_union(snapped)) if f.area > 1e-6]


def reference(lines, bridges, excluded_outlines):
    """(closed outlines, parts, net part area) of the faces bounded by ``lines`` and
    ``bridges``; faces whose outline matches one of ``excluded_outlines`` (a
    person's or recognition's over decision, not geometry) hold nothing."""
    fs = faces(lines, bridges)
    outers = [Polygon(f.exterior) for f in fs]
    excl = [any(abs(o.area - x.area) < 1e-2 * max(1.0, x.area) ** 0.5 and
                o.symmetric_difference(x).area < 1e-2 * max(1.0, x.area) ** 0.5
                for x in excluded_outlines) for o in outers]
    parts = area = 0
    for i, f in enumerate(fs):
        if excl[i]:
            parts += 1
            continue
        pt = f.representative_point()
        depth = sum(1 for j, o in enumerate(outers)
                    if j != i and not excl[j] and o.area > outers[i].area and o.contains(pt))
        if depth % 2 == 0:
            parts += 1
            area += f.area
    return len(fs), parts, area


def ring(contour):
    pts = contour.points(0.005)
    return Polygon(pts)


def check(rec, lines, bridges):
    assert unique_outlines(rec), "an outline comes out twice"
    outlines = [c for p in rec.parts for c in [p.outer] + list(p.holes)]
    excluded = [ring(p.outer) for p in rec.parts if p.excluded]
    n_faces, n_parts, area = reference(lines, bridges, excluded)
    assert len(outlines) == n_faces
    assert len(rec.parts) == n_parts
    assert net_area(rec) == pytest.approx(area, rel=1e-3, abs=0.05)


def subsets(ids):
    ids = sorted(ids)
    for k in range(len(ids) + 1):
        yield from (frozenset(c) for c in itertools.combinations(ids, k))


def bridge_flags(rec):
    """Under flags whose fix adds bridging segments (close a gap, join a chain)."""
    return {f.id: f for f in rec.flags if f.kind == "under" and f.action in ("close", "join")}


# -- the DeepNest example (the reproduction) --------------------------------

@pytest.fixture(scope="module")
def deepnest():
    return read_drawing(DEEPNEST, ImportOptions()), dxf_lines(DEEPNEST)


def net_area(rec):
    return sum(ring(p.outer).area - sum(ring(h).area for h in p.holes)
               for p in rec.parts if not p.excluded)


def unique_outlines(rec):
    outlines = [c for p in rec.parts for c in [p.outer] + list(p.holes)]
    keys = [tuple(round(v, 3) for v in c.bbox) + (round(abs(c.area), 1),) for c in outlines]
    return len(keys) == len(set(keys))


def test_deepnest_accepting_f1_gives_each_part_once(deepnest):
    """The drawing's parts overlap each other a little (the designer's drawing),
    so the noded faces of the whole sheet are not its parts; the reference here
    is shapely's face of the two open chains plus the bridge, and conservation:
    closing F1 adds exactly that part and keeps every other one."""
    drawing, lines = deepnest
    prop = recognise(drawing, RecogniseOptions())
    fixes = bridge_flags(prop)
    assert set(fixes) == {"F1"} and len(prop.open_chains) == 2
    rec = recognise(drawing, RecogniseOptions(accept_fixes=frozenset({"F1"})))
    assert unique_outlines(rec)
    boxes = [tuple(round(v, 3) for v in p.outer.bbox) for p in rec.parts]
    assert len(boxes) == len(set(boxes)) == len(prop.parts) + 1
    assert (0.0, 0.0, 600.0, 200.0) in boxes               # the plate border is still there
    assert len(rec.active_parts()) == 13 and not rec.open_chains
    (new,) = [p for p in rec.parts
              if tuple(round(v, 3) for v in p.outer.bbox) not in
              {tuple(round(v, 3) for v in q.outer.bbox) for q in prop.parts}]
    chain_lines = [LineString(path_points(c.segments, 0.005)) for c in prop.open_chains]
    (face,) = faces(chain_lines, fixes["F1"].fix, 0.01)
    assert ring(new.outer).area == pytest.approx(face.area, rel=1e-3)
    assert net_area(rec) == pytest.approx(net_area(prop) + ring(new.outer).area, rel=1e-6)


# -- generated drawings ------------------------------------------------------------

def gaps_in_a_grid():
    """Three separate squares with gaps, one square drawn as two L-shapes (two gaps),
    and a common-edge 2x2 grid whose neighbour is a gapped square touching it."""
    return (S.square_with_gap(0.2) + S.square_with_gap(0.3, x=40.0)
            + S.square_two_gaps(0.25, x=80.0)
            + S.grid_lines(2, 2, x0=0.0, y0=60.0)
            + S.square_with_gap(0.35, x=20.0, y=60.0, size=20.0))


def gap_with_hole():
    """A gapped part with a gapped hole and a circle island in the hole."""
    return (S.square_with_gap(0.3, size=60.0) + S.square_with_gap(0.2, x=10, y=10, size=40.0)
            + [S.circle(30.0, 30.0, 8.0)])


@pytest.mark.parametrize("make", [gaps_in_a_grid, gap_with_hole])
def test_any_subset_of_fixes_gives_each_part_once(make):
    edges = make()
    drawing = S.drawing(edges)
    prop = recognise(drawing, RecogniseOptions())
    fixes = bridge_flags(prop)
    assert fixes, "the generated drawing must propose gap fixes"
    lines = edge_lines(edges)
    for chosen in subsets(fixes):
        rec = recognise(drawing, RecogniseOptions(accept_fixes=chosen))
        check(rec, lines, [b for i in chosen for b in fixes[i].fix])
