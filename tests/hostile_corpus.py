"""A generated corpus of hostile inputs for the CLI (issue #16 item 8).

:func:`generate` writes many variants into a folder and returns them as
:class:`Case` (file, verbs to run, extra options).  Families:

* ``nonfinite``: every numeric group code of every entity type (LINE, CIRCLE,
  ARC, ELLIPSE, LWPOLYLINE with bulges, 2-D POLYLINE, SPLINE with knots and
  weights, POINT, TEXT, INSERT, MINSERT) and of the ``$INSUNITS`` header set to
  ``nan``, ``inf``, ``-inf``, ``1e300`` and ``1e17`` in turn.  The generator
  builds each base drawing with ezdxf using a distinct sentinel number per
  value, then replaces one sentinel's value line at a time, so the group code
  it hits is known;
* ``binary``: binary DXF files with nan / inf doubles;
* ``blocks``: deep and wide nesting, huge MINSERT grids, self-reference;
* ``spline``: bad knots and weights; ``ellipse``: zero and NaN axes;
* ``text``: truncated files, binary garbage, wrong group codes, missing y
  coordinates, mixed decimal separators, unknown ``$INSUNITS`` codes,
  drawings with nothing cuttable;
* ``nodes``: a FIFO, ``/dev/zero``, a directory, a char device as input;
* ``profiles``: hostile machine profiles (NaN origin, newlines in templates,
  motion outside the table in header/footer, tiny chord_tol, ...).

Every case is meant to end with exit code 0, 1 or 2, never a traceback or an
internal error (3), within the per-call time and memory cap of the runner.
"""

from __future__ import annotations

import io
import json
import os
import random
import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import ezdxf

ALL_VERBS = ("inspect", "recognise", "run", "post")

#: Values put into one numeric group code at a time.
HOSTILE_VALUES = ("nan", "inf", "-inf", "1e300", "1e17")


@dataclass
class Case:
    """One corpus input: ``path`` (file, node or folder), a label naming what is
    hostile, and the extra options every verb gets (e.g. ``--machine``)."""

    family: str
    label: str
    path: str
    options: List[str] = field(default_factory=list)
    verbs: Tuple[str, ...] = ALL_VERBS
    expect: Optional[int] = None        # exit code every verb must give, when known


class _Sentinels:
    """Distinct numbers used as placeholders; each maps to its entity type."""

    def __init__(self) -> None:
        self.k = 0
        self.values: set = set()

    def __call__(self, base: float) -> float:
        self.k += 1
        # a value whose written form is unique in the file: base + k/8192 + 1/65536
        # (exactly representable, so ezdxf writes it back unchanged)
        v = base + self.k / 8192.0 + 1.0 / 65536.0
        self.values.add(v)
        return v


def _square(msp, x0: float = 0.0, y0: float = 0.0, size: float = 100.0) -> None:
    pts = [(x0, y0), (x0 + size, y0), (x0 + size, y0 + size), (x0, y0 + size)]
    msp.add_lwpolyline(pts, close=True, dxfattribs={"layer": "CUT"})


