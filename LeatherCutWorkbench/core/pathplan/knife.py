"""Tangential knife: where the blade must lift, turn and plunge again.

A tangential knife follows the path heading; at a joint where the heading
changes by more than the machine's lift angle (degrees) the blade cannot turn
in the material, so the head lifts, rotates and plunges.  The joint between a
lead-in and its contour counts like any other joint.  The first plunge of a cut
item is not a lift (the knife is already up after the idle move and turns to
the first heading in the air).
"""

from __future__ import annotations

from typing import List, Optional, Sequence

from ..geometry import Segment, turn_angle


def lift_indices(segments: Sequence[Segment], lift_angle: Optional[float]) -> List[int]:
    """Indices ``i`` (>= 1) of ``segments`` before which the knife lifts:
    ``turn_angle(end heading of i-1, start heading of i) > lift_angle``.
    Zero-length segments are skipped (they carry no heading).  ``None`` = no
    tangential knife, no lifts."""
    if lift_angle is None:
        return []
    out: List[int] = []
    prev = None
    for i, seg in enumerate(segments):
        if seg.length <= 1e-9:
            continue
        if prev is not None and turn_angle(prev.end_heading(), seg.start_heading()) > lift_angle + 1e-9:
            out.append(i)
        prev = seg
    return out
