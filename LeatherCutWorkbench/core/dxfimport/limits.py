"""Limits of the import and the checks that enforce them (documented in docs/CLI.md,
"Limits of the import").

Hostile or broken files must end in one clear refusal, never in a hang, an
exhausted memory or a traceback.  Every check here raises :class:`InputError`
naming the file and, where there is one, the entity (type, handle, layer,
block) or the line:

* only regular files are read (a FIFO would block forever, ``/dev/zero`` never
  ends), at most :data:`MAX_FILE_BYTES`;
* no ``nan`` / ``inf`` value anywhere in an ASCII DXF (:func:`scan_nonfinite`,
  with the line number), and no non-finite number in any imported edge, mark
  or text, whatever the file format (:func:`check_geometry`);
* coordinates at most :data:`MAX_COORDINATE_MM` from the origin and a drawing
  at most :data:`MAX_DRAWING_SIZE_MM` across (after the unit conversion):
  beyond that no tolerance in mm means anything, and grid indexes and entry
  candidates would grow without bound;
* block expansion: at most :data:`MAX_MINSERT_CELLS` cells per MINSERT and
  :data:`MAX_EXPANDED_ENTITIES` entities after every INSERT is replaced by its
  block (counted before anything is expanded, so a 10-level fan-out is refused
  at once).
"""

from __future__ import annotations

import math
import os
import re
import stat
from typing import Any, Iterable, Optional, Tuple

from ..errors import InputError
from ..model import ArcEdge, EllipseEdge, LineEdge, SplineEdge, TextNote

#: Largest DXF file read (bytes).
MAX_FILE_BYTES = 256 * 1024 * 1024
#: Largest number of entities after block expansion (INSERT / MINSERT contents).
MAX_EXPANDED_ENTITIES = 2_000_000
#: Largest MINSERT grid (rows x columns).
MAX_MINSERT_CELLS = 100_000
#: Largest |x| or |y| of any imported point, mm.
MAX_COORDINATE_MM = 1.0e9
#: Largest width or height of the imported drawing, mm (100 km: a drawing in the
#: wrong unit still gets its units-implausible hint; beyond it nothing is a drawing).
MAX_DRAWING_SIZE_MM = 1.0e8

_NODE_KINDS = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
               (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"),
               (stat.S_ISDIR, "a directory"))

#: Where a value that reads as inf may start (a 3-digit exponent, searched in the
#: lower-cased data; ``nan`` / ``inf`` are found with bytes.find), after which
#: the whole value line is checked.
_BIG_EXPONENT = re.compile(rb"e\+?\d{3}")
_NONFINITE_VALUE = re.compile(rb"[+-]?(?:nan|inf(?:inity)?|(?:\d+\.?\d*|\.\d+)e\+?\d{3,})",
                              re.I)
_ENTITY_START = re.compile(rb"(?:^|\n)[ \t]*0[ \t]*\r?\n[ \t]*([A-Za-z_][A-Za-z_0-9]*)[ \t]*\r?\n")
_HEADER_VAR = re.compile(rb"\n[ \t]*9[ \t]*\r?\n[ \t]*(\$[A-Za-z_0-9]+)")
_HANDLE = re.compile(rb"\n[ \t]*5[ \t]*\r?\n[ \t]*([0-9A-Fa-f]+)[ \t]*\r?\n")


