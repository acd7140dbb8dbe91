"""A cut plan plus the parts' marks and lines -> one pass per tool, in machine order.

Every mark (drill hole, notch, point) and internal / stitch line of a part is
given to the tool its role is mapped to (post/tools.py).  Order:

* one pass per tool, so each tool is selected once (the fewest tool changes a
  job can have): pens / markers / scribes / crease wheels first, then notch
  tools, then punches, the main tool (knife, torch) last;
* so every mark, line and strike is done before the main tool cuts any part
  free (its outer contour), and while the material still lies as nested;
* what the main knife does besides the plan -- notch slits of
  ``notch_length`` mm into the part along the outline normal, lines mapped to
  the knife -- is cut right before the outer contour of its part (after its
  holes, nearest first), so it too happens before the part is free.

Within a pass, lines are ordered by the path planner (nearest neighbour, both
directions) and strikes by nearest neighbour.  Coordinates are drawn (plan)
positions in mm; writers subtract the tool offset.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

from ..core.geometry import LineSeg, Point, dist, reverse_path
from ..core.model import CutItem, CutPlan, Finding, OpenChain, Part
from .tools import Tool, role_of

#: Order of the passes by tool kind (the main tool always comes last).
_KIND_RANK = {"pen": 0, "marker": 0, "scribe": 0, "crease": 1, "notch": 2, "punch": 3}


@dataclass
class ToolPass:
    """What one tool does: ``items`` to draw / cut (in order) and ``points``
    to strike (in order), drawn coordinates (mm); ``roles`` counts what each
    role contributed."""

    tool: Tool
    items: List[CutItem] = field(default_factory=list)
    points: List[Point] = field(default_factory=list)
    roles: Dict[str, int] = field(default_factory=dict)

    def plan(self, home: Point) -> CutPlan:
        return CutPlan(items=list(self.items), home=home)


@dataclass
class ToolJob:
    """All passes in machine order (main tool last) and what was left undone."""

    passes: List[ToolPass]
    home: Point = (0.0, 0.0)
    findings: List[Finding] = field(default_factory=list)

    @property
    def main(self) -> ToolPass:
        return self.passes[-1]


def line_role(layer: str) -> str:
    """``stitch`` for AAMA layer 14 and layers named like stitch / sew lines,
    else ``internal``."""
    name = layer.strip().lower()
    return "stitch" if name == "14" or "stitch" in name or "sew" in name else "internal"


def _tool_for(role: str, layer: str, mapping: Dict[str, Tool]) -> Optional[Tool]:
    return mapping.get(f"layer:{layer}") or mapping.get(role)


def notch_slit(part: Part, at: Point, length: float) -> LineSeg:
    """A slit of ``length`` mm from the outline point nearest ``at`` into the
    part, along the inward normal of the outer contour (stored
    counter-clockwise, so inward is to the left of the direction of travel)."""
    from shapely.geometry import LinearRing
    from shapely.geometry import Point as SPoint

    ring = LinearRing(part.outer.points(0.01))
    s = ring.project(SPoint(at))
    q = ring.interpolate(s)
    a, b = ring.interpolate(s - 0.05), ring.interpolate(s + 0.05)
    tx, ty = b.x - a.x, b.y - a.y
    n = math.hypot(tx, ty) or 1.0
    if part.outer.area < 0:               # a clockwise outline: inward is to the right
        tx, ty = -tx, -ty
    nx, ny = -ty / n, tx / n
    return LineSeg((q.x, q.y), (q.x + length * nx, q.y + length * ny))


def _nn_points(points: Sequence[Point], start: Point) -> List[Point]:
    left = list(points)
    out: List[Point] = []
    here = start
    while left:
        k = min(range(len(left)), key=lambda i: dist(here, left[i]))
        here = left.pop(k)
        out.append(here)
    return out


def _nn_items(items: Sequence[CutItem], start: Point) -> List[CutItem]:
    """Open items in nearest-neighbour order from ``start``, each cut from its
    nearer end."""
    left = list(items)
    out: List[CutItem] = []
    here = start
    while left:
        k = min(range(len(left)), key=lambda i: min(dist(here, left[i].start), dist(here, left[i].end)))
        it = left.pop(k)
        if dist(here, it.end) < dist(here, it.start):
            segs = reverse_path(it.segments)
            it = CutItem(it.contour_id, it.part_id, it.kind, segs[0].start, segs)
        out.append(it)
        here = it.end
    return out


def _order_lines(chains: Sequence[OpenChain], home: Point) -> List[CutItem]:
    from ..core.pathplan import PlanOptions, plan

    if not chains:
        return []
    return plan([], list(chains), PlanOptions(method="nn", home=home, bound_time=0.01)).items


def build_tool_job(plan: CutPlan, parts: Sequence[Part], mapping: Dict[str, Tool],
                   main: Tool, notch_length: float) -> ToolJob:
    """Passes of ``plan`` (the main tool's cut) and of the marks and lines of
    ``parts`` under ``mapping`` (role -> tool).  With an empty mapping the job
    is the plan alone."""
    job = ToolJob(passes=[], home=plan.home)
    by_tool: Dict[str, ToolPass] = {}
    lines_of: Dict[str, List[OpenChain]] = {}
    before_outer: Dict[str, List[CutItem]] = {}
    undone: Dict[str, int] = {}

    def count(p: ToolPass, role: str) -> None:
        p.roles[role] = p.roles.get(role, 0) + 1

    main_pass = ToolPass(main)
    for part in parts:
        for m in part.marks:
            role = role_of(m.kind)
            tool = _tool_for(role, m.src.layer, mapping)
            if tool is None:
                undone[role] = undone.get(role, 0) + 1
                continue
            if tool.main:
                slit = notch_slit(part, m.position, notch_length)
                before_outer.setdefault(part.id, []).append(
                    CutItem(f"{part.id}/notch", part.id, "open", slit.start, [slit]))
                count(main_pass, role)
                continue
            p = by_tool.setdefault(tool.name, ToolPass(tool))
            p.points.append(m.position)
            count(p, role)
        for ln in part.lines:
            role = line_role(ln.layer)
            tool = _tool_for(role, ln.layer, mapping)
            if tool is None:
                undone[role] = undone.get(role, 0) + 1
                continue
            if tool.main:
                before_outer.setdefault(part.id, []).append(
                    CutItem(ln.id, part.id, "open", ln.start, list(ln.segments)))
                count(main_pass, role)
                continue
            p = by_tool.setdefault(tool.name, ToolPass(tool))
            lines_of.setdefault(tool.name, []).append(ln)
            count(p, role)
    for name, p in by_tool.items():
        p.items = _order_lines(lines_of.get(name, []), plan.home)
        p.points = _nn_points(p.points, plan.home)
    placed = set()
    for it in plan.items:
        if it.kind == "outer" and it.part_id in before_outer and it.part_id not in placed:
            here = main_pass.items[-1].end if main_pass.items else plan.home
            main_pass.items.extend(_nn_items(before_outer[it.part_id], here))
            placed.add(it.part_id)
        main_pass.items.append(it)
    lost = sum(len(v) for k, v in before_outer.items() if k not in placed)
    if lost:
        job.findings.append(Finding("warning", "tool-work-without-part",
                                    f"{lost} notch slit(s) / knife line(s) belong to parts that "
                                    "are not cut; not written"))
    job.passes = sorted(by_tool.values(), key=lambda p: (_KIND_RANK.get(p.tool.kind, 4),
                                                         p.tool.number)) + [main_pass]
    for role, n in sorted(undone.items() if mapping else ()):
        job.findings.append(Finding("info", "role-not-mapped",
                                    f"{n} {role} mark(s)/line(s) are not done: no tool is mapped "
                                    f"to role {role!r} (profile tool_map or --tool-map)"))
    return job
