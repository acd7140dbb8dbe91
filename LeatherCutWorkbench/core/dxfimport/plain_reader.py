"""A fast reader for *plain* ASCII DXF drawings; everything else goes to ezdxf.

Why hand-written: ``ezdxf.readfile`` builds its whole object model (tags,
ExtendedTags, one DXFEntity with a DXFNamespace per entity, the entity
database) -- measured 38.6 CPU s and 861 MiB for 1 M LINEs, more than the
rest of the import and recognition together -- while the importer reads a
handful of attributes of each entity.  ezdxf has no cheaper public path that
still hands us entities (``ezdxf.addons.iterdxf`` needs a file written with
its own layout and still builds the entity objects).

A drawing is *plain* when every value is ASCII, it has no BLOCKS content, no
paper space entities and its model space holds only LINE, LWPOLYLINE, ARC,
CIRCLE and POINT entities written with the group codes of the DXF reference,
each with a (hex, non-zero) handle, owned by the model space block record,
its subclass markers either absent or as ezdxf reads them (LWPOLYLINE needs
its own, and no LWPOLYLINE in an R12 file), points given as complete 10/20
pairs and an extrusion of (0, 0, 1) when one is given.  For such a file :func:`read_plain` returns a
:class:`PlainDocument` that answers the few questions the importer asks a
document (``modelspace()``, ``header``, ``layers``, ``blocks``, ``layouts``,
``dxfversion``) with the values ezdxf would give; the entity converters in
:mod:`.entities` run unchanged on its entities, except LINEs: runs of LINEs
with the same tags are read column by column into lean :class:`PlainLine`
objects and :func:`convert_plain` makes their edges a block at a time (1 M
LINEs are most of a big drawing's import).  For anything else (an
unknown group code, a missing or repeated one, a value that is not a number
where one is due, a DXF version ezdxf would upgrade, ...) it returns None
and the caller uses ezdxf, so every refusal and repair of the ezdxf path
stays exactly as it is.  tests/test_fast_reader.py checks that both paths
give the same drawing on every fixture the fast path accepts.

All checks on the raw bytes (non-finite numbers, decimal commas, data after
EOF) happen before, in :mod:`.reader`, for both paths.
"""

from __future__ import annotations

from itertools import chain, repeat
from operator import attrgetter
from typing import Any, Callable, Dict, Iterator, List, Optional, Tuple

import numpy as np

from ..model import EdgeSource, LineEdge
from ..progress import ProgressFn, report
from .limits import check_expanded

#: Entity types the fast path reads.
PLAIN_TYPES = frozenset(("LINE", "LWPOLYLINE", "ARC", "CIRCLE", "POINT"))

#: DXF versions ezdxf loads as they are (R13 / R14 are upgraded: not plain).
_VERSIONS = frozenset(("AC1009", "AC1015", "AC1018", "AC1021", "AC1024", "AC1027", "AC1032"))

