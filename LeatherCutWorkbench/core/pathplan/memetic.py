"""The memetic genetic algorithm with islands (the planner's default search).

A GK-style memetic GA (Gutin & Karapetyan 2010) with GLNS-style
large-neighbourhood moves (Smith & Imeson 2017), compiled with numba
(:mod:`.kernels`):

* population per island of randomised nearest-neighbour tours, each improved
  by 2-opt / Or-opt with neighbour lists and don't-look bits, cluster
  re-insertion (a moved item re-picks its candidate) and the exact entry DP;
* a generation makes one child by order crossover of two tournament-selected
  parents (or copies one), repairs precedence, re-optimises entries by the DP,
  improves it by local search, then by a few iterated ruin-and-recreate moves
  (remove 2..k items -- random, a tour segment, related by distance, or the
  worst detours -- and re-insert each at its cheapest place and candidate,
  with noise), and replaces the worst individual when better and new;
* an island whose best has not improved for a while restarts its population
  around the best;
* ``ISLANDS`` islands evolve in parallel threads (the kernels release the
  GIL) and pass their best tour to the next island every epoch.

Determinism: the number of islands, the epoch length and every random number
(splitmix64 streams seeded from ``seed``) are fixed by the seed and the size,
never by the machine or the clock, so a run that ends by its generation
budget (``max_iterations``) or by convergence gives the same tour on any
machine; only the time limit is clock-dependent.
"""

from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, List, Optional, Tuple

import numpy as np

from . import kernels as K
from .instance import EuclidInstance, Instance, MatrixInstance
from .nn import nearest_neighbour
from .result import SearchResult, stop_reason

#: islands (fixed: the result must not depend on the number of cores)
ISLANDS = 2
#: neighbour-list length
NEAR = 10
#: kernels already called once in this process (see run_memetic)
_loaded: dict = {}


def pack(inst: Instance) -> Tuple[tuple, tuple]:
    """The structure and problem tuples of :mod:`.kernels` for ``inst``."""
    m = inst.m
    sizes = np.array([len(c) for c in inst.cands], dtype=np.int64)
    cptr = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    cids = np.concatenate(inst.cands).astype(np.int64)
    near_l, neard_l = inst.neighbours(NEAR)
    kk = max(1, max((len(r) for r in near_l), default=1))
    near = np.full((m, kk), -1, dtype=np.int64)
    neard = np.full((m, kk), np.inf)
    for k, (r, d) in enumerate(zip(near_l, neard_l)):
        near[k, :len(r)] = r
        neard[k, :len(d)] = d
    P = problem_tuple(inst)
    pptr, pidx = _csr(inst.preds)
    sptr, sidx = _csr(inst.succs)
    flags = np.array([int(inst.has_precedence), int(inst.symmetric)], dtype=np.int64)
    S = (cptr, cids, near, neard, pptr, pidx, sptr, sidx, flags)
    return S, P


def _csr(lists) -> Tuple[np.ndarray, np.ndarray]:
    sizes = np.array([len(x) for x in lists], dtype=np.int64)
    ptr = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    idx = np.array([v for x in lists for v in x], dtype=np.int64)
    return ptr, idx


def problem_tuple(inst: Instance) -> tuple:
    """``(mode, D, en, sn, X, tp)`` pricing moves exactly like ``inst.cost``."""
    dummy_d = np.zeros((1, 1))
    dummy_i = np.zeros(1, dtype=np.int64)
    if isinstance(inst, MatrixInstance):
        return (0, np.ascontiguousarray(inst.D, dtype=np.float64), np.asarray(inst.en, dtype=np.int64),
                np.asarray(inst.sn, dtype=np.int64), np.zeros((1, 6)), np.zeros(4))
    if isinstance(inst, EuclidInstance):
        X = np.zeros((inst.n, 6))
        X[:, 0:2] = inst.E
        X[:, 2:4] = inst.S
        tm = getattr(inst, "time_params", None)
        if tm is None:
            return (1, dummy_d, dummy_i, dummy_i, X, np.zeros(4))
        X[:, 4] = inst.exit_heading
        X[:, 5] = inst.entry_heading
        return (2, dummy_d, dummy_i, dummy_i, X, np.asarray(tm, dtype=np.float64))
    raise TypeError(f"no compiled cost model for {type(inst).__name__}")


def _seed_state(seed: int, island: int) -> np.ndarray:
    st = np.array([np.uint64((int(seed) * 1_000_003 + 7919 * (island + 1)) % (1 << 64))], dtype=np.uint64)
    K.rnd_u64(st)
    return st


