"""Hides as a leather cutter needs them: the jagua-rs bin-packing JSON
(Baldacci hides with holes and quality zones), hides used and utilisation per
hide, grain tolerance, and remnants that the next nest reads back."""

import json
import os

import ezdxf
from shapely.geometry import Polygon

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting import read_hide_dxf
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.options import parse_rotations

from nest_shapes import rect
from test_nest_cli import run_json

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def test_bin_packing_json_snake_case_bins_zones_and_stock(tmp_path):
    sq = [[0, 0], [100, 0], [100, 100], [0, 100]]
    inst = {"name": "t", "items": [
        {"id": 0, "demand": 2, "min_quality": 1,
         "shape": {"type": "simple_polygon", "data": [[0, 0], [30, 0], [30, 20], [0, 20]]}},
        {"id": 1, "demand": 1, "shape": {"type": "simple_polygon",
                                         "data": [[0, 0], [10, 0], [10, 10], [0, 10]]}}],
        "bins": [{"id": 7, "stock": 2, "cost": 1,
                  "shape": {"type": "polygon", "data": {"outer": sq, "inner": [
                      [[40, 40], [50, 40], [50, 50], [40, 50]]]}},
                  "zones": [{"quality": 1, "shape": {"type": "simple_polygon",
                                                     "data": [[0, 0], [50, 0], [50, 30], [0, 30]]}},
                            {"quality": 0, "shape": {"type": "simple_polygon",
                                                     "data": [[80, 80], [90, 80], [90, 90]]}}]}]}
    path = tmp_path / "bins.json"
    path.write_text(json.dumps(inst))
    got = read_esicup(str(path))
    assert got.strip_height is None
    assert [h.id for h in got.hides] == ["bin7_1", "bin7_2"]
    h = got.hides[0]
    assert h.base_grade == 2 and len(h.defects) == 2 and [g for g, _ in h.zones] == [1]
    assert [p.grade for p in got.parts] == [1, 2]      # no min_quality = full quality


def test_baldacci_test1_hides_run_directly_and_respect_quality(capsys):
    path = os.path.join(DATA, "Test1_first2hides.json")
    inst = read_esicup(path)
    d = run_json(capsys, "--esicup", path, "--time", "8", "--workers", "1")
    m = d["metrics"]
    assert m["checked"] and m["hides_available"] == 2 and 1 <= m["hides"] <= 2
    assert m["placed_count"] >= 1       # how many fit in 8 s depends on the load
    for c in d["containers"]:
        assert 0.3 < c["utilisation"] < 1.0
    # items without min_quality need full quality (2): never on a quality-1 zone
    for g in m["grades"]:
        assert g["material_grade"] >= g["part_grade"]
    assert any(g["part_grade"] == 2 for g in m["grades"])
    lay = [p for p in d["placements"]]
    assert len(lay) == m["placed_count"]
    assert sum(p.quantity for p in inst.parts) == m["placed_count"] + m["unplaced_count"]


def test_grain_tolerance_rotations_stay_within_the_tolerance():
    rots, _ = parse_rotations("0+-5")
    assert rots == [0.0, 2.5, 5.0, 355.0, 357.5]
    parts = [rect("a", 50, 10, q=6)]
    opts = NestOptions(container=ContainerSpec.sheet(60, 80), rotations_override=rots,
                       time_budget=1, workers=1)
    lay = nest(parts, opts)
    assert check_layout(parts, lay, rotations_override=rots) == []
    assert lay.unplaced == []
    assert {p.angle for p in lay.placements} <= set(rots)


def _hide(path):
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    for n in ("HIDE", "DEFECT", "ZONE_3"):
        doc.layers.add(n)
    msp.add_lwpolyline([(0, 0), (300, 0), (300, 200), (0, 200)], close=True, dxfattribs={"layer": "HIDE"})
    msp.add_lwpolyline([(250, 150), (270, 150), (270, 170), (250, 170)], close=True,
                       dxfattribs={"layer": "DEFECT"})
    msp.add_lwpolyline([(200, 0), (300, 0), (300, 100), (200, 100)], close=True,
                       dxfattribs={"layer": "ZONE_3"})
    doc.saveas(path)