#: Group codes any plain entity may carry whose value the importer never
#: reads (linetype and its scale, lineweight, thickness, true colour,
#: transparency); subclass markers (100) are checked by :func:`_markers`.
_IGNORED = frozenset((100, 6, 48, 370, 39, 420, 440))
#: Float attributes by entity type: group code -> ezdxf attribute name.
_FLOATS: Dict[str, Dict[int, str]] = {
    "LINE": {},
    "ARC": {40: "radius", 50: "start_angle", 51: "end_angle"},
    "CIRCLE": {40: "radius"},
    "POINT": {50: "angle"},
    "LWPOLYLINE": {43: "const_width", 38: "elevation"},
}
#: Point attributes by entity type: x group code -> ezdxf attribute name.
_POINTS: Dict[str, Dict[int, str]] = {
    "LINE": {10: "start", 11: "end"},
    "ARC": {10: "center"},
    "CIRCLE": {10: "center"},
    "POINT": {10: "location"},
    "LWPOLYLINE": {},
}
#: Attributes without which the entity is not plain (ezdxf would fill a default).
_REQUIRED: Dict[str, Tuple[str, ...]] = {
    "LINE": ("start", "end"), "ARC": ("center", "radius", "start_angle", "end_angle"),
    "CIRCLE": ("center", "radius"), "POINT": ("location",), "LWPOLYLINE": (),
}
#: Subclass markers (group 100) ezdxf expects, in order, and the group codes
#: each subclass may hold; ezdxf reads an attribute only inside its subclass.
_SUBCLASSES: Dict[str, Tuple[Tuple[str, frozenset], ...]] = {
    "LINE": (("AcDbLine", frozenset((39, 10, 20, 30, 11, 21, 31, 210, 220, 230))),),
    "CIRCLE": (("AcDbCircle", frozenset((39, 10, 20, 30, 40, 210, 220, 230))),),
    "ARC": (("AcDbCircle", frozenset((39, 10, 20, 30, 40, 210, 220, 230))),
            ("AcDbArc", frozenset((50, 51)))),
    "POINT": (("AcDbPoint", frozenset((10, 20, 30, 39, 50, 210, 220, 230))),),
    "LWPOLYLINE": (("AcDbPolyline", frozenset((90, 70, 43, 38, 39, 10, 20, 40, 41, 42,
                                                210, 220, 230))),),
}
#: Codes before the first marker, and in the AcDbEntity subclass.
_HEAD_CODES = frozenset((5, 330))
_ENTITY_CODES = frozenset((8, 62, 6, 370, 48, 420, 440, 67))
_Z_AXIS = (0.0, 0.0, 1.0)
#: Bytes of lines split per step: bounds the memory of the split lines of a big file.
_CHUNK_BYTES = 1 << 18


class _NotPlain(Exception):
    """The drawing is not plain: the caller reads it with ezdxf."""


class Attribs:
    """An entity's attributes as ezdxf's ``entity.dxf`` offers them: read as
    attributes, with ``get``, and ``vars()`` lists those present in the file."""

    def get(self, key: str, default: Any = None) -> Any:
        return self.__dict__.get(key, default)


class PlainEntity:
    """One plain entity: ``dxftype()``, ``dxf``; LWPOLYLINE also ``lwpoints``
    (``values.tolist()`` rows x, y, start width, end width, bulge) and ``closed``."""

    __slots__ = ("_type", "dxf", "lwpoints", "closed")

    def __init__(self, dxftype: str, dxf: Attribs):
        self._type = dxftype
        self.dxf = dxf

    def dxftype(self) -> str:
        return self._type


class PlainLine:
    """One plain LINE without extrusion, kept lean (a big drawing is mostly
    LINEs): ``dxftype()``, ``dxf`` made on demand; :func:`convert_plain` reads
    the slots (points as (x, y, z), ``layer`` / ``color`` None when absent)."""

    __slots__ = ("start", "end", "handle", "layer", "color")
    _type = "LINE"

    def __init__(self, start: Tuple[float, float, float], end: Tuple[float, float, float],
                 handle: str, layer: Optional[str], color: Optional[int]):
        self.start = start
        self.end = end
        self.handle = handle
        self.layer = layer
        self.color = color

    def dxftype(self) -> str:
        return "LINE"

    @property
    def dxf(self) -> Attribs:
        attrs: Dict[str, Any] = {"start": self.start, "end": self.end, "handle": self.handle}
        if self.layer is not None:
            attrs["layer"] = self.layer
        if self.color is not None:
            attrs["color"] = self.color
        dxf = Attribs()
        dxf.__dict__ = attrs
        return dxf


class _LwPoints:
    """``lwpoints.values.tolist()`` as ezdxf >= 1.1 offers it."""

    __slots__ = ("_rows",)

    def __init__(self, rows: List[List[float]]):
        self._rows = rows

    @property
    def values(self) -> "_LwPoints":
        return self

    def tolist(self) -> List[List[float]]:
        return self._rows