def check_regular_file(path: str) -> int:
    """Size in bytes of ``path``; InputError unless it is an existing regular
    file of at most :data:`MAX_FILE_BYTES`."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise InputError("file not found", path) from None
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc.strerror or exc}", path) from exc
    for test, what in _NODE_KINDS:
        if test(st.st_mode):
            extra = ", not a DXF file" if what == "a directory" else ""
            raise InputError(f"is {what}{extra}: only regular files are read", path)
    if not stat.S_ISREG(st.st_mode):
        raise InputError("is not a regular file: only regular files are read", path)
    if st.st_size > MAX_FILE_BYTES:
        raise InputError(f"the file has {st.st_size / 2 ** 20:.0f} MiB, more than the "
                         f"{MAX_FILE_BYTES // 2 ** 20} MiB limit of the import", path)
    return st.st_size


def _entity_at(data: bytes, pos: int) -> str:
    """'TYPE #handle' of the entity (or header/table record) holding byte ``pos``."""
    lo = max(0, pos - 65536)
    starts = list(_ENTITY_START.finditer(data, lo, pos))
    if not starts:
        return "entity"
    m = starts[-1]
    var = _HEADER_VAR.findall(data, m.end() - 1, pos)
    if var:                          # a header variable, e.g. $DIMASZ
        return f"header variable {var[-1].decode('latin-1')}"
    kind = m.group(1).decode("latin-1")
    h = _HANDLE.search(data, m.end() - 1, pos)
    return f"{kind} #{h.group(1).decode()}" if h else kind


def _group_code(data: bytes, pos: int) -> str:
    """The group code on the line before the value line starting at ``pos``."""
    start = data.rfind(b"\n", 0, pos)
    return data[start + 1:pos].strip().decode("latin-1", "replace") if start >= 0 else "?"


def scan_nonfinite(path: str, data: bytes) -> None:
    """InputError at the first value line of an ASCII DXF that reads as nan or
    inf (``nan``, ``inf``, ``-Infinity``, ``1e999``), naming line, group code
    and entity."""
    for pos in _hints(data.lower()):
        start = data.rfind(b"\n", 0, pos) + 1
        end = data.find(b"\n", pos)
        raw = data[start:end if end >= 0 else len(data)].strip()
        if not _NONFINITE_VALUE.fullmatch(raw) or math.isfinite(float(raw)):
            continue
        code = _group_code(data, start - 1)
        if not _is_float_code(code):
            continue                # a text, name or handle ('NaN' layer, handle 1E309)
        line = data.count(b"\n", 0, start) + 1
        raise InputError(f"{_entity_at(data, start)}: group code {code} at line {line} is "
                         f"{raw.decode('latin-1')!r}, not a finite number", path)


def _hints(low: bytes) -> Iterable[int]:
    """Positions in the lower-cased file where a nan / inf value may be."""
    for needle in (b"nan", b"inf"):
        pos = low.find(needle)
        while pos >= 0:
            yield pos
            pos = low.find(needle, pos + 1)
    for m in _BIG_EXPONENT.finditer(low):
        yield m.start()


def _is_float_code(code: str) -> bool:
    """True for group codes whose value is a floating point number (DXF reference)."""
    try:
        c = int(code)
    except ValueError:
        return False
    return (10 <= c <= 59 or 110 <= c <= 149 or 210 <= c <= 239 or 460 <= c <= 469
            or 1010 <= c <= 1059)


def describe_source(src: Any) -> str:
    """'LINE #2F on layer 'CUT' in block 'B'' for an EdgeSource."""
    where = f" in block {src.block!r}" if getattr(src, "block", "") else ""
    handle = f" #{src.handle}" if getattr(src, "handle", "") else ""
    return f"{src.dxftype or 'entity'}{handle} on layer {src.layer!r}{where}"


def _numbers(item: Any) -> Iterable[float]:
    """Every number of an edge, mark or text that must be finite."""
    t = type(item)
    if t is LineEdge:
        return (*item.start, *item.end)
    if t is ArcEdge:
        return (*item.center, item.radius, item.start_angle, item.sweep)
    if t is EllipseEdge:
        return (*item.center, *item.major_axis, item.ratio, item.start_param, item.end_param)
    if t is SplineEdge:
        return [v for p in item.poles for v in p] + list(item.knots) + list(item.weights)
    return (*item.position, getattr(item, "height", 0.0))


def _box(item: Any) -> Tuple[float, float, float, float]:
    from .extents import edge_bounds

    if hasattr(item, "position"):
        x, y = item.position
        return (x, y, x, y)
    return edge_bounds(item)


def check_geometry(path: str, box: Optional[Tuple[float, float, float, float]],
                   items: Iterable[Any]) -> None:
    """InputError naming the entity when the drawing's ``box`` (mm) holds a
    non-finite number, reaches beyond :data:`MAX_COORDINATE_MM` or is wider or
    taller than :data:`MAX_DRAWING_SIZE_MM`.  ``items`` (edges, marks, texts)
    are only walked to find the culprit, or for the numbers the box does not
    show (spline knots and weights, angles)."""
    items = list(items)
    for it in items:
        t = type(it)
        if t is SplineEdge and not all(map(math.isfinite, _numbers(it))):
            raise InputError(f"{describe_source(it.src)}: a pole, knot or weight is not a "
                             f"finite number", path)
        if t is TextNote and not (all(map(math.isfinite, _numbers(it)))
                                  and max(map(abs, it.position)) <= MAX_COORDINATE_MM):
            raise InputError(f"{describe_source(it.src)}: the text's position or height is not "
                             f"a finite number within {MAX_COORDINATE_MM:.0e} mm", path)
    if box is None:
        return
    ok = all(map(math.isfinite, box))
    if ok and max(map(abs, box)) <= MAX_COORDINATE_MM and \
            box[2] - box[0] <= MAX_DRAWING_SIZE_MM and box[3] - box[1] <= MAX_DRAWING_SIZE_MM:
        return
    for it in items:
        if not all(map(math.isfinite, _numbers(it))):
            raise InputError(f"{describe_source(it.src)}: a coordinate, radius, angle or ratio "
                             f"is not a finite number", path)
    for it in items:
        b = _box(it)
        if max(map(abs, b)) > MAX_COORDINATE_MM:
            raise InputError(f"{describe_source(it.src)}: coordinate {max(map(abs, b)):.6g} mm is "
                             f"beyond the limit of {MAX_COORDINATE_MM:.0e} mm from the origin",
                             path)
    # too wide: name the item farthest from the median centre of all items
    xs = sorted((b[0] + b[2]) / 2 for b in map(_box, items))
    ys = sorted((b[1] + b[3]) / 2 for b in map(_box, items))
    mx, my = xs[len(xs) // 2], ys[len(ys) // 2]

    def reach(it: Any) -> float:
        b = _box(it)
        return max(abs(b[0] - mx), abs(b[2] - mx), abs(b[1] - my), abs(b[3] - my))

    far = max(items, key=reach)
    size = max(box[2] - box[0], box[3] - box[1])
    raise InputError(f"the drawing is {size:.6g} mm across, more than the "
                     f"{MAX_DRAWING_SIZE_MM / 1e6:.0f} km limit; farthest out: "
                     f"{describe_source(far.src)}", path)


def minsert_cells(rows: Any, cols: Any, handle: str, path: str) -> int:
    """Cells of a MINSERT grid; InputError beyond :data:`MAX_MINSERT_CELLS`."""
    n = max(int(rows), 1) * max(int(cols), 1)
    if n > MAX_MINSERT_CELLS:
        raise InputError(f"MINSERT #{handle}: {rows} x {cols} = {n} cells, more than the "
                         f"limit of {MAX_MINSERT_CELLS} cells per MINSERT", path)
    return n


def check_expanded(total: int, biggest: str, path: str) -> None:
    """InputError when block expansion would give more than
    :data:`MAX_EXPANDED_ENTITIES` entities (``biggest`` names the INSERT that
    contributes most)."""
    if total > MAX_EXPANDED_ENTITIES:
        raise InputError(f"expanding the blocks would give {total:.3g} entities, more than the "
                         f"limit of {MAX_EXPANDED_ENTITIES}; largest contribution: {biggest}",
                         path)
