"""Certified lower bounds on the tour cost of an instance.

Both bounds hold for every tour that visits each item once through one of its
candidates (any order, any entries, precedence ignored -- a relaxation), so
the planner can state "no plan of these candidates travels less than X".

* two-neighbour: a tour enters and leaves every item once, so its cost is
  sum_k (in_k + out_k) / 2.  For each candidate the cheapest way in and out
  from other items bounds both edges (for symmetric instances the two edges go
  to two *different* items, giving the nearest and second-nearest item).
* Held-Karp: 1-trees with Lagrangian node penalties (subgradient ascent) on
  the symmetric matrix of minimum item-to-item costs, which is at most the cost
  of any edge between the two items.

Written by hand (numpy): no maintained Python library computes GTSP bounds.
"""

from __future__ import annotations

import time
from typing import Optional, Tuple

import numpy as np

from .instance import EuclidInstance, Instance, MatrixInstance


def two_neighbour_bound(inst: Instance) -> float:
    """Sum over items of min over candidates of (in + out) / 2."""
    m = inst.m
    if m < 2:
        return 0.0
    if isinstance(inst, EuclidInstance):
        ts, te = inst.trees()
        q = min(inst.n, max(8, 3 * inst.n // m + 8))
        if inst.symmetric:
            a, b = _two_nearest_other(ts, inst.S, inst.item_of, q, m)
            per_cand = (a + b) / 2.0
        else:
            din, _ = _two_nearest_other(te, inst.S, inst.item_of, q, m)
            dout, _ = _two_nearest_other(ts, inst.E, inst.item_of, q, m)
            per_cand = (din + dout) / 2.0
    else:
        per_cand = np.empty(inst.n)
        offs = np.concatenate([[0], np.cumsum([len(c) for c in inst.cands])[:-1]])
        allc = np.concatenate(inst.cands)
        for g in range(inst.n):
            out = np.minimum.reduceat(inst.to_many(g, allc), offs)
            inn = np.minimum.reduceat(inst.from_many(allc, g), offs)
            k = inst.item_of[g]
            out[k] = np.inf
            inn[k] = np.inf
            if inst.symmetric and m > 2:
                two = np.partition(out, 1)[:2]
                per_cand[g] = two.sum() / 2.0
            else:
                per_cand[g] = (out.min() + inn.min()) / 2.0
    best = np.full(m, np.inf)
    np.minimum.at(best, inst.item_of, per_cand)
    return float(best.sum())


def _two_nearest_other(tree, pts: np.ndarray, item_of: np.ndarray, q: int,
                       m: int) -> Tuple[np.ndarray, np.ndarray]:
    """Distance from each point to the nearest point of another item, and to
    the nearest point of a third item (falls back to the first when the query
    window holds no third item -- still a valid bound)."""
    d, idx = tree.query(pts, k=q)
    d = d.reshape(len(pts), -1)
    idx = idx.reshape(len(pts), -1)
    ok = idx < len(item_of)
    own = np.where(ok, item_of[np.where(ok, idx, 0)], -1)
    mine = item_of[: len(pts)][:, None] if len(pts) == len(item_of) else item_of[:, None]
    mask = ok & (own != mine)
    rows = np.arange(len(pts))
    has1 = mask.any(axis=1)
    j1 = mask.argmax(axis=1)
    a = np.where(has1, d[rows, j1], 0.0)
    o1 = own[rows, j1]
    mask2 = mask & (own != o1[:, None])
    has2 = mask2.any(axis=1)
    j2 = mask2.argmax(axis=1)
    b = np.where(has2, d[rows, j2], a)
    return a, b


def item_min_matrix(inst: Instance) -> np.ndarray:
    """Symmetric m x m matrix of minimum candidate-to-candidate costs."""
    if isinstance(inst, MatrixInstance):
        W = inst.item_min_matrix().copy()
    else:
        W = np.vstack([inst.item_min_dist_rows(k) for k in range(inst.m)])
        W = np.minimum(W, W.T)
    np.fill_diagonal(W, np.inf)
    return W


def _one_tree(W: np.ndarray) -> Tuple[float, np.ndarray]:
    """Minimum 1-tree: MST on nodes 1..m-1 (Prim, O(m^2) numpy) plus the two
    cheapest edges at node 0.  Returns (cost, degrees)."""
    m = len(W)
    deg = np.zeros(m)
    sub = W[1:, 1:]
    n = m - 1
    in_tree = np.zeros(n, dtype=bool)
    key = sub[0].copy()
    parent = np.zeros(n, dtype=np.int64)
    in_tree[0] = True
    key[0] = np.inf
    total = 0.0
    for _ in range(n - 1):
        j = int(key.argmin())
        total += key[j]
        deg[j + 1] += 1
        deg[parent[j] + 1] += 1
        in_tree[j] = True
        key[j] = np.inf
        row = sub[j]
        upd = (row < key) & ~in_tree
        key[upd] = row[upd]
        parent[upd] = j
    r = W[0, 1:]
    two = np.argpartition(r, 1)[:2]
    total += r[two].sum()
    deg[0] = 2
    deg[two + 1] += 1
    return float(total), deg


def held_karp_bound(W: np.ndarray, upper: float, max_iter: int = 150,
                    deadline: Optional[float] = None) -> float:
    """Held-Karp 1-tree bound with subgradient ascent (Polyak steps towards
    ``upper``, a known tour cost).  Any iterate is a valid bound; the best is
    returned."""
    m = len(W)
    if m < 3:
        return float(2 * np.min(W[0, 1:])) if m == 2 else 0.0
    pi = np.zeros(m)
    best = -np.inf
    lam, since = 2.0, 0
    for _ in range(max_iter):
        Wp = W + pi[:, None] + pi[None, :]
        cost, deg = _one_tree(Wp)
        L = cost - 2.0 * pi.sum()
        if L > best + 1e-9:
            best, since = L, 0
        else:
            since += 1
            if since >= 5:
                lam, since = lam / 2.0, 0
        g = deg - 2.0
        gg = float(g @ g)
        if gg == 0 or lam < 1e-4 or (deadline is not None and time.perf_counter() > deadline):
            break
        pi += lam * max(upper - L, 1e-6 * max(upper, 1.0)) / gg * g
    return float(max(best, 0.0))


def lower_bound(inst: Instance, upper: float, time_budget: float = 2.0,
                max_items_hk: int = 1500) -> Tuple[float, dict]:
    """max(two-neighbour, Held-Karp on item minimum costs) and the parts."""
    t0 = time.perf_counter()
    tn = two_neighbour_bound(inst)
    parts = {"two_neighbour": tn}
    if 3 <= inst.m <= max_items_hk:
        W = item_min_matrix(inst)
        hk = held_karp_bound(W, upper, deadline=t0 + time_budget)
        parts["held_karp"] = hk
    return max(parts.values()), parts
