"""Colours and line styles of LeatherCut objects in the 3D view.

One table, used by the view and documented in docs/WORKBENCH.md (colour
legend).  The colours match the SVG preview of ``leathercut run``
(post/svg_preview.py) so the workbench and the CLI speak the same language.
Everything here is a no-op without the GUI.
"""

from __future__ import annotations

import FreeCAD


def _rgb(hex_colour: str):
    h = hex_colour.lstrip("#")
    return tuple(int(h[i:i + 2], 16) / 255.0 for i in (0, 2, 4))


#: kind -> (hex colour, line width px, line pattern (0xffff solid), point size px)
KINDS = {
    "layer": ("#404040", 1.0, 0xFFFF, 2.0),
    "outer": ("#1f5fbf", 2.0, 0xFFFF, 2.0),      # part outlines: blue
    "hole": ("#c62828", 2.0, 0xFFFF, 2.0),       # holes: red
    "lead_in": ("#ef6c00", 2.0, 0xFFFF, 2.0),    # lead-ins / lead-outs: orange
    "open": ("#757575", 1.5, 0xF0F0, 2.0),       # stray open chains: grey, dashed
    "excluded": ("#bdbdbd", 1.0, 0xCCCC, 2.0),   # excluded contours: light grey, dotted
    "marks": ("#6a1b9a", 1.0, 0xFFFF, 5.0),      # drill holes / notches: purple points
    "container": ("#5d4037", 2.0, 0xFFFF, 2.0),  # sheet / strip / hide outline: brown
    "defect": ("#b71c1c", 2.0, 0x3333, 2.0),     # hide defects: dark red, dotted
    "cut": ("#1f5fbf", 2.0, 0xFFFF, 2.0),        # cutting moves: blue, solid
    "idle": ("#2e7d32", 1.0, 0x0F0F, 2.0),       # idle moves (knife up): green, dashed
    "entry": ("#000000", 1.0, 0xFFFF, 7.0),      # entry points: black dots
}

FLAG_PENDING = "#d500f9"    # a flag nobody decided yet: magenta
FLAG_DECIDED = "#00897b"    # decided: teal
PLACED_OK = "#f3e9dc"       # placed part face: leather beige
PLACED_EDGE = "#1f5fbf"
PLACED_COLLIDES = "#e53935"  # overlapping / outside the container: red
PART_FACE = "#f3e9dc"       # a recognised part chosen for the cut: leather beige, see-through


def set_pattern(vo, pattern: int) -> None:
    """Solid / dashed / dotted lines on a Part view provider (``DrawStyle``)."""
    if "DrawStyle" not in vo.PropertiesList:
        return
    vo.DrawStyle = {0xFFFF: "Solid", 0x0F0F: "Dashed", 0xF0F0: "Dashed"}.get(pattern, "Dotted")


def colour(kind: str):
    return _rgb(KINDS[kind][0])


def style_kind(obj, kind: str) -> None:
    if not FreeCAD.GuiUp or kind not in KINDS:
        return
    vo = obj.ViewObject
    hexc, width, pattern, psize = KINDS[kind]
    rgb = _rgb(hexc)
    vo.LineColor = rgb
    vo.PointColor = rgb
    vo.LineWidth = width
    vo.PointSize = psize
    set_pattern(vo, pattern)


def style_flag(obj) -> None:
    if not FreeCAD.GuiUp or obj.ViewObject is None:
        return
    vo = obj.ViewObject
    pending = obj.Decision == "Undecided"
    vo.LineColor = _rgb(FLAG_PENDING if pending else FLAG_DECIDED)
    vo.PointColor = vo.LineColor
    vo.LineWidth = 4.0 if pending else 2.0
    set_pattern(vo, 0xFFFF if obj.Decision not in ("Exclude", "Reject") else 0xCCCC)


def style_placed(obj) -> None:
    if not FreeCAD.GuiUp or obj.ViewObject is None:
        return
    vo = obj.ViewObject
    bad = bool(getattr(obj, "Collides", False))
    vo.ShapeColor = _rgb(PLACED_COLLIDES if bad else PLACED_OK)
    vo.LineColor = _rgb(PLACED_COLLIDES if bad else PLACED_EDGE)
    vo.LineWidth = 2.0


def style_part(obj) -> None:
    """A recognised part: its face see-through beige under the contour lines;
    hidden while it is not included."""
    if not FreeCAD.GuiUp or obj.ViewObject is None:
        return
    vo = obj.ViewObject
    vo.ShapeColor = _rgb(PART_FACE)
    vo.LineColor = _rgb(KINDS["outer"][0])
    vo.LineWidth = 1.0
    vo.Transparency = 60
    vo.Visibility = bool(getattr(obj, "Include", True))
