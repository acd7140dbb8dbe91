"""``leathercut nest`` end to end: ESICUP and DXF input, every container kind,
the JSON report, layout JSON / DXF / SVG outputs and bad input."""

import json
import os

import ezdxf
import pytest

from LeatherCutWorkbench.cli import main

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def run_json(capsys, *argv):
    code = main(["nest", *argv, "--json"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out)


def parts_dxf(path):
    doc = ezdxf.new(units=4)          # mm
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (80, 0), (80, 50), (0, 50)], close=True)
    msp.add_lwpolyline([(20, 10), (40, 10), (40, 30), (20, 30)], close=True)   # hole of the first
    msp.add_lwpolyline([(100, 0), (160, 0), (160, 15), (115, 15), (115, 40), (100, 40)], close=True)
    msp.add_circle((200, 20), 18)
    doc.saveas(path)


def test_esicup_strip_report_and_outputs(capsys, tmp_path):
    lay, dxf, svg = (str(tmp_path / n) for n in ("lay.json", "out.dxf", "pic.svg"))
    d = run_json(capsys, "--esicup", os.path.join(DATA, "shapes0.json"), "--time", "1",
                 "--workers", "1", "--layout-out", lay, "--dxf-out", dxf, "--svg-out", svg)
    m = d["metrics"]
    assert d["container"] == {"kind": "strip", "width_mm": 40.004}
    assert m["placed_count"] == 43 and d["unplaced"] == [] and m["checked"] is True
    assert 0.5 < m["density"] < 0.75
    assert len(d["placements"]) == 43
    assert set(d["placements"][0]) == {"part", "copy", "container", "x", "y", "angle", "mirrored"}
    assert d["outputs"] == {"layout": lay, "dxf": dxf, "svg": svg}
    L = json.load(open(lay))
    assert set(L) == {"containers", "items"}
    assert L["containers"][0]["id"] == "strip" and L["containers"][0]["defects"] == []
    it = L["items"][0]
    assert {"part", "copy", "container", "angle", "mirrored", "polygon", "holes"} <= set(it)
    xs = [x for i in L["items"] for x, _ in i["polygon"]]
    ys = [y for i in L["items"] for _, y in i["polygon"]]
    assert min(xs) >= -1e-3 and max(xs) <= m["strip_length_mm"] + 1e-3  # checker tolerance
    assert min(ys) >= -1e-3 and max(ys) <= 40.004 + 1e-3
    doc = ezdxf.readfile(dxf)
    assert len(doc.modelspace().query("LWPOLYLINE[layer=='PARTS']")) == 43   # one per contour
    assert open(svg).read().startswith("<svg")


def test_dxf_parts_on_sheets_with_rotations_and_copies(capsys, tmp_path):
    src = str(tmp_path / "parts.dxf")
    parts_dxf(src)
    d = run_json(capsys, src, "--sheet", "200x120", "--copies", "3", "--spacing", "2",
                 "--margin", "5", "--rotations", "0,90", "--time", "1",
                 "--workers", "1")
    assert d["container"]["kind"] == "sheet"
    assert d["metrics"]["placed_count"] + len(d["unplaced"]) == 9
    assert d["metrics"]["unplaced_count"] == len(d["unplaced"])
    assert all(p["angle"] in (0.0, 90.0) for p in d["placements"])
    assert d["metrics"]["utilisation"] > 0
    assert [c["id"] for c in d["containers"]] == [f"sheet{i + 1}" for i in range(d["metrics"]["sheets"])]


def test_dxf_parts_on_a_hide(capsys, tmp_path):
    src, hide = str(tmp_path / "parts.dxf"), str(tmp_path / "hide.dxf")
    parts_dxf(src)
    doc = ezdxf.new(units=4)          # mm
    msp = doc.modelspace()
    msp.add_ellipse((300, 200), major_axis=(300, 0), ratio=0.7, dxfattribs={"layer": "HIDE"})
    msp.add_circle((300, 200), 25, dxfattribs={"layer": "DEFECT"})
    doc.saveas(hide)
    d = run_json(capsys, src, "--hide", hide, "--copies", "4", "--time", "1", "--workers", "1",
                 "--margin", "3")
    assert d["container"] == {"kind": "hide", "hides": ["hide1"]}
    assert d["metrics"]["placed_count"] == 12
    c = d["containers"][0]
    assert c["defects"] == 1 and c["utilisation"] > c["utilisation_gross"] > 0


def test_bad_input_exits_2(capsys, tmp_path):
    assert main(["nest", str(tmp_path / "missing.dxf"), "--sheet", "100x100"]) == 2
    assert "no such file" in capsys.readouterr().err
    assert main(["nest", "--esicup", str(tmp_path / "missing.json")]) == 2
    bad = tmp_path / "bad.json"
    bad.write_text('{"items": []}')
    assert main(["nest", "--esicup", str(bad)]) == 2
    assert "strip_height" in capsys.readouterr().err
    src = str(tmp_path / "parts.dxf")
    parts_dxf(src)
    assert main(["nest", src]) == 2
    assert "no container" in capsys.readouterr().err
    assert main(["nest", src, "--strip", "100", "--rotations", "sideways"]) == 2
    assert "bad --rotations" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["nest", src, "--sheet", "100by100"])


def test_run_nests_when_a_container_is_given(capsys, tmp_path):
    src = str(tmp_path / "parts.dxf")
    parts_dxf(src)
    out = tmp_path / "job"
    code = main(["run", src, "-o", str(out), "--sheet", "300x200", "--nest-time", "0.5",
                 "--nest-workers", "1", "--spacing", "2"])
    assert code == 0, capsys.readouterr().err
    rep = json.load(open(out / "report.json"))
    n = rep["nesting"]
    assert n["placed"] == 3 and n["unplaced"] == [] and n["containers"] == ["sheet1"]
    assert n["checked"] is True and 0 < n["utilisation"] < 1
