"""Options of the path-planning stage."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ..geometry import Point

METHODS = ("ga", "aco", "nn")
OBJECTIVES = ("distance", "time")


@dataclass
class PlanOptions:
    """How to order the cut and choose entry points.

    * ``method``: ``"ga"`` (genetic algorithm, default), ``"aco"`` (max-min
      ant system) or ``"nn"`` (nearest neighbour, the fast baseline).
    * ``time_limit``: search budget in seconds (the GA and ACO stop earlier
      when converged).  ``max_iterations``: when set, the GA stops after this
      many generations and the ACO after this many iterations; the time limit
      still caps the run.  ``seed``: random seed; the same seed gives the same
      plan unless the time limit ended the search (``metrics.stopped_by ==
      "time"``) -- an iteration budget reached within the time limit makes the
      plan the same on any machine.
    * ``entry_spacing``: mm between entry candidates along edges (vertices are
      always candidates); ``max_candidates`` per contour.
    * ``home``: machine zero (mm); the head starts and ends there.
    * ``lift_angle``: degrees; a tangential knife lifts where the heading
      changes by more than this.  None = no tangential knife.
    * ``rapid_speed`` / ``cut_speed``: mm/min; ``accel``: mm/s^2;
      ``lift_time_s``: seconds per knife lift (time estimate only).
    * ``cut_open_chains``: cut open chains (not lead-ins) too.
    * ``common_edge_tol``: mm within which shared edges are matched.
    * ``bound_time``: seconds allowed for the lower bound.
    * ``objective``: what the search minimises -- ``"distance"`` (idle travel,
      mm; default) or ``"time"`` (idle seconds: trapezoidal rapid moves with
      ``rapid_speed`` and ``accel``, ``lift_time_s`` per idle move and, with a
      tangential knife, the blade turn at ``turn_speed`` degrees/s between
      contours; see :mod:`.timecost`).
    """

    method: str = "ga"
    time_limit: float = 10.0
    max_iterations: Optional[int] = None
    seed: int = 1
    entry_spacing: float = 20.0
    max_candidates: int = 64
    home: Point = (0.0, 0.0)
    lift_angle: Optional[float] = None
    rapid_speed: float = 20000.0
    cut_speed: float = 6000.0
    accel: float = 1000.0
    lift_time_s: float = 0.3
    cut_open_chains: bool = True
    common_edge_tol: float = 0.05
    bound_time: float = 1.0
    objective: str = "distance"
    turn_speed: float = 360.0
