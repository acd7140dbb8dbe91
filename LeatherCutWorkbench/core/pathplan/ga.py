"""Memetic genetic algorithm over the visiting order (the planner's default).

Following the DP + GA scheme of the cut-path literature: a small population of
orders, order crossover (OX) between two tournament-selected parents, the child
repaired to respect precedence, its entry points chosen exactly by the DP and
then improved by local search (2-opt / Or-opt <-> DP); mutation is a local
double-bridge kick followed by local search, kept when it shortens the tour
(iterated local search).  The first individual is nearest-neighbour.  All
randomness comes from one ``random.Random(seed)`` and no decision depends on
the clock, so the same seed gives the same tour whenever the run ends by
convergence or by its generation budget.  The run stops when
``stall_generations`` generations in a row did not improve the best tour
(``"converged"``), after ``max_iterations`` generations (``"iterations"``) or at the time
limit (``"time"``: the only ending that depends on machine speed).
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass
from typing import Callable, List, Optional, Sequence, Tuple

from .dp import optimal_entries, window_entries
from .instance import Instance
from .localsearch import improve, local_search
from .nn import nearest_neighbour
from .precedence import repair


@dataclass
class SearchResult:
    order: List[int]
    choice: List[int]
    cost: float
    iterations: int
    nn_cost: float
    stopped_by: str     # "converged", "iterations" or "time"


def stop_reason(converged: bool, iterations_done: bool) -> str:
    """Why a search loop ended (see :class:`SearchResult`)."""
    return "converged" if converged else "iterations" if iterations_done else "time"


def double_bridge(inst: Instance, t: List[int], rng: random.Random,
                  max_len: int) -> Optional[Tuple[int, int, int]]:
    """Swap two adjacent random segments of ``t`` in place (a local
    double-bridge).  Returns the cut positions ``(p1, p2, p3)`` of
    ``t[p1:p2] + t[p2:p3]`` before the swap, or None when the swap would break
    precedence (``t`` is then unchanged)."""
    m = len(t)
    if m < 5:
        return None
    lmax = max(1, min(max_len, (m - 1) // 3))
    l1 = rng.randint(1, lmax)
    l2 = rng.randint(1, lmax)
    p1 = rng.randint(1, m - l1 - l2)
    p2, p3 = p1 + l1, p1 + l1 + l2
    B, C = t[p1:p2], t[p2:p3]
    if inst.has_precedence:
        bset = set(B)
        if any(p in bset for x in C for p in inst.preds[x]):
            return None
    t[p1:p3] = C + B
    return p1, p2, p3


def ils(inst: Instance, t: List[int], c: List[int], cost: float, near, neard,
        rng: random.Random, kicks: int, deadline: float, max_len: int = 30) -> float:
    """Iterated local search: ``kicks`` double-bridge kicks, each followed by
    local search around the changed edges; a kick is kept only if the tour got
    shorter.  Returns the final cost (``t``, ``c`` updated in place).  Costs are
    tracked incrementally and recomputed exactly at the end."""
    m = len(t)
    d = inst.item_cost_fn(c)
    multi = inst.n > inst.m
    for _ in range(kicks):
        if time.perf_counter() > deadline:
            break
        t0, c0 = t[:], c[:]
        a = t0
        cut = double_bridge(inst, t, rng, max_len)
        if cut is None:
            continue
        p1, p2, p3 = cut
        x, b0, bl, c0_, cl, y = a[p1 - 1], a[p1], a[p2 - 1], a[p2], a[p3 - 1], a[p3 % m]
        delta = (d(x, c0_) + d(cl, b0) + d(bl, y)) - (d(x, b0) + d(bl, c0_) + d(cl, y))
        l2 = p3 - p2
        touched = [t[p1 - 1], t[p1], t[p1 + l2 - 1], t[p1 + l2], t[p3 - 1], t[p3 % m]]
        gain = local_search(inst, t, c, near, neard, active=touched, deadline=deadline)
        if multi:
            pos = sorted(t.index(x) for x in touched)
            lo, hi = (pos[0] - 2, pos[-1] + 2) if pos[-1] - pos[0] <= 4 * max_len \
                else (p1 - 3, p3 + 2)
            gain += window_entries(inst, t, c, lo, hi)
        if delta - gain < -1e-9:
            cost += delta - gain
        else:
            t[:] = t0
            c[:] = c0
    return inst.tour_cost(t, c)


def order_crossover(p1: Sequence[int], p2: Sequence[int], rng: random.Random) -> List[int]:
    """OX on the orders without the anchor (position 0 stays the anchor): a
    slice of ``p1`` is kept in place, the other items follow ``p2``'s order."""
    m = len(p1)
    if m <= 3:
        return list(p1)
    a = rng.randint(1, m - 2)
    b = rng.randint(a + 1, m - 1)
    keep = p1[a:b + 1]
    ks = set(keep)
    rest = [x for x in p2[1:] if x not in ks]
    child = [p1[0]] + rest[:a - 1] + list(keep) + rest[a - 1:]
    return child


