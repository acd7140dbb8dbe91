"""The fast reader for plain ASCII DXF (core/dxfimport/plain_reader.py) gives the
same imported drawing as the ezdxf path -- edges, marks, texts, layers, units,
findings, statistics, or the same refusal -- on every DXF fixture in
tests/data, on drawings written by ezdxf in R12 and R2000 with every plain
entity kind, and on the whole hostile corpus; and it declines what is not plain."""

import os
import sys

import ezdxf
import pytest

from LeatherCutWorkbench.core.dxfimport import ImportOptions, plain_reader, read_drawing, reader
from LeatherCutWorkbench.core.dxfimport.plain_reader import PlainLine, read_plain
from LeatherCutWorkbench.core.errors import InputError

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hostile_corpus  # noqa: E402

DATA = os.path.join(os.path.dirname(__file__), "data")


def _import(path, options, plain: bool):
    """(drawing or None, refusal message or None, reader used)."""
    saved = reader.read_plain
    if not plain:
        reader.read_plain = lambda data: None
    try:
        d = read_drawing(path, options)
    except InputError as exc:
        return None, str(exc), None
    finally:
        reader.read_plain = saved
    return d, None, d.stats["file"].get("reader")


def _same(path, options=ImportOptions()) -> str:
    """Asserts both paths agree; returns the reader the default path used."""
    fast, fast_err, used = _import(path, options, plain=True)
    slow, slow_err, slow_used = _import(path, options, plain=False)
    assert fast_err == slow_err, path
    if fast is None:
        return "refused"
    assert slow_used == "ezdxf"
    for name in ("edges", "marks", "texts", "units", "units_source", "dxf_version", "offset",
                 "findings", "pieces"):
        assert getattr(fast, name) == getattr(slow, name), (path, name)
    a, b = dict(fast.stats), dict(slow.stats)
    a["file"] = {k: v for k, v in a["file"].items() if k != "reader"}
    b["file"] = {k: v for k, v in b["file"].items() if k != "reader"}
    assert a == b, path
    return used


def _plain_drawing(path, version, units=4, layers=True):
    doc = ezdxf.new(version)
    if units is not None:
        doc.header["$INSUNITS"] = units
    if layers:
        doc.layers.add("CUT", color=1)
        doc.layers.add("Pen 2", color=3)
    msp = doc.modelspace()
    msp.add_line((0, 0), (40, 0), dxfattribs={"layer": "CUT", "color": 5})
    msp.add_line((40, 0), (40, 30, 2.5), dxfattribs={"layer": "CUT"})
    msp.add_arc((20, 30), 20, 0, 180, dxfattribs={"layer": "CUT"})
    msp.add_line((0, 30), (0, 0), dxfattribs={"layer": "CUT"})
    msp.add_circle((20, 15), 4, dxfattribs={"layer": "Pen 2"})
    msp.add_circle((100, 100), -1)                       # skipped: radius not positive
    msp.add_arc((300, 0), 5, 30, 30)                     # skipped: zero-length arc
    if version != "R12":                                 # no LWPOLYLINE in R12
        msp.add_lwpolyline([(60, 0, 0, 0, 0.4), (90, 0, 1, 1, 0), (90, 20), (60, 20, 0, 0, -1)],
                           format="xyseb", close=True, dxfattribs={"layer": "CUT"})
        msp.add_lwpolyline([(0, 60), (10, 60)], dxfattribs={"const_width": 0.5})
        msp.add_lwpolyline([(0, 80)])                    # one vertex: skipped
    msp.add_point((20, 15), dxfattribs={"layer": "CUT"})
    doc.saveas(path)


@pytest.mark.parametrize("version", ["R12", "R2000", "R2018"])
@pytest.mark.parametrize("units", [4, 1, 99, None])
def test_plain_drawings_take_the_fast_path_with_the_same_result(tmp_path, version, units):
    path = str(tmp_path / "plain.dxf")
    _plain_drawing(path, version, units)
    assert _same(path) == "plain"
    assert _same(path, ImportOptions(cleanup=False, units="inch")) == "plain"