def _entity_docs() -> "tuple[Dict[str, ezdxf.document.Drawing], set]":
    """One R2000 drawing per entity type; every numeric value of the entity
    under test is a sentinel (plus a plain 100 mm reference square)."""
    s = _Sentinels()
    docs = {}

    def new():
        doc = ezdxf.new("R2000")
        doc.header["$INSUNITS"] = 4
        _square(doc.modelspace(), 200.0, 200.0)
        return doc, doc.modelspace()

    doc, msp = new()
    msp.add_line((s(10), s(10), s(0)), (s(60), s(20), s(0)))
    docs["LINE"] = doc
    doc, msp = new()
    msp.add_circle((s(50), s(50)), s(20))
    docs["CIRCLE"] = doc
    doc, msp = new()
    msp.add_arc((s(50), s(50)), s(20), s(10), s(120))
    docs["ARC"] = doc
    doc, msp = new()
    msp.add_ellipse((s(50), s(50)), major_axis=(s(30), s(1), 0), ratio=s(0.5),
                    start_param=s(0.0), end_param=s(3.0))
    docs["ELLIPSE"] = doc
    doc, msp = new()
    msp.add_lwpolyline([(s(0), s(0), 0, 0, s(0.3)), (s(50), s(0), 0, 0, 0),
                        (s(50), s(40), 0, 0, s(-0.2)), (s(0), s(40), 0, 0, 0)],
                       format="xyseb", close=True)
    docs["LWPOLYLINE"] = doc
    doc, msp = new()
    pl = msp.add_polyline2d([(s(0), s(0)), (s(50), s(0)), (s(50), s(40))], close=True)
    pl.vertices[0].dxf.bulge = s(0.25)
    docs["POLYLINE"] = doc
    doc, msp = new()
    sp = msp.add_open_spline([(s(0), s(0)), (s(20), s(30)), (s(40), s(-10)), (s(60), s(10))],
                             degree=3, knots=[0, 0, 0, 0, 1, 1, 1, 1])
    sp.dxf.flags = sp.dxf.flags | 4      # rational
    sp.weights = [s(1.0), s(2.0), s(1.5), s(1.0)]
    sp.knots = [0.0, 0.0, 0.0, 0.0, s(1.0), s(1.0), s(1.0), s(1.0)]
    docs["SPLINE"] = doc
    doc, msp = new()
    msp.add_point((s(5), s(5)))
    msp.add_text("label", dxfattribs={"insert": (s(5), s(8)), "height": s(2.5),
                                      "rotation": s(15)})
    docs["POINT_TEXT"] = doc
    doc, msp = new()
    blk = doc.blocks.new("PIECE")
    blk.add_lwpolyline([(0, 0), (30, 0), (30, 20), (0, 20)], close=True)
    blk.add_circle((15, 10), 3)
    msp.add_blockref("PIECE", (s(10), s(10)), dxfattribs={
        "xscale": s(1.0), "yscale": s(1.0), "rotation": s(30)})
    docs["INSERT"] = doc
    doc, msp = new()
    blk = doc.blocks.new("CELL")
    blk.add_circle((0, 0), 2)
    ref = msp.add_blockref("CELL", (s(10), s(10)))
    ref.dxf.row_count = 3
    ref.dxf.column_count = 3
    ref.dxf.row_spacing = s(10)
    ref.dxf.column_spacing = s(10)
    docs["MINSERT"] = doc
    return docs, s.values


def _to_text(doc) -> str:
    buf = io.StringIO()
    doc.write(buf)
    return buf.getvalue()


def _value_lines(text: str, sentinels: set) -> List[Tuple[int, str]]:
    """(index of the value line, group code) of every sentinel in ``text``."""
    lines = text.split("\n")
    out = []
    frac = re.compile(r"^-?\d+\.\d+$")
    in_geometry = False          # BLOCKS and ENTITIES only (header values may collide)
    for i in range(1, len(lines), 2):
        v = lines[i].strip()
        if lines[i - 1].strip() == "2" and i >= 3 and lines[i - 2].strip() == "SECTION":
            in_geometry = v in ("BLOCKS", "ENTITIES")
        if in_geometry and frac.match(v) and float(v) in sentinels:
            out.append((i, lines[i - 1].strip()))
    return out


def _nonfinite_cases(folder: str) -> List[Case]:
    cases = []
    docs, sentinels = _entity_docs()
    for kind, doc in docs.items():
        text = _to_text(doc)
        lines = text.split("\n")
        seen: Dict[str, int] = {}
        for idx, code in _value_lines(text, sentinels):
            # every value at a code's first occurrence, one (rotating) at the others
            k = seen[code] = seen.get(code, -1) + 1
            values = HOSTILE_VALUES if k == 0 else (HOSTILE_VALUES[k % len(HOSTILE_VALUES)],)
            for value in values:
                variant = list(lines)
                variant[idx] = value
                name = f"nf_{kind}_{code}_{idx}_{value.replace('-', 'm')}.dxf"
                path = os.path.join(folder, name)
                with open(path, "w", encoding="utf-8") as fh:
                    fh.write("\n".join(variant))
                # nan/inf are refused by the import every verb shares: inspect plus one
                # later verb in turn; finite extremes (1e300, 1e17) go through all four
                later = ("recognise", "run", "post")[len(cases) % 3]
                verbs = ("inspect", later) if "n" in value else ALL_VERBS
                cases.append(Case("nonfinite", f"{kind} group {code} = {value}", path,
                                  verbs=verbs, expect=2 if "n" in value else None))
    return cases


