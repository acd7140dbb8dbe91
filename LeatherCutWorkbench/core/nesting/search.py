"""Anytime improvement of the bottom-left fill by late-acceptance local search.

A solution is the order in which the copies are fed to the bottom-left fill
plus, per copy, either a forced variant (orientation) or "greedy" (the fill
tries every allowed orientation and keeps the best).  Its cost is the tuple
(area left unplaced, containers used, extent of the last container): fewer
unplaced parts first, then fewer sheets / hides, then the shortest strip or
the most compact last sheet.

Moves: swap two copies, move one copy elsewhere in the order, or change one
copy's orientation choice.  Only the placements after the first changed
position are recomputed (the prefix is reused), so late changes are cheap.
A move is accepted when its cost is not worse than the current cost or than
the cost ``history`` steps ago (late-acceptance hill climbing, Burke & Bykov):
this walks over the long plateaus strip lengths have without getting stuck.
A fill that already left out more than could be accepted is abandoned early.

Strips are searched by shrinking (:func:`run_strip_search`): the strip is
closed a little shorter than the best layout and the order is searched until
every piece fits again.

Each worker process runs its own search with its own random stream (derived
from the seed and the worker index i) and start order; the best result wins, ties going to the lowest worker index.
With ``max_evaluations`` each worker stops after exactly that many layouts,
so the result only depends on the seed and the worker count; with only a
time budget it also depends on the machine's speed.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

from .blf import BinSpec, Placer
from .shapes import Variant

Gene = Tuple[int, Optional[int]]          # (type index, forced variant or None)
Placements = List[Tuple[int, int, int, int, int]]


@dataclass
class Problem:
    """Everything a worker needs (picklable)."""

    variants: List[Variant]
    type_variants: List[List[int]]
    type_grade: List[int]
    type_area: List[float]
    bins: List[BinSpec]
    open_new: bool
    max_bins: Optional[int]

    def placer(self) -> Placer:
        return Placer(self.variants, self.type_variants, self.type_grade, self.bins,
                      self.open_new, self.max_bins)


def cost_of(problem: Problem, seq: Sequence[Gene], placements: Placements) -> Tuple[float, int, int]:
    """(area left out, containers used, extent of the last container): lower is
    better, compared in that order."""
    unplaced_area = 0.0
    last_bin = -1
    for (si, b, vi, tx, ty) in placements:
        if b < 0:
            unplaced_area += problem.type_area[seq[si][0]]
        last_bin = max(last_bin, b)
    extent = 0
    for (si, b, vi, tx, ty) in placements:
        if b == last_bin and b >= 0:
            extent = max(extent, tx + problem.variants[vi].bbox[2])
    return (round(unplaced_area, 6), last_bin + 1, extent)


def start_orders(problem: Problem, copies: Sequence[int]) -> List[List[Gene]]:
    """Deterministic start orders: by area, by bounding-box length, by height."""
    def dims(t: int) -> Tuple[int, int]:
        v = problem.variants[problem.type_variants[t][0]]
        return v.bbox[2] - v.bbox[0], v.bbox[3] - v.bbox[1]

    keys = [
        lambda t: (-problem.type_area[t], t),
        lambda t: (-max(dims(t)), t),
        lambda t: (-dims(t)[1], -problem.type_area[t], t),
        lambda t: (-dims(t)[0] * dims(t)[1], t),
    ]
    return [[(t, None) for t in sorted(copies, key=k)] for k in keys]


def _mutate(rng: random.Random, seq: List[Gene], problem: Problem) -> Tuple[List[Gene], int]:
    """A random neighbour of ``seq`` that really differs (no swap of two copies
    of the same part, no orientation change of a part with one orientation) and
    the first position that changed."""
    n = len(seq)
    new = list(seq)
    for _ in range(20):
        r = rng.random()
        if r < 0.2:
            i = rng.randrange(n)
            t, cur = new[i]
            if len(problem.type_variants[t]) < 2:
                continue
            opts: List[Optional[int]] = [None] + list(problem.type_variants[t])
            new[i] = (t, rng.choice([o for o in opts if o != cur]))
            return new, i
        if n < 2:
            break
        i, j = sorted(rng.sample(range(n), 2))
        if r < 0.6:
            if new[i] == new[j]:
                continue
            new[i], new[j] = new[j], new[i]
            return new, i
        if rng.random() < 0.5:
            i, j = j, i                       # move backwards or forwards
        lo, hi = min(i, j), max(i, j)
        if all(g == new[i] for g in new[lo:hi + 1]):
            continue
        g = new.pop(i)
        new.insert(j, g)
        return new, lo
    return new, n


def run_search(problem: Problem, copies: List[int], seed: int, worker: int,
               time_budget: float, max_evaluations: Optional[int],
               history: int = 40, tick=None) -> Tuple[Tuple[float, int, int], List[Gene], Placements, int]:
    """One worker's search; returns (cost, order, placements, evaluations)."""
    deadline = time.monotonic() + time_budget
    placer = problem.placer()
    rng = random.Random(seed * 1000003 + worker)
    best = None
    for k, order in enumerate(start_orders(problem, copies)):
        if k and (time.monotonic() > deadline):
            break
        tr = placer.place(order)
        c = cost_of(problem, order, tr.placements)
        if best is None or c < best[0]:
            best = (c, order, tr)
    evals = 4
    cur_cost, cur_seq, cur_pl = best
    if worker % 2 == 1 and len(copies) > 1:     # diversify the second start
        cur_seq = list(cur_seq)
        rng.shuffle(cur_seq)
        cur_pl = placer.place(cur_seq)
        cur_cost = cost_of(problem, cur_seq, cur_pl.placements)
    hist = [cur_cost] * history
    step = 0
    while True:
        if max_evaluations is not None and evals >= max_evaluations:
            break
        if time.monotonic() > deadline:
            break
        if tick is not None and evals % 10 == 0 and tick(best[0]) is False:
            from ..errors import CancelledError
            raise CancelledError("nesting cancelled")
        new_seq, first = _mutate(rng, cur_seq, problem)
        slot = step % history
        h = hist[slot]
        step += 1
        evals += 1
        new_pl = placer.place(new_seq, cur_pl, first,
                              give_up=(max(cur_cost[0], h[0]), problem.type_area))
        if new_pl is not None:                # None: left out more than could be accepted
            c = cost_of(problem, new_seq, new_pl.placements)
            if c <= cur_cost or c <= h:
                cur_cost, cur_seq, cur_pl = c, new_seq, new_pl
                if c < best[0]:
                    best = (c, new_seq, new_pl)
        if cur_cost < h:
            hist[slot] = cur_cost
    return best[0], best[1], best[2].placements, evals


