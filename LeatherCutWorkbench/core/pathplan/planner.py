"""The planning stage entry point: parts -> ordered cut job with metrics."""

from __future__ import annotations

import math
import time
from typing import List, Optional, Sequence

import numpy as np

from ..errors import InputError, LeatherCutError
from ..model import CutItem, CutPlan, Finding, OpenChain, Part
from ..progress import ProgressFn, report
from .aco import run_aco
from .bounds import lower_bound
from .ga import SearchResult, run_ga
from .instance import EuclidInstance
from .items import PlanItem, build_items
from .metrics import plan_metrics
from .nn import nearest_neighbour
from .options import METHODS, OBJECTIVES, PlanOptions
from .precedence import violations
from .timecost import time_instance


def _check_options(o: PlanOptions) -> None:
    if o.method not in METHODS:
        raise InputError(f"unknown planning method {o.method!r}; use one of {', '.join(METHODS)}")
    for name in ("time_limit", "entry_spacing", "rapid_speed", "cut_speed"):
        v = getattr(o, name)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"plan option {name} must be a positive number, got {v!r}")
    if o.accel < 0 or o.lift_time_s < 0:
        raise InputError("plan options accel and lift_time_s must not be negative")
    if o.lift_angle is not None and not (0 <= o.lift_angle <= 180):
        raise InputError(f"lift angle must be within 0..180 degrees, got {o.lift_angle}")
    if o.max_candidates < 1:
        raise InputError("max_candidates must be at least 1")
    if o.max_iterations is not None and o.max_iterations < 1:
        raise InputError(f"plan iterations must be at least 1, got {o.max_iterations}")
    if o.objective not in OBJECTIVES:
        raise InputError(f"unknown plan objective {o.objective!r}; use one of {', '.join(OBJECTIVES)}")
    if o.turn_speed < 0:
        raise InputError(f"plan option turn_speed must not be negative, got {o.turn_speed!r}")


def build_instance(items: Sequence[PlanItem], preds: Sequence[Sequence[int]],
                   home) -> EuclidInstance:
    """The routing instance: item 0 = home (machine zero), item k+1 = items[k]."""
    S = [home]
    E = [home]
    clusters = [[0]]
    for it in items:
        ids = []
        for c in it.cands:
            ids.append(len(S))
            S.append(c.start)
            E.append(c.end)
        clusters.append(ids)
    ipreds = [[]] + [[q + 1 for q in ps] for ps in preds]
    return EuclidInstance(clusters, np.array(S, dtype=float), np.array(E, dtype=float), ipreds)


def plan(parts: Sequence[Part], open_chains: Sequence[OpenChain],
         options: PlanOptions = PlanOptions(), progress: Optional[ProgressFn] = None) -> CutPlan:
    """Order the cut and choose entry points (see package docstring).

    Excluded parts are not cut.  Raises InputError for bad options."""
    _check_options(options)
    t0, c0 = time.perf_counter(), time.process_time()
    report(progress, 0.0, "building entry candidates")
    items, preds, findings = build_items(
        parts, open_chains if options.cut_open_chains else [],
        entry_spacing=options.entry_spacing, max_candidates=options.max_candidates,
        cut_open_chains=options.cut_open_chains, common_edge_tol=options.common_edge_tol)
    home = (float(options.home[0]), float(options.home[1]))
    if not items:
        findings.append(Finding("warning", "nothing-to-cut", "no contour to cut"))
        out = CutPlan(items=[], home=home, method=options.method, findings=findings)
        out.metrics = _metrics(out, options, 0.0, 0.0, 0.0, {}, 0, t0, c0, 0)
        return out
    inst = build_instance(items, preds, home)

    def prog(f: float, msg: str) -> None:
        report(progress, 0.05 + 0.85 * f, msg)

    report(progress, 0.05, f"planning {len(items)} cut items ({inst.n - 1} entry candidates)")
    if options.method == "nn":
        order, choice = nearest_neighbour(inst)
        cost = inst.tour_cost(order, choice)
        res = SearchResult(order, choice, cost, 1, cost, "converged")
    else:
        search = run_aco if options.method == "aco" else run_ga
        target = inst if options.objective == "distance" else time_instance(inst, items, options)
        res = search(target, time_limit=options.time_limit, seed=options.seed,
                     max_iterations=options.max_iterations, progress=prog)
        if target is not inst:
            # the bound and the NN baseline are idle distances (mm)
            res.cost = inst.tour_cost(res.order, res.choice)
            res.nn_cost = inst.tour_cost(*nearest_neighbour(inst))
    bad = violations(res.order, inst.preds)
    if bad:
        raise LeatherCutError(f"internal error: planned order breaks {bad} precedence rule(s)")
    report(progress, 0.9, "computing lower bound")
    lb, lb_parts = lower_bound(inst, res.cost, time_budget=options.bound_time, max_items_hk=600)
    drawing = inst.tour_cost(list(range(inst.m)), [int(c[0]) for c in inst.cands])
    cut_items: List[CutItem] = []
    cand_base = [int(c[0]) for c in inst.cands]
    for it in res.order[1:]:
        item = items[it - 1]
        cut_items.append(item.realise(item.cands[res.choice[it] - cand_base[it]], options.lift_angle))
    out = CutPlan(items=cut_items, home=home, method=options.method, findings=findings)
    out.metrics = _metrics(out, options, drawing, res.nn_cost, lb, lb_parts, res.iterations,
                           t0, c0, inst.n - 1, stopped_by=res.stopped_by)
    report(progress, 1.0, "cut path planned")
    return out


def _metrics(out: CutPlan, o: PlanOptions, drawing: float, nn: float, lb: float,
             lb_parts: dict, iterations: int, t0: float, c0: float, n_cands: int,
             stopped_by: str = "converged") -> dict:
    m = plan_metrics(out, o.rapid_speed, o.cut_speed, o.accel, o.lift_time_s)
    idle = m["idle_mm"]
    return {
        "idle_mm": round(idle, 3),
        "cut_mm": round(m["cut_mm"], 3),
        "lifts": m["lifts"],
        "est_time_s": round(m["est_time_s"], 2),
        "drawing_order_idle_mm": round(drawing, 3),
        "nn_idle_mm": round(nn, 3),
        "lower_bound_mm": round(lb, 3),
        "lower_bound_parts": {k: round(v, 3) for k, v in lb_parts.items()},
        "gap_to_lower_bound": round(idle / lb - 1.0, 4) if lb > 0 else None,
        "idle_saving_vs_drawing_order": round(1.0 - idle / drawing, 4) if drawing > 0 else None,
        "precedence_violations": 0,
        "method": o.method,
        "objective": o.objective,
        "seed": o.seed,
        "time_s": round(time.perf_counter() - t0, 3),
        "cpu_s": round(time.process_time() - c0, 3),
        "iterations": iterations,
        "converged": stopped_by == "converged",
        "stopped_by": stopped_by,
        "items": len(out.items),
        "entry_candidates": n_cands,
    }