def test_windows_line_ends_and_decimal_commas_take_the_fast_path(tmp_path):
    src = str(tmp_path / "plain.dxf")
    _plain_drawing(src, "R2000")
    text = open(src, "rb").read()
    crlf = tmp_path / "crlf.dxf"
    crlf.write_bytes(text.replace(b"\n", b"\r\n"))
    assert _same(str(crlf)) == "plain"
    commas = tmp_path / "commas.dxf"
    commas.write_bytes(b"0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n1F\n8\nCUT\n10\n0,5\n20\n1,25\n"
                       b"11\n10,5\n21\n1,25\n0\nENDSEC\n0\nEOF\n")
    d, err, used = _import(str(commas), ImportOptions(), plain=True)
    assert err is None and used == "plain"
    assert any(f.code == "decimal-commas" for f in d.findings)
    assert (d.edges[0].start, d.edges[0].end) == ((0.5, 1.25), (10.5, 1.25))
    assert _same(str(commas)) == "plain"


def test_every_fixture_in_tests_data_gives_the_same_drawing():
    used = {}
    for root, _dirs, files in os.walk(DATA):
        for name in files:
            if name.lower().endswith(".dxf"):
                path = os.path.join(root, name)
                used[name] = _same(path)
    assert used["cases.dxf"] == "plain"
    # blocks, splines, texts, binary, damaged files: declined, read by ezdxf
    for name in ("dxf2gcode_Bogen_Ellipsen_Polylinien_Block.dxf", "ezdxf_recover01.dxf",
                 "acadsharp_sample_AC1015_binary.dxf"):
        assert used[name] == "ezdxf", name


def test_the_hostile_corpus_gives_the_same_result_on_both_paths(tmp_path):
    cases = hostile_corpus.generate(str(tmp_path / "corpus"))
    seen = {"plain": 0, "ezdxf": 0, "refused": 0}
    for case in cases:
        if case.family in ("nodes", "profiles") or not os.path.isfile(case.path):
            continue
        seen[_same(case.path)] += 1
    assert seen["plain"] >= 5 and seen["ezdxf"] >= 20 and seen["refused"] >= 100, seen


@pytest.mark.parametrize("entity", [
    "0\nINSERT\n5\n1F\n2\nB\n10\n0\n20\n0\n",                       # blocks
    "0\nTEXT\n5\n1F\n10\n0\n20\n0\n40\n1\n1\nhi\n",                  # texts
    "0\nLINE\n5\n1F\n10\n0\n20\n0\n11\n1\n21\n1\n210\n0\n220\n0\n230\n-1\n",  # OCS
    "0\nLINE\n10\n0\n20\n0\n11\n1\n21\n1\n",                         # no handle
    "0\nLINE\n5\n1F\n10\n0\n11\n1\n21\n1\n",                         # no y
    "0\nLINE\n5\n1F\n10\n0\n20\n0\n10\n1\n20\n1\n11\n1\n21\n1\n",   # start twice
    "0\nCIRCLE\n5\n1F\n10\n0\n20\n0\n",                              # no radius
    "0\nLINE\n5\n1F\n10\n0\n20\n0\n11\n1\n21\n1\n67\n1\n",           # paper space
    "0\nLINE\n5\n1F\n10\n0\n20\n0\n11\n1\n21\n1\n1001\nAPP\n",       # XDATA
    "0\nLWPOLYLINE\n5\n1F\n90\n3\n10\n0\n20\n0\n10\n1\n20\n1\n",     # count differs
    "0\nLINE\n5\n1F\n8\nL\xe9\n10\n0\n20\n0\n11\n1\n21\n1\n",        # not ASCII
])
def test_what_is_not_plain_is_declined(entity):
    ok = "0\nLINE\n5\n1E\n10\n0\n20\n0\n11\n1\n21\n1\n"
    text = "0\nSECTION\n2\nENTITIES\n{}0\nENDSEC\n0\nEOF\n"
    assert read_plain(text.format(ok).encode()) is not None
    assert read_plain(text.format(ok + entity).encode("latin-1")) is None


