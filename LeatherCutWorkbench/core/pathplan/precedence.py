"""Precedence between items: checking an order and repairing one.

``preds[k]`` lists the items that must be visited before item ``k``.  The
anchor (item 0) has no predecessors and is always first.
"""

from __future__ import annotations

import heapq
from typing import List, Sequence


def violations(order: Sequence[int], preds: Sequence[Sequence[int]]) -> int:
    """Number of (before, after) pairs that ``order`` visits the wrong way round."""
    pos = {it: i for i, it in enumerate(order)}
    return sum(1 for k, ps in enumerate(preds) if k in pos
               for p in ps if p in pos and pos[p] > pos[k])


def repair(order: Sequence[int], preds: Sequence[Sequence[int]],
           succs: Sequence[Sequence[int]]) -> List[int]:
    """The precedence-respecting order closest to ``order``: repeatedly take the
    earliest item (by its position in ``order``) whose predecessors are all
    placed.  An order that already respects precedence comes back unchanged."""
    rank = {it: i for i, it in enumerate(order)}
    missing = {it: sum(1 for p in preds[it] if p in rank) for it in order}
    heap = [rank[it] for it in order if missing[it] == 0]
    heapq.heapify(heap)
    out: List[int] = []
    while heap:
        it = order[heapq.heappop(heap)]
        out.append(it)
        for s in succs[it]:
            if s in missing:
                missing[s] -= 1
                if missing[s] == 0:
                    heapq.heappush(heap, rank[s])
    if len(out) != len(order):
        raise ValueError("precedence constraints contain a cycle")
    return out
