"""Nearest-neighbour baseline: from where the head is, go to the nearest
candidate of an item that may be visited now (all its predecessors done)."""

from __future__ import annotations

import random
from typing import List, Optional, Tuple

import numpy as np

from .instance import EuclidInstance, Instance


def nearest_neighbour(inst: Instance, rng: Optional[random.Random] = None,
                      choose_among: int = 1) -> Tuple[List[int], List[int]]:
    """Greedy tour from the anchor.  Returns ``(order, choice)``.

    With ``rng`` and ``choose_among > 1`` the next item is drawn at random
    among the ``choose_among`` nearest allowed items (diverse starts for the
    genetic algorithm)."""
    m = inst.m
    missing = [len(p) for p in inst.preds]
    alive = np.zeros(inst.n, dtype=bool)
    visited = [False] * m
    choice = [0] * m
    anchor = 0
    visited[anchor] = True
    for s in inst.succs[anchor]:
        missing[s] -= 1
    for k in range(1, m):
        if missing[k] == 0:
            alive[inst.cands[k]] = True
    # start at the anchor candidate nearest to the rest (anchor is usually a single point)
    g = int(inst.cands[anchor][0])
    choice[anchor] = g
    order = [anchor]
    item_of = inst.item_of
    tree = inst.trees()[0] if isinstance(inst, EuclidInstance) else None
    all_idx = np.arange(inst.n)
    while len(order) < m:
        nxt = None
        if tree is not None:
            want = max(1, choose_among)
            k = 16
            while k <= 1024:
                _, ii = tree.query((inst.ex[g], inst.ey[g]), k=min(k, inst.n))
                ii = np.atleast_1d(ii)
                ii = ii[ii < inst.n]
                ok = ii[alive[ii]]
                _, first = np.unique(item_of[ok], return_index=True)
                uniq = ok[np.sort(first)][:want].tolist()
                if len(uniq) >= want or k >= inst.n:
                    if uniq:
                        nxt = uniq[rng.randrange(min(want, len(uniq)))] if (rng and want > 1) else uniq[0]
                    break
                k *= 4
        if nxt is None:
            idx = all_idx[alive]
            row = inst.to_many(g, idx)
            if rng is not None and choose_among > 1:
                top = np.argsort(row, kind="stable")[: choose_among * 4]
                seen_items, pick = [], []
                for j in top:
                    it = int(item_of[idx[j]])
                    if it not in seen_items:
                        seen_items.append(it)
                        pick.append(int(idx[j]))
                    if len(pick) >= choose_among:
                        break
                nxt = pick[rng.randrange(len(pick))]
            else:
                nxt = int(idx[int(row.argmin())])
        it = int(item_of[nxt])
        visited[it] = True
        choice[it] = nxt
        order.append(it)
        alive[inst.cands[it]] = False
        for s in inst.succs[it]:
            missing[s] -= 1
            if missing[s] == 0 and not visited[s]:
                alive[inst.cands[s]] = True
        g = nxt
    return order, choice