class _Header:
    def __init__(self, values: Dict[str, Any]):
        self._values = values

    def get(self, key: str, default: Any = None) -> Any:
        return self._values.get(key, default)


class _Layer:
    __slots__ = ("dxf",)

    def __init__(self, name: str):
        self.dxf = Attribs()
        self.dxf.name = name


class _NoBlocks:
    def get(self, name: str, default: Any = None) -> Any:
        return default


class PlainDocument:
    """What the importer asks of a DXF document, for a plain drawing."""

    def __init__(self, entities: List[PlainEntity], header: Dict[str, Any], layers: List[str]):
        self._entities = entities
        self.header = _Header(header)
        self.dxfversion: str = header.get("$ACADVER", "AC1009")
        self.layers = [_Layer(n) for n in layers]
        self.blocks = _NoBlocks()
        self.layouts: List[Any] = []   # no paper space entities (else not plain)

    def modelspace(self) -> List[PlainEntity]:
        return self._entities

    def drop_entities(self) -> None:
        """Forget the entities once converted (they are most of the memory)."""
        self._entities = []


def read_plain(data: bytes) -> Optional[PlainDocument]:
    """The plain drawing in the ASCII DXF ``data``, or None when it is not plain."""
    if not data.isascii():
        return None
    if b"\r" in data:
        data = data.replace(b"\r\n", b"\n")
        if b"\r" in data:
            return None
    try:
        return _Parser().parse(_Stream(data))
    except (_NotPlain, ValueError, IndexError, StopIteration):   # truncated or odd: ezdxf decides
        return None


def _chunks(data: bytes) -> Iterator[Tuple[List[int], List[str]]]:
    """(group codes, values) of ``data``, a few MiB of lines at a time."""
    pos, n = 0, len(data)
    carry: Optional[str] = None
    while pos < n:
        end = data.find(b"\n", min(pos + _CHUNK_BYTES, n - 1))
        if end < 0:
            end = n
        lines = data[pos:end].decode("ascii").split("\n")
        pos = end + 1
        if carry is not None:
            lines.insert(0, carry)
            carry = None
        if len(lines) % 2:
            carry = lines.pop()
        yield list(map(int, lines[0::2])), lines[1::2]
    if carry is not None and carry.strip():
        raise _NotPlain("odd number of lines")


class _Stream:
    """The (group code, value) pairs of a file: one by one, or up to the next
    group code 0 (an entity's tags) with a C-level search."""

    def __init__(self, data: bytes):
        self._chunks = _chunks(data)
        self.codes: List[int] = []
        self.values: List[str] = []
        self.i = 0

    def _more(self) -> bool:
        for codes, values in self._chunks:
            self.codes = self.codes[self.i:] + codes
            self.values = self.values[self.i:] + values
            self.i = 0
            return True
        return False

    def __iter__(self) -> "_Stream":
        return self

    def __next__(self) -> Tuple[int, str]:
        while self.i >= len(self.codes):
            if not self._more():
                raise StopIteration
        i = self.i
        self.i = i + 1
        return self.codes[i], self.values[i]

    def entity(self) -> Tuple[str, List[int], List[str]]:
        """The next entity: its type (the value of a group code 0) and the codes
        and values of its tags, up to (not including) the next group code 0;
        ``("ENDSEC", [], [])`` consumes only the ENDSEC pair."""
        while self.i >= len(self.codes):
            if not self._more():
                raise _NotPlain("entities not closed")
        i = self.i
        if self.codes[i] != 0:
            raise _NotPlain("entity without type")
        dxftype = self.values[i]
        if dxftype == "ENDSEC":
            self.i = i + 1
            return dxftype, [], []
        if dxftype not in PLAIN_TYPES:
            raise _NotPlain(f"{dxftype} is not a plain entity")
        while True:
            try:
                j = self.codes.index(0, i + 1)
            except ValueError:
                if not self._more():
                    raise _NotPlain("not closed") from None
                i = 0            # _more keeps the lists from the entity's group 0 on
                continue
            self.i = j
            return dxftype, self.codes[i + 1:j], self.values[i + 1:j]


