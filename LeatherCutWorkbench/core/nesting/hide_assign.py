"""Hides: which copy goes on which hide of a fixed, small set.

The order search (:mod:`search`) feeds every copy to the first hide where
it fits, so a change early in the order re-places everything after it on
every hide, and no single move takes a copy from one hide to another.  On
large parts (Baldacci Test2: 34 car-seat parts, five on a hide) it ends
with one poorly filled hide and a hide set larger than needed.

Here the hide set is fixed -- first the k smallest hides, k the hides the
worker's first fill used (:func:`search._assign_hides`), or on the order-search
worker the hides of its best layout once that search stalled -- and each hide has
its own sequence of copies, filled on its own by the bottom-left fill; a
copy that does not fit its hide is then tried, in turn, at the end of the
other hides' sequences (first fit across the set, :meth:`AssignmentSearch._spill`)
and stays unplaced only when no hide has room.  The
cost is the part area left unplaced over all hides: a smooth guide (like
the strip search's shrunk strip) that is 0 exactly when the set holds every
copy.  Once it does, one hide of the set is swapped for a smaller unused
hide (each swap at most once from a set; a hide is dropped only when every
swap was tried) -- a step down, as a strip is shrunk -- and the search makes
that set hold every copy again.  Moves
(late-acceptance hill climbing): move a copy (an unplaced one, mostly) to
another hide, swap two copies of different hides, change one hide's
sequence (:func:`search._mutate`), fill one hide from another side
(:attr:`blf.Placer.gravity`: each hide has its own), or exchange a hide of the set with an
unused one while the set's net area stays strictly below the last set
that held every copy (5 % above the k smallest before there is one).  A move
re-fills only the hides it touches, from the first changed position.

When the search on a set stalls with copies left out (``REPAIR_AFTER``
fills without less area unplaced), :meth:`AssignmentSearch._repair` tries
to fit each left-out copy into one of the hides with the most free area by
overlap minimisation (:mod:`hide_separation`): the bottom-left fill packs
these hides at 52-58 % where the set needs ~60 %.  A separated hide keeps
its explicit placements as a trace (:func:`_explicit_trace`: each copy a
forced gene, so a later move that re-fills the hide from position k keeps
the first k placements and fills the rest into the gaps).

Every state that leaves less area unplaced is reported (a knapsack: both
hides of Test1_first2hides are the set).  A step down may also drop a hide
(its copies spread over the others, unplaced): the step size adapts as the
strip search's does.
"""

from __future__ import annotations

import math
import random
import time
from typing import Callable, List, Optional, Sequence, Tuple

from .blf import BinState, Placer, Trace
from .hide_patterns import HidePatterns

Gene = Tuple[int, Optional[int]]
Placements = List[Tuple[int, int, int, int, int]]

#: hide swaps keep the set's net area within this share of the k smallest hides'
SLACK = 0.05
#: fills without less area unplaced before a stuck set is given up
PATIENCE = 600
#: the first step down from a set that holds every copy, as a share of its
#: net area, and the bounds of the adaptive step
STEP = 0.04
MIN_STEP = 0.005
MAX_STEP = 0.25
#: the search tries k - 1 hides only when the copies fill at most this share of them
MAX_FILL = 0.66
#: fills without less area unplaced on a set before its best state is repaired
#: by separation (:meth:`AssignmentSearch._repair`; 250 repaired nothing in a
#: 2-worker Test5 run at 60 s, 100 fitted the last copy of an 11-hide set:
#: 53.72 -> 54.37 %, measured twice), at most this many copies
#: left out, the hides (most free area first) tried per copy, seconds per try
#: and per repair; only with at least ``REPAIR_MIN_S`` left before the deadline
REPAIR_AFTER = 100
REPAIR_MAX_COPIES = 4
REPAIR_HIDES = 3
REPAIR_TRY_S = 3.0
REPAIR_S = 8.0
REPAIR_MIN_S = 3.0
#: a copy taken in place of smaller ones: they make this much more room than it needs
ROOM = 1.15
#: share of the moves that fill one hide from another side (:attr:`blf.Placer.gravity`)
GRAVITY_P = 0.05
GRAVITIES = ("x", "y", "-x", "-y")
#: seconds between two looks at the other workers' best (:meth:`AssignmentSearch.run`)
ADOPT_S = 0.5
#: seconds between two recombinations of the hide packings seen
#: (:meth:`AssignmentSearch._recombine`, only when new ones came), and the
#: solver's time limit: at most this many seconds, this share of the time left
RECOMBINE_S = 2.0
RECOMBINE_MAX_S = 0.5
RECOMBINE_SHARE = 0.05


