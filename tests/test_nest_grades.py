"""Grades reach the parts: from a DXF grade text or layer, from ``--grade``,
and the hide report says on which material grade every copy lies."""


import ezdxf
import pytest

from LeatherCutWorkbench.cli import main
from LeatherCutWorkbench.core.dxfimport.grades import grade_of_layer, grade_of_text, parse_grade
from LeatherCutWorkbench.core.errors import InputError

from nest_shapes import write_hide_dxf
from test_nest_cli import run_json


def test_grade_texts_layers_and_letters():
    assert grade_of_text("Grade: A") == 4 and grade_of_text("GRADE=b") == 3
    assert grade_of_text("Quality: 2") == 2 and grade_of_text("Qualität: 1") == 1
    assert grade_of_text("Piece Name: vamp") is None and grade_of_text("Grade: Z") is None
    assert grade_of_layer("GRADE_C") == 2 and grade_of_layer("quality_3") == 3
    assert grade_of_layer("PARTS") is None
    assert parse_grade("D") == 1 and parse_grade(5) == 5
    with pytest.raises(InputError):
        parse_grade("best")


def _parts_dxf(path):
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (60, 0), (60, 40), (0, 40)], close=True)            # text: A
    msp.add_text("Grade: A", dxfattribs={"height": 3}).set_placement((10, 20))
    doc.layers.add("GRADE_2")
    msp.add_lwpolyline([(100, 0), (150, 0), (150, 30), (100, 30)], close=True,
                       dxfattribs={"layer": "GRADE_2"})                              # layer: 2
    msp.add_lwpolyline([(200, 0), (240, 0), (240, 30), (200, 30)], close=True)      # none
    doc.saveas(path)


def _hide_dxf(path):
    """A 400 x 200 hide of base grade 1 with a grade-A (4) zone on its left half."""
    write_hide_dxf(path, (400, 200), "HIDE", "ZONE_A", (0, 0, 150, 200))


def test_dxf_grades_and_cli_override_decide_where_parts_lie(capsys, tmp_path):
    src, hide = str(tmp_path / "parts.dxf"), str(tmp_path / "hide.dxf")
    _parts_dxf(src)
    _hide_dxf(hide)
    d = run_json(capsys, src, "--hide", hide, "--time", "3", "--workers", "1")
    found = {f["message"] for f in d["findings"] if f["code"] == "part-grade"}
    assert found == {"part P1: grade 4 from its text", "part P2: grade 2 from its layer"}
    grades = {g["part"]: g for g in d["metrics"]["grades"]}
    assert grades["P1"]["part_grade"] == 4 and grades["P1"]["material_grade"] == 4
    assert grades["P2"]["part_grade"] == 2
    assert grades["P3"]["part_grade"] == 0

    # --grade replaces the drawing's grade: now P3 needs grade A too, P1 nothing
    d = run_json(capsys, src, "--hide", hide, "--time", "3", "--workers", "1",
             "--grade", "P3=A", "--grade", "P1=0")
    grades = {g["part"]: g for g in d["metrics"]["grades"]}
    assert grades["P3"]["part_grade"] == 4 and grades["P3"]["material_grade"] == 4
    assert grades["P1"]["part_grade"] == 0


def test_grade_option_errors_are_one_line(capsys, tmp_path):
    src, hide = str(tmp_path / "parts.dxf"), str(tmp_path / "hide.dxf")
    _parts_dxf(src)
    _hide_dxf(hide)
    assert main(["nest", src, "--hide", hide, "--grade", "P1"]) == 2
    assert "bad --grade" in capsys.readouterr().err
    assert main(["nest", src, "--hide", hide, "--grade", "P1=best"]) == 2
    assert "bad grade" in capsys.readouterr().err
    assert main(["nest", src, "--hide", hide, "--grade", "nope=A", "--time", "0"]) == 2
    assert "names no part" in capsys.readouterr().err
