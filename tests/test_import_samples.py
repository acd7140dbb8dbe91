"""DXF import of every real sample in tests/data/samples (sources and licences
in tests/data/samples/README.md): each imports with real counts or is refused."""

import os
from collections import Counter, defaultdict

import pytest

from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing
from LeatherCutWorkbench.core.model import ArcEdge, EllipseEdge, SplineEdge

SAMPLES = os.path.join(os.path.dirname(__file__), "data", "samples")


def sample(name):
    return os.path.join(SAMPLES, name)


def test_every_sample_imports_or_is_refused_clearly():
    names = sorted(n for n in os.listdir(SAMPLES) if n.lower().endswith(".dxf"))
    assert len(names) == 8
    for n in names:
        d = read_drawing(sample(n))
        assert d.edges, n
        assert d.stats["bbox_mm"] is not None


def test_doppelte_linien_every_line_twice():
    d = read_drawing(sample("dxf2gcode_1997_simplified_doppelte_linien.dxf"))
    assert d.stats["entities_found"] == {"LINE": 908}
    assert d.stats["cleanup"]["duplicates_removed"] == 454
    assert d.stats["cleanup"]["edges_after"] == 454 and len(d.edges) == 454
    assert {e.src.layer for e in d.edges} == {" 1"}   # leading space kept
    # the file has no HEADER section: ezdxf's default $INSUNITS (6, metres) is not
    # the file's statement, so mm is assumed (a 51 mm drawing) with a warning
    assert d.units == "mm" and d.units_source == "assumed"
    assert any(f.code == "units-missing" for f in d.findings)
    mm = read_drawing(sample("dxf2gcode_1997_simplified_doppelte_linien.dxf"), ImportOptions(units="mm"))
    assert 45 < mm.stats["size_mm"][0] < 60
    # every end point is shared by exactly two lines: closed loops only
    deg = Counter()
    for e in mm.edges:
        deg[(round(e.start[0], 6), round(e.start[1], 6))] += 1
        deg[(round(e.end[0], 6), round(e.end[1], 6))] += 1
    assert set(deg.values()) == {2}


def test_recover01_is_repaired_and_cleaned():
    d = read_drawing(sample("ezdxf_recover01.dxf"))
    f = d.stats["file"]
    assert f["recovered"] and f["recover_fixes"] == 68
    assert any(x.code == "recovered" and "68 fixes" in x.message for x in d.findings)
    assert d.stats["entities_found"] == {"LINE": 1441, "TEXT": 63}
    c = d.stats["cleanup"]
    # 238 bit-identical duplicates (either direction) + 1 equal on the 0.01 mm grid
    assert c["duplicates_removed"] == 239
    # 18 lines with identical end points + 2 shorter than 1e-6 mm
    assert c["zero_length_removed"] == 20
    assert c["overlaps_removed"] > 0 and c["t_junction_splits"] > 0
    assert len(d.texts) == 63


def test_deepnest_needs_recover_and_keeps_arcs():
    d = read_drawing(sample("deepnest_ReadMeExampleSmall.dxf"))
    assert d.stats["file"]["recovered"]
    assert d.stats["entities_found"] == {"ARC": 405, "CIRCLE": 13, "LINE": 254, "POLYLINE": 1}
    assert sum(isinstance(e, ArcEdge) for e in d.edges) == 418
    assert d.units_source == "assumed"


def test_binary_kitchen_sink():
    d = read_drawing(sample("acadsharp_sample_AC1015_binary.dxf"))
    s = d.stats
    assert s["file"]["binary"] and s["dxf_version"] == "AC1015"
    assert d.units == "inch" and s["units"]["mm_per_unit"] == 25.4
    kinds = Counter(type(e) for e in d.edges)
    assert kinds[SplineEdge] == 2 and kinds[EllipseEdge] == 1 and kinds[ArcEdge] >= 9
    skipped = {x["type"] for x in s["skipped"]}
    assert {"3DFACE", "3DSOLID", "REGION", "MESH", "HATCH", "XLINE", "RAY", "MLINE", "WIPEOUT",
            "IMAGE", "MULTILEADER", "DIMENSION"} <= skipped
    # every skipped entity is named by handle in a finding (or counted in a summary)
    named = sum(1 for f in d.findings if f.code == "skipped-entity" and "#" in f.message)
    assert named == len(s["skipped_entities"]) > 40
    assert s["paper_space_ignored"] == {}   # its layouts hold only viewports
    assert len(d.marks) == 6 and len(d.texts) >= 34
    assert any(t.src.dxftype == "ATTRIB" for t in d.texts)


