"""Feed words for a controller that applies F to the linear axes only.

The post raises the F word of a cut that also turns the knife
(``rotary_in_feed``, :func:`..gcode.rotary_feed`) because GRBL takes F along
the move's length in all axes.  grblHAL with ``$701=1`` applies F to the
linear axes only: the raised F would then drive XY faster than the cut feed
(up to 40000/12000 of it).  :func:`linear_feed_only` undoes the raise on the
blocks to send -- each rotating cut's F divided by the factor the post applied,
every other F capped at the profile's ``cut_feed`` -- so XY never runs faster
than ``cut_feed``.  Units: mm/min, rotary axis units as in the profile.
"""

from __future__ import annotations

import math
import re
from typing import Tuple

from ..gcode import fmt
from ..gcode_reader import GcodeError, interpreter_for
from ..profiles import MachineProfile
from .job import SendJob

_F = re.compile(r"F(\d+\.?\d*)")


def linear_feed_only(job: SendJob, profile: MachineProfile) -> Tuple[SendJob, int]:
    """A copy of ``job`` whose F words never exceed the XY speed the post meant;
    returns it and the number of blocks changed."""
    it = interpreter_for(profile)
    rot = profile.rotary_axis if profile.rotary_axis != profile.lift_axis else ""
    moves_of = {}
    for n, line in enumerate(job.source):
        try:
            moves_of[n] = it.execute(line, n + 1)
        except GcodeError:
            moves_of[n] = []
    out = SendJob(job.name, job.source, list(job.blocks), list(job.segs), list(job.index),
                  job.segment_ids, job.job_segs, job.fence)
    changed = 0
    for k, block in enumerate(out.blocks):
        m = _F.search(block)
        if not m:
            continue
        f = float(m.group(1))
        want = min(f, profile.cut_feed)
        i = job.index[k]
        motion = [mv for mv in moves_of.get(i, []) if mv.kind in ("line", "arc")] \
            if i is not None else []
        if rot and motion:
            mv = motion[-1]
            turn = abs(mv.end.get(rot, 0.0) - mv.start.get(rot, 0.0))
            xy = _xy_length(mv)
            if turn > 1e-9 and xy > 1e-9:
                want = min(f / (math.hypot(xy, turn) / xy), profile.cut_feed)
        if want < f - 1e-6:
            out.blocks[k] = block[:m.start()] + "F" + fmt(want, 0) + block[m.end():]
            changed += 1
    return out, changed


def _xy_length(mv) -> float:
    if mv.kind == "arc":
        cx, cy = mv.center
        r = math.hypot(mv.start["X"] - cx, mv.start["Y"] - cy)
        a0 = math.atan2(mv.start["Y"] - cy, mv.start["X"] - cx)
        a1 = math.atan2(mv.end["Y"] - cy, mv.end["X"] - cx)
        sweep = (a1 - a0) % (2 * math.pi) if mv.ccw else (a0 - a1) % (2 * math.pi)
        return r * sweep
    return math.hypot(mv.end["X"] - mv.start["X"], mv.end["Y"] - mv.start["Y"])