def run_ga(inst: Instance, *, time_limit: float, seed: int, pop_size: int = 0,
           max_iterations: Optional[int] = None, stall_generations: int = 40, kicks: int = 0,
           progress: Optional[Callable[[float, str], None]] = None) -> SearchResult:
    """Genetic algorithm; returns the best tour found (anchor first).
    ``time_limit`` in seconds caps the run; ``max_iterations`` (generations,
    None = no limit) bounds it independently of machine speed."""
    t_start = time.perf_counter()
    deadline = t_start + time_limit
    rng = random.Random(seed)
    near, neard = inst.neighbours(10)
    m = inst.m
    kicks = kicks or max(30, min(m // 2, 1000))
    if pop_size <= 0:
        pop_size = 8 if m <= 300 else 6 if m <= 1500 else 4

    t, c = nearest_neighbour(inst)
    nn_cost = inst.tour_cost(t, c)
    if m <= 3:
        c, cost = optimal_entries(inst, t)
        return SearchResult(t, c, cost, 0, nn_cost, "converged")
    cost = improve(inst, t, c, near, neard, deadline=deadline)
    pop: List[Tuple[float, List[int], List[int]]] = [(cost, t, c)]
    # diverse starts: randomised nearest-neighbour, each improved (a full local
    # search each: only one for large jobs), then kicked copies of the best.
    # Decided by size, not by measured time, so a seed gives one result.
    n_random = pop_size - 1 if m <= 1000 else 1
    while len(pop) < 1 + n_random and time.perf_counter() < deadline:
        t2, c2 = nearest_neighbour(inst, rng, choose_among=3)
        c2, _ = optimal_entries(inst, t2)
        cst = improve(inst, t2, c2, near, neard, deadline=deadline)
        pop.append((cst, t2, c2))
    while len(pop) < pop_size and time.perf_counter() < deadline:
        t2, c2 = t[:], c[:]
        for _ in range(max(1, m // 20)):
            double_bridge(inst, t2, rng, 50)
        cst = improve(inst, t2, c2, near, neard, deadline=deadline)
        pop.append((cst, t2, c2))
    pop.sort(key=lambda x: x[0])
    best = pop[0][0]
    gen = 0
    stall = 0
    budget = max_iterations if max_iterations is not None else float("inf")
    while gen < budget and stall < stall_generations and time.perf_counter() < deadline:
        gen += 1
        i1 = min(rng.randrange(len(pop)), rng.randrange(len(pop)))
        i2 = min(rng.randrange(len(pop)), rng.randrange(len(pop)))
        if i1 == i2:
            i2 = (i1 + 1) % len(pop)
        p1, p2 = pop[i1], pop[i2]
        child = order_crossover(p1[1], p2[1], rng)
        if inst.has_precedence:
            child = repair(child, inst.preds, inst.succs)
        cc, _ = optimal_entries(inst, child)
        cst = improve(inst, child, cc, near, neard, deadline=deadline)
        cst = ils(inst, child, cc, cst, near, neard, rng, kicks, deadline)
        if inst.n > inst.m:
            cst = improve(inst, child, cc, near, neard, deadline=deadline)
        worst = pop[-1][0]
        if cst < worst - 1e-9 and all(abs(cst - q[0]) > 1e-6 * max(1.0, cst) for q in pop):
            pop[-1] = (cst, child, cc)
            pop.sort(key=lambda x: x[0])
        if pop[0][0] < best - 1e-6 * max(1.0, best):
            best = pop[0][0]
            stall = 0
        else:
            stall += 1
        if progress is not None:
            progress(min(1.0, (time.perf_counter() - t_start) / max(time_limit, 1e-9)),
                     f"genetic algorithm: generation {gen}, best {best:.1f}")
    cost, t, c = pop[0]
    return SearchResult(list(t), list(c), cost, gen, nn_cost,
                        stop_reason(stall >= stall_generations, gen >= budget))