def _binary_cases(folder: str) -> List[Case]:
    """Binary DXF with non-finite doubles (no text to scan: the converted
    geometry is checked)."""
    cases = []
    nan, inf = float("nan"), float("inf")
    for label, add in (("LINE start nan", lambda m: m.add_line((nan, 0), (10, 10))),
                       ("CIRCLE radius inf", lambda m: m.add_circle((5, 5), inf)),
                       ("ARC centre -inf", lambda m: m.add_arc((-inf, 5), 3, 0, 90)),
                       ("POINT nan", lambda m: m.add_point((nan, nan))),
                       ("LWPOLYLINE vertex inf", lambda m: m.add_lwpolyline(
                           [(0, 0), (inf, 0), (5, 5)]))):
        doc = ezdxf.new("R2000")
        _square(doc.modelspace(), 200, 200)
        add(doc.modelspace())
        path = os.path.join(folder, "bin_" + label.replace(" ", "_") + ".dxf")
        doc.saveas(path, fmt="bin")
        cases.append(Case("binary", label, path, expect=2))
    return cases


def _write(folder: str, name: str, doc) -> str:
    path = os.path.join(folder, name)
    doc.saveas(path)
    return path


def _block_cases(folder: str) -> List[Case]:
    cases = []
    # deep nesting: 10 levels x fan-out 10 = 1e10 leaf inserts if expanded
    for depth, fan in ((10, 10), (6, 12), (40, 1)):
        doc = ezdxf.new("R2000")
        msp = doc.modelspace()
        doc.blocks.new("L0").add_circle((0, 0), 1)
        for lvl in range(1, depth + 1):
            blk = doc.blocks.new(f"L{lvl}")
            for k in range(fan):
                blk.add_blockref(f"L{lvl - 1}", (3.0 * k, 0.0))
        msp.add_blockref(f"L{depth}", (0, 0))
        cases.append(Case("blocks", f"nested {depth} levels x {fan}",
                          _write(folder, f"nest_{depth}x{fan}.dxf", doc),
                          expect=2 if fan ** depth > 2_000_000 else None))
    for rows, cols in ((10000, 10000), (100001, 1), (1, 2 ** 31 - 1)):
        doc = ezdxf.new("R2000")
        doc.blocks.new("C").add_circle((0, 0), 1)
        ref = doc.modelspace().add_blockref("C", (0, 0))
        ref.dxf.row_count, ref.dxf.column_count = rows, cols
        ref.dxf.row_spacing, ref.dxf.column_spacing = 3.0, 3.0
        cases.append(Case("blocks", f"MINSERT {rows} x {cols}",
                          _write(folder, f"minsert_{rows}x{cols}.dxf", doc), expect=2))
    doc = ezdxf.new("R2000")
    blk = doc.blocks.new("SELF")
    blk.add_circle((0, 0), 1)
    blk.add_blockref("SELF", (5, 0))
    doc.modelspace().add_blockref("SELF", (0, 0))
    cases.append(Case("blocks", "self-referencing block", _write(folder, "self_ref.dxf", doc)))
    doc = ezdxf.new("R2000")
    doc.modelspace().add_blockref("MISSING", (0, 0))
    _square(doc.modelspace())
    cases.append(Case("blocks", "missing block", _write(folder, "missing_block.dxf", doc)))
    return cases


