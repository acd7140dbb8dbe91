"""Pattern pieces of AAMA / ASTM files: one :class:`PieceInfo` per INSERT.

Built after clean-up from the ``src.piece`` key every edge, mark and text of a
piece carries: name, size, quantity, category and annotation from the block's
``Key: value`` TEXTs, the grain line direction (layer 7) and the mirror line
(layer 6).
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Sequence

from ..model import LineEdge, Mark, PieceInfo, TextNote
from . import aama
from .extents import bounds


def build_pieces(inserts: Dict[str, "tuple[str, str]"], edges: Sequence[Any],
                 marks: Sequence[Mark], texts: Sequence[TextNote]) -> Dict[str, PieceInfo]:
    """PieceInfo per piece key (in model-space order) with indices into the lists."""
    pieces = {key: PieceInfo(key=key, name=block, block=block, insert_handle=handle)
              for key, (block, handle) in inserts.items()}
    for i, e in enumerate(edges):
        p = pieces.get(e.src.piece)
        if p is None:
            continue
        p.edges.append(i)
        if type(e) is LineEdge:
            if e.src.role == "grain" and p.grain_angle is None:
                dx, dy = e.end[0] - e.start[0], e.end[1] - e.start[1]
                p.grain_angle = round(math.degrees(math.atan2(dy, dx)) % 180.0, 6) % 180.0
            elif e.src.role == "mirror" and p.mirror_line is None:
                p.mirror_line = (e.start, e.end)
    for i, m in enumerate(marks):
        p = pieces.get(m.src.piece)
        if p is not None:
            p.marks.append(i)
    for i, t in enumerate(texts):
        p = pieces.get(t.src.piece)
        if p is None:
            continue
        p.texts.append(i)
        kv = aama.key_value(t.text)
        if kv is None:
            continue
        key, value = kv
        if key == "piece name" and value:
            p.name = value
        elif key == "size":
            p.size = value
        elif key == "quantity":
            p.quantity = aama.parse_quantity(value)
        elif key == "category":
            p.category = value
        elif key == "annotation":
            p.annotation = value
    for p in pieces.values():
        cut: List[Any] = [edges[i] for i in p.edges if edges[i].src.role == "cut"]
        p.bbox = bounds(cut)
    return pieces