class _Parser:
    """Section by section; raises _NotPlain on anything not plain."""

    def __init__(self) -> None:
        self.header: Dict[str, Any] = {}
        self.layers: List[str] = []
        self.entities: List[Any] = []      # PlainEntity or PlainLine
        #: handle of the *Model_Space block record: the owner (330) of every entity
        self.owner: Optional[str] = None

    def parse(self, pairs: _Stream) -> PlainDocument:
        for code, value in pairs:
            if (code, value) == (0, "EOF"):
                break
            if (code, value) != (0, "SECTION"):
                raise _NotPlain("not a section")
            code, name = next(pairs)
            if code != 2:
                raise _NotPlain("section without name")
            if self._section(name, pairs) != (0, "ENDSEC"):
                raise _NotPlain("section not closed")
        if "$ACADVER" in self.header and self.header["$ACADVER"] not in _VERSIONS:
            raise _NotPlain("DXF version ezdxf would upgrade")
        if self.header.get("$ACADVER", "AC1009") == "AC1009" and any(
                e._type == "LWPOLYLINE" for e in self.entities):
            raise _NotPlain("LWPOLYLINE in an R12 drawing")
        folded = [n.lower() for n in self.layers]
        if len(set(folded)) != len(folded):
            raise _NotPlain("layer defined twice")
        # ezdxf creates the required layers a file lacks (document.py)
        for required in ("0", "Defpoints"):
            if required.lower() not in folded:
                self.layers.append(required)
        return PlainDocument(self.entities, self.header, self.layers)

    def _section(self, name: str, pairs: _Stream) -> Tuple[int, str]:
        if name == "HEADER":
            return self._header(pairs)
        if name == "TABLES":
            return self._tables(pairs)
        if name == "BLOCKS":
            return self._blocks(pairs)
        if name == "ENTITIES":
            return self._entities(pairs)
        if name in ("CLASSES", "OBJECTS", "THUMBNAILIMAGE", "ACDSDATA"):
            for code, value in pairs:
                if code == 0 and value == "ENDSEC":
                    return code, value
            raise _NotPlain("section not closed")
        raise _NotPlain(f"unknown section {name}")

    def _header(self, pairs: _Stream) -> Tuple[int, str]:
        var = ""
        for code, value in pairs:
            if code == 0:
                return code, value
            if code == 9:
                var = value
                if var in self.header:
                    raise _NotPlain("header variable repeated")
            elif var == "$ACADVER" and code == 1:
                self.header[var] = value
            elif var == "$INSUNITS" and code == 70:
                self.header[var] = int(value)
        raise _NotPlain("header not closed")

    def _tables(self, pairs: _Stream) -> Tuple[int, str]:
        table, record, handle = "", "", ""
        for code, value in pairs:
            if code == 0:
                if value == "ENDSEC":
                    return code, value
                if value == "TABLE":
                    code, table = next(pairs)
                    if code != 2:
                        raise _NotPlain("table without name")
                record, handle = value, ""
            elif code == 5:
                handle = value
            elif code == 2 and table == "LAYER" and record == "LAYER":
                if value != value.strip() or not value:
                    raise _NotPlain("layer name with spaces around it")
                self.layers.append(value)
            elif (code == 2 and table == "BLOCK_RECORD" and record == "BLOCK_RECORD"
                  and value.lower() == "*model_space"):
                if self.owner is not None or not handle:
                    raise _NotPlain("model space record twice or without handle")
                self.owner = handle
        raise _NotPlain("tables not closed")

    def _blocks(self, pairs: _Stream) -> Tuple[int, str]:
        for code, value in pairs:
            if code == 0 and value not in ("BLOCK", "ENDBLK"):
                if value == "ENDSEC":
                    return code, value
                raise _NotPlain("block content")
        raise _NotPlain("blocks not closed")

    def _entities(self, pairs: _Stream) -> Tuple[int, str]:
        names: Dict[str, str] = {}
        makers: Dict[Tuple, Callable[[List[str]], Any]] = {}
        append = self.entities.append
        last: Tuple[str, List[int]] = ("", [])
        make: Callable[[List[str]], Any] = _make
        while True:
            dxftype, codes, values = pairs.entity()
            if dxftype == "ENDSEC":
                return 0, dxftype
            if dxftype != last[0] or codes != last[1]:   # most entities repeat the last layout
                key = (dxftype, *codes)
                make = makers.get(key)
                if make is None:
                    make = makers[key] = self._maker(dxftype, _plan(dxftype, codes), names)
                last = (dxftype, codes)
            append(make(values))
            if isinstance(make, _LineReader):
                make.run(pairs, codes, self.entities)

    def _maker(self, dxftype: str, plan: List[Tuple], names: Dict[str, str]
               ) -> Callable[[List[str]], Any]:
        """The function making an entity from its tag values, for one plan."""
        owner = self.owner
        line = _LineReader.for_plan(plan, names, owner) if dxftype == "LINE" else None
        return line or (lambda values: _make(dxftype, plan, values, names, owner))