def test_nested_blocks_sample_matches_ezdxf_extents():
    d = read_drawing(sample("dxf2gcode_Bogen_Ellipsen_Polylinien_Block.dxf"))
    assert d.stats["entities_found"] == {"INSERT": 15}
    assert sum(b["inserts"] for b in d.stats["blocks"]) == 120
    assert d.stats["cleanup"]["duplicates_removed"] == 28
    # ezdxf.bbox.extents on this file: (-279.7186, -352.1538) .. (1166.9520, 847.1538) inch
    assert [v / 25.4 for v in d.stats["bbox_mm"]] == pytest.approx(
        [-279.7186489, -352.1537527, 1166.9519649, 847.1537526], abs=1e-3)
    assert any(isinstance(e, EllipseEdge) for e in d.edges)


def test_visicut_lines_and_t_junctions():
    d = read_drawing(sample("visicut_6_HG2_Korpusinnen_2.dxf"))
    assert d.stats["entities_found"] == {"LINE": 855}
    assert 440 < d.stats["size_mm"][0] < 460 and 280 < d.stats["size_mm"][1] < 290
    assert d.stats["cleanup"]["t_junction_splits"] > 0
    raw = read_drawing(sample("visicut_6_HG2_Korpusinnen_2.dxf"), ImportOptions(cleanup=False))
    assert len(raw.edges) == 855 and raw.stats["cleanup"] is None


def _loops(edges, ndigits=3):
    """Connected components of the end-point graph and whether every vertex has degree 2."""
    adj = defaultdict(list)
    for i, e in enumerate(edges):
        a = (round(e.start[0], ndigits), round(e.start[1], ndigits))
        b = (round(e.end[0], ndigits), round(e.end[1], ndigits))
        adj[a].append(b)
        adj[b].append(a)
    seen, comps = set(), 0
    for v in adj:
        if v in seen:
            continue
        comps += 1
        stack = [v]
        while stack:
            u = stack.pop()
            if u not in seen:
                seen.add(u)
                stack.extend(adj[u])
    return comps, all(len(n) == 2 for n in adj.values())


def test_gmx_aama_pieces():
    d = read_drawing(sample("GMX1016S18_AAMA.DXF"))
    assert d.stats["pattern"] == "aama"
    assert (d.units, d.units_source) == ("mm", "aama-text")
    assert d.stats["join_tolerance_hint_mm"] == pytest.approx(0.152)
    assert len(d.pieces) == 150
    names = Counter(p.name for p in d.pieces.values())
    assert len(names) == 10 and set(names.values()) == {15}
    sizes = {p.size for p in d.pieces.values()}
    assert len(sizes) == 15 and "42" in sizes
    p = d.pieces["GMX1016S18FR_42"]
    assert p.name == "GMX1016S18FR" and p.size == "42" and p.quantity == 1
    assert p.grain_angle is not None and 0 <= p.grain_angle < 180
    # roles by AAMA layer
    by_role = Counter(e.src.role for e in d.edges)
    assert by_role["grain"] == 150 and by_role["mirror"] == 45
    kinds = Counter(m.kind for m in d.marks)
    assert kinds["notch"] == 31 and kinds["drill"] == 15
    assert sum(1 for x in d.pieces.values() if x.mirror_line) == 45
    # every piece's cut edges chain into exactly one closed loop
    for key, piece in d.pieces.items():
        cut = [d.edges[i] for i in piece.edges if d.edges[i].src.role == "cut"]
        assert all(e.src.piece == key for e in cut)
        comps, closed = _loops(cut)
        assert (comps, closed) == (1, True), key
    # nothing was merged across the 15 stacked sizes: boundary length per piece kept
    raw = read_drawing(sample("GMX1016S18_AAMA.DXF"), ImportOptions(cleanup=False))
    assert len({e.src.piece for e in raw.edges if e.src.role == "cut"}) == 150
    assert d.stats["cleanup"]["duplicates_removed"] == 0


def test_wm_slim_tank_english_units_and_half_pieces():
    d = read_drawing(sample("WM_SLIM_TANK.DXF"))
    assert (d.units, d.units_source) == ("inch", "aama-text")
    assert d.stats["join_tolerance_hint_mm"] == pytest.approx(0.006 * 25.4)
    assert len(d.pieces) == 28
    assert {p.name for p in d.pieces.values()} == {"TANK_SR_BK", "TANK_SR_FR"} or \
        len({p.name for p in d.pieces.values()}) == 2
    assert all(p.mirror_line is not None for p in d.pieces.values())
    assert sum(1 for e in d.edges if e.src.role == "cut" and e.src.dxftype == "POLYLINE") > 168
    assert 1300 < d.stats["size_mm"][0] < 1450      # ~54 inch
