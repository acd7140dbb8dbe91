"""Read a layout JSON (the ``--layout-out`` schema of :mod:`core.nesting.outputs`)
back into a :class:`~LeatherCutWorkbench.core.model.Layout`, so a layout nested
once, or edited by hand, is cut as it stands (``--layout-in``).

Only the placements (part, copy, container, angle in degrees, mirrored, x, y in
mm) and the containers (id, kind, outline, defects, zones) are read; the
``polygon`` / ``holes`` of each item are derived data and ignored: the parts
come from recognising the drawing again.  Bad input raises InputError naming
the file and the item.
"""

from __future__ import annotations

import json
from typing import Any, List

from .errors import InputError
from .model import Container, Layout, Placement, Point


def _ring(value: Any, path: str, what: str) -> List[Point]:
    try:
        pts = [(float(p[0]), float(p[1])) for p in value]
    except (TypeError, ValueError, IndexError):
        raise InputError(f"{what}: not a list of [x, y] points", source=path)
    if len(pts) < 3:
        raise InputError(f"{what}: a polygon needs at least 3 points", source=path)
    return pts


def read_layout_json(path: str) -> Layout:
    """The layout stored in ``path`` (see module doc)."""
    try:
        with open(path, "r", encoding="utf-8") as fh:
            data = json.load(fh)
    except OSError as exc:
        raise InputError(f"cannot read the layout: {exc.strerror}", source=path)
    except ValueError as exc:
        raise InputError(f"not a layout JSON file: {exc}", source=path)
    if not isinstance(data, dict) or not isinstance(data.get("items"), list) \
            or not isinstance(data.get("containers"), list):
        raise InputError("not a layout JSON file: 'containers' and 'items' lists expected",
                         source=path)
    containers = []
    for k, c in enumerate(data["containers"]):
        try:
            cid, kind = str(c["id"]), str(c.get("kind", "sheet"))
            zones = [(int(z["grade"]), _ring(z["outline"], path, f"container {cid} zone"))
                     for z in c.get("zones", [])]
        except (KeyError, TypeError, ValueError, AttributeError):
            raise InputError(f"container {k}: needs 'id' and 'outline'", source=path)
        containers.append(Container(
            cid, kind, _ring(c.get("outline"), path, f"container {cid} outline"),
            [_ring(d, path, f"container {cid} defect") for d in c.get("defects", [])], zones))
    placements = []
    for k, it in enumerate(data["items"]):
        try:
            placements.append(Placement(part_id=str(it["part"]), copy=int(it["copy"]),
                                        container=str(it["container"]), x=float(it["x"]),
                                        y=float(it["y"]), angle=float(it.get("angle", 0.0)),
                                        mirrored=bool(it.get("mirrored", False))))
        except (KeyError, TypeError, ValueError, AttributeError):
            raise InputError(f"item {k}: needs part, copy, container, x and y", source=path)
    return Layout(containers=containers, placements=placements)
