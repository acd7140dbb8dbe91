"""DXF of the cut job (ASCII R12, written with ezdxf).

R12 keeps only LINE, ARC, CIRCLE, POLYLINE and TEXT, which every CAM and
cutter software reads.  Coordinates are plan (table) coordinates in mm.
Layers:

* ``CUT``     -- contours and open chains, in cutting order (arcs stay arcs,
  full circles are CIRCLEs, flattened curves POLYLINEs),
* ``LEAD_IN`` -- the lead-in segments of each item,
* ``IDLE``    -- knife-up travel: home -> first item -> ... -> home,
* ``MARKS``   -- point marks (drill holes, notches) passed in the options,
* ``ORDER``   -- the cut order number of each item as TEXT at its start,
* ``TOOL_<NAME>`` -- one layer per further tool of a multi-tool job (pen and
  crease lines, punch points with a circle of the punch diameter; drawn
  positions, see post/tool_export.py).
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from typing import Dict, List, Optional

from ..core.geometry import ArcSeg, CurveSeg, LineSeg
from ..core.model import CutPlan, Mark
from .profiles import MachineProfile

LAYERS = {"CUT": 7, "LEAD_IN": 3, "IDLE": 8, "MARKS": 1, "ORDER": 5}


@dataclass
class DxfOptions:
    marks: List[Mark] = field(default_factory=list)
    text_height: float = 5.0          # mm, height of the order numbers
    tool_layers: Dict[str, tuple] = field(default_factory=dict)   # layer -> (segments, points)


def export(plan: CutPlan, profile: Optional[MachineProfile] = None, options=None) -> str:
    """The DXF text (R12) of ``plan``.  ``profile`` only adds the table outline
    check: a job outside the table raises SafetyError like the other writers."""
    import ezdxf

    from . import safety
    from .toolpath import build_toolpath

    opts = options if isinstance(options, DxfOptions) else DxfOptions()
    if profile is not None:
        safety.check_moves(build_toolpath(plan, profile, 0.0), profile)
    doc = ezdxf.new("R12")
    for name, color in LAYERS.items():
        doc.layers.add(name, color=color)
    msp = doc.modelspace()
    for n, item in enumerate(plan.items, 1):
        for k, seg in enumerate(item.segments):
            layer = "LEAD_IN" if k < item.lead_in_count else "CUT"
            _add_segment(msp, seg, layer)
        msp.add_text(str(n), height=opts.text_height,
                     dxfattribs={"layer": "ORDER", "insert": item.start})
    for a, b in plan.idle_moves():
        if a != b:
            msp.add_line(a, b, dxfattribs={"layer": "IDLE"})
    for m in opts.marks:
        msp.add_point(m.position, dxfattribs={"layer": "MARKS"})
    for k, (name, (segs, points)) in enumerate(opts.tool_layers.items()):
        doc.layers.add(name, color=10 + 20 * k)
        for seg in segs:
            _add_segment(msp, seg, name)
        for p in points:
            msp.add_point(p, dxfattribs={"layer": name})
    buf = io.StringIO()
    doc.write(buf)
    return buf.getvalue()


def _add_segment(msp, seg, layer: str) -> None:
    attrs = {"layer": layer}
    if isinstance(seg, LineSeg):
        msp.add_line(seg.start, seg.end, dxfattribs=attrs)
    elif isinstance(seg, ArcSeg):
        if abs(abs(seg.sweep) - 360.0) < 1e-9:
            msp.add_circle(seg.center, seg.radius, dxfattribs=attrs)
            return
        a0, a1 = seg.start_angle, seg.start_angle + seg.sweep
        if seg.sweep < 0:        # DXF arcs run counter-clockwise
            a0, a1 = a1, a0
        msp.add_arc(seg.center, seg.radius, a0 % 360.0, a1 % 360.0, dxfattribs=attrs)
    elif isinstance(seg, CurveSeg):
        msp.add_polyline2d(list(seg.pts), dxfattribs=attrs)
