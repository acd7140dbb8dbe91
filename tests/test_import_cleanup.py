"""DXF import clean-up: zero-length edges, duplicates, collinear overlaps,
T-junctions; per piece in AAMA files (generated geometry)."""

import ezdxf
import pytest

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing
from LeatherCutWorkbench.core.dxfimport.cleanup import clean
from LeatherCutWorkbench.core.model import ArcEdge, EdgeSource, LineEdge


def L(a, b, piece="", role="cut"):
    return LineEdge(a, b, EdgeSource(dxftype="LINE", piece=piece, role=role))


def total_length(edges):
    return sum(((e.end[0] - e.start[0]) ** 2 + (e.end[1] - e.start[1]) ** 2) ** 0.5 for e in edges)


def test_zero_length_and_duplicates_in_both_directions():
    edges = [L((0, 0), (10, 0)), L((10, 0), (0, 0)), L((0, 0), (10, 0)), L((5, 5), (5, 5)),
             L((0, 0), (0.003, 0)), L((0, 1), (10, 1.000001))]
    out, c = clean(edges, 0.01)
    assert c.zero_length == 1 and c.duplicates == 2
    assert len(out) == 3
    assert out[0] is edges[0]                # first of the duplicates kept
    assert any(e is edges[4] for e in out)   # short but real edge kept (no gap opened)
    assert c.by_type == {"LINE": 3}


def test_arc_duplicates_reversed_and_full_circles():
    src = EdgeSource(dxftype="ARC")
    a = ArcEdge((0, 0), 5, 10, 80, src)
    b = ArcEdge((0, 0), 5, 90, -80, src)         # same arc, other direction
    c_ = ArcEdge((0, 0), 5, 0, 360, src)
    d = ArcEdge((0, 0), 5, 0, 360, src)
    e = ArcEdge((0, 0), 5, 10, -80, src)         # different arc (other side)
    out, c = clean([a, b, c_, d, e], 0.01)
    assert c.duplicates == 2 and out == [a, c_, e]


def test_collinear_overlaps_keep_the_union():
    # two parts sharing an edge, each drawing it with its own (overlapping) lines
    edges = [L((0, 0), (100, 0)), L((150, 0), (40, 0)), L((60, 0), (80, 0)), L((0, 5), (10, 5))]
    out, c = clean(edges, 0.01)
    on_axis = [e for e in out if e.start[1] == 0 and e.end[1] == 0]
    assert total_length(on_axis) == pytest.approx(150)
    assert c.overlaps == 2 and c.overlap_length == pytest.approx(60 + 20)
    assert sorted(sorted((e.start[0], e.end[0])) for e in on_axis) == [[0, 100], [100, 150]]


def test_collinear_but_touching_lines_are_untouched():
    edges = [L((0, 0), (10, 10)), L((10, 10), (20, 20)), L((20, 20.5), (30, 30.5))]
    out, c = clean(edges, 0.01)
    assert c.overlaps == 0 and out == edges


def test_t_junction_split_counted():
    edges = [L((0, 0), (100, 0)), L((40, 0), (40, 30)), L((70, 0.004), (70, 30)),
             L((100, 0), (100, 30))]
    out, c = clean(edges, 0.01)
    assert c.t_junctions == 2
    base = sorted((e for e in out if abs(e.start[1]) < 0.01 and abs(e.end[1]) < 0.01),
                  key=lambda e: min(e.start[0], e.end[0]))
    assert [(round(e.start[0], 6), round(e.end[0], 6)) for e in base] == [(0, 40), (40, 70), (70, 100)]
    # the split point is the touching end point itself: the graph meets exactly
    assert base[1].end == (70, 0.004)


def test_arc_end_on_line_splits_the_line():
    src = EdgeSource(dxftype="ARC")
    arc = ArcEdge((50, 0), 10, 0, 180, src)     # ends at (60, 0) and (40, 0)
    out, c = clean([L((0, 0), (100, 0)), arc], 0.01)
    assert c.t_junctions == 2 and len(out) == 4


def test_groups_never_merge_across_pieces_or_roles():
    edges = [L((0, 0), (10, 0), piece="A"), L((0, 0), (10, 0), piece="B"),
             L((0, 0), (10, 0), piece="A", role="internal"), L((5, 0), (5, 5), piece="B", role="mark")]
    out, c = clean(edges, 0.01)
    assert c.duplicates == 0 and c.t_junctions == 0 and len(out) == 4