_LINE = "0\nLINE\n5\n{h}\n8\nCUT\n10\n{x}\n20\n0\n11\n{x2}\n21\n0\n"
_R2000 = "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n0\nENDSEC\n"


@pytest.mark.parametrize("header, body", [
    ("", _LINE.format(h="1F", x=0, x2=10) + _LINE.format(h="1F", x=20, x2=30)),  # same handle
    ("", _LINE.format(h="0", x=0, x2=10)),                       # ezdxf refuses handle 0
    ("", _LINE.format(h="XYZ", x=0, x2=10)),                     # ezdxf renumbers
    ("", "0\nCIRCLE\n5\nab\n8\nC\n10\n0\n20\n0\n40\n-1\n"),       # skipped, named by handle
    ("", "0\nLINE\n5\n1F\n8\nCUT\n10\n1_0\n20\n0\n11\n  1.5  \n21\n1\n"),
    ("", "0\nARC\n5\n1F\n8\nCUT\n10\n0\n20\n0\n40\n5\n50\n-30\n51\n400\n"),
    ("", "0\nLWPOLYLINE\n5\n20\n8\nCUT\n90\n2\n10\n0\n20\n0\n10\n5\n20\n5\n"),   # R12
    (_R2000, "0\nLWPOLYLINE\n5\n20\n8\nCUT\n90\n2\n10\n0\n20\n0\n10\n5\n20\n5\n"),  # no marker
    (_R2000, "0\nLWPOLYLINE\n5\n20\n100\nAcDbEntity\n8\nCUT\n100\nAcDbPolyline\n90\n2\n70\n1\n"
             "10\n0\n20\n0\n42\n1\n10\n5\n20\n0\n"),
    (_R2000, "0\nLINE\n5\n1F\n100\nAcDbEntity\n100\nAcDbLine\n8\nCUT\n10\n0\n20\n0\n11\n1\n21\n1\n"),
    (_R2000, "0\nLINE\n5\n1F\n100\nAcDbEntity\n8\nCUT\n100\nAcDbCircle\n10\n0\n20\n0\n11\n1\n21\n1\n"),
    (_R2000, "0\nARC\n5\n1F\n100\nAcDbEntity\n8\nA\n100\nAcDbCircle\n10\n0\n20\n0\n40\n5\n"
             "100\nAcDbArc\n50\n0\n51\n90\n"),
])
def test_odd_but_readable_entities_give_the_same_result(tmp_path, header, body):
    path = tmp_path / "odd.dxf"
    path.write_text(header + "0\nSECTION\n2\nENTITIES\n" + body + "0\nENDSEC\n0\nEOF\n")
    _same(str(path))


def test_an_entity_owned_by_paper_space_without_its_67_flag_gives_the_same_result(tmp_path):
    doc = ezdxf.new("R2000")
    doc.modelspace().add_line((0, 0), (10, 0))
    doc.paperspace().add_line((0, 0), (5, 5))
    src = tmp_path / "paper.dxf"
    doc.saveas(src)
    lines = src.read_text().split("\n")
    out = []
    for k in range(0, len(lines) - 1, 2):       # drop the 67 (paper space) flags
        if lines[k].strip() != "67":
            out += lines[k:k + 2]
    path = tmp_path / "owner.dxf"
    path.write_text("\n".join(out) + "\n")
    assert _same(str(path)) == "ezdxf"
    assert _same(str(src)) == "ezdxf"


def _progress_and_drawing(path, options, plain: bool):
    calls = []
    saved = reader.read_plain
    if not plain:
        reader.read_plain = lambda data: None
    try:
        d = read_drawing(path, options, progress=lambda f, msg: calls.append((f, msg)))
    finally:
        reader.read_plain = saved
    return calls, d


