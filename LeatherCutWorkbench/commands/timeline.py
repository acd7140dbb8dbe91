"""The knife's position over machine time along a cut plan (no Qt: used by
*Simulate* and testable headless)."""

from __future__ import annotations

import bisect
from typing import List, Optional, Tuple

from ..core.geometry import dist, path_points


class Timeline:
    """The knife's position over machine time (s) along the plan, timed with the
    planner's own model (:func:`core.pathplan.metrics.move_time`): every idle
    move and every cut run between two knife lifts is a rest-to-rest move with
    the acceleration ``accel`` (mm/s²) up to its speed (mm/min), and each lift
    adds ``lift_time_s`` with the knife standing.  So ``duration`` is the plan's
    estimated time.  Within one move the knife is drawn at its mean speed."""

    def __init__(self, plan, rapid_speed: float, cut_speed: float, accel: float,
                 lift_time_s: float, passes=None):
        """``passes`` -- (tool name, feed mm/min, items, strike points) in machine
        order, from a multi-tool job -- plays every tool's pass in turn;
        ``what[k]`` is (tool, number in its pass, pass size) of item ``k``."""
        from ..core.pathplan.metrics import move_time
        self.points: List[Tuple[float, float]] = [plan.home]
        self.times: List[float] = [0.0]
        self.item_at: List[int] = [-1]
        self.what: List[Tuple[str, int, int]] = []
        self._move_time = move_time
        here = plan.home
        for tool, feed, items, strikes in passes or [("", cut_speed, plan.items, [])]:
            n = len(items) + len(strikes)
            for k, it in enumerate(items):
                self.what.append((tool, k + 1, n))
                i = len(self.what) - 1
                self._move([here, it.start], rapid_speed, accel, -1)
                cuts = [0] + sorted(it.lifts) + [len(it.segments)]
                for j, (a, b) in enumerate(zip(cuts, cuts[1:])):
                    if j > 0:
                        self._wait(lift_time_s, i)
                    if b > a:
                        run = it.segments[a:b]
                        self._move(path_points(run, 0.1), feed, accel, i,
                                   sum(seg.length for seg in run))
                here = it.end
            for k, p in enumerate(strikes):
                self.what.append((tool, len(items) + k + 1, n))
                self._move([here, p], rapid_speed, accel, -1)
                self._wait(lift_time_s, len(self.what) - 1)
                here = p
        self._move([here, plan.home], rapid_speed, accel, -1)

    def _move(self, pts, speed: float, accel: float, item: int,
              true_length: Optional[float] = None) -> None:
        """Move through ``pts``; the time is that of ``true_length`` mm (arcs
        are longer than their chords), default the polyline's length."""
        steps = [dist(a, b) for a, b in zip(pts, pts[1:])]
        length = sum(steps)
        if length <= 0:
            return
        t0 = self.times[-1]
        total = self._move_time(length if true_length is None else true_length, speed, accel)
        done = 0.0
        for p, d in zip(pts[1:], steps):
            done += d
            self.points.append(p)
            self.times.append(t0 + total * done / length)
            self.item_at.append(item)

    def _wait(self, seconds: float, item: int) -> None:
        if seconds > 0:
            self.points.append(self.points[-1])
            self.times.append(self.times[-1] + seconds)
            self.item_at.append(item)

    @property
    def duration(self) -> float:
        return self.times[-1]

    def at(self, t: float):
        """(position, item index or -1 when idle) at machine time ``t``."""
        t = min(max(t, 0.0), self.duration)
        k = max(1, bisect.bisect_left(self.times, t))
        if k >= len(self.times):
            return self.points[-1], -1
        t0, t1 = self.times[k - 1], self.times[k]
        f = 0.0 if t1 <= t0 else (t - t0) / (t1 - t0)
        a, b = self.points[k - 1], self.points[k]
        return (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])), self.item_at[k]


def timeline_of(job) -> Timeline:
    """The job's stored plan timed with the options the planner uses for this job
    (the machine profile's speeds when PlanFromMachine is set)."""
    from ..document import pipeline
    plan = pipeline.stored_plan(job)
    opts = pipeline.with_machine(pipeline.stage_options(job, "Plan"), job)
    tools = pipeline.tool_job(job, plan)
    passes = None if tools is None else [
        (p.tool.name, opts.cut_speed if p.tool.main else p.tool.feed, p.items, p.points)
        for p in tools.passes]
    return Timeline(plan, opts.rapid_speed, opts.cut_speed, opts.accel, opts.lift_time_s, passes)
