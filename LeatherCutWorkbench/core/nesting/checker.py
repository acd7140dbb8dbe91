"""Independent validity check of a layout (shapely; shares no code with the engine).

A layout is valid when, within the length tolerance ``tol`` (mm):

* every placement names a known part, a copy index below its quantity, no
  copy twice, and a known container;
* its angle is one the part allows (to 1e-6 degrees) and it is mirrored only
  if the part allows mirroring;
* the placed true shape lies inside its container's outline (area outside
  <= tol x perimeter);
* it overlaps no defect and no other part beyond tol x the shorter perimeter
  (an overlap thinner than tol everywhere has at most that area); parts in a
  hole of another part are fine;
* it keeps ``spacing - tol`` from every other part and ``margin - tol`` from
  the container edge and the defects;
* on a hide, it lies only in zones of its grade or better (the innermost /
  smallest zone containing a point decides its grade, else ``base_grade``);
  a part with graded regions (``Part.grade_regions``): each region (where
  regions overlap, the smallest decides) lies on material of the region's
  grade or better, the rest of the part on material of the part's grade or
  better, and a region of grade 0 may also cover defects.

:func:`check_layout` returns a list of problems (empty = valid).
"""

from __future__ import annotations

from typing import Dict, List, Optional, Sequence, Set

from shapely import affinity, prepared
from shapely.geometry import Polygon, box
from shapely.strtree import STRtree

from ..model import Container, Layout, Part


def part_polygon(part: Part, chord_tol: float = 0.05) -> Polygon:
    """The part's true shape (holes included), in part coordinates."""
    return Polygon(part.outer.points(chord_tol), [h.points(chord_tol) for h in part.holes])


def placed_polygon(poly: Polygon, x: float, y: float, angle: float, mirrored: bool) -> Polygon:
    """Mirror about the part's Y axis, rotate about its origin, translate."""
    g = poly
    if mirrored:
        g = affinity.scale(g, xfact=-1.0, yfact=1.0, origin=(0, 0))
    if angle:
        g = affinity.rotate(g, angle, origin=(0, 0))
    return affinity.translate(g, x, y)


def _angle_ok(angle: float, allowed: Optional[Sequence[float]]) -> bool:
    if allowed is None:
        return True
    for a in allowed:
        d = (angle - a) % 360.0
        if min(d, 360.0 - d) <= 1e-6:
            return True
    return False


def _graded_pieces(part: Part, whole: Polygon, chord_tol: float) -> List[tuple]:
    """(grade, shape, label) of the part's regions (smallest first, each
    without the smaller ones) and of the rest, in part coordinates."""
    regs = sorted(((g, Polygon(c.points(chord_tol)), k) for k, (g, c) in enumerate(part.grade_regions)),
                  key=lambda r: r[1].area)
    out, taken = [], Polygon()
    for g, poly, k in regs:
        out.append((g, poly.intersection(whole).difference(taken), f"region {k}"))
        taken = taken.union(poly)
    out.append((part.grade, whole.difference(taken), "rest"))
    return [o for o in out if not o[1].is_empty]


def _zone_grade_region(c: Container, grade: int):
    """The part of the hide a part of ``grade`` may use (shapely geometry)."""
    region = Polygon(c.outline) if c.base_grade >= grade else Polygon()
    for zg, ring in sorted(c.zones, key=lambda z: -abs(Polygon(z[1]).area)):
        zp = Polygon(ring)
        region = region.union(zp) if zg >= grade else region.difference(zp)
    return region


class _ContainerShapes:
    """A container's outline, defects and per-grade zone regions as shapely
    geometry, built once per check (a hide with 30 holes and 20 zones took
    ~30 ms per placed copy to rebuild: 240 copies of Baldacci Scarpa
    overran a 10 s budget by the check alone).  Prepared geometries answer
    "fully inside" quickly; only parts that are not get an area test."""

    def __init__(self, c: Container) -> None:
        self.c = c
        self.outline = Polygon(c.outline)
        self.outline_prep = prepared.prep(self.outline)
        self.defects = [Polygon(d) for d in c.defects]
        self.defect_tree = STRtree(self.defects) if self.defects else None
        self._zones: Dict[int, tuple] = {}

    def outside_area(self, g: Polygon) -> float:
        return 0.0 if self.outline_prep.covers(g) else g.difference(self.outline).area

    def defects_near(self, g: Polygon, reach: float) -> List[int]:
        """Indices (ascending) of the defects whose bounding box comes within
        ``reach`` of ``g``'s; the others neither overlap nor come closer."""
        if self.defect_tree is None or g.is_empty:
            return []
        x0, y0, x1, y1 = g.bounds
        probe = box(x0 - reach, y0 - reach, x1 + reach, y1 + reach)
        return sorted(int(k) for k in self.defect_tree.query(probe))

    def below_grade_area(self, sh: Polygon, grade: int) -> float:
        if grade not in self._zones:
            region = _zone_grade_region(self.c, grade)
            self._zones[grade] = (region, prepared.prep(region))
        region, prep = self._zones[grade]
        return 0.0 if prep.covers(sh) else sh.difference(region).area


