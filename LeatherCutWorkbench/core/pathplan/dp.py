"""Exact entry-point choice for a fixed visiting order (dynamic programming).

For a fixed order of items the best candidate of every item is found exactly by
a shortest path through the layered graph: layer ``i`` holds the candidates of
the ``i``-th item, edges go from each candidate's end to each next candidate's
start.  The tour is closed, so the first layer (the anchor item) is carried as
a row dimension: state ``F[s, j]`` is the cheapest way to reach candidate ``j``
of the current layer when the tour started at anchor candidate ``s``.  Work is
O(|C0| * sum |C_i| |C_i+1|), vectorised with numpy layer by layer.
"""

from __future__ import annotations

from typing import List, Sequence, Tuple

import numpy as np

from .instance import Instance


def optimal_entries(inst: Instance, tour: Sequence[int]) -> Tuple[List[int], float]:
    """Best candidate for every item of ``tour`` (anchor first).

    Returns ``(choice, cost)`` where ``choice[item]`` is the chosen candidate id
    (a list indexed by item) and ``cost`` the closed-tour cost."""
    m = len(tour)
    cands = inst.cands
    C0 = cands[tour[0]]
    if m == 1:
        B = inst.block(C0, C0)
        j = int(np.argmin(np.diag(B)))
        choice = [0] * inst.m
        choice[tour[0]] = int(C0[j])
        return choice, float(B[j, j])
    if len(C0) == 1:
        return _entries_single_anchor(inst, tour)
    F = inst.block(C0, cands[tour[1]])                  # (c0, c1)
    back: List[np.ndarray] = []
    for i in range(2, m):
        B = inst.block(cands[tour[i - 1]], cands[tour[i]])  # (ci-1, ci)
        T = F[:, :, None] + B[None, :, :]
        arg = T.argmin(axis=1)                          # (c0, ci)
        F = np.take_along_axis(T, arg[:, None, :], axis=1)[:, 0, :]
        back.append(arg)
    Bc = inst.block(cands[tour[m - 1]], C0)             # (c_last, c0)
    closing = F + Bc.T                                  # (c0, c_last)
    last = closing.argmin(axis=1)
    tot = closing[np.arange(len(C0)), last]
    s = int(tot.argmin())
    cost = float(tot[s])
    idx = [0] * m
    idx[0] = s
    idx[m - 1] = int(last[s])
    for i in range(m - 1, 1, -1):
        idx[i - 1] = int(back[i - 2][s, idx[i]])
    choice = [0] * inst.m
    for i, it in enumerate(tour):
        choice[it] = int(cands[it][idx[i]])
    return choice, cost


def _entries_single_anchor(inst: Instance, tour: Sequence[int]) -> Tuple[List[int], float]:
    """The same DP when the anchor has one candidate (machine zero): the
    state is a vector per layer."""
    m = len(tour)
    cands = inst.cands
    g0 = int(cands[tour[0]][0])
    F = inst.to_many(g0, cands[tour[1]])
    back: List[np.ndarray] = []
    for i in range(2, m):
        T = F[:, None] + inst.block(cands[tour[i - 1]], cands[tour[i]])
        arg = T.argmin(axis=0)
        F = T[arg, np.arange(T.shape[1])]
        back.append(arg)
    close = F + inst.from_many(cands[tour[m - 1]], g0)
    j = int(close.argmin())
    cost = float(close[j])
    choice = [0] * inst.m
    choice[tour[0]] = g0
    for i in range(m - 1, 0, -1):
        choice[tour[i]] = int(cands[tour[i]][j])
        if i > 1:
            j = int(back[i - 2][j])
    return choice, cost


def window_entries(inst: Instance, t: List[int], c: List[int], lo: int, hi: int) -> float:
    """Re-choose the candidates of the items at positions ``lo..hi`` of ``t``
    exactly, the items just outside the window keeping theirs (a local DP
    after a local change).  Updates ``c`` in place; returns the cost decrease."""
    m = len(t)
    lo, hi = max(1, lo), min(m - 1, hi)
    if hi < lo:
        return 0.0
    cands = inst.cands
    before, after = c[t[lo - 1]], c[t[(hi + 1) % m]]
    old = inst.cost(before, c[t[lo]]) + inst.cost(c[t[hi]], after)
    for i in range(lo, hi):
        old += inst.cost(c[t[i]], c[t[i + 1]])
    F = inst.to_many(before, cands[t[lo]])
    back = []
    for i in range(lo + 1, hi + 1):
        T = F[:, None] + inst.block(cands[t[i - 1]], cands[t[i]])
        arg = T.argmin(axis=0)
        F = T[arg, np.arange(T.shape[1])]
        back.append(arg)
    close = F + inst.from_many(cands[t[hi]], after)
    j = int(close.argmin())
    new = float(close[j])
    if new >= old - 1e-9:
        return 0.0
    for i in range(hi, lo - 1, -1):
        c[t[i]] = int(cands[t[i]][j])
        if i > lo:
            j = int(back[i - lo - 1][j])
    return old - new
