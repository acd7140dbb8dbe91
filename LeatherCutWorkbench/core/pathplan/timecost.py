"""Idle *time* as the objective (``PlanOptions.objective == "time"``).

The cost of the idle move from candidate g to candidate h is what the machine
spends on it, in seconds:

* the rest-to-rest move over the straight-line distance L at the rapid speed
  v with acceleration a -- L/v + v/a when it reaches v (L >= v^2/a), else
  2 sqrt(L/a) (the same trapezoidal model as :func:`.metrics.move_time`), so a
  short hop costs more than its length suggests;
* with a tangential knife, at least the time to turn the blade in the air from
  g's exit heading to h's entry heading at ``turn_speed`` degrees/s (the turn
  overlaps the move);
* ``lift_time_s`` for lifting and plunging the knife (one per idle move).
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import numpy as np

from .instance import EuclidInstance


class TimeInstance(EuclidInstance):
    """An :class:`EuclidInstance` whose costs are idle-move seconds."""

    def __init__(self, clusters: Sequence[Sequence[int]], start_xy: np.ndarray, end_xy: np.ndarray,
                 preds: Sequence[Sequence[int]], *, rapid_speed: float, accel: float,
                 lift_time_s: float, turn_speed: float = 0.0,
                 entry_heading: Optional[np.ndarray] = None,
                 exit_heading: Optional[np.ndarray] = None):
        super().__init__(clusters, start_xy, end_xy, preds)
        self.symmetric = False if turn_speed > 0 else self.symmetric
        v = rapid_speed / 60.0
        w = math.radians(turn_speed) if turn_speed > 0 else 0.0
        #: (v mm/s, a mm/s^2, lift s, turn rad/s) as the compiled kernels read them
        self.time_params = (v, float(accel), float(lift_time_s), w)
        n = self.n
        self.entry_heading = np.zeros(n) if entry_heading is None else np.radians(entry_heading)
        self.exit_heading = np.zeros(n) if exit_heading is None else np.radians(exit_heading)

    def time_of_length(self, L: np.ndarray) -> np.ndarray:
        """Seconds of a rest-to-rest rapid move of length ``L`` (mm) plus the lift."""
        v, a, lift, _ = self.time_params
        L = np.asarray(L, dtype=float)
        if a <= 0:
            t = L / v
        else:
            with np.errstate(invalid="ignore"):
                t = np.where(L >= v * v / a, L / v + v / a, 2.0 * np.sqrt(np.maximum(L, 0.0) / a))
        return np.where(L > 0, t, 0.0) + lift

    def _turn(self, g: np.ndarray, h: np.ndarray) -> np.ndarray:
        d = np.abs(self.entry_heading[h] - self.exit_heading[g]) % (2 * math.pi)
        return np.minimum(d, 2 * math.pi - d) / self.time_params[3]

    def block(self, G: np.ndarray, H: np.ndarray) -> np.ndarray:
        G = np.asarray(G)
        H = np.asarray(H)
        t = self.time_of_length(super().block(G, H))
        if self.time_params[3] > 0:
            lift = self.time_params[2]
            t = np.maximum(t - lift, self._turn(G[:, None], H[None, :])) + lift
        return t

    def cost(self, g: int, h: int) -> float:
        return float(self.block(np.asarray([g]), np.asarray([h]))[0, 0])

    def item_cost_fn(self, c: Sequence[int]):
        cost = self.cost

        def d(a: int, b: int) -> float:
            return cost(c[a], c[b])
        return d

    def to_many(self, g: int, H: np.ndarray) -> np.ndarray:
        return self.block(np.asarray([g]), H)[0]

    def from_many(self, G: np.ndarray, h: int) -> np.ndarray:
        return self.block(G, np.asarray([h]))[:, 0]


def candidate_headings(items) -> Tuple[List[float], List[float]]:
    """(entry heading, exit heading) in degrees of every candidate of the plan
    items, in instance order (home first): the heading of the first and of the
    last segment the knife cuts for that candidate."""
    entry = [0.0]
    exit_ = [0.0]
    for it in items:
        for cand in it.cands:
            segs = [s for s in it.realise(cand, None).segments if s.length > 1e-9]
            entry.append(segs[0].start_heading() if segs else 0.0)
            exit_.append(segs[-1].end_heading() if segs else 0.0)
    return entry, exit_


def time_instance(inst: EuclidInstance, items, o) -> TimeInstance:
    """The planner's routing instance ``inst`` priced in idle seconds with the
    speeds of the plan options ``o`` (turns only with a tangential knife)."""
    entry = exit_ = None
    if o.lift_angle is not None and o.turn_speed > 0:
        entry, exit_ = (np.array(h) for h in candidate_headings(items))
    return TimeInstance(inst.cand_lists, inst.S, inst.E, inst.preds, rapid_speed=o.rapid_speed,
                        accel=o.accel, lift_time_s=o.lift_time_s,
                        turn_speed=o.turn_speed if entry is not None else 0.0,
                        entry_heading=entry, exit_heading=exit_)