@pytest.mark.parametrize("options", [ImportOptions(), ImportOptions(cleanup=False, units="inch")])
def test_runs_of_lines_in_changing_layouts_give_the_same_drawing_and_progress(tmp_path, options):
    """The fast path builds LINE edges in one loop (plain_reader.convert_plain)
    with one reader per tag layout: layouts that change from one LINE to the
    next (layer, colour, z, extrusion, subclass markers), signed zeros, other
    entities in between and enough entities for several progress reports give
    the same drawing and the same progress calls as the ezdxf path."""
    layouts = [
        "0\nLINE\n5\n{h}\n8\nCUT\n10\n{x}\n20\n-0.0\n11\n{x2}\n21\n-0\n",
        "0\nLINE\n5\n{h}\n8\nCUT\n62\n3\n10\n{x}\n20\n1\n30\n-2.5\n11\n{x2}\n21\n1\n31\n0\n",
        "0\nLINE\n5\n{h}\n10\n{x}\n20\n2\n11\n{x2}\n21\n2\n",                    # layer 0
        "0\nLINE\n5\n{h}\n8\nPen 2\n10\n{x}\n20\n3\n11\n{x2}\n21\n3\n210\n0\n220\n0\n230\n1\n",
        "0\nLINE\n5\n{h}\n100\nAcDbEntity\n8\nCUT\n100\nAcDbLine\n10\n{x}\n20\n4\n11\n{x2}\n21\n4\n",
        "0\nCIRCLE\n5\n{h}\n8\nCUT\n10\n{x}\n20\n50\n40\n2\n",
    ]
    body = []
    for k in range(1300):
        x = -0.0 if k % 7 == 0 else k * 0.25 - 40
        body.append(layouts[(k // 3 + k % 2) % len(layouts)].format(h=f"{k + 0x20:X}", x=x,
                                                                     x2=x + 1.5))
    path = tmp_path / "runs.dxf"
    path.write_text(_R2000 + "0\nSECTION\n2\nENTITIES\n" + "".join(body) + "0\nENDSEC\n0\nEOF\n")
    assert _same(str(path), options) == "plain"
    fast_calls, fast = _progress_and_drawing(str(path), options, plain=True)
    slow_calls, slow = _progress_and_drawing(str(path), options, plain=False)
    assert fast_calls == slow_calls
    assert sum("converting entities" in msg for _f, msg in fast_calls) == 3
    kinds = [(k // 3 + k % 2) % len(layouts) for k in range(1300)]
    assert fast.stats["entities_converted"] == {"CIRCLE": kinds.count(5), "LINE": 1300 - kinds.count(5)}
    # both LINE readers ran: the lean one, and the general one for the extrusion layout
    entities = read_plain(path.read_bytes()).modelspace()
    assert sum(type(e) is PlainLine for e in entities) == 1300 - kinds.count(5) - kinds.count(3)
    # the same floats to the last bit and sign (== would take -0.0 for 0.0)
    def points(d):
        return [repr((e.start, e.end)) for e in d.edges if hasattr(e, "end")]
    assert points(fast) == points(slow) and len(points(fast)) > 500


@pytest.mark.parametrize("chunk", [64, 100, 1 << 18])
def test_runs_of_lines_across_chunk_boundaries_give_the_same_drawing(tmp_path, monkeypatch, chunk):
    """LINEs of one layout are read a run at a time within a chunk of the file
    (plain_reader._LineReader.run): a LINE whose tags go on past its layout
    (a colour tag here and there) must not be cut at a chunk boundary."""
    monkeypatch.setattr(plain_reader, "_CHUNK_BYTES", chunk)
    body = []
    for k in range(600):
        body.append(f"0\nLINE\n5\n{k + 0x20:X}\n8\nCUT\n10\n{k}\n20\n0\n11\n{k}\n21\n5\n")
        if k % 5 == 3:
            body.append("62\n3\n")
    path = tmp_path / "runs.dxf"
    path.write_text("0\nSECTION\n2\nENTITIES\n" + "".join(body) + "0\nENDSEC\n0\nEOF\n")
    assert _same(str(path), ImportOptions(cleanup=False)) == "plain"
    fast, _err, _used = _import(str(path), ImportOptions(cleanup=False), plain=True)
    assert [e.src.color for e in fast.edges] == [3 if k % 5 == 3 else 256 for k in range(600)]
