"""DXF import: every supported entity, coordinate system and block transform,
checked against ezdxf's own geometry (decompose/flatten) on generated files."""

import math

import ezdxf
import numpy as np
import pytest
import shapely
from ezdxf import disassemble
from ezdxf.math import BSpline

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing
from LeatherCutWorkbench.core.model import ArcEdge, EllipseEdge, LineEdge, SplineEdge

RAW = ImportOptions(cleanup=False)


def sample(e, n=64):
    """Points along one of our edges (mm)."""
    if isinstance(e, LineEdge):
        return [e.start, e.end]
    if isinstance(e, ArcEdge):
        return [(e.center[0] + e.radius * math.cos(math.radians(e.start_angle + e.sweep * k / n)),
                 e.center[1] + e.radius * math.sin(math.radians(e.start_angle + e.sweep * k / n)))
                for k in range(n + 1)]
    if isinstance(e, EllipseEdge):
        mx, my = e.major_axis
        nx, ny = -my * e.ratio, mx * e.ratio
        out = []
        for k in range(n + 1):
            s = e.start_param + (e.end_param - e.start_param) * k / n
            out.append((e.center[0] + mx * math.cos(s) + nx * math.sin(s),
                        e.center[1] + my * math.cos(s) + ny * math.sin(s)))
        return out
    if isinstance(e, SplineEdge):
        bs = BSpline(e.poles, order=e.degree + 1, knots=e.knots, weights=e.weights or None)
        return [(p.x, p.y) for p in bs.approximate(n)]
    raise TypeError(e)


def assert_same_geometry(path, drawing, scale=1.0, tol=1e-3):
    """Our edges and ezdxf's decomposed primitives cover the same curves."""
    doc = ezdxf.readfile(path)
    theirs = []
    for prim in disassemble.to_primitives(disassemble.recursive_decompose(doc.modelspace()),
                                          max_flattening_distance=1e-5):
        if prim.entity.dxftype() in ("POINT", "TEXT", "MTEXT", "ATTRIB"):
            continue
        pts = [(v.x * scale, v.y * scale) for v in prim.vertices()]
        if len(pts) > 1:
            theirs.append(shapely.LineString(pts))
    ours = [shapely.LineString(sample(e, 512)) for e in drawing.edges]
    a, b = shapely.MultiLineString(ours), shapely.MultiLineString(theirs)
    # every vertex of one set lies on the other (flattening error << tol)
    for src, dst in ((a, b), (b, a)):
        pts = shapely.get_coordinates(src)
        d = shapely.distance(shapely.points(pts), dst)
        assert d.max() < tol * max(1.0, scale), f"max deviation {d.max()}"


def new_doc(version="R2010"):
    """A new drawing in mm (ezdxf's default $INSUNITS is 6 = metres)."""
    doc = ezdxf.new(version)
    doc.header["$INSUNITS"] = 4
    return doc


def save(doc, tmp_path, name="t.dxf"):
    p = str(tmp_path / name)
    doc.saveas(p)
    return p


def test_lines_arcs_circles_in_mm_with_sources(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    ln = msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "CUT", "color": 1})
    msp.add_arc((5, 5), 3, 30, 120, dxfattribs={"layer": "CUT"})
    msp.add_circle((20, 20), 4)
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    assert d.units == "mm" and d.units_source == "header"
    kinds = sorted(type(e).__name__ for e in d.edges)
    assert kinds == ["ArcEdge", "ArcEdge", "LineEdge"]
    line = next(e for e in d.edges if isinstance(e, LineEdge))
    assert line.start == (0.0, 0.0) and line.end == (10.0, 0.0)
    assert (line.src.layer, line.src.color, line.src.handle, line.src.dxftype, line.src.role) == \
        ("CUT", 1, ln.dxf.handle, "LINE", "cut")
    arc = next(e for e in d.edges if isinstance(e, ArcEdge) and abs(e.sweep) < 360)
    assert arc.center == pytest.approx((5, 5)) and arc.radius == pytest.approx(3)
    assert arc.start_angle == pytest.approx(30) and arc.sweep == pytest.approx(90)
    circle = next(e for e in d.edges if isinstance(e, ArcEdge) and abs(e.sweep) == 360)
    assert circle.radius == pytest.approx(4)
    assert d.stats["bbox_mm"] == pytest.approx([0, 0, 24, 24])
    assert_same_geometry(p, d)


