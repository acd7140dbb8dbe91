"""Plan metrics: idle and cut length, lifts and an estimated machine time.

Time model (documented in docs/CLI.md): every move -- an idle move between
cut items, or a cut run between two knife lifts -- starts and ends at rest and
follows a trapezoidal speed profile with acceleration ``accel`` (mm/s^2) up to
the move's speed (rapid for idle moves, cut speed for cuts; mm/min in the
options).  A move of length L at top speed v takes L/v + v/a when it reaches v
(L >= v^2/a), else 2*sqrt(L/a).  Each lift adds ``lift_time_s``.
"""

from __future__ import annotations

import math
from typing import Dict, Sequence

from ..geometry import dist
from ..model import CutItem, CutPlan


def move_time(length: float, speed_mm_min: float, accel: float) -> float:
    """Seconds for a rest-to-rest move of ``length`` mm (trapezoidal profile)."""
    if length <= 0:
        return 0.0
    v = speed_mm_min / 60.0
    if accel <= 0:
        return length / v
    if length >= v * v / accel:
        return length / v + v / accel
    return 2.0 * math.sqrt(length / accel)


def cut_runs(item: CutItem) -> Sequence[float]:
    """Lengths (mm) of the runs of ``item`` between knife lifts."""
    cuts = [0] + sorted(item.lifts) + [len(item.segments)]
    return [sum(s.length for s in item.segments[a:b]) for a, b in zip(cuts, cuts[1:]) if b > a]


def plan_metrics(plan: CutPlan, rapid_speed: float, cut_speed: float, accel: float,
                 lift_time_s: float) -> Dict[str, float]:
    """idle_mm, cut_mm, lifts, est_time_s of a finished plan."""
    idle = [dist(a, b) for a, b in plan.idle_moves()]
    t = sum(move_time(d, rapid_speed, accel) for d in idle)
    lifts = 0
    cut = 0.0
    for it in plan.items:
        runs = cut_runs(it)
        cut += sum(runs)
        t += sum(move_time(r, cut_speed, accel) for r in runs)
        lifts += len(it.lifts)
    t += lifts * lift_time_s
    return {"idle_mm": sum(idle), "cut_mm": cut, "lifts": lifts, "est_time_s": t}