def _plan(dxftype: str, codes: List[int]) -> List[Tuple]:
    """How to read an entity of type ``dxftype`` whose tags have these group
    codes: steps (op, attribute, value indexes).  Everything that depends on
    the codes alone (unknown or repeated codes, incomplete points, required
    attributes) is checked here, once per distinct code sequence."""
    floats = _FLOATS[dxftype]
    points = _POINTS[dxftype]
    lw = dxftype == "LWPOLYLINE"
    steps: List[Tuple] = []
    names: set = set()

    def once(name: str) -> None:
        if name in names:
            raise _NotPlain(f"{name} repeated")
        names.add(name)

    i, n = 0, len(codes)
    while i < n:
        code = codes[i]
        if code in points or code == 210:
            name = points.get(code, "extrusion")
            once(name)
            if i + 1 >= n or codes[i + 1] != code + 10:
                raise _NotPlain("point without y")
            iz = i + 2 if i + 2 < n and codes[i + 2] == code + 20 else -1
            steps.append(("p", name, i, i + 1, iz))
            i = i + 2 if iz < 0 else i + 3
            continue
        if code in floats:
            once(floats[code])
            steps.append(("f", floats[code], i))
        elif code in (5, 8):
            name = "handle" if code == 5 else "layer"
            once(name)
            steps.append(("s", name, i))
        elif code == 62:
            once("color")
            steps.append(("i", "color", i))
        elif code == 67:
            steps.append(("z", "", i))
        elif code == 330:
            steps.append(("o", "", i))
        elif lw and code == 10:
            if i + 1 >= n or codes[i + 1] != 20:
                raise _NotPlain("vertex without y")
            steps.append(("v", "", i, i + 1))
            i += 2
            continue
        elif lw and code in (40, 41, 42):
            if not steps or steps[-1][0] not in ("v", "w"):
                raise _NotPlain("vertex value before the first vertex")
            steps.append(("w", "", i, code - 38))   # row columns 2, 3: widths, 4: bulge
        elif lw and code in (70, 90):
            name = "flags" if code == 70 else "count"
            once(name)
            steps.append(("i", name, i))
        elif code not in _IGNORED:
            raise _NotPlain(f"group code {code} in {dxftype}")
        i += 1
    steps.extend(_markers(dxftype, codes))
    if "handle" not in names:
        raise _NotPlain("no handle")
    for name in _REQUIRED[dxftype]:
        if name not in names:
            raise _NotPlain(f"{dxftype} without {name}")
    return steps


