"""Max-min ant system (Stuetzle & Hoos) over the visiting order.

Each ant builds an order from the anchor, choosing the next allowed item (all
predecessors visited) among the current item's nearest neighbours with
probability proportional to pheromone^alpha * (1 / distance)^beta, falling back
to the nearest allowed item when no neighbour is allowed.  Entry points of
every ant's order are chosen by the exact DP; the iteration's best ant is then
improved by local search (2-opt / Or-opt <-> DP).  Only the best ant deposits
pheromone; trails are kept within [tau_min, tau_max].  Deterministic per seed
unless the time budget cuts the run.
"""

from __future__ import annotations

import random
import time
from typing import Callable, List, Optional

import numpy as np

from .dp import optimal_entries
from .result import SearchResult, stop_reason
from .instance import Instance
from .localsearch import improve
from .nn import nearest_neighbour


def _construct(inst: Instance, tau: np.ndarray, near, neard, rng: random.Random,
               alpha: float, beta: float) -> List[int]:
    m = inst.m
    missing = [len(p) for p in inst.preds]
    visited = [False] * m
    alive = np.zeros(inst.n, dtype=bool)
    allowed = [False] * m
    for k in range(m):
        if k != 0 and missing[k] == 0:
            allowed[k] = True
            alive[inst.cands[k]] = True
    visited[0] = True
    for s in inst.succs[0]:
        missing[s] -= 1
        if missing[s] == 0:
            allowed[s] = True
            alive[inst.cands[s]] = True
    order = [0]
    cur = 0
    g = int(inst.cands[0][0])
    all_idx = np.arange(inst.n)
    while len(order) < m:
        opts, weights = [], []
        trow = tau[cur]
        for y, dy in zip(near[cur], neard[cur]):
            if allowed[y] and not visited[y]:
                opts.append(y)
                weights.append((trow[y] ** alpha) * (1.0 / (dy + 1.0)) ** beta)
        if opts:
            r = rng.random() * sum(weights)
            acc = 0.0
            nxt = opts[-1]
            for y, w in zip(opts, weights):
                acc += w
                if acc >= r:
                    nxt = y
                    break
            C = inst.cands[nxt]
            g = int(C[int(inst.to_many(g, C).argmin())])
        else:
            idx = all_idx[alive]
            g = int(idx[int(inst.to_many(g, idx).argmin())])
            nxt = int(inst.item_of[g])
        visited[nxt] = True
        alive[inst.cands[nxt]] = False
        order.append(nxt)
        for s in inst.succs[nxt]:
            missing[s] -= 1
            if missing[s] == 0 and not visited[s]:
                allowed[s] = True
                alive[inst.cands[s]] = True
        cur = nxt
    return order


def run_aco(inst: Instance, *, time_limit: float, seed: int, n_ants: int = 8,
            alpha: float = 1.0, beta: float = 3.0, rho: float = 0.1,
            max_iterations: Optional[int] = None, stall_iterations: int = 25,
            progress: Optional[Callable[[float, str], None]] = None) -> SearchResult:
    """MMAS; returns the best tour found (anchor first)."""
    t_start = time.perf_counter()
    deadline = t_start + time_limit
    rng = random.Random(seed)
    near, neard = inst.neighbours(12)
    m = inst.m
    t, c = nearest_neighbour(inst)
    nn_cost = inst.tour_cost(t, c)
    if m <= 3:
        c, cost = optimal_entries(inst, t)
        return SearchResult(t, c, cost, 0, nn_cost, "converged")
    best_cost = improve(inst, t, c, near, neard, deadline=deadline)
    best_t, best_c = t[:], c[:]
    tau_max = 1.0 / (rho * max(best_cost, 1e-9))
    tau_min = tau_max / (2.0 * m)
    tau = np.full((m, m), tau_max, dtype=np.float32 if m > 2000 else np.float64)
    it = 0
    stall = 0
    budget = max_iterations if max_iterations is not None else float("inf")
    while it < budget and stall < stall_iterations and time.perf_counter() < deadline:
        it += 1
        ib_cost, ib_t, ib_c = np.inf, None, None
        for _ in range(n_ants):
            if time.perf_counter() > deadline:
                break
            order = _construct(inst, tau, near, neard, rng, alpha, beta)
            ch, cst = optimal_entries(inst, order)
            if cst < ib_cost:
                ib_cost, ib_t, ib_c = cst, order, ch
        if ib_t is None:
            break
        ib_cost = improve(inst, ib_t, ib_c, near, neard, deadline=deadline)
        if ib_cost < best_cost - 1e-6 * max(1.0, best_cost):
            best_cost, best_t, best_c = ib_cost, ib_t[:], ib_c[:]
            stall = 0
            tau_max = 1.0 / (rho * best_cost)
            tau_min = tau_max / (2.0 * m)
        else:
            stall += 1
        # evaporate, then the best ant deposits (iteration best, every 5th the global best)
        tau *= (1.0 - rho)
        dep_t, dep_cost = (best_t, best_cost) if it % 5 == 0 else (ib_t, ib_cost)
        a = np.asarray(dep_t)
        b = np.roll(a, -1)
        tau[a, b] += 1.0 / max(dep_cost, 1e-9)
        if inst.symmetric:
            tau[b, a] += 1.0 / max(dep_cost, 1e-9)
        np.clip(tau, tau_min, tau_max, out=tau)
        if progress is not None:
            progress(min(1.0, (time.perf_counter() - t_start) / max(time_limit, 1e-9)),
                     f"ant colony: iteration {it}, best {best_cost:.1f}")
    return SearchResult(best_t, best_c, best_cost, it, nn_cost,
                        stop_reason(stall >= stall_iterations, it >= budget))