def test_inch_drawing_is_scaled_to_mm(tmp_path):
    doc = new_doc("R2010")
    doc.header["$INSUNITS"] = 1
    doc.modelspace().add_line((0, 0), (2, 1))
    doc.modelspace().add_circle((1, 1), 0.5)
    d = read_drawing(save(doc, tmp_path), RAW)
    assert d.units == "inch" and d.units_source == "header"
    line = next(e for e in d.edges if isinstance(e, LineEdge))
    assert line.end == pytest.approx((50.8, 25.4))
    circle = next(e for e in d.edges if isinstance(e, ArcEdge))
    assert circle.radius == pytest.approx(12.7)


def test_arc_with_negative_extrusion_is_mirrored_into_world(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    # OCS with extrusion (0,0,-1): OCS x = -WCS x
    msp.add_arc((10, 5), 2, 0, 90, dxfattribs={"extrusion": (0, 0, -1)})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    (arc,) = d.edges
    assert isinstance(arc, ArcEdge)
    assert arc.center == pytest.approx((-10, 5))
    pts = sample(arc, 2)
    ends = {tuple(np.round(pts[0], 9)), tuple(np.round(pts[-1], 9))}
    assert ends == {(-12.0, 5.0), (-10.0, 7.0)}
    # the arc passes through the WCS point at OCS angle 45 deg, i.e. x mirrored
    mid = pts[1]
    assert mid == pytest.approx((-10 - 2 * math.cos(math.radians(45)), 5 + 2 * math.sin(math.radians(45))))
    assert_same_geometry(p, d)


def test_ellipses_full_partial_and_reversed(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    msp.add_ellipse((0, 0), major_axis=(10, 0), ratio=0.5)
    msp.add_ellipse((30, 0), major_axis=(0, 8), ratio=0.25, start_param=0.3, end_param=2.5)
    msp.add_ellipse((60, 0), major_axis=(5, 5), ratio=0.6, start_param=1.0, end_param=4.0,
                    dxfattribs={"extrusion": (0, 0, -1)})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    assert [type(e) for e in d.edges] == [EllipseEdge] * 3
    full = d.edges[0]
    assert full.end_param - full.start_param == pytest.approx(2 * math.pi)
    assert full.ratio == pytest.approx(0.5) and math.hypot(*full.major_axis) == pytest.approx(10)
    assert_same_geometry(p, d)


def test_lwpolyline_bulges_closed_and_width_note(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0, 0), (10, 0, 1), (10, 10, 0), (0, 10, -0.5)], format="xyb",
                       close=True)
    msp.add_lwpolyline([(20, 0), (30, 0), (30, 5)], dxfattribs={"elevation": 3})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    kinds = [type(e).__name__ for e in d.edges]
    assert kinds.count("ArcEdge") == 2 and kinds.count("LineEdge") == 4
    semi = next(e for e in d.edges if isinstance(e, ArcEdge) and abs(e.sweep) == pytest.approx(180))
    assert semi.center == pytest.approx((10, 5)) and semi.radius == pytest.approx(5)
    assert semi.sweep > 0  # positive bulge = counter-clockwise
    neg = next(e for e in d.edges if isinstance(e, ArcEdge) and e is not semi)
    assert neg.sweep == pytest.approx(-4 * math.degrees(math.atan(0.5)))
    # ezdxf's reference flattens bulges via cubic Beziers (radial error ~2.7e-4 r)
    assert_same_geometry(p, d, tol=3e-3)
    assert not any(f.code == "width-ignored" for f in d.findings)
    doc.modelspace().add_lwpolyline([(0, 20), (10, 20)], dxfattribs={"const_width": 0.5})
    wide = read_drawing(save(doc, tmp_path, "wide.dxf"), RAW)
    assert len(wide.edges) == 7
    assert any(f.code == "width-ignored" for f in wide.findings)


def test_lwpolyline_in_flipped_ocs(tmp_path):
    doc = new_doc("R2010")
    doc.modelspace().add_lwpolyline([(0, 0, 0.4), (10, 0, 0), (10, 10, 0)], format="xyb",
                                    dxfattribs={"extrusion": (0, 0, -1)})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    xs = [x for e in d.edges for x, _ in sample(e)]
    assert max(xs) <= 1e-9  # mirrored to negative x
    assert_same_geometry(p, d, tol=3e-3)