def _markers(dxftype: str, codes: List[int]) -> List[Tuple]:
    """Steps checking the subclass markers: none at all (R12 style, which ezdxf
    reads as one group; not for LWPOLYLINE, which ezdxf refuses without its
    marker), or exactly AcDbEntity then the type's subclasses, each group code
    in its own subclass.  Other layouts are not plain (ezdxf would drop or move
    attributes)."""
    at = [i for i, c in enumerate(codes) if c == 100]
    if not at:
        if dxftype == "LWPOLYLINE":
            raise _NotPlain("LWPOLYLINE without its subclass marker")
        return []
    expected = (("AcDbEntity", _ENTITY_CODES),) + _SUBCLASSES[dxftype]
    if len(at) != len(expected) or not set(codes[:at[0]]) <= _HEAD_CODES:
        raise _NotPlain("subclass markers not as ezdxf writes them")
    steps = []
    for k, (i, (name, allowed)) in enumerate(zip(at, expected)):
        end = at[k + 1] if k + 1 < len(at) else len(codes)
        if not set(codes[i + 1:end]) <= allowed:
            raise _NotPlain(f"group code outside its subclass {name}")
        steps.append(("m", name, i))
    return steps


class _LineReader:
    """A faster :func:`_make` for the LINEs of one tag layout (most of a big
    drawing): the same checks, the steps unrolled, a lean :class:`PlainLine`;
    :meth:`run` reads the LINEs of the same layout that follow at once.  Made
    by :meth:`for_plan`, None when the plan has an extrusion (:func:`_make`
    reads those)."""

    def __init__(self, at: Dict[str, Tuple], checks: List[Tuple], names: Dict[str, str],
                 owner: Optional[str]):
        self.sx, self.sy, self.sz = at["start"]
        self.ex, self.ey, self.ez = at["end"]
        self.ih = at["handle"][0]
        self.il = at["layer"][0] if "layer" in at else -1
        self.ic = at["color"][0] if "color" in at else -1
        self.checks = checks
        self.names = names
        self.owner = owner

    @classmethod
    def for_plan(cls, plan: List[Tuple], names: Dict[str, str], owner: Optional[str]
                 ) -> Optional["_LineReader"]:
        at: Dict[str, Tuple] = {}
        checks = []
        for step in plan:
            if step[0] in "omz":
                checks.append(step)
            elif step[1] == "extrusion":
                return None
            else:
                at[step[1]] = step[2:]
        return cls(at, checks, names, owner)

    def __call__(self, values: List[str]) -> PlainLine:
        for step in self.checks:
            _check(step, values, self.owner)
        handle = values[self.ih]
        if not handle or handle != handle.strip() or not int(handle, 16):
            raise _NotPlain("empty handle, spaces around it or handle 0")
        layer = None
        if self.il >= 0:
            layer = values[self.il]
            if not layer or layer != layer.strip():
                raise _NotPlain("empty layer, or spaces around it")
            layer = self.names.setdefault(layer, layer)
        sz, ez, ic = self.sz, self.ez, self.ic
        return PlainLine((float(values[self.sx]), float(values[self.sy]),
                          float(values[sz]) if sz >= 0 else 0.0),
                         (float(values[self.ex]), float(values[self.ey]),
                          float(values[ez]) if ez >= 0 else 0.0),
                         handle, layer, int(values[ic]) if ic >= 0 else None)

    def run(self, pairs: "_Stream", codes: List[int], entities: List[Any]) -> None:
        """Append to ``entities`` the LINEs with tag codes ``codes`` that follow
        in the stream's current chunk, read column by column (one ``map`` of
        ``float``, ``int`` or a check over each attribute's values: the same
        conversions and checks as :meth:`__call__`, without a Python loop per
        LINE)."""
        row = [0, *codes]
        width = len(row)
        cs, vs, start = pairs.codes, pairs.values, pairs.i
        m = (len(cs) - start - 1) // width      # rows followed by a code in this chunk
        if m < 2:
            return
        same = (np.asarray(cs[start:start + m * width]).reshape(m, width) == row).all(axis=1)
        types = vs[start:start + m * width:width]
        m = min(m if same.all() else int(same.argmin()),
                m if types.count("LINE") == m else [t == "LINE" for t in types].index(False))
        if m and cs[start + m * width] != 0:    # the last LINE goes on: more tags, not this layout
            m -= 1
        if m < 1:
            return
        end = start + m * width

        def col(j: int) -> List[str]:
            return vs[start + 1 + j:end:width]

        for step in self.checks:
            values = col(step[2])
            if (values.count(self.owner) != m if step[0] == "o" else
                    values.count(step[1]) != m if step[0] == "m" else any(map(int, values))):
                raise _NotPlain("owner, subclass marker or paper space flag")
        handles = col(self.ih)
        if "" in handles or list(map(str.strip, handles)) != handles or \
                not all(map(int, handles, repeat(16))):
            raise _NotPlain("empty handle, spaces around it or handle 0")
        layers: Any = repeat(None)
        if self.il >= 0:
            layers = col(self.il)
            if any(not name or name != name.strip() for name in set(layers)):
                raise _NotPlain("empty layer, or spaces around it")
            layers = list(map(self.names.setdefault, layers, layers))
        colors = map(int, col(self.ic)) if self.ic >= 0 else repeat(None)

        def floats(j: int) -> Any:
            return map(float, col(j)) if j >= 0 else repeat(0.0)
        starts = zip(floats(self.sx), floats(self.sy), floats(self.sz))
        ends = zip(floats(self.ex), floats(self.ey), floats(self.ez))
        entities.extend(map(PlainLine, starts, ends, handles, layers, colors))
        pairs.i = end