def _spline_cases(folder: str) -> List[Case]:
    cases = []
    bad = {
        "decreasing knots": dict(knots=[0, 0, 0, 0, 2, 1, 1, 1, 1]),
        "too few knots": dict(knots=[0, 0, 1]),
        "negative weights": dict(weights=[1, -2, 1, 1, 1]),
        "zero weights": dict(weights=[0, 0, 0, 0, 0]),
        "all knots equal": dict(knots=[1] * 9),
        "degree 0": dict(degree=0),
        "degree 30": dict(degree=30),
    }
    for label, patch in bad.items():
        doc = ezdxf.new("R2000")
        msp = doc.modelspace()
        _square(msp, 200, 200)
        pts = [(0, 0), (10, 20), (30, -5), (50, 15), (70, 0)]
        sp = msp.add_open_spline(pts, degree=3)
        if "knots" in patch:
            sp.knots = patch["knots"]
        if "weights" in patch:
            sp.dxf.flags = sp.dxf.flags | 4
            sp.weights = patch["weights"]
        if "degree" in patch:
            sp.dxf.__dict__["degree"] = patch["degree"]   # bypass ezdxf's check
        name = "spline_" + label.replace(" ", "_") + ".dxf"
        cases.append(Case("spline", label, _write(folder, name, doc)))
    base = ezdxf.new("R2000")
    _square(base.modelspace(), 200, 200)
    base.modelspace().add_ellipse((50, 50), major_axis=(30.125, 0.0625, 0), ratio=0.4375)
    text = _to_text(base)
    for label, swaps in (("zero major axis", {"30.125": "0", "0.0625": "0"}),
                         ("ratio 0", {"0.4375": "0"}), ("ratio 7", {"0.4375": "7"}),
                         ("ratio -1", {"0.4375": "-1"})):
        patched = "\n".join(swaps.get(v.strip(), v) for v in text.split("\n"))
        path = os.path.join(folder, "ellipse_" + label.replace(" ", "_") + ".dxf")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(patched)
        cases.append(Case("ellipse", label, path))
    return cases


def _r12(entities: str, header: str = "") -> str:
    head = f"0\nSECTION\n2\nHEADER\n{header}0\nENDSEC\n" if header else ""
    return f"{head}0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n"


_LINE = "0\nLINE\n8\n0\n10\n{x1}\n20\n{y1}\n11\n{x2}\n21\n{y2}\n"