def test_polyline_2d_and_3d_and_mesh_skipped(tmp_path):
    doc = new_doc("R2000")
    msp = doc.modelspace()
    pl = msp.add_polyline2d([(0, 0), (10, 0), (10, 10)], close=True)
    pl.vertices[0].dxf.bulge = 0.3
    msp.add_polyline3d([(0, 0, 0), (5, 5, 5), (10, 0, 0)])
    mesh = msp.add_polymesh((2, 2))
    for m in range(2):
        for n in range(2):
            mesh.set_mesh_vertex((m, n), (m, n, m * n))
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    kinds = [type(e).__name__ for e in d.edges]
    assert kinds.count("ArcEdge") == 1 and kinds.count("LineEdge") == 4
    skipped = [f for f in d.findings if f.code == "skipped-entity"]
    assert len(skipped) == 1 and "POLYLINE" in skipped[0].message and mesh.dxf.handle in skipped[0].message
    assert any(f.code == "projected-3d" for f in d.findings)


def test_spline_kept_as_true_bspline(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    cps = [(0, 0), (10, 20), (30, -10), (50, 10), (60, 0)]
    s1 = msp.add_open_spline(cps, degree=3)
    msp.add_rational_spline(cps, weights=[1, 2, 0.5, 1, 1], degree=2)
    msp.add_spline(fit_points=[(0, 50), (20, 70), (40, 40), (60, 60)])
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    splines = [e for e in d.edges if isinstance(e, SplineEdge)]
    assert len(splines) == 3
    a, b, c = splines
    assert a.poles == [pytest.approx(q) for q in cps] and a.degree == 3 and a.weights == []
    assert a.knots == pytest.approx(list(s1.knots)) and len(a.knots) == len(cps) + 4
    assert b.weights == [1, 2, 0.5, 1, 1] and b.degree == 2
    assert not a.from_fit_points and c.from_fit_points
    assert any(f.code == "spline-from-fit-points" for f in d.findings)
    # the curve passes through its fit points
    ours = shapely.LineString(sample(c, 400))
    for fp in [(0, 50), (20, 70), (40, 40), (60, 60)]:
        assert ours.distance(shapely.Point(fp)) < 1e-3
    assert_same_geometry(p, d, tol=2e-2)


def test_points_are_marks_and_texts_are_notes(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    msp.add_line((0, 0), (1, 0))
    msp.add_point((3, 4), dxfattribs={"layer": "DRILL"})
    msp.add_text("Hello", dxfattribs={"height": 2.5, "insert": (1, 2)})
    msp.add_mtext("Line1\\PLine2", dxfattribs={"insert": (5, 6), "char_height": 3})
    d = read_drawing(save(doc, tmp_path), RAW)
    (mark,) = d.marks
    assert mark.position == (3.0, 4.0) and mark.src.layer == "DRILL" and mark.src.role == "mark"
    texts = {t.text: t for t in d.texts}
    assert texts["Hello"].position == (1.0, 2.0) and texts["Hello"].height == 2.5
    assert texts["Line1\nLine2"].position == (5.0, 6.0)
    assert all(t.src.role == "annotation" for t in d.texts)


def _nested_doc():
    doc = new_doc("R2010")
    inner = doc.blocks.new("INNER", base_point=(1, 0))
    inner.add_line((1, 0), (4, 0))
    inner.add_arc((2, 2), 1, 0, 90, dxfattribs={"layer": "0", "color": 0})
    inner.add_lwpolyline([(0, 0, 0.5), (3, 0, 0), (3, 3, 0)], format="xyb")
    inner.add_ellipse((0, 3), (2, 0), 0.5, 0.2, 2.0)
    mid = doc.blocks.new("MID")
    mid.add_blockref("INNER", (10, 0), dxfattribs={"rotation": 30, "xscale": -1})
    mid.add_circle((0, 0), 1.5)
    top = doc.blocks.new("TOP", base_point=(2, 2))
    top.add_blockref("MID", (0, 5), dxfattribs={"xscale": 2, "yscale": 0.5, "rotation": 15})
    msp = doc.modelspace()
    msp.add_blockref("TOP", (100, 50), dxfattribs={"rotation": -40, "layer": "PARTS", "color": 3})
    msp.add_blockref("TOP", (0, 0), dxfattribs={"xscale": -1.5, "yscale": 1.5})
    return doc


def test_nested_blocks_three_deep_with_mirror_rotation_and_non_uniform_scale(tmp_path):
    doc = _nested_doc()
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    # 2 top inserts x (INNER: 1 line + 1 arc + 2 polyline segments + 1 ellipse, MID: 1 circle)
    assert len(d.edges) == 2 * 6
    # non-uniform scale (2 x 0.5) turns the circle and the arcs into ellipses
    assert not any(isinstance(e, ArcEdge) for e in d.edges)
    assert d.stats["entities_found"] == {"INSERT": 2}
    assert d.stats["entities_after_explosion"] == {"ARC": 2, "CIRCLE": 2, "ELLIPSE": 2, "LINE": 2,
                                                   "LWPOLYLINE": 2}
    assert {b["name"]: b["inserts"] for b in d.stats["blocks"]} == {"INNER": 2, "MID": 2, "TOP": 2}
    paths = {e.src.block for e in d.edges}
    assert paths == {"TOP/MID/INNER", "TOP/MID"}
    # layer 0 / BYBLOCK inherit from the INSERT; handle names the model-space INSERT
    arc = next(e for e in d.edges if e.src.dxftype == "ARC" and e.src.layer == "PARTS")
    assert arc.src.color == 3 and arc.src.handle == doc.modelspace()[0].dxf.handle
    # exact reference: INNER's own geometry mapped by the product of the three
    # INSERT matrices (ezdxf's virtual INSERTs cannot carry the shear that a
    # non-uniform scale of a rotated child creates, so decompose() is not exact here)
    doc = ezdxf.readfile(p)
    mid_ins = next(e for e in doc.blocks["TOP"] if e.dxftype() == "INSERT")
    inner_ins = next(e for e in doc.blocks["MID"] if e.dxftype() == "INSERT")
    inner_pts = []
    for e in doc.blocks["INNER"]:
        if e.dxftype() == "LWPOLYLINE":
            for v in e.virtual_entities():
                inner_pts += _entity_points(v)
        else:
            inner_pts += _entity_points(e)
    for k, top_ins in enumerate(doc.modelspace()):
        m = inner_ins.matrix44() @ mid_ins.matrix44() @ top_ins.matrix44()
        expected = [(q.x, q.y) for q in m.transform_vertices(inner_pts)]
        ours = shapely.MultiLineString([shapely.LineString(sample(e, 2048)) for e in d.edges
                                        if e.src.block == "TOP/MID/INNER"])
        dist = shapely.distance(shapely.points(expected), ours)
        assert dist.max() < 1e-4, k


def _entity_points(e, n=50):
    """Points (block coordinates) on LINE / ARC / ELLIPSE ``e``."""
    if e.dxftype() == "LINE":
        return [e.dxf.start, e.dxf.end]
    if e.dxftype() == "ARC":
        return list(e.construction_tool().vertices(
            [e.dxf.start_angle + (e.dxf.end_angle - e.dxf.start_angle) % 360 * k / n for k in range(n + 1)]))
    if e.dxftype() == "ELLIPSE":
        return list(e.vertices([e.dxf.start_param + (e.dxf.end_param - e.dxf.start_param) * k / n
                                for k in range(n + 1)]))
    raise TypeError(e.dxftype())


def test_nested_uniform_mirrored_blocks_match_ezdxf(tmp_path):
    doc = new_doc("R2010")
    inner = doc.blocks.new("INNER", base_point=(1, 0))
    inner.add_arc((2, 2), 1, 10, 200)
    inner.add_lwpolyline([(0, 0, 0.5), (3, 0, 0), (3, 3, 0)], format="xyb")
    inner.add_ellipse((0, 3), (2, 1), 0.5, 0.2, 2.0)
    mid = doc.blocks.new("MID")
    mid.add_blockref("INNER", (10, 0), dxfattribs={"rotation": 30, "xscale": -1, "yscale": 1})
    top = doc.blocks.new("TOP", base_point=(2, 2))
    top.add_blockref("MID", (0, 5), dxfattribs={"xscale": 2, "yscale": -2, "rotation": 15})
    doc.modelspace().add_blockref("TOP", (100, 50), dxfattribs={"rotation": -40, "xscale": 3,
                                                                "yscale": 3})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    assert sum(isinstance(e, ArcEdge) for e in d.edges) == 2   # true arcs survive
    assert_same_geometry(p, d, tol=5e-3)


def test_uniformly_scaled_mirrored_block_keeps_true_arcs(tmp_path):
    doc = new_doc("R2010")
    b = doc.blocks.new("B")
    b.add_arc((0, 0), 5, 0, 90)
    b.add_circle((10, 0), 2)
    doc.modelspace().add_blockref("B", (0, 0), dxfattribs={"xscale": -2, "yscale": 2, "rotation": 10})
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    assert all(isinstance(e, ArcEdge) for e in d.edges)
    arc = next(e for e in d.edges if abs(e.sweep) < 360)
    assert arc.radius == pytest.approx(10) and arc.sweep == pytest.approx(-90)  # mirrored: clockwise
    assert_same_geometry(p, d)


def test_minsert_grid_and_attribs(tmp_path):
    doc = new_doc("R2010")
    b = doc.blocks.new("CELL")
    b.add_lwpolyline([(0, 0), (5, 0), (5, 5), (0, 5)], close=True)
    b.add_attdef("TAG", (0, 0))
    msp = doc.modelspace()
    ins = msp.add_blockref("CELL", (0, 0), dxfattribs={"rotation": 90})
    ins.dxf.row_count, ins.dxf.column_count = 2, 3
    ins.dxf.row_spacing, ins.dxf.column_spacing = 10, 20
    ins2 = msp.add_blockref("CELL", (200, 0))
    ins2.add_attrib("TAG", "part-7", (201, 1))
    p = save(doc, tmp_path)
    d = read_drawing(p, RAW)
    assert len(d.edges) == 4 * (6 + 1)
    # the grid turns with the insert: columns run along +Y, rows along -X
    xs = sorted({round(e.start[0], 6) for e in d.edges if e.start[0] < 100})
    ys = sorted({round(e.start[1], 6) for e in d.edges if e.start[0] < 100})
    assert xs == [-15.0, -10.0, -5.0, 0.0] and ys == [0.0, 5.0, 20.0, 25.0, 40.0, 45.0]
    (t,) = d.texts
    assert t.text == "part-7" and t.position == pytest.approx((201, 1)) and t.src.dxftype == "ATTRIB"
    assert any("ATTDEF" in f.message for f in d.findings)
    assert_same_geometry(p, d)


def test_minsert_with_zero_column_count_reads_as_one_column(tmp_path):
    doc = new_doc("R2010")
    doc.blocks.new("CELL").add_line((0, 0), (5, 0))
    zero = doc.modelspace().add_blockref("CELL", (500, 0))
    zero.dxf.row_count, zero.dxf.column_count = 2, 0
    zero.dxf.row_spacing, zero.dxf.column_spacing = 10, 20
    p = save(doc, tmp_path)
    # ezdxf does not write a column count of 0 (seen in the wild): patch it in
    text = open(p).read()
    marker = "AcDbMInsertBlock\n  2\nCELL\n 10\n500.0\n 20\n0.0\n 30\n0.0\n"
    assert marker in text
    open(p, "w").write(text.replace(marker, marker + " 70\n0\n"))
    assert ezdxf.readfile(p).modelspace()[0].dxf.column_count == 0
    d = read_drawing(p, RAW)
    assert sorted((e.start, e.end) for e in d.edges) == [((500.0, 0.0), (505.0, 0.0)),
                                                         ((500.0, 10.0), (505.0, 10.0))]
    assert any(f.code == "minsert-zero-count" for f in d.findings)


def test_3d_and_infinite_entities_skipped_with_handles_and_not_in_extents(tmp_path):
    doc = new_doc("R2010")
    msp = doc.modelspace()
    msp.add_line((0, 0), (10, 10))
    face = msp.add_3dface([(0, 0, 0), (1, 0, 1), (1, 1, 2)])
    xl = msp.add_xline((0, 0), (1, 1))
    ray = msp.add_ray((5, 5), (1, 0))
    hatch = msp.add_hatch()
    hatch.paths.add_polyline_path([(0, 0), (1, 0), (1, 1)])
    d = read_drawing(save(doc, tmp_path), RAW)
    assert len(d.edges) == 1
    assert d.stats["bbox_mm"] == pytest.approx([0, 0, 10, 10])
    msgs = " | ".join(f.message for f in d.findings if f.code == "skipped-entity")
    for ent, kind in ((face, "3DFACE"), (xl, "XLINE"), (ray, "RAY"), (hatch, "HATCH")):
        assert f"{kind} #{ent.dxf.handle}" in msgs
    reasons = {s["type"]: s["reason"] for s in d.stats["skipped"]}
    assert "3-D" in reasons["3DFACE"] and "infinite" in reasons["XLINE"]


def test_paper_space_ignored_with_note(tmp_path):
    doc = new_doc("R2010")
    doc.modelspace().add_line((0, 0), (1, 0))
    doc.layout("Layout1").add_line((0, 0), (100, 100))
    doc.layout("Layout1").add_circle((0, 0), 3)
    d = read_drawing(save(doc, tmp_path), RAW)
    assert len(d.edges) == 1
    assert d.stats["paper_space_ignored"] == {"Layout1": 2}
    assert any(f.code == "paper-space-ignored" and "Layout1" in f.message for f in d.findings)


def test_unreferenced_blocks_are_not_imported(tmp_path):
    doc = new_doc("R2010")
    doc.blocks.new("ARROW").add_line((0, 0), (1000, 1000))
    doc.modelspace().add_line((0, 0), (1, 0))
    d = read_drawing(save(doc, tmp_path), RAW)
    assert len(d.edges) == 1 and d.stats["blocks"] == []


def test_progress_is_reported_and_can_cancel(tmp_path):
    from LeatherCutWorkbench.core.errors import CancelledError

    doc = new_doc("R2010")
    for i in range(3000):
        doc.modelspace().add_line((i, 0), (i, 1))
    p = save(doc, tmp_path)
    seen = []
    read_drawing(p, RAW, progress=lambda f, m: seen.append(f) or True)
    assert seen[0] == 0.0 and seen[-1] == 1.0 and len(seen) >= 6
    assert seen == sorted(seen)
    steps = []
    read_drawing(p, progress=lambda f, m: steps.append((f, m)) or True)
    assert [f for f, _ in steps] == sorted(f for f, _ in steps)
    assert any(m.startswith("clean-up") and 0.8 <= f <= 0.95 for f, m in steps)
    with pytest.raises(CancelledError):
        read_drawing(p, RAW, progress=lambda f, m: f < 0.5)


def test_cached_block_instances_equal_entity_by_entity_conversion(tmp_path):
    """A block used many times is converted once and mapped per INSERT; the
    result must equal converting each instance from its own block copy."""
    import random

    def build(shared):
        doc = new_doc("R2010")
        rnd = random.Random(7)
        for k in range(12):
            name = "P" if shared else f"P{k}"
            if name not in doc.blocks:
                b = doc.blocks.new(name, base_point=(1, 2))
                b.add_line((0, 0), (10, 0), dxfattribs={"layer": "0", "color": 0})
                b.add_arc((5, 5), 3, 20, 250, dxfattribs={"extrusion": (0, 0, -1)})
                b.add_lwpolyline([(0, 0, 0.3), (8, 0, 0), (8, 6, -0.6)], format="xyb", close=True)
                b.add_ellipse((3, 3), (2, 1), 0.4, 0.5, 5.0)
                b.add_open_spline([(0, 0), (3, 4), (6, -2), (9, 1)])
                b.add_point((4, 4), dxfattribs={"layer": "DRILL"})
                b.add_text("T", dxfattribs={"insert": (1, 1), "height": 2})
                b.add_3dface([(0, 0, 0), (1, 0, 1), (1, 1, 2)])
            doc.modelspace().add_blockref(name, (rnd.uniform(0, 100), rnd.uniform(0, 100)), dxfattribs={
                "rotation": rnd.uniform(0, 360), "xscale": rnd.choice((1, -1, 2)),
                "yscale": rnd.choice((1, 0.5, -1)), "layer": f"L{k % 3}", "color": k % 5})
        return read_drawing(save(doc, tmp_path, f"s{int(shared)}.dxf"), RAW)

    shared, single = build(True), build(False)
    from LeatherCutWorkbench.core.dxfimport import blocks
    assert blocks.compile_block(ezdxf.readfile(str(tmp_path / "s1.dxf")).blocks["P"]) is not None

    def norm(d):
        out = []
        for e in d.edges:
            pts = [tuple(round(c, 9) for c in p) for p in sample(e, 8)]
            out.append((type(e).__name__, e.src.layer, e.src.color, e.src.role, pts))
        return out

    assert norm(shared) == norm(single)
    assert [(m.position, m.kind, m.src.layer) for m in shared.marks] == \
        [(m.position, m.kind, m.src.layer) for m in single.marks]
    assert [(t.text, t.position, t.height) for t in shared.texts] == \
        [(t.text, t.position, t.height) for t in single.texts]
    assert shared.stats["entities_after_explosion"] == single.stats["entities_after_explosion"]
    assert shared.stats["skipped"] == single.stats["skipped"] and shared.stats["skipped"][0]["count"] == 12
