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

Hides: odd workers run the copy-to-hide search (:mod:`hide_assign`) right
after a quick first fill; even workers run the order search and hand over to
the copy-to-hide search on their own best set once that search has stalled
on a layout that places every copy (:func:`_stalled`; Baldacci Test6 at 60 s:
the order search finds 13 hides / 782 M units^2 by 12 s and nothing better
after, the hand-over steps that set down to 13 hides of 751-767 M or 12).  The
parent hands every worker the others' best complete hide layout
(:attr:`Budget.shared`); a copy-to-hide search takes it over when it beats its
own, so the two workers step down from the best set (in different lanes)
instead of one of them from a worse one.

Each worker process runs its own search with its own random stream (derived
from the seed and the worker index i) and start order; the best result wins, ties going to the lowest worker index.
With ``max_evaluations`` each worker stops after exactly that many layouts,
so the result only depends on the seed and the worker count (as long as the
time budget does not end the search first); with only a time budget it also
depends on the machine's speed.

Time (see :class:`Budget`): the first fill is never abandoned but switches to
convex-hull no-fit polygons once ``first_fill_until`` passes; every later
evaluation is abandoned when ``t_end`` passes or Stop is pressed, so a worker
ends at most one no-fit polygon computation after its deadline.  Every new
best layout is handed to ``on_best`` (the parent process shows it live and
keeps it when the user presses Stop).
"""

from __future__ import annotations

import math
import random
import time
import traceback
from dataclasses import dataclass
from queue import Empty
from typing import Callable, List, Optional, Sequence, Tuple

import numpy as np

from .blf import BinSpec, Placer
from .convex_sums import warm_up
from .hide_choice import (as_hide_indices, first_affected, hide_cost, initial_order, swap_hides,
                          tight_order, used_positions)
from .hide_patterns import HidePatterns
from .shapes import Variant

Gene = Tuple[int, Optional[int]]          # (type index, forced variant or None)
Placements = List[Tuple[int, int, int, int, int]]
Cost = Tuple[float, int, int]


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

    #: grid units per mm (the hide prune compares areas in grid units)
    scale: float = 1.0
    #: hides: net area (mm^2) per available hide; the search then also chooses
    #: the hides and their fill order (:mod:`hide_choice`)
    hide_net: Optional[List[float]] = None
    #: hides: :class:`part_regions.RegionCheck` for parts with graded regions
    region_check: Optional[object] = None

    def placer(self) -> Placer:
        return Placer(self.variants, self.type_variants, self.type_grade, self.bins,
                      self.open_new, self.max_bins,
                      type_area=[a * self.scale * self.scale for a in self.type_area],
                      region_check=self.region_check)


def cost_of(problem: Problem, seq: Sequence[Gene], placements: Placements,
            hide_order: Optional[Sequence[int]] = None) -> tuple:
    """(area left out, containers used, extent of the last container): lower is
    better, compared in that order.  Hides (``problem.hide_net``): see
    :func:`hide_choice.hide_cost` (the net area of the hides used and the
    part area on the least-filled one come before
    the extent)."""
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
    if problem.hide_net is not None:
        order = hide_order if hide_order is not None else range(len(problem.hide_net))
        return hide_cost(placements, order, problem.hide_net, unplaced_area, extent,
                         [problem.type_area[seq[si][0]] for (si, _b, _v, _x, _y) in placements])
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


def _from_least_filled(rng: random.Random, seq: List[Gene], placements: Placements,
                       problem: Problem) -> Tuple[List[Gene], int]:
    """Hides: a copy on the least-filled hide moved to a random earlier place
    in the order (the fill then tries it on the other hides first) -- a step
    towards emptying that hide.  Returns (order, first changed position), -1
    when no copy can move."""
    on: dict = {}
    for (si, b, _vi, _tx, _ty) in placements:
        if b >= 0:
            on.setdefault(b, []).append(si)
    if len(on) < 2:
        return seq, -1
    least = min(on, key=lambda b: (sum(problem.type_area[seq[si][0]] for si in on[b]), b))
    i = rng.choice(on[least])
    if i == 0:
        return seq, -1
    j = rng.randrange(i)
    new = list(seq)
    new.insert(j, new.pop(i))
    return new, j


@dataclass
class Budget:
    """What one worker may spend and whom it tells (times: ``time.monotonic()``).

    * ``t_end`` -- the search ends; an evaluation still running is abandoned;
    * ``first_fill_until`` -- the first fill (never abandoned) computes exact
      no-fit polygons only until then, coarse (convex-hull) ones afterwards,
      so a first valid layout exists early even on hundreds of parts;
    * ``max_evaluations`` -- stop after this many layouts (None: no limit);
    * ``stop`` -- returns True when the user pressed Stop (keep the best);
    * ``on_best(cost, order, placements)`` -- called on every new best layout;
    * ``tick(best_cost)`` -- called every few evaluations; False = cancel;
    * ``hard_stop`` -- the first fill goes on with bounding boxes only;
    * ``give_up_at`` -- even the first fill ends then (copies left unplaced);
    * ``shared()`` -- the best layout another worker found since the last
      call, (cost, order, placements on hide indices), or None (hides: the
      copy-to-hide search steps down from it when it beats its own);
    * ``copies`` -- the part type of every copy, sorted: a layout whose order
      or placements do not hold exactly these is refused (:func:`cost_of`
      counts only the copies left out, so one that lost a copy would look
      complete and win), and ``on_lost(where)`` hears of it (the search's
      call chain)."""

    t_end: float
    first_fill_until: float = math.inf
    max_evaluations: Optional[int] = None
    stop: Optional[Callable[[], bool]] = None
    on_best: Optional[Callable[[Cost, List[Gene], Placements], None]] = None
    tick: Optional[Callable[[Cost], bool]] = None
    hard_stop: float = math.inf
    give_up_at: float = math.inf
    shared: Optional[Callable[[], Optional[Tuple[Cost, List[Gene], Placements]]]] = None
    copies: Optional[Sequence[int]] = None
    on_lost: Optional[Callable[[str], None]] = None

    def done(self, evals: int) -> bool:
        if self.max_evaluations is not None and evals >= self.max_evaluations:
            return True
        if self.stop is not None and self.stop():
            return True
        return time.monotonic() > self.t_end

    def check_cancel(self, evals: int, best_cost: Cost) -> None:
        if self.tick is not None and evals % 10 == 0 and self.tick(best_cost) is False:
            from ..errors import CancelledError
            raise CancelledError("nesting cancelled")

    def improved(self, cost: Cost, order: List[Gene], placements: Placements) -> None:
        if self.copies is not None and not holds_every_copy(self.copies, order, placements):
            if self.on_lost is not None:
                self.on_lost(" < ".join(f.name for f in reversed(traceback.extract_stack(limit=9)[:-1])))
            return
        if self.on_best is not None:
            self.on_best(cost, list(order), list(placements))


def holds_every_copy(copies: Sequence[int], order: Sequence[Gene], placements: Placements) -> bool:
    """Does ``order`` hold exactly the part types ``copies`` (sorted), and
    ``placements`` one entry (placed or not) per position of ``order``?"""
    return len(order) == len(copies) == len(placements) and \
        sorted(g[0] for g in order) == list(copies) and \
        sorted(p[0] for p in placements) == list(range(len(order)))


#: hides: worker 0's very first fill tries this many orientations per copy,
#: coarse inner-fit regions only (its next fills, coarse until
#: ``first_fill_until`` then exact, try four): one inner-fit region per hide and
#: part instead of four -- Baldacci Test9 (11 copies that fit no hide try every
#: hide) 896 coarse inner-fit regions and 1.45 s on one core, 225 and 0.48 s so
FIRST_CAP_HIDES = 1


def _first_fills(problem: Problem, placer: Placer, copies: Sequence[int], worker: int,
                 budget: Budget, quick: bool = False):
    """The worker's first layout (its own start order, never abandoned), then
    the other start orders while they are cheap; returns (cost, order, trace, evals).
    ``quick`` (always on worker 0): the first fill tries four orientations only
    (and, with ``quick``, the other start orders too).  Worker 0 on hides
    answers first with a coarse fill of ``FIRST_CAP_HIDES`` orientations,
    parts with graded regions wholly of their strictest grade
    (:attr:`Placer.whole_grade`), then fills with four.  The sum kernel
    (numba, :func:`convex_sums.warm_up`) is loaded by each worker, by worker
    0 only after its first fill (numpy makes the sums meanwhile: the few
    thousand of coarse inner-fit regions, or a sheet's exact no-fit polygons
    up to ``first_fill_until``); on hides after its four-orientation fill
    when that is coarse (past ``first_fill_until``: Baldacci Test9/10 at
    T = 10 s under load 5 on 2 cores, the kernel's ~1.5 s wall before it
    left the search with the one-orientation layout)."""
    starts = start_orders(problem, copies)
    first_hides = worker == 0 and problem.hide_net is not None
    if worker != 0:
        warm_up()
    k = worker % len(starts)
    starts = starts[k:] + starts[:k]
    t0 = time.monotonic()
    placer.clock.stop_at = budget.t_end
    placer.clock.hard_stop = budget.hard_stop
    placer.clock.give_up_at = budget.give_up_at
    placer.clock.stop = budget.stop
    # worker 0 answers fast: exact no-fit polygons only briefly, four orientations
    cap = 4 if worker == 0 or quick else None
    if first_hides:
        placer.clock.exact_until, cap = -math.inf, FIRST_CAP_HIDES
        placer.whole_grade = True
    else:
        placer.clock.exact_until = budget.first_fill_until
    tr = placer.place(starts[0], abortable=False, variant_cap=cap)
    placer.whole_grade = False
    hides = placer.bin_order
    best = (cost_of(problem, starts[0], tr.placements, hides), starts[0], tr)
    budget.improved(best[0], best[1], _out(tr.placements, hides))
    evals = 1
    if not first_hides or time.monotonic() < budget.first_fill_until:
        warm_up()
    if first_hides:
        placer.clock.exact_until = budget.first_fill_until
        if not budget.done(evals):
            # the four-orientation fill (coarse once ``first_fill_until`` passed): at
            # T = 10 s often the best layout worker 0 has before the deadline
            best, evals, _ = _better(problem, placer, budget, best, starts[0], evals, 4)
        warm_up()
    # worker 0 keeps searching with coarse NFPs for pairs not cached yet when exact
    # ones are expensive (arc-rich garment outlines: tens of ms each) -- many cheap
    # evaluations; the other workers search exactly
    # (hides: exact always -- a coarse layout of concave leather parts wastes hides)
    if worker != 0 or placer.nfps.mean_exact_s() < 0.005 or problem.hide_net is not None:
        placer.clock.exact_until = math.inf
    if worker == 0 and problem.hide_net is not None and not budget.done(evals):
        # the quick first fill again, exactly
        best, evals, _ = _better(problem, placer, budget, best, starts[0], evals, None)
    cheap = (time.monotonic() - t0) < 0.25 * max(budget.t_end - t0, 0.0)
    for order in starts[1:]:
        if not cheap or budget.done(evals):
            break
        # the copy-to-hide worker (``quick``) re-fills every hide itself and only
        # needs their hide count and copies: four orientations (Baldacci Test5
        # under load: its search started with 50 s of 60 left instead of 20)
        best, evals, filled = _better(problem, placer, budget, best, order, evals,
                                      4 if quick else None)
        if not filled:
            break
    return best, evals


def _better(problem: Problem, placer: Placer, budget: Budget, best, order: List[Gene],
            evals: int, cap: Optional[int]):
    """One more (abortable) fill of ``order`` with at most ``cap`` orientations
    per copy (None: the placer's default); returns (best, evaluations, whether
    the fill ran to its end), the fill's layout reported and kept when it is
    better."""
    tr = placer.place(order, variant_cap=cap)
    if tr is not None:
        hides = placer.bin_order
        c = cost_of(problem, order, tr.placements, hides)
        if c < best[0]:
            best = (c, order, tr)
            budget.improved(c, order, _out(tr.placements, hides))
    return best, evals + 1, tr is not None


def _out(placements: Placements, hide_order: Optional[List[int]]) -> Placements:
    """Placements as they leave the worker (hide positions -> hide indices)."""
    return placements if hide_order is None else as_hide_indices(placements, hide_order)


def run_search(problem: Problem, copies: List[int], seed: int, worker: int,
               budget: Budget, history: int = 40) -> Tuple[Cost, List[Gene], Placements, int]:
    """One worker's search; returns (cost, order, placements, evaluations).

    Worker 0 lets a copy without a forced orientation try at most four of a
    freely turning part's orientations (its evaluations are about three
    times cheaper; orientation moves still force any of them), the other
    workers try all."""
    placer = problem.placer()
    placer.variant_cap = 4 if worker == 0 else None
    choose_hides = problem.hide_net is not None and len(problem.hide_net) > 1
    if problem.hide_net is not None:
        placer.bin_order = initial_order(problem.hide_net)
        # odd workers fill hides bottom-up instead of left to right: Baldacci
        # Test2's long seat parts pack differently (more copies on the five
        # smallest hides in a first fill); the best worker wins
        placer.gravity = "y" if worker % 2 == 1 else "x"
    rng = random.Random(seed * 1000003 + worker)
    # odd workers on hides: a quick first fill, then the copy-to-hide search
    # on the smallest hides (see _assign_hides)
    assign = choose_hides and worker % 2 == 1
    # ... with exact inner-fit regions (the part's own outline against the hide
    # outline's pockets): the tight sets need copies whose convex hull would
    # cross a concave stretch of the outline
    placer.concave_fit = assign
    best, evals = _first_fills(problem, placer, copies, worker, budget, quick=assign)
    cur_cost, cur_seq, cur_pl = best
    cur_hides = best_hides = placer.bin_order
    # every hide packing this worker's fills make, for the copy-to-hide search
    # to recombine (hide_patterns)
    patterns = HidePatterns(np.bincount(copies, minlength=len(problem.type_area)),
                            problem.hide_net, problem.type_area) if choose_hides else None
    if patterns is not None:
        patterns.add_layout(cur_seq, cur_pl.placements, cur_hides)
    if assign:
        if not budget.done(evals):
            k = len(used_positions(cur_pl.placements))
            k = min(k, _fewest_loose(problem.hide_net, sum(problem.type_area[c] for c in copies)))
            seed_hides = tight_order(problem.hide_net, k)[:k]
            best, best_hides, evals = _assign_hides(problem, placer, rng, budget, best,
                                                    best_hides, evals, seed_hides, worker=worker,
                                                    patterns=patterns)
        return best[0], best[1], _out(best[2].placements, best_hides), evals
    if worker % 2 == 1 and len(copies) > 1 and not budget.done(evals):
        seq = list(cur_seq)                   # diversify the second worker's start
        rng.shuffle(seq)
        tr = placer.place(seq)
        evals += 1
        if tr is not None:
            cur_seq, cur_pl = seq, tr
            cur_cost = cost_of(problem, cur_seq, cur_pl.placements, cur_hides)
    if choose_hides:
        # the fewest hides the first fills used, as the smallest hides (worker 0),
        # and one hide fewer (worker 1): the utilisation the hide choice can give
        k = len(used_positions(cur_pl.placements)) - (worker % 2)
        order = tight_order(problem.hide_net, k)
        if k >= 1 and order != cur_hides and not budget.done(evals):
            placer.bin_order = order
            tr = placer.place(cur_seq)
            evals += 1
            if tr is not None:
                c = cost_of(problem, cur_seq, tr.placements, order)
                if c < cur_cost:
                    cur_cost, cur_pl, cur_hides = c, tr, order
                    if c < best[0]:
                        best, best_hides = (c, cur_seq, tr), order
                        budget.improved(c, cur_seq, _out(tr.placements, order))
    hist = [cur_cost] * history
    step = 0
    t_start = last_gain = time.monotonic()
    while (len(copies) > 1 or choose_hides) and not budget.done(evals):
        budget.check_cancel(evals, best[0])
        if choose_hides and _stalled(t_start, last_gain, budget.t_end, best[0]):
            # the order search has stalled on a complete layout: step its hide
            # set down with the copy-to-hide search (module doc of hide_assign),
            # with exact inner-fit regions as the odd workers; its fills keep
            # this worker's four orientations (cheaper, and unlike worker 1's)
            placer.concave_fit = True
            used = [best_hides[p] for p in used_positions(best[2].placements)]
            best, best_hides, evals = _assign_hides(problem, placer, rng, budget, best,
                                                    best_hides, evals, used, worker=worker,
                                                    patterns=patterns)
            break
        new_hides, first = cur_hides, -1
        if choose_hides and (len(copies) < 2 or rng.random() < 0.15):
            new_hides, pos = swap_hides(rng, cur_hides, cur_pl.placements, problem.hide_net,
                                        [problem.type_area[cur_seq[si][0]]
                                         for (si, _b, _v, _x, _y) in cur_pl.placements])
            if pos >= 0:
                first = first_affected(cur_pl.placements, pos)
            new_seq = cur_seq
        if first < 0 and choose_hides and len(copies) > 1 and rng.random() < 0.25:
            new_hides = cur_hides
            new_seq, first = _from_least_filled(rng, cur_seq, cur_pl.placements, problem)
        if first < 0:
            if len(copies) < 2:
                break
            new_hides = cur_hides
            new_seq, first = _mutate(rng, cur_seq, problem)
        slot = step % history
        h = hist[slot]
        step += 1
        evals += 1
        placer.bin_order = new_hides
        new_pl = placer.place(new_seq, cur_pl, first,
                              give_up=(max(cur_cost[0], h[0]), problem.type_area))
        if new_pl is not None:                # None: gave up early or out of time
            if patterns is not None:
                patterns.add_layout(new_seq, new_pl.placements, new_hides)
            c = cost_of(problem, new_seq, new_pl.placements, new_hides)
            if c <= cur_cost or c <= h:
                cur_cost, cur_seq, cur_pl, cur_hides = c, new_seq, new_pl, new_hides
                if c < best[0]:
                    if c[:3] < best[0][:3]:      # area left out, hides, their net area
                        last_gain = time.monotonic()
                    best, best_hides = (c, new_seq, new_pl), new_hides
                    budget.improved(c, new_seq, _out(new_pl.placements, new_hides))
        if cur_cost < h:
            hist[slot] = cur_cost
    return best[0], best[1], _out(best[2].placements, best_hides), evals


#: the order search (even workers, hides) hands over to the copy-to-hide search
#: when its best layout places every copy and has not improved in area left
#: out, hides or their net area (tie-breaks do not count) for this share of
#: the time since the search began, with at least ``HANDOVER_MIN_S`` left
STALL_SHARE = 0.15
HANDOVER_MIN_S = 8.0


#: the copy-to-hide worker starts on at most the fewest smallest hides the
#: copies fill at most this share of (its quick first fill may use more)
LOOSE_FILL = 0.5


def _fewest_loose(net: Sequence[float], item_area: float) -> int:
    """The fewest k such that the copies fill at most ``LOOSE_FILL`` of the
    k smallest hides' net area (all hides when none does)."""
    total = 0.0
    for k, a in enumerate(sorted(net), 1):
        total += a
        if item_area <= LOOSE_FILL * total:
            return k
    return len(net)


