"""Mirrored and rotated block inserts through the real importer (ezdxf-written DXF)."""

import math

import pytest

ezdxf = pytest.importorskip("ezdxf")
dxfimport = pytest.importorskip("LeatherCutWorkbench.core.dxfimport")

from LeatherCutWorkbench.core.geometry import ArcSeg  # noqa: E402
from LeatherCutWorkbench.core.recognition import recognise  # noqa: E402
from LeatherCutWorkbench.core.recognition.from_part import signed_path_area  # noqa: E402


def test_mirrored_block_inserts_give_equal_ccw_parts(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    blk = doc.blocks.new("TAB")
    # 30 x 20 tab with two rounded corners (bulges) and a 3 mm lead-in
    blk.add_lwpolyline([(0, 0, 0), (26, 0, 0.41421356), (30, 4, 0), (30, 20, 0),
                        (4, 20, 0.41421356), (0, 16, 0)], format="xyb", close=True)
    blk.add_circle((15, 10), 4)
    blk.add_line((10, -3), (10, 0))
    msp = doc.modelspace()
    msp.add_blockref("TAB", (0, 0))
    msp.add_blockref("TAB", (100, 0), dxfattribs={"xscale": -1})
    msp.add_blockref("TAB", (200, 0), dxfattribs={"rotation": 90})
    path = tmp_path / "tabs.dxf"
    doc.saveas(path)

    rec = recognise(dxfimport.read_drawing(str(path)))
    assert len(rec.parts) == 3 and not rec.flags and not rec.open_chains
    expect = 30 * 20 - 2 * (16 - 4 * math.pi) - math.pi * 16
    for p in rec.parts:
        outer = signed_path_area(p.outer.segments)
        hole = signed_path_area(p.holes[0].segments)
        assert outer > 0 and hole < 0                       # outer CCW, hole CW
        assert outer + hole == pytest.approx(expect, rel=1e-6)
        assert sum(isinstance(s, ArcSeg) for s in p.outer.segments) == 2
        (li,) = p.lead_ins
        assert li.length == pytest.approx(3.0)
    mirrored = next(p for p in rec.parts if p.outer.bbox[2] <= 100.0 + 1e-6
                    and p.outer.bbox[0] >= 70.0 - 1e-6)
    assert mirrored.outer.bbox == pytest.approx((70, 0, 100, 20), abs=1e-6)
    assert mirrored.lead_ins[0].start == pytest.approx((90.0, -3.0))


def test_cases_fixture_gives_the_documented_result(data_dir):
    import os

    rec = recognise(dxfimport.read_drawing(os.path.join(data_dir, "recognise", "cases.dxf")))
    assert len(rec.parts) == 15 and len(rec.active_parts()) == 14
    assert sum(len(p.holes) for p in rec.parts) == 2
    leads = sorted((tuple(round(v, 6) for v in li.start), li.role)
                   for p in rec.parts for li in p.lead_ins)
    assert leads == [((5.0, -3.0), "lead_in"), ((62.0, -3.0), "lead_in")]
    assert len(rec.open_chains) == 2
    assert sorted(f.kind for f in rec.flags) == ["over", "under"]
    scrap = next(p for p in rec.parts if p.excluded)
    assert scrap.outer.bbox == pytest.approx((130, 10, 140, 20))
    grid = [p for p in rec.parts if 170 <= p.outer.bbox[0] < 200]
    assert len(grid) == 6 and all(p.outer.shared for p in grid)
    island = next(p for p in rec.parts if p.outer.bbox[0] == pytest.approx(320))
    frame = next(p for p in rec.parts if p.outer.bbox[0] == pytest.approx(300))
    assert island.parent_id == frame.id and len(frame.holes) == 1
