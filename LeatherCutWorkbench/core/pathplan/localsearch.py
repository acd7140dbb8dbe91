"""Local search on the visiting order: 2-opt and Or-opt with neighbour lists.

The order ``t`` is a list of items with the anchor at position 0 (never moved);
``c[item]`` is the chosen candidate.  Moves are evaluated with the current
candidates; Or-opt of a single item also picks that item's best candidate at
its new place (cluster re-insertion).  Only the ``k`` nearest items of each
item are tried (neighbour lists) and items whose surroundings did not change
are skipped (a work queue = "don't-look bits").  Every move is checked
against precedence before it is applied, so a valid order stays valid.

Written by hand: no library offers asymmetric, precedence-aware 2-opt/Or-opt
on clusters; the loops are plain Python on lists, which is faster than numpy
for the scalar work they do.
"""

from __future__ import annotations

import time
from collections import deque
from typing import Iterable, List, Optional, Sequence

from .dp import optimal_entries
from .instance import Instance

EPS = 1e-7


def local_search(inst: Instance, t: List[int], c: List[int],
                 near: Sequence[Sequence[int]], neard: Sequence[Sequence[float]],
                 active: Optional[Iterable[int]] = None, max_seg: int = 3,
                 deadline: Optional[float] = None) -> float:
    """Improve ``t`` (and ``c``) in place until no move in the neighbourhood
    helps.  Returns the total cost decrease."""
    m = len(t)
    if m < 4:
        return 0.0
    cost = inst.cost
    asym = not inst.symmetric
    prec = inst.has_precedence
    partners, preds, succs = inst.partners, inst.preds, inst.succs
    cands = inst.cands
    multi = [len(cl) > 1 for cl in inst.cand_lists]
    to_many, from_many = inst.to_many, inst.from_many
    pos = [0] * inst.m
    for i, x in enumerate(t):
        pos[x] = i
    queue = deque(t if active is None else active)
    inq = [False] * inst.m
    for x in queue:
        inq[x] = True
    gain_total = 0.0
    pops = 0

    d = inst.item_cost_fn(c)

    def rev_internal(p: int, q: int) -> float:
        s = 0.0
        for k in range(p, q):
            x, y = c[t[k]], c[t[k + 1]]
            s += cost(y, x) - cost(x, y)
        return s

    def rev_ok(p: int, q: int) -> bool:
        for k in range(p, q + 1):
            for y in partners[t[k]]:
                if p <= pos[y] <= q:
                    return False
        return True

    def push(*xs: int) -> None:
        for x in xs:
            if not inq[x]:
                inq[x] = True
                queue.append(x)

    def two_opt(a: int) -> float:
        i = pos[a]
        for side in (0, 1):
            if side == 0:
                other = t[(i + 1) % m]
                d1 = d(a, other)
            else:
                other = t[i - 1]
                d1 = d(other, a)
            for b, nb in zip(near[a], neard[a]):
                if nb >= d1:
                    break
                j = pos[b]
                if side == 0:
                    x, y = (i, j) if i < j else (j, i)
                else:
                    x, y = ((i - 1) % m, (j - 1) % m)
                    if x > y:
                        x, y = y, x
                if y - x < 2:
                    continue
                ta, tb, te, tf = t[x], t[x + 1], t[y], t[(y + 1) % m]
                delta = d(ta, te) + d(tb, tf) - d(ta, tb) - d(te, tf)
                if delta < -EPS and asym:
                    delta += rev_internal(x + 1, y)
                if delta < -EPS and (not prec or rev_ok(x + 1, y)):
                    t[x + 1:y + 1] = t[x + 1:y + 1][::-1]
                    for k in range(x + 1, y + 1):
                        pos[t[k]] = k
                    push(ta, tb, te, tf)
                    return -delta
        return 0.0

    def or_opt(a: int) -> float:
        i = pos[a]
        if i == 0:
            return 0.0
        for L in range(1, max_seg + 1):
            if i + L - 1 > m - 1 or L > m - 3:
                break
            seg = t[i:i + L]
            s1, sL = seg[0], seg[-1]
            p, nx = t[i - 1], t[(i + L) % m]
            rem = d(p, s1) + d(sL, nx) - d(p, nx)
            if rem <= EPS:
                continue
            segset = set(seg)
            internal = rev_internal(i, i + L - 1) if (asym and L > 1) else 0.0
            if prec and L > 1 and any(y in segset for x in seg for y in partners[x]):
                can_rev = False
            else:
                can_rev = True
            best = EPS
            best_move = None
            ends = (s1,) if L == 1 else (s1, sL)
            for e in ends:
                for b, nb in zip(near[e], neard[e]):
                    if nb >= rem:
                        break
                    if b in segset:
                        continue
                    q0 = pos[b]
                    for q in (q0, (q0 - 1) % m):
                        u, v = t[q], t[(q + 1) % m]
                        if u in segset or v in segset:
                            continue
                        duv = d(u, v)
                        if L == 1 and multi[s1]:
                            C = cands[s1]
                            arr = to_many(c[u], C) + from_many(C, c[v])
                            k = int(arr.argmin())
                            g = rem - (float(arr[k]) - duv)
                            if g > best:
                                best, best_move = g, (q, False, int(C[k]))
                            continue
                        g = rem - (d(u, s1) + d(sL, v) - duv)
                        if g > best:
                            best, best_move = g, (q, False, None)
                        if L > 1 and can_rev:
                            g = rem - (d(u, sL) + d(s1, v) - duv + internal)
                            if g > best:
                                best, best_move = g, (q, True, None)
            if best_move is None:
                continue
            q, rev, newc = best_move
            if prec:
                if q > i + L - 1:
                    lo, hi = i + L, q
                    if any(lo <= pos[y] <= hi for x in seg for y in succs[x]):
                        continue
                else:
                    lo, hi = q + 1, i - 1
                    if any(lo <= pos[y] <= hi for x in seg for y in preds[x]):
                        continue
            u, v = t[q], t[(q + 1) % m]
            del t[i:i + L]
            if rev:
                seg = seg[::-1]
            ins = q - L + 1 if q > i + L - 1 else q + 1
            t[ins:ins] = seg
            lo, hi = min(i, ins), max(i + L - 1, ins + L - 1)
            for k in range(lo, hi + 1):
                pos[t[k]] = k
            if newc is not None:
                c[s1] = newc
            push(p, nx, s1, sL, u, v)
            return best
        return 0.0

    while queue:
        a = queue.popleft()
        inq[a] = False
        pops += 1
        if deadline is not None and (pops & 255) == 0 and time.perf_counter() > deadline:
            break
        g = two_opt(a)
        if g <= 0.0:
            g = or_opt(a)
        if g > 0.0:
            gain_total += g
            push(a)
    return gain_total


def improve(inst: Instance, t: List[int], c: List[int],
            near: Sequence[Sequence[int]], neard: Sequence[Sequence[float]],
            active: Optional[Iterable[int]] = None,
            deadline: Optional[float] = None) -> float:
    """Alternate local search on the order with the exact entry-point DP until
    neither improves.  Returns the final tour cost; ``t`` and ``c`` are updated
    in place."""
    dp_useful = inst.n > inst.m
    while True:
        local_search(inst, t, c, near, neard, active, deadline=deadline)
        cur = inst.tour_cost(t, c)
        if not dp_useful or (deadline is not None and time.perf_counter() > deadline):
            return cur
        c2, cost2 = optimal_entries(inst, t)
        if cost2 >= cur - 1e-6:
            return cur
        m = len(t)
        pos = {x: i for i, x in enumerate(t)}
        changed = [k for k in t if c2[k] != c[k]]
        c[:] = c2
        act = set()
        for k in changed:
            i = pos[k]
            act.update((k, t[i - 1], t[(i + 1) % m]))
        active = sorted(act, key=pos.__getitem__)
