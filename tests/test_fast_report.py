"""The fast ``recognise --json`` report gives the same figures and the same
value as the plain code: one-pass contour measures of line-only contours equal
``signed_path_area`` / ``Contour.length`` / ``Contour.bbox`` bit for bit (on
real drawings and on loops with -0.0, tiny and huge coordinates), and the
one-line-per-row JSON text parses to exactly the report ``json.dumps`` gives."""

import io
import json
import random
from pathlib import Path

from LeatherCutWorkbench.cli import _json_default, main
from LeatherCutWorkbench.cli.json_rows import write_rows
from LeatherCutWorkbench.cli.recognise_cmd import _contour_stats, recognition_json
from LeatherCutWorkbench.core.dxfimport import read_drawing
from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.model import Contour
from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise
from LeatherCutWorkbench.core.recognition.from_part import signed_path_area

DATA = Path(__file__).parent / "data"
DRAWINGS = sorted(DATA.glob("**/*.dxf"))


def _plain(c: Contour):
    return abs(signed_path_area(c.segments)), c.length, c.bbox


def _loops():
    rng = random.Random(16)
    for _ in range(200):
        n = rng.randrange(1, 12)
        scale = rng.choice((1e-6, 1.0, 1e3, 1e9))
        pts = [(rng.uniform(-1, 1) * scale, rng.uniform(-1, 1) * scale) for _ in range(n)]
        pts[0] = (-0.0, pts[0][1])
        yield Contour("C1", [LineSeg(pts[i], pts[(i + 1) % n]) for i in range(n)])


def test_line_contour_measures_equal_the_plain_code_bit_for_bit():
    checked = 0
    for c in _loops():
        assert _contour_stats(c) == _plain(c)
        checked += 1
    for path in DRAWINGS:
        rec = recognise(read_drawing(str(path)), RecogniseOptions())
        for p in rec.parts:
            for c in [p.outer] + list(p.holes):
                assert _contour_stats(c) == _plain(c), (path.name, c.id)
                checked += 1
    assert checked > 500


def test_row_text_parses_to_the_same_report_with_one_line_per_part(capsys):
    path = DATA / "recognise" / "cases.dxf"
    data = recognition_json(recognise(read_drawing(str(path)), RecogniseOptions()), str(path))
    out = io.StringIO()
    write_rows(data, out, default=_json_default)
    text = out.getvalue()
    assert json.loads(text) == json.loads(json.dumps(data, indent=2, default=_json_default))
    lines = text.splitlines()
    assert sum(1 for ln in lines if ln.startswith('    {"id": "P')) == len(data["parts"]) > 3
    assert main(["recognise", str(path), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["parts"] == json.loads(json.dumps(data["parts"]))


def test_rows_of_empty_and_nested_containers():
    data = {"a": [], "b": {}, "c": [[1, 2], {"x": [3]}], "d": {"e": [{"f": None}]}, "g": "é"}
    out = io.StringIO()
    write_rows(data, out)
    assert json.loads(out.getvalue()) == data
    assert '\n    [1, 2],\n    {"x": [3]}\n' in out.getvalue()