def _stalled(t_start: float, last_gain: float, t_end: float, best_cost: Cost) -> bool:
    """True when the order search should hand over (see ``STALL_SHARE``)."""
    now = time.monotonic()
    return best_cost[0] == 0 and t_end - now >= HANDOVER_MIN_S and \
        now - last_gain >= STALL_SHARE * (t_end - t_start)


def _assign_hides(problem: Problem, placer: Placer, rng: random.Random, budget: Budget,
                  best, best_hides: List[int], evals: int, hides: List[int], *, worker: int = 0,
                  patterns: "Optional[HidePatterns]" = None):
    """Hides, odd workers right after a quick first fill (even workers once
    their order search stalled, on the hides of their best layout): the
    copy-to-hide search of :mod:`hide_assign` on ``hides`` -- the k smallest,
    k the hides the first fill used (at most :func:`_fewest_loose`): the best
    utilisation k hides can give; the search may
    swap in hides up to 5 % more net area while copies are left over -- until
    the deadline.  The even workers' order search meanwhile finds complete
    sets from the largest hides down (on Test2 and Test10 the odd worker's own
    order search made only 5-10 fills in 30-45 s: every orientation of large
    parts, exactly, and repeated what the even worker did).  A complete layout
    another worker found (``budget.shared``) that beats this search's best is
    taken over; ``worker`` % 2 is the search's lane (its step-down choice,
    :class:`hide_assign.AssignmentSearch`), so the two workers then try
    different smaller sets from the same one.  Returns the best
    (cost, order, trace), its hide order and the evaluations."""
    from .blf import Trace
    from .hide_assign import AssignmentSearch, as_layout, from_layout, from_placed
    net = problem.hide_net
    item_area = sum(problem.type_area[g[0]] for g in best[1])
    genes = from_layout(best[2].placements, best[1], best_hides, hides, problem.type_area, net)
    holder = [best, best_hides]
    every = sorted(g[0] for g in best[1])

    def expired() -> bool:
        budget.check_cancel(evals + s.evals, holder[0][0])
        return budget.done(evals + s.evals)

    def on_better(state) -> None:
        seq, placements, order = as_layout(state)
        if not holds_every_copy(every, seq, placements):
            return      # (see Budget.copies; kept out of ``holder`` too, which adopt compares)
        c = cost_of(problem, seq, placements, order)
        if c < holder[0][0]:
            holder[0], holder[1] = (c, seq, Trace(placements, [])), order
            budget.improved(c, seq, _out(placements, order))

    def adopt():
        """Another worker's complete layout when it beats this search's best."""
        got = budget.shared() if budget.shared is not None else None
        other = from_placed(placer, got[1], got[2]) if got is not None else None
        if other is None:
            return None
        seq, placements, order = as_layout(other)
        c = cost_of(problem, seq, placements, order)
        if not c < holder[0][0]:
            return None
        holder[0], holder[1] = (c, seq, Trace(placements, [])), order
        return other

    s = AssignmentSearch(problem, placer, rng, _mutate, expired, budget.t_end, lane=worker % 2,
                         patterns=patterns)
    st = s.start(hides, genes)
    if st is not None:
        s.run(st, net, on_better, item_area, adopt=adopt)
    return holder[0], holder[1], evals + s.evals