def settings(m: int) -> dict:
    """Search settings by size (fixed by m, never by the machine)."""
    return {
        "pop": 12 if m <= 300 else 8 if m <= 600 else 4 if m <= 1500 else 2,
        "epoch": max(1, min(25, 4000 // max(m, 1))),
        "full_dp": m <= 600,
        "p_cross": 0.5,
        "lns_steps": 8 if m <= 300 else 16,
        "kmax": max(4, min(30, m // 8)),
        "noise": 0.1,
        "accept": 0.002,
        "restart_after": 60 + m // 2,
        "stall_limit": 400 + 4 * m,
        # large jobs: start individuals as perturbed copies of the first one
        "cheap_start": max(8, m // 10) if m > 600 else 0,
    }


def run_memetic(inst: Instance, *, time_limit: float, seed: int,
                max_iterations: Optional[int] = None,
                progress: Optional[Callable[[float, str], None]] = None) -> SearchResult:
    """Memetic GA on ``inst``; returns the best tour found (anchor first).

    ``time_limit`` (s) caps the run; ``max_iterations`` (generations per
    island, None = no limit) bounds it independently of the machine.  The run
    also ends when the best tour has not improved for ``stall_limit``
    generations ("converged")."""
    t_start = time.perf_counter()
    deadline = t_start + time_limit
    m = inst.m
    order, choice = nearest_neighbour(inst)
    nn_cost = inst.tour_cost(order, choice)
    S, P = pack(inst)
    t0 = np.asarray(order, dtype=np.int64)
    c0 = np.asarray(choice, dtype=np.int64)
    if m <= 3:
        cost = K.dp_full(t0, c0, S, P)
        return SearchResult(t0.tolist(), c0.tolist(), float(cost), 0, nn_cost, "converged")
    cfg = settings(m)
    states = [_seed_state(seed, i) for i in range(ISLANDS)]
    pops = [(np.empty((cfg["pop"], m), dtype=np.int64), np.empty((cfg["pop"], m), dtype=np.int64),
             np.empty(cfg["pop"])) for _ in range(ISLANDS)]
    stats = [np.zeros(2, dtype=np.int64) for _ in range(ISLANDS)]
    workers = max(1, min(ISLANDS, os.cpu_count() or 1))
    with ThreadPoolExecutor(max_workers=workers) as pool:
        def each(fn):
            # the first call of a kernel in a process loads (or compiles) it:
            # done by one thread alone, the others wait (numba's cache
            # loading is not safe to run concurrently)
            first = 0 if _loaded.get(fn.__name__) else 1
            if first:
                fn(0)
                _loaded[fn.__name__] = True
            futs = [pool.submit(fn, i) for i in range(first, ISLANDS)]
            for f in futs:
                f.result()

        def init(i: int) -> None:
            K.init_island(pops[i][0], pops[i][1], pops[i][2], t0, c0, i == 0, S, P, states[i],
                          cfg["cheap_start"])

        def epoch(i: int) -> None:
            K.evolve(pops[i][0], pops[i][1], pops[i][2], stats[i], step, S, P, states[i],
                     cfg["full_dp"], cfg["p_cross"], cfg["lns_steps"], cfg["kmax"], cfg["noise"],
                     cfg["restart_after"], cfg["accept"])

        each(init)
        budget = max_iterations if max_iterations is not None else float("inf")
        gen = 0
        best = min(float(p[2].min()) for p in pops)
        since = 0
        while gen < budget and since < cfg["stall_limit"] and time.perf_counter() < deadline:
            step = int(min(cfg["epoch"], budget - gen))
            each(epoch)
            gen += step
            _migrate(pops)
            now = min(float(p[2].min()) for p in pops)
            if now < best - 1e-9 * max(1.0, best):
                best = now
                since = 0
            else:
                since += step
            if progress is not None:
                progress(min(1.0, (time.perf_counter() - t_start) / max(time_limit, 1e-9)),
                         f"genetic algorithm: generation {gen}, best {best:.1f}")
    i_best = min(range(ISLANDS), key=lambda i: (float(pops[i][2].min()), i))
    j = int(np.argmin(pops[i_best][2]))
    t = pops[i_best][0][j].copy()
    c = pops[i_best][1][j].copy()
    return SearchResult(t.tolist(), c.tolist(), float(inst.tour_cost(t.tolist(), c.tolist())), gen,
                        nn_cost, stop_reason(since >= cfg["stall_limit"], gen >= budget))


def _migrate(pops: List[tuple]) -> None:
    """Ring migration: each island's best replaces the worst of the next
    island unless that island already holds an equal tour."""
    bests = [(p[0][int(np.argmin(p[2]))].copy(), p[1][int(np.argmin(p[2]))].copy(), float(p[2].min()))
             for p in pops]
    n = len(pops)
    for i in range(n):
        t, c, cst = bests[(i - 1) % n]
        pt, pc, pcost = pops[i]
        if np.any(np.abs(pcost - cst) <= 1e-9 * max(1.0, cst)):
            continue
        w = int(np.argmax(pcost))
        if cst < pcost[w]:
            pt[w] = t
            pc[w] = c
            pcost[w] = cst
