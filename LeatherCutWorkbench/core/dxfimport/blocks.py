"""Walking model space: INSERTs exploded to any depth with full transforms.

Each INSERT's ``matrix44()`` (ezdxf: base point, non-uniform and negative
scale, rotation, OCS) is composed onto the parent's affine map, so nested
blocks, mirrors and non-uniform scale come out exact (circles become ellipses
where they must).  MINSERT grids are expanded (a row or column count of 0,
seen in the wild, is read as 1).  ATTRIBs become texts.  DXF inheritance is
honoured: entities on layer ``0`` inside a block take the INSERT's layer, and
colour BYBLOCK (0) takes the INSERT's colour.

Only entities reachable from model space are imported: unreferenced block
definitions (arrow heads, library blocks) are not part of the drawing.  From a
block's second INSERT on, its converted content is reused (:mod:`.blockcache`).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import Any, Callable, Optional

from ezdxf.math import OCS, Matrix44, Vec3

from ..model import EdgeSource
from ..progress import ProgressFn, report
from .blockcache import compile_block, flat, map_edge, map_mark, map_text
from .entities import EDGE_CONVERTERS, TEXT_CONVERTERS, Collector, point, skip_reason
from .limits import check_expanded, minsert_cells
from .transform import Affine, compose

#: Deeper nesting than this is treated as a cyclic block reference.
MAX_DEPTH = 32


@dataclass
class Rules:
    """How layers map to roles for this file (plain drawing or AAMA pattern)."""

    role_of_layer: Callable[[str], str]
    mark_kind_of_layer: Callable[[str], str]
    pieces_from_inserts: bool = False


class Walker:
    """Converts every model-space entity (and block content) into ``out``."""

    def __init__(self, doc: Any, out: Collector, rules: Rules):
        self.doc = doc
        self.out = out
        self.rules = rules
        self.insert_counts: Counter = Counter()
        #: piece key -> (block name, insert handle) in model-space order
        self.piece_inserts: "dict[str, tuple[str, str]]" = {}
        self._roles: "dict[str, str]" = {}
        self._cache: "dict[str, Optional[list]]" = {}
        self._sizes: "dict[str, int]" = {}

    def _role(self, layer: str) -> str:
        role = self._roles.get(layer)
        if role is None:
            role = self._roles[layer] = self.rules.role_of_layer(layer)
        return role

    def walk(self, entities: "list[Any]", root: Affine, progress: Optional[ProgressFn],
             lo: float, hi: float) -> None:
        """Convert the model-space ``entities`` under ``root`` (unit scale);
        progress goes from ``lo`` to ``hi``.  (A plain drawing is converted by
        :func:`.plain_reader.convert_plain` instead.)"""
        self._check_expansion(entities)
        n = max(len(entities), 1)
        step = max(n // 50, 500)
        for i, e in enumerate(entities):
            if i % step == 0:
                report(progress, lo + (hi - lo) * i / n, f"converting entities ({i}/{n})")
            piece = ""
            if self.rules.pieces_from_inserts and e.dxftype() == "INSERT":
                piece = self._piece_key(e)
            self.visit(e, root, "", "", None, None, piece, 0)

    def _check_expansion(self, entities: "list[Any]") -> None:
        """Refuse (limits.py) before expanding anything when the blocks would
        expand to too many entities or a MINSERT grid is too large."""
        total, biggest, most = 0, "", 0
        for e in entities:
            if e.dxftype() != "INSERT":
                total += 1
                continue
            n = self._expanded(e, (), 0)
            total += n
            if n > most:
                biggest, most = f"INSERT #{e.dxf.get('handle', '?')} of block {e.dxf.name!r} " \
                                f"({n:.3g} entities)", n
        check_expanded(total, biggest, self.out.path)

    def _expanded(self, ins: Any, stack: "tuple[str, ...]", depth: int) -> int:
        """Entities an INSERT expands to (its ATTRIBs, every grid cell, nested
        blocks); cyclic, too deep or missing blocks count 1 (they are skipped)."""
        name = ins.dxf.name
        definition = self.doc.blocks.get(name)
        if definition is None or depth >= MAX_DEPTH or name in stack:
            return 1
        rows, cols = _grid_shape(ins.dxf)
        cells = minsert_cells(rows, cols, ins.dxf.get("handle", "?"), self.out.path)
        size = self._sizes.get(name)
        if size is None:
            size = sum(self._expanded(c, stack + (name,), depth + 1) if c.dxftype() == "INSERT"
                       else 1 for c in definition)
            self._sizes[name] = size
        return cells * size + len(ins.attribs)

    def _piece_key(self, insert: Any) -> str:
        name = insert.dxf.name
        key, k = name, 1
        while key in self.piece_inserts:
            k += 1
            key = f"{name}#{k}"
        self.piece_inserts[key] = (name, insert.dxf.get("handle", ""))
        return key

    def visit(self, e: Any, t: Affine, block: str, top_handle: str,
              parent_layer: Optional[str], parent_color: Optional[int], piece: str, depth: int) -> None:
        """Convert ``e`` (inside ``block`` path, under affine ``t``)."""
        dxftype = e.dxftype()
        out = self.out
        if dxftype == "INSERT":
            self.explode(e, t, block, top_handle, parent_layer, parent_color, piece, depth)
            return
        out.exploded[dxftype] += 1
        attrs = vars(e.dxf)   # attributes present in the file (fast; absent = DXF default)
        layer = attrs.get("layer", "0")
        if parent_layer is not None and layer == "0":
            layer = parent_layer
        color = attrs.get("color", 256)
        if color == 0 and parent_color is not None:
            color = parent_color
        handle = top_handle or attrs.get("handle") or ""
        conv = EDGE_CONVERTERS.get(dxftype)
        if conv is not None:
            conv(e, t, EdgeSource(layer, color, handle, dxftype, block, self._role(layer), piece), out)
            out.converted[dxftype] += 1
            return
        conv = TEXT_CONVERTERS.get(dxftype)
        if conv is not None:
            conv(e, t, EdgeSource(layer, color, handle, dxftype, block, "annotation", piece), out)
            out.converted[dxftype] += 1
            return
        if dxftype == "POINT":
            role = self._role(layer)
            role = "mark" if role == "cut" else role
            point(e, t, EdgeSource(layer, color, handle, dxftype, block, role, piece), out,
                  self.rules.mark_kind_of_layer(layer))
            out.converted[dxftype] += 1
            return
        level, reason = skip_reason(dxftype)
        out.skip(e, level, reason, block)

    def explode(self, ins: Any, t: Affine, block: str, top_handle: str,
                parent_layer: Optional[str], parent_color: Optional[int], piece: str, depth: int) -> None:
        """Convert the block content of INSERT/MINSERT ``ins`` and its ATTRIBs."""
        out = self.out
        dxf = ins.dxf
        name = dxf.name
        path = f"{block}/{name}" if block else name
        definition = self.doc.blocks.get(name)
        if definition is None:
            out.skip(ins, "warning", f"block definition {name!r} is missing", block)
            return
        if depth >= MAX_DEPTH or name in block.split("/"):
            out.skip(ins, "warning", f"cyclic or too deep block reference ({path})", block)
            return
        self.insert_counts[name] += 1
        attrs = vars(dxf)
        own_layer = attrs.get("layer", "0")
        layer = parent_layer if parent_layer is not None and own_layer == "0" else own_layer
        color = attrs.get("color", 256)
        # BYBLOCK, or BYLAYER on an inherited layer 0, passes the outer colour on
        if parent_color is not None and (color == 0 or (color == 256 and own_layer == "0")):
            color = parent_color
        handle = top_handle or attrs.get("handle") or ""
        base = ins.matrix44()
        for offset in self._grid_offsets(ins):
            m = base if offset is None else base @ Matrix44.translate(offset.x, offset.y, offset.z)
            tt = compose(t, list(m))
            items = self._compiled(name, definition) if flat(tt) else None
            if items is not None:
                self._instance(items, tt, path, handle, layer, color, piece, depth + 1)
            else:
                for child in definition:
                    self.visit(child, tt, path, handle, layer, color, piece, depth + 1)
            tat = t if offset is None else compose(t, list(Matrix44.translate(offset.x, offset.y, offset.z)))
            for attrib in ins.attribs:
                out.exploded["ATTRIB"] += 1
                TEXT_CONVERTERS["ATTRIB"](attrib, tat, EdgeSource(
                    attrib.dxf.get("layer", layer), attrib.dxf.get("color", color), handle,
                    "ATTRIB", block, "annotation", piece), out)
                out.converted["ATTRIB"] += 1

    def _compiled(self, name: str, definition: Any) -> Optional[list]:
        """Cached items of block ``name`` from its second use on (None: not cacheable)."""
        if self.insert_counts[name] < 2:
            return None
        if name not in self._cache:
            self._cache[name] = compile_block(definition)
        return self._cache[name]

    def _instance(self, items: list, t: Affine, block: str, top_handle: str,
                  parent_layer: str, parent_color: int, piece: str, depth: int) -> None:
        """Same result as visiting every child of a cached block under ``t``."""
        out = self.out
        for kind, e, dxftype, own_layer, own_color, edges, marks, texts in items:
            if kind == "I":
                self.explode(e, t, block, top_handle, parent_layer, parent_color, piece, depth)
                continue
            out.exploded[dxftype] += 1
            if kind == "X":
                out.skip(e, *skip_reason(dxftype), block)
                continue
            layer = parent_layer if own_layer == "0" else own_layer
            color = parent_color if own_color == 0 else own_color
            if texts:
                src = EdgeSource(layer, color, top_handle, dxftype, block, "annotation", piece)
                out.texts.extend(map_text(n, t, src) for n in texts)
            if edges:
                src = EdgeSource(layer, color, top_handle, dxftype, block, self._role(layer), piece)
                for g in edges:
                    mapped = map_edge(g, t, src)
                    if mapped is None:
                        out.skip(e, "warning", "curve degenerates under the block's scale", block)
                    else:
                        out.edges.append(mapped)
            if marks:
                role = self._role(layer)
                src = EdgeSource(layer, color, top_handle, dxftype, block,
                                 "mark" if role == "cut" else role, piece)
                kind_of = self.rules.mark_kind_of_layer(layer)
                out.marks.extend(map_mark(m, t, kind_of, src) for m in marks)
            out.converted[dxftype] += 1

    def _grid_offsets(self, ins: Any) -> "list[Optional[Vec3]]":
        """World offsets of the MINSERT grid cells ([None] for a plain INSERT)."""
        dxf = ins.dxf
        if dxf.get("row_count", 1) < 1 or dxf.get("column_count", 1) < 1:
            self.out.note("minsert-zero-count", "MINSERT with a row or column count of 0 "
                          "read as 1", dxf.get("handle", "?"))
        rows, cols = _grid_shape(dxf)
        if rows == 1 and cols == 1:
            return [None]
        rsp = dxf.get("row_spacing", 0.0)
        csp = dxf.get("column_spacing", 0.0)
        ocs = OCS(dxf.extrusion)
        rot = dxf.get("rotation", 0.0)
        cells = []
        for r in range(rows):
            for c in range(cols):
                v = Vec3(c * csp, r * rsp, 0.0).rotate_deg(rot)
                cells.append(ocs.to_wcs(v) if (r or c) else None)
        return cells


def _grid_shape(dxf: Any) -> "tuple[int, int]":
    """(rows, columns) of a MINSERT grid as expanded: counts below 1 read as 1,
    and a direction without spacing is a single row / column."""
    rows = dxf.get("row_count", 1)
    cols = dxf.get("column_count", 1)
    rows = max(rows, 1) if dxf.get("row_spacing", 0.0) else 1
    cols = max(cols, 1) if dxf.get("column_spacing", 0.0) else 1
    return rows, cols