def run_strip_search(problem: Problem, copies: List[int], seed: int, worker: int,
                     budget: Budget, history: int = 30):
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
    rng = random.Random(seed * 1000003 + worker)
    open_placer = problem.placer()
    nfps = open_placer.nfps
    x0, y0, _, y1 = problem.bins[0].rect
    best, evals = _first_fills(problem, open_placer, copies, worker, budget)
    best_len = best[0][2]
    seq = list(best[1])
    step_frac = 0.02
    min_frac = 0.0005

    while len(copies) > 1 and not budget.done(evals):
        target = x0 + int((best_len - x0) * (1.0 - step_frac))
        placer = Placer(problem.variants, problem.type_variants, problem.type_grade,
                        [_Bin("sheet", (x0, y0, target, y1))], False, 1, nfps)
        cur_pl = placer.place(seq)
        evals += 1
        if cur_pl is None:
            break                             # out of time
        cur_cost = cost_of(problem, seq, cur_pl.placements)
        hist = [cur_cost] * history
        stall = 0
        limit = max(60, 3 * len(copies))
        step = 0
        while cur_cost[0] > 0 and stall < limit and not budget.done(evals):
            budget.check_cancel(evals, best[0])
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
            if new_pl is not None:            # None: gave up early or out of time
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
            budget.improved(cur_cost, seq, cur_pl.placements)
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


