"""Drag-knife compensation: the path of the swivel axis that makes the blade tip
follow the drawn contour.

A drag knife's blade tip trails its swivel axis by ``blade_offset`` mm along
the direction of travel (tip = axis - blade_offset * unit direction), so a
machine that drives the axis along the drawing rounds every corner and stops
short of every end.  The compensated axis path, for a tip that must follow a
drawn path:

* **lines** are shifted forward by the offset along their direction: the axis
  runs from ``start + r u`` to ``end + r u`` (the end of a path is therefore
  extended by the offset);
* **arcs** of radius R become concentric arcs of radius sqrt(R^2 + r^2) turned
  ahead by atan(r / R) (the blade stays tangent; exact, the pair rotates
  rigidly about the centre);
* **corners** whose turn is sharper than ``swivel_angle`` degrees get a
  *swivel arc*: the axis circles the corner at radius r from the incoming to
  the outgoing direction while the tip stays on the corner (the axis moves at
  right angles to the blade, so the tip does not move); smaller turns are
  joined by a straight move (the tip cuts the corner short by at most
  r (1 - cos(turn / 2)), 0.004 mm for r = 0.25 mm and 10 degrees);
* **alignment before each plunge**: the knife goes down with the tip on the
  entry point and the blade in the direction it had at the end of the previous
  cut (the blade keeps its direction in the air; +X before the first cut), then
  turns into the first cutting direction like at a corner: a swivel arc around
  the entry, or a straight move for a turn within ``swivel_angle``.

Written here by hand: no maintained library computes drag-knife offsets
(peer tools -- dxf2gcode, GRBL-Plotter, bCNC -- each carry their own code).
Units mm and degrees.
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

from ..core.geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment, dist

#: Heading (degrees) the blade is assumed to have before the first cut of a job.
START_DIRECTION = 0.0

#: Pieces shorter than this (mm) carry no direction and are skipped.
_EPS = 1e-9


def _unit(deg: float) -> Point:
    a = math.radians(deg)
    return (math.cos(a), math.sin(a))


def _ahead(p: Point, deg: float, r: float) -> Point:
    u = _unit(deg)
    return (p[0] + r * u[0], p[1] + r * u[1])


def _signed_turn(h_from: float, h_to: float) -> float:
    """Turn from ``h_from`` to ``h_to`` in degrees, in (-180, 180]."""
    d = (h_to - h_from + 180.0) % 360.0 - 180.0
    return 180.0 if d == -180.0 else d


def _flat(segments: Sequence[Segment]) -> List[Segment]:
    """Lines and arcs only (a flattened curve is its polyline); no null pieces."""
    out: List[Segment] = []
    for s in segments:
        if isinstance(s, CurveSeg):
            out.extend(LineSeg(a, b) for a, b in zip(s.pts, s.pts[1:]) if dist(a, b) > _EPS)
        elif s.length > _EPS:
            out.append(s)
    return out


def _axis_piece(seg: Segment, r: float) -> Segment:
    """The axis path while the tip follows ``seg`` with the blade tangent."""
    if isinstance(seg, LineSeg):
        h = seg.start_heading()
        return LineSeg(_ahead(seg.start, h, r), _ahead(seg.end, h, r))
    lead = math.degrees(math.atan2(r, seg.radius))
    lead = lead if seg.sweep > 0 else -lead
    return ArcSeg(seg.center, math.hypot(seg.radius, r), seg.start_angle + lead, seg.sweep)


def swivel(corner: Point, h_from: float, h_to: float, r: float,
           flatten: Optional[float] = None) -> Optional[Segment]:
    """The swivel arc (radius ``r`` about the tip at ``corner``) turning the
    blade from heading ``h_from`` to ``h_to`` the short way; None for no turn.
    With ``flatten`` (mm) it is a polyline within that chord deviation."""
    turn = _signed_turn(h_from, h_to)
    if abs(turn) < 1e-9:
        return None
    arc = ArcSeg(corner, r, h_from, turn)
    return CurveSeg(tuple(arc.points(flatten))) if flatten else arc


def compensate(segments: Sequence[Segment], blade_offset: float, swivel_angle: float,
               blade_heading: Optional[float], flatten: Optional[float] = None
               ) -> Tuple[List[Tuple[Segment, int]], Optional[float]]:
    """Axis path for a tip that cuts ``segments`` (a connected path, mm).

    ``blade_heading`` is the blade's direction (degrees) when the knife goes
    down, None when unknown (no alignment arc then).  ``flatten`` (mm): write
    swivel arcs as polylines this close to the arc, for outputs that split arcs
    (every chord of a swivel arc pulls the tip along the blade, and the pulls
    add up, so they need a far finer tolerance than the contour).  Returns the axis pieces,
    each with the index of the drawn segment it belongs to (a swivel arc
    belongs to the segment after the corner), and the blade heading at the end
    (None for a path with no length)."""
    r = blade_offset
    out: List[Tuple[Segment, int]] = []
    heading = blade_heading
    here: Optional[Point] = None          # tip position at the end of the last piece
    for k, seg in enumerate(segments):
        for piece in _flat([seg]):
            h = piece.start_heading()
            if heading is not None and here is None:
                here = piece.start          # alignment at the plunge
            if heading is not None:
                turn = abs(_signed_turn(heading, h))
                if turn > swivel_angle + 1e-9:
                    arc = swivel(here, heading, h, r, flatten)
                    if arc is not None:
                        out.append((arc, k))
                elif turn > 1e-9:
                    out.append((LineSeg(_ahead(here, heading, r), _ahead(here, h, r)), k))
            out.append((_axis_piece(piece, r), k))
            heading = piece.end_heading()
            here = piece.end
    return out, (heading if out else blade_heading)


def swivel_tolerance(profile) -> Optional[float]:
    """Chord tolerance (mm) for swivel arcs of ``profile``: None when the output
    keeps arcs (G2/G3), else 1/1000 of the blade offset (the pulls of ~100
    chords on a half turn then move the tip by under 0.005 mm)."""
    if profile.arcs == "split" or profile.dialect == "hpgl":
        return profile.blade_offset * 1e-3
    return None
