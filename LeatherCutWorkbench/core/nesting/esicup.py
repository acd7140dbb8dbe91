"""Reader for ESICUP strip-packing instances in the jagua-rs / sparrow JSON format.

Format (see tests/data/nest/README.md): ``strip_height``; ``items`` with ``id``,
``demand``, optional ``allowed_orientations`` (degrees; absent = any angle)
and ``shape`` of type ``simple_polygon`` (vertices, not closed), ``polygon``
(``outer`` + ``inner`` rings) or ``rectangle`` (``x_min, y_min, width,
height``).  Items become :class:`Part` objects with line segments, so the
instance runs through exactly the same engine as recognised DXF parts.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import List, Sequence

from ..errors import InputError
from ..geometry import LineSeg, signed_area
from ..model import Contour, Part


@dataclass
class EsicupInstance:
    name: str
    strip_height: float
    parts: List[Part]

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


def read_esicup(path: str) -> EsicupInstance:
    """Read an instance file; errors name the file and the item."""
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
    except OSError as exc:
        raise InputError(f"cannot read ESICUP instance: {exc.strerror}", path) from None
    except json.JSONDecodeError as exc:
        raise InputError(f"not a JSON file (line {exc.lineno}: {exc.msg})", path) from None
    try:
        height = float(data["strip_height"])
        items = data["items"]
    except (KeyError, TypeError, ValueError):
        raise InputError("not an ESICUP strip-packing instance (needs strip_height and items)",
                         path) from None
    parts: List[Part] = []
    for n, it in enumerate(items):
        iid = str(it.get("id", n))
        src = f"{path}: item {iid}"
        try:
            shape = it["shape"]
            kind = shape.get("type")
            holes: List[Contour] = []
            if kind == "simple_polygon":
                outer = _contour(f"{iid}/outer", shape["data"], True)
            elif kind == "polygon":
                outer = _contour(f"{iid}/outer", shape["data"]["outer"], True)
                holes = [_contour(f"{iid}/hole{k}", r, False)
                         for k, r in enumerate(shape["data"].get("inner", []))]
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
        parts.append(Part(id=iid, outer=outer, holes=holes, name=iid, quantity=demand,
                          rotations=rots, mirror_allowed=False))
    if not parts:
        raise InputError("instance has no items", path)
    return EsicupInstance(name=str(data.get("name", "")), strip_height=height, parts=parts)