def _check(step: Tuple, values: List[str], owner: Optional[str]) -> None:
    """The checks of a plan: owner (330) is the model space, subclass marker
    as expected, paper space flag (67) zero."""
    op = step[0]
    if op == "o":
        if values[step[2]] != owner:
            raise _NotPlain("owner is not the model space")
    elif op == "m":
        if values[step[2]] != step[1]:
            raise _NotPlain("unexpected subclass marker")
    elif int(values[step[2]]) != 0:      # "z": group 67, paper space
        raise _NotPlain("paper space entity")


def _make(dxftype: str, plan: List[Tuple], values: List[str], names: Dict[str, str],
          owner: Optional[str]) -> PlainEntity:
    """The entity from its tag ``values`` read as ``plan`` says; ``names`` keeps
    one string object per layer name (a million entities share a few layers);
    an owner handle (330) must be ``owner``, the model space (ezdxf files an
    entity under the layout its owner names)."""
    attrs: Dict[str, Any] = {}
    rows: List[List[float]] = []
    for step in plan:
        op = step[0]
        if op == "p":
            iz = step[4]
            attrs[step[1]] = (float(values[step[2]]), float(values[step[3]]),
                              float(values[iz]) if iz >= 0 else 0.0)
        elif op == "s":
            value = values[step[2]]
            if not value or value != value.strip():
                raise _NotPlain("empty handle or layer, or spaces around it")
            if step[1] == "handle" and not int(value, 16):    # ezdxf refuses handle 0
                raise _NotPlain("handle 0")
            attrs[step[1]] = value if step[1] == "handle" else names.setdefault(value, value)
        elif op == "f":
            attrs[step[1]] = float(values[step[2]])
        elif op == "v":
            rows.append([float(values[step[2]]), float(values[step[3]]), 0.0, 0.0, 0.0])
        elif op == "w":
            rows[-1][step[3]] = float(values[step[2]])
        elif op == "i":
            attrs[step[1]] = int(values[step[2]])
        else:
            _check(step, values, owner)
    if attrs.get("extrusion", _Z_AXIS) != _Z_AXIS:
        raise _NotPlain("an OCS entity")
    e = PlainEntity(dxftype, Attribs())
    if dxftype == "LWPOLYLINE":
        if attrs.pop("count", len(rows)) != len(rows):
            raise _NotPlain("vertex count differs from the vertices")
        e.lwpoints = _LwPoints(rows)
        e.closed = bool(attrs.get("flags", 0) & 1)
    e.dxf.__dict__ = attrs
    return e