def run_strip_search(problem: Problem, copies: List[int], seed: int, worker: int,
                     time_budget: float, max_evaluations: Optional[int],
                     history: int = 30, tick=None):
    """Strip search by shrinking: cut the strip to a length a little shorter than
    the best layout so far and search the order until everything fits again.

    With the strip closed at the target length, the bottom-left fill leaves
    out what does not fit, and the area left out is a much smoother guide than
    the strip length itself (which only one piece decides).  When all pieces
    fit, the layout is the new best and the target shrinks again; when the
    search stalls, the shrink step halves (2 % down to 0.05 %); when even the
    smallest step fails, the best order is kicked by a few random changes and
    the cycle starts again (iterated local search)."""
    from .blf import BinSpec as _Bin
    deadline = time.monotonic() + time_budget
    rng = random.Random(seed * 1000003 + worker)
    open_placer = problem.placer()
    nfps = open_placer.nfps
    x0, y0, _, y1 = problem.bins[0].rect
    best = None
    starts = start_orders(problem, copies)
    if worker % 2 == 1:
        starts = starts[1:] + starts[:1]
    for k, order in enumerate(starts):
        if k and time.monotonic() > deadline:
            break
        tr = open_placer.place(order)
        c = cost_of(problem, order, tr.placements)
        if best is None or c < best[0]:
            best = (c, order, tr)
    evals = len(starts)
    best_len = best[0][2]
    seq = list(best[1])
    step_frac = 0.02
    min_frac = 0.0005

    def stop() -> bool:
        if max_evaluations is not None and evals >= max_evaluations:
            return True
        return time.monotonic() > deadline

    while not stop() and len(copies) > 1:
        target = x0 + int((best_len - x0) * (1.0 - step_frac))
        placer = Placer(problem.variants, problem.type_variants, problem.type_grade,
                        [_Bin("sheet", (x0, y0, target, y1))], False, 1, nfps)
        cur_pl = placer.place(seq)
        evals += 1
        cur_cost = cost_of(problem, seq, cur_pl.placements)
        hist = [cur_cost] * history
        stall = 0
        limit = max(60, 3 * len(copies))
        step = 0
        while cur_cost[0] > 0 and stall < limit and not stop():
            if tick is not None and evals % 10 == 0 and tick(best[0]) is False:
                from ..errors import CancelledError
                raise CancelledError("nesting cancelled")
            left_out = [p[0] for p in cur_pl.placements if p[1] < 0]
            if left_out and rng.random() < 0.3:
                # move a piece that did not fit to an earlier place in the order
                i = rng.choice(left_out)
                j = rng.randrange(i + 1) if i > 0 else 0
                new_seq = list(seq)
                new_seq.insert(j, new_seq.pop(i))
                first = j
            else:
                new_seq, first = _mutate(rng, seq, problem)
            slot = step % history
            h = hist[slot]
            step += 1
            stall += 1
            evals += 1
            new_pl = placer.place(new_seq, cur_pl, first,
                                  give_up=(max(cur_cost[0], h[0]), problem.type_area))
            if new_pl is not None:            # None: left out more than could be accepted
                c = cost_of(problem, new_seq, new_pl.placements)
                if c < cur_cost:
                    stall = 0
                if c <= cur_cost or c <= h:
                    seq, cur_pl, cur_cost = new_seq, new_pl, c
            if cur_cost < h:
                hist[slot] = cur_cost
        if cur_cost[0] == 0:
            best = (cur_cost, list(seq), cur_pl)
            best_len = cur_cost[2]
            step_frac = min(0.02, step_frac * 1.5)
        else:
            seq = list(best[1])
            step_frac /= 2.0
            if step_frac < min_frac:
                # every shrink step failed: kick the best order (a few random swaps)
                # and start over with big steps -- an iterated local search
                step_frac = 0.02
                for _ in range(max(2, len(seq) // 8)):
                    seq, _ = _mutate(rng, seq, problem)
    return best[0], best[1], best[2].placements, evals


def search(problem: Problem, copies: List[int], seed: int, worker: int, time_budget: float,
           max_evaluations: Optional[int], tick=None):
    """The right search for the container kind (strip: shrinking; else order search)."""
    fn = run_strip_search if problem.bins[0].kind == "strip" else run_search
    return fn(problem, copies, seed, worker, time_budget, max_evaluations, tick=tick)


def _worker_entry(args):
    problem, copies, seed, worker, budget, max_eval = args
    return search(problem, copies, seed, worker, budget, max_eval)