def problem_labels(problems: Sequence[str]) -> Set[str]:
    """The copies (``PART#COPY``) that :func:`check_layout`'s problems name
    first: one per problem (of an overlapping pair, the first)."""
    return {msg.split(" ", 1)[0].rstrip(":") for msg in problems}


def check_layout(parts: Sequence[Part], layout: Layout, spacing: float = 0.0,
                 margin: float = 0.0, tol: float = 1e-3, chord_tol: float = 0.05,
                 rotations_override: Optional[List[float]] = None,
                 mirror_override: Optional[bool] = None,
                 free_rotation: bool = False) -> List[str]:
    """Problems found in ``layout`` (empty list = valid).  See module doc."""
    problems: List[str] = []
    by_id: Dict[str, Part] = {p.id: p for p in parts}
    conts: Dict[str, Container] = {c.id: c for c in layout.containers}
    shapes: Dict[str, _ContainerShapes] = {}
    base = {p.id: part_polygon(p, chord_tol) for p in parts}
    graded = {p.id: _graded_pieces(p, base[p.id], chord_tol) for p in parts if p.grade_regions}
    seen = set()
    placed: List[Polygon] = []
    labels: List[str] = []
    where: List[str] = []
    for pl in layout.placements:
        lab = f"{pl.part_id}#{pl.copy}"
        part = by_id.get(pl.part_id)
        if part is None:
            problems.append(f"{lab}: unknown part")
            continue
        if (pl.part_id, pl.copy) in seen:
            problems.append(f"{lab}: placed twice")
        seen.add((pl.part_id, pl.copy))
        if not 0 <= pl.copy < part.quantity:
            problems.append(f"{lab}: copy index outside quantity {part.quantity}")
        allowed = None if free_rotation else (
            rotations_override if rotations_override is not None else part.rotations)
        if not _angle_ok(pl.angle, allowed):
            problems.append(f"{lab}: angle {pl.angle:g} not allowed ({allowed})")
        mir_ok = part.mirror_allowed if mirror_override is None else mirror_override
        if pl.mirrored and not mir_ok:
            problems.append(f"{lab}: mirrored but mirroring is not allowed")
        c = conts.get(pl.container)
        if c is None:
            problems.append(f"{lab}: unknown container {pl.container!r}")
            continue
        cs = shapes.get(c.id)
        if cs is None:
            cs = shapes[c.id] = _ContainerShapes(c)
        g = placed_polygon(base[pl.part_id], pl.x, pl.y, pl.angle, pl.mirrored)
        per = g.exterior.length
        outline = cs.outline
        out_area = cs.outside_area(g)
        if out_area > tol * per:
            problems.append(f"{lab}: {out_area:.4g} mm2 outside container {c.id}")
        if margin > tol and g.exterior.distance(outline.exterior) < margin - tol \
                and out_area <= tol * per:
            problems.append(f"{lab}: closer than the margin {margin:g} mm to the edge of {c.id}")
        pieces = [(part.grade, g, "")] if part.id not in graded else [
            (pg, placed_polygon(sh, pl.x, pl.y, pl.angle, pl.mirrored), f" {lab}")
            for pg, sh, lab in graded[part.id]]
        strict = g
        for pg, sh, _lab in pieces:
            if pg <= 0 and part.id in graded:        # a grade-0 region may cover defects
                strict = strict.difference(sh)
        for k in cs.defects_near(strict, max(margin, 0.0) + tol):
            dp = cs.defects[k]
            ov = strict.intersection(dp).area
            if ov > tol * min(per, dp.exterior.length):
                problems.append(f"{lab}: covers defect {k} of {c.id} ({ov:.4g} mm2)")
            elif margin > tol and strict.distance(dp) < margin - tol:
                problems.append(f"{lab}: closer than the margin {margin:g} mm to defect {k} of {c.id}")
        for pg, sh, plab in pieces:
            if pg <= 0 or not (c.zones or c.base_grade < pg):
                continue
            bad = cs.below_grade_area(sh, pg)
            if bad > tol * per:
                problems.append(f"{lab}{plab}: {bad:.4g} mm2 in material below grade {pg}")
        placed.append(g)
        labels.append(lab)
        where.append(pl.container)
    # pairwise overlap and spacing
    if placed:
        tree = STRtree(placed)
        reach = max(spacing - tol, 0.0)
        for i, g in enumerate(placed):
            probe = g.buffer(reach, 4) if reach > 0 else g
            for j in tree.query(probe):
                j = int(j)
                if j <= i or where[i] != where[j]:
                    continue
                h = placed[j]
                lim = tol * min(g.exterior.length, h.exterior.length)
                ov = g.intersection(h).area
                if ov > lim:
                    problems.append(f"{labels[i]} overlaps {labels[j]} by {ov:.4g} mm2")
                elif reach > 0 and g.distance(h) < spacing - tol:
                    problems.append(f"{labels[i]} and {labels[j]} are {g.distance(h):.4g} mm apart "
                                    f"(spacing {spacing:g} mm)")
    for (pid, cp) in layout.unplaced:
        if (pid, cp) in seen:
            problems.append(f"{pid}#{cp}: both placed and unplaced")
    return problems