def _aama(tmp_path, sizes=("S", "M"), units="ENGLISH"):
    doc = ezdxf.new("R12")
    msp = doc.modelspace()
    for t in ("Style Name: TEST", "Units: " + units, "TOLERANCE: .006", "Sample Size: M"):
        msp.add_text(t)
    for size in sizes:
        b = doc.blocks.new(f"BACK_{size}")
        outline = [(0, 0), (10, 0), (10, 8), (0, 8)]
        # boundary as two open polylines that chain into one loop (layer 1)
        b.add_polyline2d(outline[:3], dxfattribs={"layer": "1"})
        b.add_polyline2d(outline[2:] + [outline[0]], dxfattribs={"layer": "1"})
        b.add_polyline2d(outline + [outline[0]], dxfattribs={"layer": "84"})   # validation copy
        b.add_circle((5, 4), 1, dxfattribs={"layer": "11"})                   # cut-out
        b.add_line((5, 1), (5, 7), dxfattribs={"layer": "7"})                 # grain
        b.add_line((0, 0), (0, 8), dxfattribs={"layer": "6"})                 # fold line
        b.add_line((2, 2), (8, 2), dxfattribs={"layer": "8"})                 # internal
        b.add_point((10, 4), dxfattribs={"layer": "4"})                       # notch
        b.add_point((3, 3), dxfattribs={"layer": "13"})                       # drill
        b.add_text("Piece Name: BACK", dxfattribs={"layer": "1"})
        b.add_text(f"SIZE: {size}", dxfattribs={"layer": "1"})
        b.add_text("QUANTITY: 2", dxfattribs={"layer": "1"})
        msp.add_blockref(f"BACK_{size}", (0, 0), dxfattribs={"layer": "1"})
    p = str(tmp_path / "aama.dxf")
    doc.saveas(p)
    return p


def test_aama_roles_pieces_units_and_per_piece_cleanup(tmp_path):
    d = read_drawing(_aama(tmp_path))
    assert d.stats["pattern"] == "aama" and (d.units, d.units_source) == ("inch", "aama-text")
    assert list(d.pieces) == ["BACK_S", "BACK_M"]
    p = d.pieces["BACK_S"]
    assert (p.name, p.size, p.quantity) == ("BACK", "S", 2)
    assert p.grain_angle == pytest.approx(90.0)
    assert p.mirror_line == ((0.0, 0.0), (0.0, 8 * 25.4))
    assert p.bbox == pytest.approx((0, 0, 254, 203.2))
    roles = {}
    for i in p.edges:
        e = d.edges[i]
        roles.setdefault(e.src.layer, set()).add(e.src.role)
    assert roles == {"1": {"cut"}, "11": {"cut"}, "84": {"ignore"}, "7": {"grain"},
                     "6": {"mirror"}, "8": {"internal"}}
    marks = sorted((d.marks[i].kind, d.marks[i].src.role) for i in p.marks)
    assert marks == [("drill", "mark"), ("notch", "mark")]
    # identical sizes stacked at one origin: nothing removed across pieces
    assert d.stats["cleanup"]["duplicates_removed"] == 0
    cut = [d.edges[i] for i in d.pieces["BACK_M"].edges if d.edges[i].src.role == "cut"]
    assert len(cut) == 5   # 4 boundary lines + the cut-out circle
    assert d.stats["join_tolerance_hint_mm"] == pytest.approx(0.006 * 25.4)


def test_pattern_mode_off_reads_aama_as_plain_drawing(tmp_path):
    d = read_drawing(_aama(tmp_path), ImportOptions(pattern_mode="off", units="inch"))
    assert d.pieces == {} and {e.src.role for e in d.edges} == {"cut"}
    # the two stacked sizes are now one group: their duplicates are removed
    assert d.stats["cleanup"]["duplicates_removed"] > 0


def test_ellipse_duplicates_and_zero_length():
    from LeatherCutWorkbench.core.model import EllipseEdge
    import math as m
    src = EdgeSource(dxftype="ELLIPSE")
    full = EllipseEdge((0, 0), (10, 0), 0.5, 0.0, 2 * m.pi, src)
    flipped = EllipseEdge((0, 0), (-10, 0), 0.5, 0.0, 2 * m.pi, src)   # same curve
    part = EllipseEdge((0, 0), (10, 0), 0.5, 0.2, 1.5, src)
    same_part = EllipseEdge((0, 0), (-10, 0), 0.5, 0.2 + m.pi, 1.5 + m.pi, src)
    other = EllipseEdge((0, 0), (10, 0), 0.5, 1.5, 2.0, src)
    tiny = EllipseEdge((5, 5), (1e-7, 0), 0.5, 0.0, 1.0, src)
    out, c = clean([full, flipped, part, same_part, other, tiny], 0.01)
    assert out == [full, part, other] and c.duplicates == 2 and c.zero_length == 1