class _Hides:
    """The set: per position a hide index, its gene sequence and its fill trace."""

    def __init__(self, hides: List[int], genes: List[List[Gene]]):
        self.hides = hides
        self.genes = genes
        self.traces: List[Optional[Trace]] = [None] * len(hides)
        self.lost = [0.0] * len(hides)      # unplaced part area per hide
        #: per position the side the hide is filled from (:attr:`blf.Placer.gravity`;
        #: None: the placer's own)
        self.gravity: List[Optional[str]] = [None] * len(hides)

    def copy(self) -> "_Hides":
        c = _Hides(list(self.hides), [list(g) for g in self.genes])
        c.traces = list(self.traces)
        c.lost = list(self.lost)
        c.gravity = list(self.gravity)
        return c

    @property
    def total(self) -> float:
        return round(sum(self.lost), 6)


class AssignmentSearch:
    """The search of the module doc on ``placer`` (its caches are reused;
    ``bin_order`` and ``max_bins`` are restored after each fill).  ``lane``
    (the worker's index among the copy-to-hide searches): a step down takes
    the lane-th nearest untried set, so two workers that share their best
    complete set (:meth:`run`'s ``adopt``) try different smaller ones."""

    def __init__(self, problem, placer: Placer, rng: random.Random,
                 mutate: Callable, expired: Callable[[], bool], deadline: float = math.inf,
                 lane: int = 0, patterns: Optional[HidePatterns] = None):
        self.problem = problem
        self.deadline = deadline          # time.monotonic() at which ``expired`` turns True
        self.placer = placer
        self.rng = rng
        self.mutate = mutate
        self.expired = expired
        self.area = problem.type_area
        self.net = problem.hide_net
        self.evals = 0
        #: the separator of :meth:`_repair` (made on first use; None: not available)
        self._separator = None
        self.repairs = [0, 0]             # repairs tried, copies they fitted
        self.lane = lane
        #: every hide packing a fill makes, recombined by :meth:`_recombine`
        self.patterns = patterns
        self.recombined = 0               # complete states the recombination gave

    # ----------------------------------------------------------------- fills
    def _fill(self, st: _Hides, p: int, first: int, limit: float) -> bool:
        """Re-fill position ``p`` of ``st`` from gene ``first``; False when the
        fill left out more than ``limit`` (abandoned) or ran out of time."""
        prev = st.traces[p]
        keep = min(first, len(prev.placements)) if prev is not None else 0
        tr = self._place_on(st, p, st.genes[p], prev if keep > 0 else None, keep,
                            give_up=(limit, self.area))
        if tr is None:
            return False
        st.traces[p] = tr
        self._recount(st, p)
        return True

    def _place_on(self, st: _Hides, p: int, seq: List[Gene], prev: Optional[Trace],
                  keep: int, **kw) -> Optional[Trace]:
        """:meth:`blf.Placer.place` of ``seq`` on hide position ``p`` of ``st``
        alone, filled from that hide's side; the placer's hide order, bin count
        and side are restored afterwards."""
        pl = self.placer
        saved = pl.bin_order, pl.max_bins, pl.gravity
        pl.bin_order, pl.max_bins = [st.hides[p]], 1
        pl.gravity = st.gravity[p] or saved[2]
        try:
            tr = pl.place(seq, prev, keep, **kw)
        finally:
            pl.bin_order, pl.max_bins, pl.gravity = saved
        self.evals += 1
        if tr is not None and self.patterns is not None:
            self.patterns.add(st.hides[p], [(seq[si][0], vi, tx, ty)
                                            for (si, b, vi, tx, ty) in tr.placements if b >= 0])
        return tr

    def _recount(self, st: _Hides, p: int) -> None:
        """``st.lost[p]``: the part area its trace leaves unplaced."""
        st.lost[p] = sum(self.area[st.genes[p][k][0]] for k in st.traces[p].unplaced)

    def start(self, hides: List[int], genes: List[List[Gene]],
              gravity: Optional[List[Optional[str]]] = None) -> Optional[_Hides]:
        st = _Hides(hides, genes)
        if gravity is not None:
            st.gravity = list(gravity)
        for p in range(len(hides)):
            if not self._fill(st, p, 0, float("inf")):
                return None
        self._spill(st, range(len(hides)))
        return st

    def _spill(self, st: _Hides, touched) -> None:
        """First fit across the set: each copy a fill of a ``touched`` hide left
        out (largest first) is appended, free to turn, to the first other hide
        (most net area not yet covered first) whose fill places it in a gap,
        and leaves its own sequence.  Without it a copy that misses its hide
        stays unplaced although another hide has room (Baldacci Test5: the
        search stalled with 6-8 M units^2 left out on 11 hides where the order
        search's first fit places everything)."""
        lost = sorted(((p, si) for p in set(touched) if st.traces[p] is not None
                       for si in st.traces[p].unplaced),
                      key=lambda x: -self.area[st.genes[x[0]][x[1]][0]])
        if not lost or len(st.hides) < 2:
            return
        gone: dict = {}
        for p, si in lost:
            if self.expired():
                break
            g = (st.genes[p][si][0], None)
            free = {q: self.net[st.hides[q]] - sum(
                self.area[x[0]] for x in st.genes[q]) for q in range(len(st.hides))}
            for q in sorted(free, key=lambda q: -free[q]):
                if q == p or st.traces[q] is None:
                    continue
                seq = st.genes[q] + [g]
                tr = self._place_on(st, q, seq, st.traces[q], len(st.genes[q]))
                if tr is not None and tr.placements[-1][1] >= 0:
                    st.genes[q], st.traces[q] = seq, tr
                    gone.setdefault(p, []).append(si)
                    break
        for p, out in gone.items():
            for si in sorted(out, reverse=True):
                _drop_unplaced(st, p, si)
            self._recount(st, p)

    # ----------------------------------------------------------------- moves
    def _neighbour(self, st: _Hides, net: Sequence[float], net_cap: float,
                   unused: List[int]) -> Tuple[_Hides, List[Tuple[int, int]]]:
        """A changed copy of ``st`` and the (position, first gene) to re-fill."""
        rng = self.rng
        n = len(st.hides)
        new = st.copy()
        r = rng.random()
        if n >= 2 and r < 0.45:
            lost = [(p, si) for p in range(n) if st.traces[p] is not None
                    for si in st.traces[p].unplaced]
            if lost and rng.random() < 0.8:
                a, i = rng.choice(lost)
            else:
                a = rng.choice([p for p in range(n) if st.genes[p]] or [0])
                if not st.genes[a]:
                    return new, []
                i = rng.randrange(len(st.genes[a]))
            b = rng.choice([p for p in range(n) if p != a])
            g = new.genes[a].pop(i)
            if rng.random() < 0.5:
                g = (g[0], None)            # free to turn on its new hide
            # often early on the new hide: placed before (and maybe instead of) others
            j = rng.randrange(len(new.genes[b]) + 1)
            if rng.random() < 0.5:
                j = rng.randrange(len(new.genes[b]) // 3 + 1)
            new.genes[b].insert(j, g)
            return new, [(a, i), (b, j)]
        if n >= 2 and r < 0.7:
            a, b = rng.sample(range(n), 2)
            if not st.genes[a] or not st.genes[b]:
                return new, []
            i, j = rng.randrange(len(st.genes[a])), rng.randrange(len(st.genes[b]))
            if st.genes[a][i][0] == st.genes[b][j][0]:
                return new, []
            new.genes[a][i], new.genes[b][j] = st.genes[b][j], st.genes[a][i]
            return new, [(a, i), (b, j)]
        if unused and r < 0.75:
            p = rng.randrange(n)
            total = sum(net[h] for h in st.hides)
            # strictly below the cap: after a step down the set must not drift
            # back to the one that already held everything (Test5 did)
            cands = [h for h in unused if total - net[st.hides[p]] + net[h] < net_cap]
            if not cands:
                return new, []
            new.hides[p] = rng.choice(cands)
            new.traces[p] = None
            return new, [(p, 0)]
        weights = [st.lost[p] + 1.0 for p in range(n)]
        p = rng.choices(range(n), weights=weights)[0]
        if len(st.genes[p]) < 1:
            return new, []
        if r > 1.0 - GRAVITY_P:
            # fill the hide from another side: the same copies may leave their
            # free material in one piece where the other side's fill leaves slivers
            now = st.gravity[p] or self.placer.gravity
            new.gravity[p] = rng.choice([g for g in GRAVITIES if g != now])
            return new, [(p, 0)]
        g, first = self.mutate(rng, new.genes[p], self.problem)
        if first >= len(g):
            return new, []
        new.genes[p] = g
        return new, [(p, first)]

    def run(self, st: _Hides, net: Sequence[float], on_better: Callable[["_Hides"], None],
            item_area: float, history: int = 50,
            adopt: Optional[Callable[[], Optional["_Hides"]]] = None) -> None:
        """Search from ``st`` until time is up; ``on_better(state)`` on every
        state that leaves less area unplaced than any before on its set.  A
        set that holds every copy is followed by a smaller one
        (:meth:`_smaller`: a step of ``frac`` x its net area, which grows
        after a success and halves when a set stays stuck for ``PATIENCE``
        fills -- then the search goes back to the last set that held every
        copy).  ``adopt()`` (asked at once, then every ``ADOPT_S`` seconds) returns a
        complete state better than any this search found (another worker's,
        :func:`from_placed`) or None; the search steps down from it when it
        needs no more net area than the set searched now, else keeps it as
        the set to go back to."""
        cur = set_best = st
        asked = -math.inf
        recombined = -math.inf              # the first recombination comes at once
        hist = [cur.total] * history
        low = cur.total
        repaired: set = set()                    # (hides, area left out) repairs tried
        cap = self._cap(cur, net)
        on_better(cur)
        step = since = spent = 0
        frac = STEP
        last_done: Optional[_Hides] = None       # the last set that held every copy
        tried: set = set()                       # step-down moves tried from last_done
        while not self.expired():
            since += 1
            spent += 1
            if adopt is not None and time.monotonic() - asked >= ADOPT_S:
                asked = time.monotonic()
                other = adopt()
                size = sum(net[h] for h in other.hides) if other is not None else 0.0
                if other is not None and size <= sum(net[h] for h in cur.hides):
                    cur = set_best = other
                    low, since, spent = cur.total, 0, 0
                    hist = [cur.total] * history
                    on_better(cur)
                elif other is not None and (last_done is None or
                                            size < sum(net[h] for h in last_done.hides)):
                    last_done, tried = other, set()     # where a stuck search goes back to
            if self.patterns is not None and self.patterns.fresh and \
                    time.monotonic() - recombined >= RECOMBINE_S:
                recombined = time.monotonic()
                other = self._recombine(last_done, net)
                if other is not None:
                    cur = set_best = other
                    low, since, spent = cur.total, 0, 0
                    hist = [cur.total] * history
                    on_better(cur)
            if cur.total < low:
                low, since, set_best = cur.total, 0, cur
                on_better(cur)
            if set_best.total > 0 and since >= REPAIR_AFTER and \
                    (tuple(set_best.hides), set_best.total) not in repaired:
                repaired.add((tuple(set_best.hides), set_best.total))
                fixed = self._repair(set_best)
                if fixed is not None:
                    cur = set_best = fixed
                    low, since = cur.total, 0
                    hist = [cur.total] * history
                    on_better(cur)
            if last_done is not None and (since > PATIENCE or spent > 4 * PATIENCE):
                cur, since, frac = last_done, 0, max(frac / 2.0, MIN_STEP)
            if cur.total == 0:
                if cur is not last_done:
                    frac = min(frac * 1.5, MAX_STEP) if last_done is not None else frac
                    last_done, tried = cur, set()
                nxt = self._smaller(cur, net, frac, item_area, tried)
                if nxt is None:
                    return
                cap = sum(net[h] for h in cur.hides)
                cur = set_best = nxt
                hist = [cur.total] * history
                low = cur.total
                since = spent = 0
                on_better(cur)
            unused = [h for h in range(len(net)) if h not in set(cur.hides)]
            new, todo = self._neighbour(cur, net, cap, unused)
            if not todo:
                continue
            slot = step % history
            step += 1
            accept = max(cur.total, hist[slot])
            if self._refill(new, todo, accept) and new.total <= accept:
                cur = new
            if cur.total < hist[slot]:
                hist[slot] = cur.total

    def _recombine(self, done: Optional[_Hides], net: Sequence[float]) -> Optional[_Hides]:
        """A complete state from the hide packings seen (:mod:`hide_patterns`)
        with fewer hides than ``done`` (the last set that held every copy),
        or as many and less net area; None when the packings give none."""
        below = (len(net) + 1, 0.0) if done is None else \
            (len(done.hides), sum(net[h] for h in done.hides))
        left = self.deadline - time.monotonic()
        cover = self.patterns.best_cover(below, min(RECOMBINE_MAX_S, RECOMBINE_SHARE * left))
        if cover is None or self.expired():
            return None
        st = _Hides([h for h, _ in cover], [[(c[0], c[1]) for c in cps] for _, cps in cover])
        st.traces = [_explicit_trace(self.placer, [c[1:] for c in cps], 0) for _, cps in cover]
        self.recombined += 1
        return st

    def _repair(self, st: _Hides) -> Optional[_Hides]:
        """A copy of ``st`` with some of its left-out copies fitted by
        overlap minimisation (module doc), largest first, each into one of the
        ``REPAIR_HIDES`` hides with the most free net area; None when none
        fitted (or too many were left out, too little time is left, or parts
        have graded regions: their inner-fit regions are not exact)."""
        lost = [(p, si) for p in range(len(st.hides)) for si in st.traces[p].unplaced]
        t0 = time.monotonic()
        if not lost or len(lost) > REPAIR_MAX_COPIES or self.problem.region_check is not None \
                or self.deadline - t0 < REPAIR_MIN_S:
            return None
        sep = self._get_separator()
        if sep is None:
            return None
        new = st.copy()
        fitted = 0
        end = min(self.deadline, t0 + REPAIR_S)
        self.repairs[0] += 1
        failed: set = set()                       # (hide position, type) that fitted nowhere
        asked = [t0]

        def give_up() -> bool:                    # ``expired`` (and Stop) ten times a second
            if time.monotonic() - asked[0] < 0.1:
                return False
            asked[0] = time.monotonic()
            return self.expired()
        while not self.expired() and time.monotonic() < end:
            lost = sorted(((p, si) for p in range(len(new.hides))
                           for si in new.traces[p].unplaced),
                          key=lambda x: -self.area[new.genes[x[0]][x[1]][0]])
            done = False
            for p, si in lost:
                t = new.genes[p][si][0]
                if (p, t) in failed:
                    continue
                free = [self.net[h] - sum(self.area[new.genes[q][pl[0]][0]]
                                          for pl in new.traces[q].placements if pl[1] >= 0)
                        for q, h in enumerate(new.hides)]
                hides = sorted(range(len(new.hides)), key=lambda q: -free[q])[:REPAIR_HIDES]
                for q, swap in [(q, False) for q in hides] + [(q, True) for q in hides]:
                    tr = new.traces[q]
                    cps = [(new.genes[q][pl[0]][0], pl[2], pl[3], pl[4])
                           for pl in tr.placements if pl[1] >= 0]
                    gone: List[Tuple[int, int, int, int]] = []
                    if swap:
                        # the copy in place of the smallest ones there (then left out:
                        # less area left out, smaller copies to fit elsewhere)
                        gone = _make_room(cps, self.area, self.area[t], free[q])
                        if not gone:
                            continue
                    elif free[q] < self.area[t]:
                        continue
                    if time.monotonic() >= end:
                        break
                    res = sep.fit(new.hides[q], cps, [t], min(end, time.monotonic() + REPAIR_TRY_S),
                                  give_up, seed=self.rng.randrange(1 << 30))
                    self.evals += 1
                    if res is None:
                        continue
                    rest = [new.genes[q][pl[0]] for pl in tr.placements
                            if pl[1] < 0 and not (q == p and pl[0] == si)]
                    rest.extend((c[0], None) for c in gone)
                    if q != p:
                        _drop_unplaced(new, p, si)
                        self._recount(new, p)
                    if self.patterns is not None:
                        self.patterns.add(new.hides[q], res)
                    new.genes[q] = [(c[0], c[1]) for c in res] + rest
                    new.traces[q] = _explicit_trace(self.placer, [c[1:] for c in res], len(rest))
                    new.lost[q] = sum(self.area[g[0]] for g in rest)
                    fitted += 1
                    done = True
                    break
                if done:
                    break
                failed.add((p, t))
            if not done:
                break
        self.repairs[1] += fitted
        return new if fitted else None

    def _get_separator(self):
        if self._separator is None:
            try:
                from .hide_separation import HideSeparator
            except ImportError:          # pragma: no cover - the project's venv has numba
                return None
            # one grid unit: every variant's outline is grown by one unit beyond
            # the chord error (:mod:`shapes`), so a deeper contact is no overlap
            self._separator = HideSeparator(self.placer, self.area, 1.0)
        return self._separator

    def _refill(self, new: _Hides, todo: List[Tuple[int, int]], accept: float) -> bool:
        """Re-fill the positions in ``todo`` (position, first changed gene);
        False when the total would exceed ``accept`` or time ran out."""
        touched = {p for p, _ in todo}
        spent = sum(new.lost[p] for p in range(len(new.hides)) if p not in touched)
        for p in sorted(touched):
            first = min(f for q, f in todo if q == p)
            if not self._fill(new, p, first, accept - spent + 1e-6):
                return False
            spent += new.lost[p]
        self._spill(new, touched)
        return True

    @staticmethod
    def _cap(st: _Hides, net: Sequence[float]) -> float:
        """Hide swaps keep a set of k hides within ``SLACK`` of the k smallest."""
        return (1.0 + SLACK) * sum(sorted(net)[:len(st.hides)])

    def _smaller(self, st: _Hides, net: Sequence[float], frac: float,
                 item_area: float, tried: set) -> Optional[_Hides]:
        """A set of less net area than ``st``'s, re-filled: one hide swapped
        for a smaller unused one, or -- once every such swap was ``tried``
        from ``st`` -- one hide dropped (its copies spread over the others,
        unplaced) while the copies fill at most ``MAX_FILL`` of the rest.
        Among the untried swaps the one whose loss of net area is nearest to
        ``frac`` x the set's (the ``lane``-th nearest; the move is added to ``tried``).  None: nothing
        smaller left.  (Drops came first when their loss was nearer: on Test5
        the search then spent its time on 10 hides that cannot hold the
        copies instead of the 11-hide swaps that can.)"""
        used = set(st.hides)
        total = sum(net[h] for h in st.hides)
        moves = [(net[h] - net[u], p, u) for p, h in enumerate(st.hides)
                 for u in range(len(net)) if u not in used and net[u] < net[h]
                 and (h, u) not in tried]
        if not moves and len(st.hides) > 1:
            moves = [(net[h], p, -1) for p, h in enumerate(st.hides)
                     if item_area <= MAX_FILL * (total - net[h]) and (h, -1) not in tried]
        if not moves:
            return None
        moves.sort(key=lambda m: abs(m[0] - frac * total))
        _loss, p, u = moves[min(self.lane, len(moves) - 1)]
        tried.add((st.hides[p], u))
        if u >= 0:
            new = st.copy()
            new.hides[p] = u
            new.traces[p] = None
            if not self._fill(new, p, 0, float("inf")):
                return None
            self._spill(new, [p])
            return new
        hides = [h for q, h in enumerate(st.hides) if q != p]
        genes = [list(g) for q, g in enumerate(st.genes) if q != p]
        _spread(genes, st.genes[p], hides, self.area, net)
        return self.start(hides, genes, [g for q, g in enumerate(st.gravity) if q != p])


def _drop_unplaced(st: _Hides, p: int, k: int) -> None:
    """Remove gene ``k`` -- one the fill left out -- from position ``p``'s
    sequence and trace (a copy left out changed no hide state, so the later
    placements stand; their sequence indices shift down by one)."""
    tr = st.traces[p]
    del st.genes[p][k]
    st.traces[p] = Trace([(si - (si > k), b, vi, tx, ty)
                          for (si, b, vi, tx, ty) in tr.placements if si != k],
                         tr.states[:k + 1] + tr.states[k + 2:])


def _make_room(cps: list, area: Sequence[float], need: float, free: float) -> list:
    """Take the smallest copies out of ``cps`` (in place) until the hide's free
    area is ``ROOM`` x ``need``, their area staying below ``need``; the copies
    taken ([] and ``cps`` unchanged when that is not possible)."""
    order = sorted(range(len(cps)), key=lambda k: area[cps[k][0]])
    out: List[int] = []
    taken = 0.0
    for k in order:
        if free + taken >= ROOM * need:
            break
        if taken + area[cps[k][0]] >= need:
            return []
        out.append(k)
        taken += area[cps[k][0]]
    if not out or free + taken < ROOM * need:
        return []
    gone = [cps[k] for k in out]
    for k in sorted(out, reverse=True):
        del cps[k]
    return gone


def _explicit_trace(placer: Placer, placed: Sequence[Tuple[int, int, int]],
                    n_unplaced: int) -> Trace:
    """A one-hide trace of explicit placements (variant, x, y), then
    ``n_unplaced`` copies left out: the bin state before each, as the fill
    builds them (free regions are computed from ``placed`` on demand)."""
    placements: Placements = []
    state = BinState(placed=(), extent=0, free={})
    states = [(state,)]
    for k, (vi, x, y) in enumerate(placed):
        state = BinState(state.placed + ((vi, x, y),),
                         max(state.extent, x + placer.variants[vi].bbox[2]), {})
        placements.append((k, 0, vi, x, y))
        states.append((state,))
    for k in range(len(placed), len(placed) + n_unplaced):
        placements.append((k, -1, -1, 0, 0))
        states.append((state.copy(),))
    return Trace(placements, states)


def _spread(genes: List[List[Gene]], rest: Sequence[Gene], hides: Sequence[int],
            area: Sequence[float], net: Sequence[float]) -> None:
    """Append ``rest`` to the hides' sequences, largest copy first, each to
    the hide with the most net area not yet claimed by its sequence."""
    for g in sorted(rest, key=lambda g: -area[g[0]]):
        free = [net[h] - sum(area[x[0]] for x in genes[p]) for p, h in enumerate(hides)]
        genes[max(range(len(hides)), key=lambda p: free[p])].append(g)


def from_layout(placements: Placements, seq: Sequence[Gene], hide_order: Sequence[int],
                hides: List[int], area: Sequence[float], net: Sequence[float]) -> List[List[Gene]]:
    """Per hide of ``hides``: the genes a first-fit layout (positions in
    ``hide_order``) put there, in their order; copies on other hides or
    unplaced are appended largest first to the hide with the most free area.
    Placed copies keep their orientation (a forced gene)."""
    genes: List[List[Gene]] = [[] for _ in hides]
    rest: List[Gene] = []
    for (si, b, vi, _tx, _ty) in placements:
        t = seq[si][0]
        h = hide_order[b] if b >= 0 else -1
        if h in hides:
            genes[hides.index(h)].append((t, vi))
        else:
            rest.append((t, seq[si][1]))
    _spread(genes, rest, hides, area, net)
    return genes


def from_placed(placer: Placer, seq: Sequence[Gene], placements: Placements) -> Optional[_Hides]:
    """A state holding a layout that places every copy (placements on hide
    *indices*, as workers report them): its hides in order of first use, per
    hide its copies as forced genes at their explicit places
    (:func:`_explicit_trace`).  None when a copy is left out."""
    hides: List[int] = []
    on: dict = {}
    for (si, b, vi, tx, ty) in placements:
        if b < 0:
            return None
        if b not in on:
            hides.append(b)
            on[b] = []
        on[b].append((seq[si][0], vi, tx, ty))
    st = _Hides(hides, [[(t, vi) for (t, vi, _x, _y) in on[h]] for h in hides])
    st.traces = [_explicit_trace(placer, [c[1:] for c in on[h]], 0) for h in hides]
    return st


def as_layout(st: _Hides) -> Tuple[List[Gene], Placements, List[int]]:
    """(sequence, placements with hide positions, hide order) of a state: the
    hides' sequences one after the other, as the order search reports them."""
    seq: List[Gene] = []
    placements: Placements = []
    for p, (g, tr) in enumerate(zip(st.genes, st.traces)):
        base = len(seq)
        seq.extend(g)
        for (si, b, vi, tx, ty) in tr.placements:
            placements.append((base + si, p if b >= 0 else -1, vi, tx, ty))
    return seq, placements, list(st.hides)
