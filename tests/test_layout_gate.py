"""The layout gate on hand-made layouts (core only), the layout JSON read back,
and run_job refusing / overriding a kept layout."""

import json

import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.job import JobOptions, arrange
from LeatherCutWorkbench.core.layout_gate import gate_layout, layout_findings, readable_area
from LeatherCutWorkbench.core.layout_json import read_layout_json
from LeatherCutWorkbench.core.model import Container, Layout, Placement, Recognition
from LeatherCutWorkbench.core.nesting.containers import rectangle
from LeatherCutWorkbench.core.nesting.options import NestOptions
from LeatherCutWorkbench.core.nesting.outputs import layout_json

from nest_shapes import rect


def sheet(defects=()):
    return Container(id="s", kind="sheet", outline=rectangle(0, 0, 400, 300), defects=list(defects))


def parts():
    return [rect("P1", 220, 200), rect("P2", 100, 100)]


def layout(x2, y2, defects=()):
    return Layout(containers=[sheet(defects)],
                  placements=[Placement("P1", 0, "s", 10, 10), Placement("P2", 0, "s", x2, y2)])


def test_readable_areas():
    assert readable_area(41410.3) == "41 410 mm²"
    assert readable_area(2.414) == "2.41 mm²"
    assert readable_area(1234567.0) == "1 234 567 mm²"


def test_overlap_named_with_a_readable_area():
    (msg,) = layout_findings(parts(), layout(10 + 220 - 100, 10 + 200 - 100))  # P2 inside P1
    assert msg == "P1#0 overlaps P2#0 by 10 000 mm²"


def test_spacing_margin_outside_and_defect():
    assert layout_findings(parts(), layout(232.4, 10), spacing=3.0) == [
        "P1#0 and P2#0 are 2.4 mm apart (spacing 3 mm)"]
    assert layout_findings(parts(), layout(233.0, 10), spacing=3.0) == []
    assert any("margin 5 mm" in m and "P2#0" in m
               for m in layout_findings(parts(), layout(300, 10), margin=5.0))
    out = layout_findings(parts(), layout(350, 10))
    assert len(out) == 1 and out[0] == "P2#0: 5 000 mm² outside container s"
    hole = [(260, 150), (280, 150), (280, 170), (260, 170)]
    (d,) = layout_findings(parts(), layout(250, 100, [hole]))
    assert d.startswith("P2#0: covers defect 0 of s")


def test_gate_refuses_or_logs_the_override():
    bad = layout(232.4, 10)
    with pytest.raises(InputError) as err:
        gate_layout(parts(), bad, spacing=3.0)
    assert "not safe to cut" in str(err.value) and "P1#0 and P2#0" in str(err.value)
    found = gate_layout(parts(), bad, spacing=3.0, allow_invalid=True)
    assert [f.code for f in found] == ["layout-override"] and "P2#0" in found[0].message
    assert gate_layout(parts(), layout(240, 10), spacing=3.0) == []


def test_arrange_gates_a_kept_layout_and_logs_overrides():
    rec = Recognition(parts=parts())
    nest = NestOptions(spacing=3.0)
    with pytest.raises(InputError):
        arrange(rec, JobOptions(nest=nest, layout=layout(232.4, 10)))
    seen = []
    lay, placed, chains = arrange(rec, JobOptions(nest=nest, layout=layout(232.4, 10),
                                                  allow_invalid_layout=True, log=seen.append))
    assert len(placed) == 2 and not chains and len(seen) == 1 and "2.4 mm apart" in seen[0]
    assert [f.code for f in lay.findings] == ["layout-override"]


def test_layout_json_round_trip_and_bad_files(tmp_path):
    path = tmp_path / "l.json"
    path.write_text(json.dumps(layout_json(parts(), layout(240, 10))))
    back = read_layout_json(str(path))
    assert back.placements == layout(240, 10).placements
    assert back.containers[0].outline == [tuple(p) for p in sheet().outline]
    for text, what in (("{", "not a layout JSON"), ('{"items": []}', "'containers' and 'items'"),
                       ('{"containers": [], "items": [{"part": "P1"}]}', "item 0")):
        path.write_text(text)
        with pytest.raises(InputError) as err:
            read_layout_json(str(path))
        assert what in str(err.value) and str(path) in str(err.value)