def _parts(path):
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    for k in range(3):
        msp.add_lwpolyline([(k * 100, 0), (k * 100 + 80, 0), (k * 100 + 80, 60), (k * 100, 60)], close=True)
    doc.saveas(path)


def test_remnant_is_a_hide_the_next_nest_reads(capsys, tmp_path):
    hide, parts, rem, l1, l2 = (str(tmp_path / n) for n in
                                ("hide.dxf", "parts.dxf", "rem.dxf", "l1.json", "l2.json"))
    _hide(hide)
    _parts(parts)
    d1 = run_json(capsys, parts, "--hide", hide, "--spacing", "2", "--time", "3", "--workers", "1",
              "--remnant-out", rem, "--layout-out", l1)
    assert d1["outputs"]["remnant"] == rem and d1["unplaced"] == []
    hides = read_hide_dxf(rem)
    assert hides and hides[0].base_grade == 1
    r = Polygon(hides[0].outline)
    used = 3 * 80 * 60
    assert r.area < 300 * 200 - used + 1e-6
    assert any(len(h.zones) == 1 for h in hides)          # the grade-3 zone is kept (clipped)
    assert sum(len(h.defects) for h in hides) >= 1       # and the defect
    # the next job on the remnant lies where the first job left material
    d2 = run_json(capsys, parts, "--hide", rem, "--time", "1", "--workers", "1", "--layout-out", l2)
    assert d2["metrics"]["checked"] and d2["metrics"]["placed_count"] >= 1
    first = [Polygon(i["polygon"]) for i in json.load(open(l1))["items"]]
    second = [Polygon(i["polygon"]) for i in json.load(open(l2))["items"]]
    for a in second:
        assert all(a.intersection(b).area < 1e-6 for b in first)


def test_a_best_layout_that_fails_the_final_check_gives_way_to_a_valid_earlier_one(monkeypatch):
    """Fault injected around the real search (Test6 hide o_0, 7 copies, one
    worker): after it, a corrupted copy of its best layout -- one copy moved
    far off the hide -- is reported as a better one.  The final check finds
    it; instead of taking that copy out (the safety net), the engine keeps
    the search's own valid layout and says so."""
    from dataclasses import replace
    from LeatherCutWorkbench.core.nesting import engine
    real = engine.search
    injected = []

    def search_then_corrupt(problem, copies, seed, worker, budget):
        res = real(problem, copies, seed, worker, budget)
        cost, order, placements, _evals = res
        bad = list(placements)
        k = next(i for i, p in enumerate(bad) if p[1] >= 0)
        si, b, vi, x, y = bad[k]
        bad[k] = (si, b, vi, x - 10 ** 9, y)              # far off the hide
        injected.append(sum(p[1] >= 0 for p in placements))     # the search's own, placed
        budget.improved((0.0,) + tuple(0 for _ in cost[1:]), order, bad)
        return res

    monkeypatch.setattr(engine, "search", search_then_corrupt)
    inst = read_esicup(os.path.join(os.path.dirname(__file__), "data", "nest",
                                    "Test6_items2_10_22_29_hide0.json"))
    full = inst.hides[0].base_grade
    parts = [replace(p, grade=full, grade_regions=[]) for p in inst.parts]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=3, workers=1,
                       rotations_override=[0.0, 90.0, 180.0, 270.0])
    lay = nest(parts, opts)
    assert injected
    codes = [f.code for f in lay.findings]
    assert "invalid-layout-replaced" in codes and "invalid-placement-removed" not in codes
    assert check_layout(parts, lay, rotations_override=[0.0, 90.0, 180.0, 270.0]) == []
    assert lay.metrics["placed_count"] == injected[0]      # the search's own layout, whole