def _text_cases(folder: str, rng: random.Random) -> List[Case]:
    cases = []

    def put(name: str, label: str, data, expect: Optional[int] = None) -> None:
        path = os.path.join(folder, name)
        with open(path, "wb") as fh:
            fh.write(data if isinstance(data, bytes) else data.encode("latin-1"))
        cases.append(Case("text", label, path, expect=expect))

    square = "".join(_LINE.format(x1=a, y1=b, x2=c, y2=d) for a, b, c, d in
                     ((0, 0, 100, 0), (100, 0, 100, 100), (100, 100, 0, 100), (0, 100, 0, 0)))
    good = _r12(square)
    put("good_square.dxf", "plain square (control)", good, expect=0)
    for n in (1, 7, 20, 37, len(good) // 2, len(good) - 6):
        put(f"truncated_{n}.dxf", f"truncated after {n} bytes", good[:n])
    for k in range(4):
        put(f"garbage_{k}.dxf", f"binary garbage {k}", bytes(rng.randrange(256)
                                                              for _ in range(2000 + k * 500)),
            expect=2)
    put("garbage_binary_header.dxf", "binary DXF sentinel then garbage",
        b"AutoCAD Binary DXF\r\n\x1a\x00" + bytes(rng.randrange(256) for _ in range(3000)))
    put("wrong_codes.dxf", "wrong group codes (letters as codes)",
        _r12("0\nLINE\nX\n0\n10\n1\nY\n2\n"))
    put("code_out_of_range.dxf", "group code 99999999", _r12("0\nLINE\n99999999\n5\n10\n1\n20\n2\n"))
    put("odd_lines.dxf", "odd number of lines", _r12(square) + "10\n")
    put("missing_y.dxf", "LINE without its y (20) group code",
        _r12("0\nLINE\n8\n0\n10\n0\n11\n100\n21\n0\n" + square), expect=2)
    put("missing_end.dxf", "LINE without its end point",
        _r12("0\nLINE\n8\n0\n10\n0\n20\n0\n" + square))
    put("mixed_separators.dxf", "number 1.234,5", _r12(square.replace("100\n", "1.234,5\n", 1)), expect=2)
    put("comma_and_point.dxf", "decimal comma beside decimal point",
        _r12(square.replace("100\n", "100,5\n", 1).replace("0\n21\n100", "0\n21\n100.5")))
    put("number_garbage.dxf", "coordinate 'abc'", _r12(square.replace("100\n", "abc\n", 1)))
    put("number_hex.dxf", "coordinate '0x1p3'", _r12(square.replace("100\n", "0x1p3\n", 1)))
    for code in (99, -5, 2 ** 40):
        put(f"insunits_{code}.dxf", f"$INSUNITS {code}",
            _r12(square, header=f"9\n$INSUNITS\n70\n{code}\n"))
    put("header_nan.dxf", "header variable $DIMSCALE = nan",
        _r12(square, header="9\n$DIMSCALE\n40\nnan\n"), expect=2)
    put("layer_nan.dxf", "layer named NaN, handle 1E309 (not numbers)",
        _r12(square.replace("8\n0\n", "5\n1E309\n8\nNaN\n", 1)), expect=0)
    put("only_text.dxf", "nothing cuttable (only a TEXT)",
        _r12("0\nTEXT\n8\n0\n10\n0\n20\n0\n40\n2\n1\nhello\n"))
    put("only_point.dxf", "nothing cuttable (only a POINT)", _r12("0\nPOINT\n8\n0\n10\n5\n20\n5\n"))
    put("open_line.dxf", "nothing closed (one open LINE)",
        _r12(_LINE.format(x1=0, y1=0, x2=50, y2=0)))
    put("empty_entities.dxf", "empty ENTITIES section", _r12(""), expect=2)
    put("far_line.dxf", "100 mm square beside a LINE to x = 1e300",
        _r12(square + _LINE.format(x1=0, y1=0, x2="1e300", y2=0)), expect=2)
    put("far_line_1e17.dxf", "square with corners at 1e17",
        _r12(square.replace("100\n", "100000000000000000\n")), expect=2)
    put("huge_offset.dxf", "square at 3e6 (honest survey offset)",
        _r12(square.replace("\n0\n", "\n3000000\n").replace("\n100\n", "\n3000100\n")),
        expect=0)
    put("nul_bytes.dxf", "NUL bytes in a value", _r12(square).replace("100", "1\x000", 1))
    put("control_chars_layer.dxf", "layer name with newline-ish control chars",
        _r12(square.replace("8\n0\n", "8\nA\x1bB\x07\n", 1)))
    put("long_line.dxf", "a 10 MB value line", _r12(square) + "999\n" + "x" * 10_000_000 + "\n")
    names = "".join(_LINE.format(x1=0, y1=0, x2=100, y2=0).replace("8\n0\n", f"8\nL{k}\n")
                    for k in range(3))
    put("many_layers.dxf", "one open line per layer", _r12(names))
    return cases


def _node_cases(folder: str) -> List[Case]:
    cases = []
    fifo = os.path.join(folder, "fifo.dxf")
    if not os.path.exists(fifo):
        os.mkfifo(fifo)
    cases.append(Case("nodes", "FIFO", fifo, expect=2))
    cases.append(Case("nodes", "/dev/zero", "/dev/zero", expect=2))
    cases.append(Case("nodes", "/dev/null", "/dev/null", expect=2))
    d = os.path.join(folder, "adir.dxf")
    os.makedirs(d, exist_ok=True)
    cases.append(Case("nodes", "directory", d, expect=2))
    cases.append(Case("nodes", "missing file", os.path.join(folder, "nope.dxf"), expect=2))
    return cases


#: Hostile machine profiles: (label, fields over the grblhal_tangential defaults).
HOSTILE_PROFILES: List[Tuple[str, Dict]] = [
    ("origin NaN", {"origin": [float("nan"), 0]}),
    ("origin inf", {"origin": [0, float("inf")]}),
    ("z_up below z_down", {"z_up": -5.0, "z_down": 1.0}),
    ("table Infinity", {"table_size": [float("inf"), 1600]}),
    ("table NaN", {"table_size": [2500, float("nan")]}),
    ("acceleration 0", {"acceleration": 0}),
    ("units_per_turn 1e-300", {"units_per_turn": 1e-300}),
    ("settle_dwell 1e12", {"settle_dwell": 1e12}),
    ("hpgl_units_per_mm 0", {"hpgl_units_per_mm": 0}),
    ("chord_tol 1e-12", {"chord_tol": 1e-12, "arcs": "split"}),
    ("cut_feed NaN", {"cut_feed": float("nan")}),
    ("lift_angle NaN", {"lift_angle": float("nan")}),
    ("name with newline", {"name": "x\nG0 X-9999 Y-9999\nM30"}),
    ("name with parenthesis", {"name": "a) G0 X-9999 (b"}),
    ("name with semicolon", {"name": "a; G0 X-9999"}),
    ("name with spaces and dashes", {"name": "Cutter 2 - hall B"}),
    ("knife_up with newline", {"knife_up": ["G0 Z5\nG0 X-9999 Y-9999"]}),
    ("knife_down with CR", {"knife_down": ["G1 Z-1 F1000\rG0 X-9999"]}),
    ("header far rapid", {"header": ["G0 X-5000 Y-5000"]}),
    ("footer far cut", {"footer": ["G1 X99999 Y99999 F1000"]}),
    ("footer far cut no F", {"footer": ["G1 X99999 Y99999"]}),
    ("header relative motion", {"header": ["G91", "G0 X-5000", "G90"]}),
    ("header G92", {"header": ["G92 X0 Y0"]}),
    ("header control char", {"header": ["G21\x07"]}),
    ("tool_on with tab-escape", {"tool_on": ["M3 S1000\x1b"]}),
    ("footer arc out of table", {"footer": ["G2 X0 Y0 I-3000 J0 F1000"]}),
    ("template unknown variable", {"knife_up": ["G0 Z{nope}"]}),
    ("max_feed 1e308", {"max_feed": 1e308}),
    ("decimals 99", {"decimals": 99}),
    ("baud 0", {"baud": 0}),
    ("rx_buffer_size 1e9", {"rx_buffer_size": 10 ** 9}),
    ("max_line_length 0", {"max_line_length": 0}),
]

#: Hostile-looking profiles that are fine.
HARMLESS_PROFILES = ("name with spaces and dashes",)


def _profile_cases(folder: str, drawing: str) -> List[Case]:
    cases = []
    for k, (label, fields) in enumerate(HOSTILE_PROFILES):
        path = os.path.join(folder, f"profile_{k}.json")
        with open(path, "w", encoding="utf-8") as fh:
            json.dump(dict({"name": f"hostile_{k}"}, **fields), fh)   # NaN/Infinity literals
        cases.append(Case("profiles", label, drawing, ["--machine", path], ("run", "post"),
                          expect=0 if label in HARMLESS_PROFILES else 2))
    return cases


def _random_mutations(folder: str, rng: random.Random, base_text: str, n: int) -> List[Case]:
    """Random byte-level damage of a valid drawing: flipped, dropped, repeated lines."""
    cases = []
    lines = base_text.split("\n")
    for k in range(n):
        v = list(lines)
        for _ in range(rng.randint(1, 4)):
            i = rng.randrange(len(v))
            op = rng.choice(("drop", "dup", "swap", "junk", "num"))
            if op == "drop":
                del v[i]
            elif op == "dup":
                v.insert(i, v[i])
            elif op == "swap" and i + 1 < len(v):
                v[i], v[i + 1] = v[i + 1], v[i]
            elif op == "junk":
                v[i] = rng.choice(("", "  ", "-", "1e999", "SECTION", "0", "EOF", "ÿ", "\x00"))
            else:
                v[i] = rng.choice(HOSTILE_VALUES)
        path = os.path.join(folder, f"mutant_{k}.dxf")
        with open(path, "w", encoding="latin-1", errors="replace") as fh:
            fh.write("\n".join(v))
        cases.append(Case("mutants", f"random mutation {k}", path))
    return cases


def generate(folder: str, seed: int = 16, mutants: int = 40) -> List[Case]:
    """Write the corpus into ``folder``; returns the cases in a fixed order."""
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(seed)
    cases = _nonfinite_cases(folder)
    cases += _binary_cases(folder)
    cases += _block_cases(folder)
    cases += _spline_cases(folder)
    text_cases = _text_cases(folder, rng)
    cases += text_cases
    cases += _node_cases(folder)
    good = next(c.path for c in text_cases if c.label.startswith("plain square"))
    cases += _profile_cases(folder, good)
    base = _to_text(_entity_docs()[0]["SPLINE"])
    cases += _random_mutations(folder, rng, base, mutants)
    return cases


def verbs_argv(case: Case, verb: str, outdir: str) -> List[str]:
    """argv of one CLI call of ``case`` (fast planning: nearest neighbour)."""
    argv = [verb, case.path]
    if verb in ("run", "post"):
        argv += ["--plan-method", "nn", "--move-to-origin", "10"]
    if verb == "run":
        argv += ["-o", outdir]
    elif verb == "post":
        argv += ["-o", os.path.join(outdir, "job.nc")]
    return argv + list(case.options)