def search(problem: Problem, copies: List[int], seed: int, worker: int, budget: Budget):
    """The right search for the container kind (strip: shrinking; else order search)."""
    fn = run_strip_search if problem.bins[0].kind == "strip" else run_search
    return fn(problem, copies, seed, worker, budget)


def worker_main(problem: Problem, copies: List[int], seed: int, worker: int, t_end: float,
                first_fill_until: float, max_evaluations: Optional[int], queue, stop_event,
                hard_stop: float = math.inf, give_up_at: float = math.inf,
                wait_first: Optional[Tuple[object, float]] = None, inbox=None) -> None:
    """Entry point of a worker process: every new best goes to ``queue`` as
    ("best", worker, cost, order, placements), every 10 evaluations
    ("evals", worker, count); a layout refused for a lost copy
    (:attr:`Budget.copies`) as ("lost", worker, call chain); the end as
    ("done", worker, evaluations) or ("error", worker, message).  ``stop_event`` set = stop now.
    ``wait_first`` = (event, time): start only once the event is set (the
    first layout exists) or the time passed.  ``inbox``: a queue of the
    other workers' best layouts (cost, order, placements), newest last
    (:attr:`Budget.shared`)."""
    if wait_first is not None:
        event, until = wait_first
        event.wait(max(0.0, until - time.monotonic()))
    def on_best(cost, order, placements):
        queue.put(("best", worker, cost, order, placements))

    ticks = [0]

    def tick(_cost) -> bool:              # called every 10 evaluations
        ticks[0] += 10
        queue.put(("evals", worker, ticks[0]))
        return True
    def shared():
        got = None
        while inbox is not None:
            try:
                got = inbox.get_nowait()
            except Empty:
                break
        return got
    budget = Budget(t_end, first_fill_until, max_evaluations, stop_event.is_set, on_best, tick,
                    hard_stop=hard_stop, give_up_at=give_up_at, shared=shared,
                    copies=sorted(copies), on_lost=lambda where: queue.put(("lost", worker, where)))
    try:
        _, _, _, evals = search(problem, copies, seed, worker, budget)
        queue.put(("done", worker, evals))
    except Exception as exc:  # reported to the parent, which raises it there
        queue.put(("error", worker, f"{type(exc).__name__}: {exc}"))
