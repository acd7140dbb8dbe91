"""The abstract routing problem every search in this package works on.

An *instance* is a generalised travelling-salesman problem with precedence:

* ``m`` items (clusters).  Item 0 is the *anchor*: it stays first in every
  tour (machine zero for a cut job, the smallest cluster for :func:`solve_gtsp`).
* each item has candidates (global ids ``0..n-1``); exactly one is chosen.  A
  candidate has a *start* (where the head arrives) and an *end* (where it
  leaves).  For a closed contour entered at a point both are that point; for a
  lead-in the start is the lead-in's free end and the end is the point where
  the contour closes; an open path has one candidate per direction.
* the travel cost from candidate ``g`` to candidate ``h`` is the distance from
  end(g) to start(h) (mm for cut jobs); it need not be symmetric.
* ``preds[k]`` lists the items that must come before item ``k``.

Two concrete cost models: :class:`EuclidInstance` (points, straight-line
travel) and :class:`MatrixInstance` (a full distance matrix, for benchmarks).
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import numpy as np


class Instance:
    """Common part: clusters, precedence, neighbour lists."""

    def __init__(self, clusters: Sequence[Sequence[int]],
                 preds: Optional[Sequence[Sequence[int]]] = None):
        self.m = len(clusters)
        self.cands: List[np.ndarray] = [np.asarray(c, dtype=np.int64) for c in clusters]
        self.cand_lists: List[List[int]] = [list(map(int, c)) for c in clusters]
        n = int(sum(len(c) for c in clusters))
        self.n = n
        self.item_of = np.empty(n, dtype=np.int64)
        for k, c in enumerate(self.cands):
            self.item_of[c] = k
        self.preds: List[List[int]] = [list(p) for p in (preds or [[] for _ in range(self.m)])]
        self.succs: List[List[int]] = [[] for _ in range(self.m)]
        for k, ps in enumerate(self.preds):
            for p in ps:
                self.succs[p].append(k)
        self.partners = [self.preds[k] + self.succs[k] for k in range(self.m)]
        self.has_precedence = any(self.preds)
        self.symmetric = True
        self._neigh: Optional[Tuple[List[List[int]], List[List[float]]]] = None
        self._neigh_k = 0

    # ---- cost model (overridden) -------------------------------------------------
    def cost(self, g: int, h: int) -> float:
        raise NotImplementedError

    def item_cost_fn(self, c: Sequence[int]):
        """``d(a, b)``: cost from item ``a`` to item ``b`` with the candidates
        currently chosen in ``c`` (a list the caller may keep updating)."""
        cost = self.cost

        def d(a: int, b: int) -> float:
            return cost(c[a], c[b])
        return d

    def block(self, G: np.ndarray, H: np.ndarray) -> np.ndarray:
        """Costs from every candidate in ``G`` (rows) to every one in ``H``."""
        raise NotImplementedError

    def to_many(self, g: int, H: np.ndarray) -> np.ndarray:
        return self.block(np.asarray([g]), H)[0]

    def from_many(self, G: np.ndarray, h: int) -> np.ndarray:
        return self.block(G, np.asarray([h]))[:, 0]

    def item_min_dist_rows(self, k: int) -> np.ndarray:
        """Symmetrised minimum cost between item ``k`` and every item (length m):
        min over both directions and all candidate pairs; a lower bound on any
        edge between the two items in any tour."""
        raise NotImplementedError

    # ---- derived ------------------------------------------------------------------
    def neighbours(self, k_near: int = 10) -> Tuple[List[List[int]], List[List[float]]]:
        """For each item its ``k_near`` nearest other items by minimum cost
        (sorted), and those costs."""
        if self._neigh is None or self._neigh_k != k_near:
            self._neigh = self._compute_neighbours(k_near)
            self._neigh_k = k_near
        return self._neigh

    def _compute_neighbours(self, k_near: int) -> Tuple[List[List[int]], List[List[float]]]:
        near: List[List[int]] = []
        nd: List[List[float]] = []
        kk = min(k_near, self.m - 1)
        for k in range(self.m):
            row = self.item_min_dist_rows(k)
            row[k] = np.inf
            if kk <= 0:
                near.append([])
                nd.append([])
                continue
            idx = np.argpartition(row, kk - 1)[:kk]
            idx = idx[np.argsort(row[idx], kind="stable")]
            near.append([int(i) for i in idx])
            nd.append([float(row[i]) for i in idx])
        return near, nd

    def tour_cost(self, tour: Sequence[int], choice: Sequence[int]) -> float:
        """Cost of the closed tour visiting items in ``tour`` order with the
        candidate ``choice[item]`` of each."""
        c = self.cost
        total = 0.0
        prev = choice[tour[-1]]
        for it in tour:
            g = choice[it]
            total += c(prev, g)
            prev = g
        return total


class EuclidInstance(Instance):
    """Candidates are points; travel cost is the straight-line distance (mm)
    from the end of one candidate to the start of the next."""

    def __init__(self, clusters: Sequence[Sequence[int]], start_xy: np.ndarray,
                 end_xy: Optional[np.ndarray] = None,
                 preds: Optional[Sequence[Sequence[int]]] = None):
        super().__init__(clusters, preds)
        self.S = np.asarray(start_xy, dtype=float).reshape(-1, 2)
        self.E = self.S if end_xy is None else np.asarray(end_xy, dtype=float).reshape(-1, 2)
        self.sx = self.S[:, 0].tolist()
        self.sy = self.S[:, 1].tolist()
        self.ex = self.E[:, 0].tolist()
        self.ey = self.E[:, 1].tolist()
        self.symmetric = bool(np.array_equal(self.S, self.E))
        self._trees = None

    def cost(self, g: int, h: int) -> float:
        return math.hypot(self.ex[g] - self.sx[h], self.ey[g] - self.sy[h])

    def item_cost_fn(self, c: Sequence[int]):
        ex, ey, sx, sy, hypot = self.ex, self.ey, self.sx, self.sy, math.hypot

        def d(a: int, b: int) -> float:
            g = c[a]
            h = c[b]
            return hypot(ex[g] - sx[h], ey[g] - sy[h])
        return d

    def block(self, G: np.ndarray, H: np.ndarray) -> np.ndarray:
        e = self.E[G]
        s = self.S[H]
        return np.hypot(e[:, None, 0] - s[None, :, 0], e[:, None, 1] - s[None, :, 1])

    def to_many(self, g: int, H: np.ndarray) -> np.ndarray:
        s = self.S[H]
        return np.hypot(s[:, 0] - self.ex[g], s[:, 1] - self.ey[g])

    def from_many(self, G: np.ndarray, h: int) -> np.ndarray:
        e = self.E[G]
        return np.hypot(e[:, 0] - self.sx[h], e[:, 1] - self.sy[h])

    def trees(self):
        """KD-trees over all start points and all end points (scipy)."""
        if self._trees is None:
            from scipy.spatial import cKDTree
            ts = cKDTree(self.S)
            te = ts if self.symmetric else cKDTree(self.E)
            self._trees = (ts, te)
        return self._trees

    def _compute_neighbours(self, k_near: int) -> Tuple[List[List[int]], List[List[float]]]:
        # Two stages instead of the dense m x m minimum: items whose bounding
        # circles are nearest (KD-tree on centres) are the candidates, then the
        # exact minimum candidate-to-candidate cost ranks them.
        from scipy.spatial import cKDTree
        kk = min(k_near, self.m - 1)
        if kk <= 0:
            return [[] for _ in range(self.m)], [[] for _ in range(self.m)]
        pts = np.vstack([self.S, self.E])
        owner = np.concatenate([self.item_of, self.item_of])
        cnt = np.bincount(owner, minlength=self.m).astype(float)
        cx = np.bincount(owner, pts[:, 0], self.m) / cnt
        cy = np.bincount(owner, pts[:, 1], self.m) / cnt
        rad = np.zeros(self.m)
        np.maximum.at(rad, owner, np.hypot(pts[:, 0] - cx[owner], pts[:, 1] - cy[owner]))
        centres = np.c_[cx, cy]
        q = min(self.m, 3 * kk + 1)
        _, idx = cKDTree(centres).query(centres, k=q)
        idx = np.asarray(idx).reshape(self.m, -1)
        near, nd = [], []
        for k in range(self.m):
            others = [int(o) for o in idx[k] if o != k and o < self.m]
            Ck = self.cands[k]
            allc = np.concatenate([self.cands[o] for o in others])
            sizes = [len(self.cands[o]) for o in others]
            offs = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
            out = self.block(Ck, allc).min(axis=0)
            if not self.symmetric:
                out = np.minimum(out, self.block(allc, Ck).min(axis=1))
            per = np.minimum.reduceat(out, offs)
            order = np.argsort(per, kind="stable")[:kk]
            near.append([others[i] for i in order])
            nd.append([float(per[i]) for i in order])
        return near, nd

    def item_min_dist_rows(self, k: int) -> np.ndarray:
        C = self.cands[k]
        a = self.block(C, np.arange(self.n)).min(axis=0)
        if not self.symmetric:
            a = np.minimum(a, self.block(np.arange(self.n), C).min(axis=1))
        out = np.full(self.m, np.inf)
        np.minimum.at(out, self.item_of, a)
        return out


class MatrixInstance(Instance):
    """Travel cost from a full matrix ``D[node, node]``; candidate ``g`` starts
    at node ``start_node[g]`` and ends at ``end_node[g]`` (default: the same)."""

    def __init__(self, D: np.ndarray, clusters: Sequence[Sequence[int]],
                 start_node: Optional[np.ndarray] = None, end_node: Optional[np.ndarray] = None,
                 preds: Optional[Sequence[Sequence[int]]] = None):
        super().__init__(clusters, preds)
        self.D = np.asarray(D, dtype=float)
        n = self.n
        self.sn = np.arange(n) if start_node is None else np.asarray(start_node)
        self.en = self.sn if end_node is None else np.asarray(end_node)
        self.symmetric = bool(np.array_equal(self.sn, self.en)) and bool(
            np.allclose(self.D, self.D.T)) if self.D.shape[0] <= 6000 else False
        # plain nested lists are much faster than numpy for scalar look-ups
        self._rows = self.D[np.ix_(self.en, self.sn)].tolist() if self.n <= 2500 else None
        self._snl = self.sn.tolist()
        self._enl = self.en.tolist()
        self._cache: dict = {}

    def cost(self, g: int, h: int) -> float:
        if self._rows is not None:
            return self._rows[g][h]
        return float(self.D[self._enl[g], self._snl[h]])

    def item_cost_fn(self, c: Sequence[int]):
        rows = self._rows
        if rows is None:
            return super().item_cost_fn(c)

        def d(a: int, b: int) -> float:
            return rows[c[a]][c[b]]
        return d

    def block(self, G: np.ndarray, H: np.ndarray) -> np.ndarray:
        return self.D[np.ix_(self.en[G], self.sn[H])]

    def to_many(self, g: int, H: np.ndarray) -> np.ndarray:
        return self.D[self._enl[g], self.sn[H]]

    def from_many(self, G: np.ndarray, h: int) -> np.ndarray:
        return self.D[self.en[G], self._snl[h]]

    def item_min_matrix(self) -> np.ndarray:
        """m x m symmetrised minimum cost between items (computed once)."""
        if getattr(self, "_itemmin", None) is None:
            order = np.concatenate(self.cands)
            sizes = np.array([len(c) for c in self.cands])
            offs = np.concatenate([[0], np.cumsum(sizes)[:-1]])
            sub = self.D[np.ix_(self.en[order], self.sn[order])]
            red = np.minimum.reduceat(np.minimum.reduceat(sub, offs, axis=0), offs, axis=1)
            self._itemmin = np.minimum(red, red.T)
        return self._itemmin

    def item_min_dist_rows(self, k: int) -> np.ndarray:
        return self.item_min_matrix()[k].copy()
