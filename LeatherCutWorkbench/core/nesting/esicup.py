"""Reader for benchmark instances in the jagua-rs / sparrow JSON formats.

Strip packing (see tests/data/nest/README.md): ``strip_height``; ``items``
with ``id``, ``demand``, optional ``allowed_orientations`` (degrees; absent =
any angle) and ``shape`` of type ``simple_polygon`` (vertices, not closed),
``polygon`` (``outer`` + ``inner`` rings) or ``rectangle`` (``x_min, y_min,
width, height``).

Bin packing with quality zones (jagua-rs; the Baldacci et al. 2014 leather
hides): ``bins`` instead of ``strip_height``, each with ``stock`` (copies,
default 1), ``cost``, ``shape`` (a polygon: ``outer`` plus ``inner`` rings =
holes of the hide) and ``zones`` (``quality`` q, ``shape``; quality 0 is a
hole); items may carry ``min_quality`` m: such an item may lie on zones of
quality >= m, an item without it needs full quality (outside every zone).
jagua-rs' older PascalCase files (``Items`` / ``Objects`` with ``Demand``,
``BaseQuality``, ``Stock``, ``Zones`` / ``Quality``, ``Shape.Outer`` /
``Shape.Inner``) read the same.  Bins become hides (:class:`Container`):
full quality = 1 + the highest quality in the file is the hide's base grade,
zones keep their quality as grade, holes and quality-0 zones are defects; an
item's grade is its ``min_quality`` (else full quality).  Items may carry
``zones`` of their own (Baldacci Test8/10: ``Zones`` with ``Quality`` q
inside an item; jagua-rs itself does not read them): a part region that must
lie on quality >= q, q = 0 anywhere on the hide (``Part.grade_regions``,
:mod:`part_regions`); the rest of the item needs the item's grade.

Items become :class:`Part` objects with line segments, so an instance runs
through exactly the same engine as recognised DXF parts.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence

from shapely.geometry import Polygon
from shapely.validation import explain_validity, make_valid

from ..errors import InputError
from ..geometry import LineSeg, signed_area
from ..model import Container, Contour, Finding, Part


@dataclass
class EsicupInstance:
    name: str
    strip_height: Optional[float]         # None for a bin-packing (hide) instance
    parts: List[Part]
    hides: List[Container] = field(default_factory=list)
    findings: List[Finding] = field(default_factory=list)   # rings repaired on reading

    @property
    def item_area(self) -> float:
        return sum(p.net_area * p.quantity for p in self.parts)


def _contour(cid: str, pts: Sequence[Sequence[float]], ccw: bool) -> Contour:
    p = [(float(x), float(y)) for x, y in pts]
    if len(p) > 1 and p[0] == p[-1]:
        p = p[:-1]
    if len(p) < 3:
        raise InputError(f"item ring {cid} has fewer than 3 vertices")
    if (signed_area(p) > 0) != ccw:
        p = p[::-1]
    segs = [LineSeg(p[i], p[(i + 1) % len(p)]) for i in range(len(p))]
    return Contour(id=cid, segments=segs)


def _valid_rings(pts: Sequence[Sequence[float]], src: str, findings: List[Finding],
                 single: bool = False) -> List[list]:
    """The ring ``pts`` as one or more simple rings covering the same area.

    Some Baldacci rings touch or cross themselves (Test10's item zones: a
    spike back along an edge, a loop of a few units); shapely's
    ``make_valid`` splits such a ring into its simple pieces (zero-area
    spikes vanish) and a warning names the ring.  A ``single`` ring (a part
    or hide outline) that would fall apart, or any ring whose repair has a
    hole, raises InputError: no simple ring keeps it."""
    ring = [(float(x), float(y)) for x, y in pts]
    if len(ring) > 1 and ring[0] == ring[-1]:
        ring = ring[:-1]
    if len(ring) < 3:
        raise InputError("ring has fewer than 3 vertices", src)
    poly = Polygon(ring)
    if poly.is_valid:
        return [ring]
    why = explain_validity(poly)
    fixed = make_valid(poly)
    pieces = [g for g in getattr(fixed, "geoms", [fixed])
              if g.geom_type == "Polygon" and g.area > 0]
    if not pieces or (single and len(pieces) > 1) or any(g.interiors for g in pieces):
        raise InputError(f"ring is not simple ({why}) and cannot be repaired into "
                         f"{'one simple ring' if single else 'simple rings'}", src)
    findings.append(Finding("warning", "ring-repaired",
                            f"ring is not simple ({why}): read as {len(pieces)} simple ring(s) "
                            f"of area {sum(g.area for g in pieces):.6g} (shoelace "
                            f"{abs(signed_area(ring)):.6g})", src))
    return [list(g.exterior.coords)[:-1] for g in pieces]


def _zone_rings(zone: Dict, src: str, findings: List[Finding]) -> List[list]:
    """The simple rings of a zone (item or hide) with ``_valid_rings``; a zone
    with holes raises InputError (no zone model keeps them)."""
    outer, inner = _rings(zone["shape"], src)
    if inner:
        raise InputError("zones with holes are not supported", src)
    return _valid_rings(outer, src, findings)


def read_esicup(path: str) -> EsicupInstance:
    """Read an instance file; errors name the file and the item."""
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
    except OSError as exc:
        raise InputError(f"cannot read ESICUP instance: {exc.strerror}", path) from None
    except json.JSONDecodeError as exc:
        raise InputError(f"not a JSON file (line {exc.lineno}: {exc.msg})", path) from None
    if isinstance(data, dict) and ("bins" in data or "Objects" in data):
        return _read_bins(path, _snake(data))
    try:
        height = float(data["strip_height"])
        items = data["items"]
    except (KeyError, TypeError, ValueError):
        raise InputError("not an ESICUP strip-packing instance (needs strip_height and items) "
                         "nor a bin-packing one (bins and items)", path) from None
    findings: List[Finding] = []
    parts = _items(path, items, findings)
    return EsicupInstance(name=str(data.get("name", "")), strip_height=height, parts=parts,
                          findings=findings)


def _items(path: str, items: Any, findings: List[Finding], grade_of=None) -> List[Part]:
    """Parts from the ``items`` list (``grade_of(item)``: the part's grade;
    repaired rings reported in ``findings``)."""
    parts: List[Part] = []
    if not isinstance(items, list):
        raise InputError("items must be a list", path)
    for n, it in enumerate(items):
        iid = str(it.get("id", n))
        src = f"{path}: item {iid}"
        try:
            shape = it["shape"]
            kind = shape.get("type")
            holes: List[Contour] = []
            if kind == "simple_polygon":
                outer = _contour(f"{iid}/outer",
                                 _valid_rings(shape["data"], src, findings, True)[0], True)
            elif kind == "polygon":
                outer = _contour(f"{iid}/outer",
                                 _valid_rings(shape["data"]["outer"], src, findings, True)[0], True)
                holes = [_contour(f"{iid}/hole{len(holes)}", h, False)
                         for k, r in enumerate(shape["data"].get("inner", []))
                         for h in _valid_rings(r, f"{src} hole {k}", findings)]
            elif kind == "rectangle":
                d = shape["data"]
                x, y, w, h = (float(d[k]) for k in ("x_min", "y_min", "width", "height"))
                outer = _contour(f"{iid}/outer", [(x, y), (x + w, y), (x + w, y + h), (x, y + h)], True)
            else:
                raise InputError(f"unsupported shape type {kind!r}", src)
            demand = int(it.get("demand", 1))
            rots = it.get("allowed_orientations")
            rots = None if rots is None else [float(a) for a in rots] or [0.0]
        except InputError:
            raise
        except (KeyError, TypeError, ValueError) as exc:
            raise InputError(f"malformed item ({type(exc).__name__}: {exc})", src) from None
        if demand < 0:
            raise InputError(f"negative demand {demand}", src)
        regions = []
        for k, z in enumerate(it.get("zones") or []):
            try:
                for n_r, r in enumerate(_zone_rings(z, f"{src} zone {k}", findings)):
                    regions.append((int(z["quality"]),
                                    _contour(f"{iid}/zone{k}" + (f".{n_r}" if n_r else ""), r, True)))
            except InputError:
                raise
            except (KeyError, TypeError, ValueError) as exc:
                raise InputError(f"malformed item zone {k} ({type(exc).__name__}: {exc})",
                                 src) from None
        parts.append(Part(id=iid, outer=outer, holes=holes, name=iid, quantity=demand,
                          rotations=rots, mirror_allowed=False,
                          grade=grade_of(it) if grade_of else 0, grade_regions=regions))
    if not parts:
        raise InputError("instance has no items", path)
    return parts


_PASCAL = {"Name": "name", "Items": "items", "Objects": "bins", "Demand": "demand",
           "BaseQuality": "min_quality", "Quality": "quality", "Stock": "stock", "Cost": "cost",
           "Zones": "zones", "Shape": "shape", "Outer": "outer", "Inner": "inner", "Id": "id",
           "AllowedOrientations": "allowed_orientations"}


def _snake(data: Any) -> Any:
    """jagua-rs' older PascalCase keys to the snake_case ones (shapes there are
    ``{"Outer", "Inner"}`` without a type: they become ``polygon`` shapes)."""
    if isinstance(data, list):
        return [_snake(v) for v in data]
    if not isinstance(data, dict):
        return data
    if "Outer" in data and "type" not in data:
        return {"type": "polygon", "data": {"outer": data["Outer"], "inner": data.get("Inner", [])}}
    return {_PASCAL.get(k, k): _snake(v) for k, v in data.items()}


def _rings(shape: Dict, src: str) -> "tuple[list, list]":
    """(outer ring, inner rings) of a bin or zone shape, as point lists."""
    kind = shape.get("type")
    if kind == "simple_polygon":
        return [(float(x), float(y)) for x, y in shape["data"]], []
    if kind == "polygon":
        d = shape["data"]
        return ([(float(x), float(y)) for x, y in d["outer"]],
                [[(float(x), float(y)) for x, y in r] for r in d.get("inner", [])])
    raise InputError(f"unsupported shape type {kind!r}", src)


def _ring_pts(c: Contour) -> list:
    return [s.start for s in c.segments]


def _read_bins(path: str, data: Dict) -> EsicupInstance:
    """A bin-packing instance with quality zones (see module doc)."""
    try:
        bins, items = data["bins"], data["items"]
        quals = [int(z["quality"]) for b in bins for z in b.get("zones", [])]
        quals += [int(it["min_quality"]) for it in items if it.get("min_quality") is not None]
        quals += [int(z["quality"]) for it in items for z in it.get("zones") or []]
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed bin-packing instance ({type(exc).__name__}: {exc})",
                         path) from None
    full = max(quals, default=0) + 1

    def grade_of(it) -> int:
        m = it.get("min_quality")
        return full if m is None else int(m)

    findings: List[Finding] = []
    parts = _items(path, items, findings, grade_of)
    hides: List[Container] = []
    for n, b in enumerate(bins):
        src = f"{path}: bin {b.get('id', n)}"
        try:
            outer, inner = _rings(b["shape"], src)
            stock = int(b.get("stock", 1))
            defects = [_ring_pts(_contour(f"{src}/hole{k}", h, True)) for k, r in enumerate(inner)
                       for h in _valid_rings(r, f"{src} hole {k}", findings)]
            zones = []
            for k, z in enumerate(b.get("zones", [])):
                for r in _zone_rings(z, f"{src} zone {k}", findings):
                    ring = _ring_pts(_contour(f"{src}/zone{k}", r, True))
                    if int(z["quality"]) <= 0:
                        defects.append(ring)
                    else:
                        zones.append((int(z["quality"]), ring))
            ring = _ring_pts(_contour(f"{src}/outer", _valid_rings(outer, src, findings, True)[0],
                                      True))
        except InputError:
            raise
        except (KeyError, TypeError, ValueError) as exc:
            raise InputError(f"malformed bin ({type(exc).__name__}: {exc})", src) from None
        for k in range(max(stock, 0)):
            hides.append(Container(id=f"bin{b.get('id', n)}" + (f"_{k + 1}" if stock > 1 else ""),
                                   kind="hide", outline=list(ring), defects=[list(d) for d in defects],
                                   zones=[(g, list(r)) for g, r in zones], base_grade=full))
    if not hides:
        raise InputError("instance has no bins", path)
    return EsicupInstance(name=str(data.get("name", "")), strip_height=None, parts=parts,
                          hides=hides, findings=findings)