def convert_plain(entities: List[Any], t: Tuple[float, ...], out: Any, role: Callable[[str], str],
                  visit: Callable[..., None], progress: Optional[ProgressFn], lo: float,
                  hi: float) -> None:
    """Convert the model-space ``entities`` of a :class:`PlainDocument` into the
    collector ``out`` under the affine map ``t`` (unit scale to mm), exactly as
    ``Walker.walk`` does -- same edges, sources, counters, progress calls and
    expansion check -- but runs of :class:`PlainLine` (most of a big drawing)
    become their :class:`LineEdge` a block at a time (:func:`_line_edges`)
    instead of one ``Walker.visit`` / ``entities.line`` / ``apply`` call chain
    each; every other entity goes to ``visit`` (``Walker.visit``).  ``role``
    maps a layer to its role (``Walker._role``).  Entities are removed from the
    list once converted, so entities and edges never all coexist."""
    check_expanded(len(entities), "", out.path)     # no INSERT in a plain drawing
    count = len(entities)
    n = max(count, 1)
    step = max(n // 50, 500)
    lines = 0
    i = 0
    while i < count:
        j = i
        while j < count and j - i < _LINE_BLOCK and type(entities[j]) is PlainLine:
            j += 1
        for k in range(-(-i // step) * step, max(j, i + 1), step):
            report(progress, lo + (hi - lo) * k / n, f"converting entities ({k}/{n})")
        if j == i:
            e, entities[i] = entities[i], None
            visit(e, t, "", "", None, None, "", 0)
            i += 1
            continue
        block = entities[i:j]
        entities[i:j] = repeat(None, j - i)
        _line_edges(block, t, role, out.edges)
        lines += j - i
        i = j
    if lines:
        out.exploded["LINE"] += lines
        out.converted["LINE"] += lines


#: PlainLines converted at a time (bounds the memory of the block's arrays).
_LINE_BLOCK = 1 << 13


def _line_edges(block: List[PlainLine], t: Tuple[float, ...], role: Callable[[str], str],
                edges: List[Any]) -> None:
    """Append the edges of ``block`` to ``edges``: what ``entities.line`` makes
    of each LINE, with the arithmetic of ``transform.apply`` done by numpy
    (the same IEEE operations in the same order: the same floats)."""
    a, b, c, tx, d, e, f, ty = t
    ends = []
    for name in ("start", "end"):
        x, y, z = np.fromiter(chain.from_iterable(map(attrgetter(name), block)), float,
                              3 * len(block)).reshape(-1, 3).T
        ends.append(zip((a * x + b * y + c * z + tx).tolist(), (d * x + e * y + f * z + ty).tolist()))
    layers = list(map(attrgetter("layer"), block))
    if None in layers:
        layers = ["0" if layer is None else layer for layer in layers]
    colors = list(map(attrgetter("color"), block))
    if None in colors:
        colors = [256 if color is None else color for color in colors]
    roles = {layer: role(layer) for layer in set(layers)}
    sources = map(EdgeSource, layers, colors, map(attrgetter("handle"), block), repeat("LINE"),
                  repeat(""), map(roles.__getitem__, layers), repeat(""))
    edges.extend(map(LineEdge, ends[0], ends[1], sources))
