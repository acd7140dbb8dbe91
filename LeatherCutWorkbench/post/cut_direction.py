"""Which way round each closed contour is cut, from the machine profile.

A torch leaves the good (square) side of its kerf on its right: outers are cut
clockwise and holes counter-clockwise so the part gets the good side.  Other
tools keep the drawn direction (recognition stores outers counter-clockwise,
holes clockwise) unless the profile's ``outer_direction`` / ``hole_direction``
say ``cw`` or ``ccw``.  The parts handed to the planner are already oriented,
so the planner and its time estimate see the direction actually cut.
"""

from __future__ import annotations

from typing import List, Optional, Sequence

from ..core.geometry import Segment, path_points, reverse_path, signed_area
from .profiles import MachineProfile


def wanted_ccw(kind: str, profile: MachineProfile) -> Optional[bool]:
    """True = counter-clockwise, False = clockwise, None = as drawn, for a
    contour of ``kind`` ``"outer"`` or ``"hole"``."""
    value = profile.outer_direction if kind == "outer" else profile.hole_direction
    if not value:
        if profile.tool != "torch":
            return None
        value = "cw" if kind == "outer" else "ccw"
    return None if value == "drawn" else value == "ccw"


def is_ccw(segments: Sequence[Segment]) -> bool:
    """Whether a closed path runs counter-clockwise."""
    return signed_area(path_points(segments, 0.1)) > 0


def oriented(segments: Sequence[Segment], kind: str, profile: MachineProfile) -> List[Segment]:
    """``segments`` running the way the profile cuts a contour of ``kind``."""
    want = wanted_ccw(kind, profile)
    if want is None or is_ccw(segments) == want:
        return list(segments)
    return reverse_path(segments)


def scrap_on_left(segments: Sequence[Segment], kind: str) -> bool:
    """Whether the scrap (outside an outer, inside a hole) lies to the left of
    the path's direction of travel."""
    ccw = is_ccw(segments)
    return (not ccw) if kind == "outer" else ccw
