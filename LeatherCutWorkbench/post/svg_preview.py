"""SVG picture of a cut plan: parts, cuts in order, idle moves dashed.

Drawn in machine coordinates (mm, Y up; the SVG flips Y so the picture looks
like the table seen from above).  Colours follow the legend in
docs/WORKBENCH.md: outer cuts blue, holes red, open chains grey, lead-ins
orange, idle moves dashed green, entry points black dots, order numbers next to
each entry.  Kerf jobs: the cut lines are the compensated tool path (the
filled parts are the drawn outlines, so the half-kerf gap shows), lead-outs
are orange like lead-ins, and tabs (given the machine profile) are drawn as
short black bars across the path.
"""

from __future__ import annotations

from typing import Any, Iterable, List, Optional, Sequence, Tuple
from xml.sax.saxutils import escape

from ..core.geometry import Point, bbox, path_points
from ..core.model import CutPlan, Part

KIND_COLOURS = {"outer": "#1f5fbf", "hole": "#c62828", "open": "#757575"}
LEAD_IN_COLOUR = "#ef6c00"
IDLE_COLOUR = "#2e7d32"
TAB_COLOUR = "#000000"
PART_FILL = "#f3e9dc"


def _path_d(pts: Sequence[Point], closed: bool) -> str:
    body = " L ".join(f"{x:.3f} {-y:.3f}" for x, y in pts)
    return f"M {body}{' Z' if closed else ''}"


def render(plan: CutPlan, parts: Iterable[Part] = (), title: str = "",
           tools: Sequence[Tuple[str, str, list, list]] = (),
           profile: Optional[Any] = None) -> str:
    """Return the SVG document text for ``plan`` (and the filled ``parts``).
    ``tools``: (name, colour, items, points) of the further tools of a
    multi-tool job, drawn in their own colour (lines, strikes as rings); with
    the machine ``profile`` its tabs are drawn too."""
    parts = list(parts)
    all_pts: List[Point] = [plan.home]
    for it in plan.items:
        all_pts.extend(path_points(it.segments, 0.2))
    for p in parts:
        all_pts.extend(p.outer.points(0.2))
    xmin, ymin, xmax, ymax = bbox(all_pts)
    w, h = max(xmax - xmin, 1.0), max(ymax - ymin, 1.0)
    pad = 0.04 * max(w, h) + 5.0
    stroke = max(w, h) / 800.0
    font = max(w, h) / 70.0
    out: List[str] = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{(w + 2 * pad):.1f}mm" '
        f'height="{(h + 2 * pad):.1f}mm" '
        f'viewBox="{xmin - pad:.3f} {-(ymax + pad):.3f} {w + 2 * pad:.3f} {h + 2 * pad:.3f}">',
        f"<title>{escape(title or 'LeatherCut cut plan')}</title>",
        f'<g id="parts" fill="{PART_FILL}" fill-rule="evenodd" stroke="none">',
    ]
    for p in parts:
        d = " ".join(_path_d(c.points(0.2), True) for c in [p.outer] + list(p.holes))
        out.append(f'<path id="part-{escape(p.id)}" d="{d}"/>')
    out.append("</g>")
    out.append(f'<g id="idle" fill="none" stroke="{IDLE_COLOUR}" stroke-width="{stroke:.3f}" '
               f'stroke-dasharray="{4 * stroke:.3f} {3 * stroke:.3f}">')
    for a, b in plan.idle_moves():
        out.append(f'<path d="{_path_d([a, b], False)}"/>')
    out.append("</g>")
    out.append(f'<g id="cuts" fill="none" stroke-width="{1.5 * stroke:.3f}">')
    for it in plan.items:
        n_out = len(it.segments) - it.lead_out_count
        lead, body = it.segments[: it.lead_in_count], it.segments[it.lead_in_count:n_out]
        for cls, piece in (("lead-in", lead), ("lead-out", it.segments[n_out:])):
            if piece:
                out.append(f'<path class="{cls}" stroke="{LEAD_IN_COLOUR}" '
                           f'd="{_path_d(path_points(piece, 0.05), False)}"/>')
        if body:
            colour = KIND_COLOURS.get(it.kind, KIND_COLOURS["open"])
            out.append(f'<path class="{it.kind}" data-contour="{escape(it.contour_id)}" '
                       f'stroke="{colour}" d="{_path_d(path_points(body, 0.05), False)}"/>')
    out.append("</g>")
    for name, colour, items, points in tools:
        out.append(f'<g id="tool-{escape(name)}" class="tool" fill="none" stroke="{colour}" '
                   f'stroke-width="{stroke:.3f}">')
        out += [f'<path d="{_path_d(path_points(it.segments, 0.05), False)}"/>' for it in items]
        out += [f'<circle cx="{x:.3f}" cy="{-y:.3f}" r="{2 * stroke:.3f}"/>' for x, y in points]
        out.append("</g>")
    if profile is not None:
        out.extend(_tabs(plan, profile, stroke))
    out.append(f'<g id="order" font-family="sans-serif" font-size="{font:.3f}">')
    for n, it in enumerate(plan.items, start=1):
        x, y = it.start
        out.append(f'<circle cx="{x:.3f}" cy="{-y:.3f}" r="{1.5 * stroke:.3f}" fill="black"/>')
        out.append(f'<text x="{x + font * 0.3:.3f}" y="{-y - font * 0.3:.3f}">{n}</text>')
    hx, hy = plan.home
    out.append(f'<text x="{hx:.3f}" y="{-hy + font:.3f}" fill="{IDLE_COLOUR}">home</text>')
    out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _tabs(plan: CutPlan, profile: Any, stroke: float) -> List[str]:
    """The tabs of ``plan`` for ``profile`` as bars across the path."""
    from .tabs import plan_tabs, point_along

    gaps = plan_tabs(plan, profile)
    if not gaps:
        return []
    out = [f'<g id="tabs" stroke="{TAB_COLOUR}" stroke-width="{4 * stroke:.3f}">']
    for i, intervals in sorted(gaps.items()):
        segs = plan.items[i].segments
        for a, b in intervals:
            pts = [point_along(segs, a), point_along(segs, b)]
            out.append(f'<path class="tab" d="{_path_d(pts, False)}"/>')
    out.append("</g>")
    return out


def legend() -> List[Tuple[str, str]]:
    """(what, colour) pairs used by the picture, for documentation and the GUI."""
    return [("outer contour cut", KIND_COLOURS["outer"]), ("hole cut", KIND_COLOURS["hole"]),
            ("open chain cut", KIND_COLOURS["open"]), ("lead-in / lead-out", LEAD_IN_COLOUR),
            ("tab (uncut)", TAB_COLOUR),
            ("idle move (dashed)", IDLE_COLOUR), ("part material", PART_FILL)]
