"""The optional sparrow engine (spyrrow in a child process) and the ESICUP reader."""

import json
import os

import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest, parse_rotations
from LeatherCutWorkbench.core.nesting.esicup import read_esicup

from nest_shapes import rect, ring

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
spyrrow = pytest.importorskip("spyrrow")


@pytest.mark.slow
def test_sparrow_strip_is_valid_and_checked():
    inst = read_esicup(os.path.join(DATA, "fu.json"))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=2,
                       engine="sparrow", seed=42, workers=1)
    lay = nest(inst.parts, opts)
    assert lay.metrics["engine"] == "sparrow" and lay.metrics["checked"]
    assert len(lay.placements) == 12 and lay.unplaced == []
    assert check_layout(inst.parts, lay) == []
    assert lay.metrics["density"] > 0.8


@pytest.mark.slow
def test_sparrow_spacing_margin_and_holes_note():
    parts = [rect("a", 30, 20, q=4), ring("r", 15, 8, q=2)]
    opts = NestOptions(container=ContainerSpec.strip(60), spacing=2, margin=3, time_budget=1,
                       engine="sparrow", seed=1, workers=1)
    lay = nest(parts, opts)
    assert check_layout(parts, lay, spacing=2, margin=3) == []
    assert len(lay.placements) == 6
    assert any(f.code == "sparrow-no-holes" for f in lay.findings)


def test_esicup_reader(tmp_path):
    inst = read_esicup(os.path.join(DATA, "shirts.json"))
    assert inst.strip_height == 40 and len(inst.parts) == 8
    assert sum(p.quantity for p in inst.parts) == 99
    assert inst.item_area == pytest.approx(2160, rel=1e-9)
    assert all(p.rotations == [0.0, 180.0] for p in inst.parts)
    assert all(p.outer.area > 0 for p in inst.parts)
    f = tmp_path / "free.json"
    f.write_text(json.dumps({"strip_height": 10, "items": [
        {"id": 0, "demand": 2, "shape": {"type": "rectangle", "data": {"x_min": 0, "y_min": 0,
                                                                      "width": 3, "height": 2}}},
        {"id": 1, "demand": 1, "shape": {"type": "polygon", "data": {
            "outer": [[0, 0], [6, 0], [6, 6], [0, 6]], "inner": [[[1, 1], [5, 1], [5, 5], [1, 5]]]}}}]}))
    inst = read_esicup(str(f))
    assert inst.parts[0].rotations is None and inst.parts[0].quantity == 2
    assert len(inst.parts[1].holes) == 1 and inst.parts[1].holes[0].area < 0
    f.write_text(json.dumps({"strip_height": 10, "items": [{"id": 7, "shape": {"type": "circle"}}]}))
    with pytest.raises(InputError, match="item 7"):
        read_esicup(str(f))


def test_parse_rotations():
    assert parse_rotations("any") == (None, None)
    assert parse_rotations("0, 180") == ([0.0, 180.0], None)
    assert parse_rotations("step:90") == ([0.0, 90.0, 180.0, 270.0], 90.0)
    assert parse_rotations("-90") == ([270.0], None)
    with pytest.raises(InputError):
        parse_rotations("step:0")
