"""Hides: recombine the single-hide packings a search has seen.

Every fill of the hide searches packs some copies on one hide; which copies
lie together on which hide is a *pattern* (hide index, multiset of part
types), valid on its own whatever the other hides hold, and still valid with
any of its copies taken away.  The search itself only recombines the hides
of one state, but a hide packed densely while the set around it failed is
worth keeping: a set of patterns -- one per hide, on distinct hides -- that
together hold every copy is a complete layout, and the fewest hides of the
least net area among the patterns seen is a small set-covering problem
(the master problem of column generation for bin packing, solved here over
the columns the search produced instead of priced ones):

    minimise    sum_p (net(hide_p) + W) x_p          (W: one more hide costs more
    subject to  sum_{p on hide h} x_p <= 1           than any net area)
                sum_p count_p(t) x_p >= demand(t)    for every part type t
                x_p in {0, 1}

solved as a mixed-integer programme by HiGHS (scipy's ``milp``: no
hand-written branch and bound).  A cover holds surplus copies where two
patterns share a type; they are taken out (a pattern less a copy is still a
packing).  Areas in grid units squared; placements (variant, x, y) in grid
units on the hide, as :mod:`blf` makes them.
"""

from __future__ import annotations

import time
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

#: one copy as a pattern holds it: (part type, variant, x, y)
Copy = Tuple[int, int, int, int]

#: patterns kept per hide; beyond it the one of least placed area gives way
MAX_PER_HIDE = 4000


class HidePatterns:
    """The packings seen per hide, and the best cover of the job's copies
    they give (:meth:`best_cover`).  ``demand``: the copies per part type
    (index = type); ``net`` and ``area``: net area per hide and part area
    per type (grid units squared)."""

    def __init__(self, demand: Sequence[int], net: Sequence[float], area: Sequence[float]):
        self.demand = np.asarray(demand, dtype=np.int64)
        self.net = list(net)
        self.area = list(area)
        #: per hide: sorted part types -> the copies of one packing of them
        self._seen: List[Dict[Tuple[int, ...], Tuple[Copy, ...]]] = [{} for _ in self.net]
        #: patterns added since the last :meth:`best_cover`
        self.fresh = 0
        self.solves = 0
        self.solve_s = 0.0

    def __len__(self) -> int:
        return sum(len(d) for d in self._seen)

    def add(self, hide: int, copies: Sequence[Copy]) -> None:
        """Keep the packing ``copies`` of ``hide`` if its multiset of types is new."""
        if not copies:
            return
        seen = self._seen[hide]
        key = tuple(sorted(c[0] for c in copies))
        if key in seen:
            return
        if len(seen) >= MAX_PER_HIDE:
            worst = min(seen, key=lambda k: sum(self.area[t] for t in k))
            if sum(self.area[t] for t in worst) >= sum(self.area[t] for t in key):
                return
            del seen[worst]
        seen[key] = tuple(copies)
        self.fresh += 1

    def add_layout(self, seq: Sequence[Tuple[int, Optional[int]]],
                   placements: Sequence[Tuple[int, int, int, int, int]],
                   hide_order: Sequence[int]) -> None:
        """Keep every hide's packing of a fill of ``seq`` (placements on
        positions of ``hide_order``, :mod:`blf`)."""
        on: Dict[int, List[Copy]] = {}
        for (si, b, vi, tx, ty) in placements:
            if b >= 0:
                on.setdefault(hide_order[b], []).append((seq[si][0], vi, tx, ty))
        for h, cps in on.items():
            self.add(h, cps)

    def best_cover(self, below: Tuple[int, float], time_limit: float
                   ) -> Optional[List[Tuple[int, List[Copy]]]]:
        """Patterns on distinct hides that hold exactly the demanded copies
        (surplus taken out), with fewer hides than ``below`` = (hides, net
        area), or as many and less net area; as [(hide, copies)] in hide
        order, or None when the patterns give none (or HiGHS found none
        within ``time_limit`` seconds)."""
        from scipy.optimize import Bounds, LinearConstraint, milp
        from scipy.sparse import coo_matrix
        self.fresh = 0
        keys = [(h, types) for h, seen in enumerate(self._seen) for types in seen]
        if not keys:
            return None
        t0 = time.monotonic()
        n_hides, n_types = len(self.net), len(self.demand)
        heavy = sum(self.net) + 1.0
        cost = np.array([self.net[h] + heavy for h, _ in keys])
        rows, cols = [], []
        for j, (h, types) in enumerate(keys):
            rows.append(h)
            cols.append(j)
            rows.extend(n_hides + t for t in types)
            cols.extend(j for _ in types)
        a = coo_matrix((np.ones(len(rows)), (rows, cols)),
                       shape=(n_hides + n_types, len(keys))).tocsr()
        lo = np.concatenate([np.zeros(n_hides), self.demand])
        hi = np.concatenate([np.ones(n_hides), np.full(n_types, np.inf)])
        # strictly better than ``below``: its objective less a hundredth of a
        # grid unit squared per hide (net areas are far apart from that)
        limit = below[0] * heavy + below[1] - 1e-2
        bound = LinearConstraint(cost[np.newaxis, :], -np.inf, limit)
        res = milp(cost, constraints=[LinearConstraint(a, lo, hi), bound],
                   integrality=np.ones(len(keys)), bounds=Bounds(0, 1),
                   options={"time_limit": max(0.05, time_limit), "presolve": True})
        self.solves += 1
        self.solve_s += time.monotonic() - t0
        if res.x is None:
            return None
        chosen = [keys[j] for j in np.flatnonzero(res.x > 0.5)]
        if sum(self.net[h] + heavy for h, _ in chosen) > limit:
            return None
        return self._trimmed(chosen)

    def _trimmed(self, chosen: List[Tuple[int, Tuple[int, ...]]]) -> List[Tuple[int, List[Copy]]]:
        """The chosen patterns' copies with each type's surplus taken out,
        from the pattern whose hide is then fullest (its free area matters
        least)."""
        out = [(h, list(self._seen[h][types])) for h, types in sorted(chosen)]
        held = np.zeros(len(self.demand), dtype=np.int64)
        for _h, cps in out:
            for c in cps:
                held[c[0]] += 1
        for t in np.flatnonzero(held > self.demand):
            for _ in range(int(held[t] - self.demand[t])):
                used = [sum(self.area[c[0]] for c in cps) / self.net[h] for h, cps in out]
                k = max((k for k in range(len(out)) if any(c[0] == t for c in out[k][1])),
                        key=lambda k: used[k])
                cps = out[k][1]
                del cps[max(i for i, c in enumerate(cps) if c[0] == t)]
        return [(h, cps) for h, cps in out if cps]
