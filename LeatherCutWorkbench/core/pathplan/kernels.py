"""Compiled kernels of the memetic search (numba, see :mod:`.jit`).

Written by hand: no library offers asymmetric, precedence-aware local search on
clusters.  Every kernel works on flat numpy arrays:

* a tour ``t`` (int64, length m): items in visiting order, the anchor item 0
  at position 0 (never moved); ``pos[item]`` its position;
* the choice ``c`` (int64, length m): the candidate id chosen for each item;
* the *problem* tuple ``P = (mode, D, en, sn, X, tp)`` that prices a move from
  candidate g to candidate h (:func:`cost`): ``mode`` 0 = matrix
  ``D[en[g], sn[h]]``; 1 = straight-line distance from the end point of g
  (``X[g, 0:2]``) to the start point of h (``X[h, 2:4]``), mm; 2 = machine
  time, s: a rest-to-rest trapezoidal move at rapid speed ``tp[0]`` (mm/s) and
  acceleration ``tp[1]`` (mm/s^2), at least the time to turn the knife in the
  air from g's exit heading ``X[g, 4]`` to h's entry heading ``X[h, 5]``
  (radians) at ``tp[3]`` rad/s when ``tp[3] > 0``, plus ``tp[2]`` s of knife
  lift and plunge per move;
* the *structure* tuple ``S = (cptr, cids, near, neard, pptr, pidx, sptr,
  sidx, flags)``: candidates of item k are ``cids[cptr[k]:cptr[k+1]]``;
  ``near[k]`` its nearest other items (-1 padded) with lower bounds ``neard``
  on any move between them; predecessors / successors of k in CSR form;
  ``flags = [has_precedence, symmetric]``.

Random numbers come from a splitmix64 generator whose state is a one-element
uint64 array owned by the caller, so a seed gives the same tour on any
machine and in any thread.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import njit

EPS = 1e-9


# ---------------------------------------------------------------- random numbers
@njit
def rnd_u64(st):
    st[0] = st[0] + np.uint64(0x9E3779B97F4A7C15)
    z = st[0]
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@njit
def rnd_int(st, n):
    """Uniform integer in 0..n-1 (n >= 1)."""
    return np.int64(rnd_u64(st) % np.uint64(n))


@njit
def rnd_float(st):
    """Uniform float in [0, 1)."""
    return float(rnd_u64(st) >> np.uint64(11)) * (1.0 / 9007199254740992.0)


# ---------------------------------------------------------------- cost model
@njit
def cost(g, h, P):
    mode, D, en, sn, X, tp = P
    if mode == 0:
        return D[en[g], sn[h]]
    dx = X[g, 0] - X[h, 2]
    dy = X[g, 1] - X[h, 3]
    L = math.sqrt(dx * dx + dy * dy)
    if mode == 1:
        return L
    v = tp[0]
    a = tp[1]
    if L <= 0.0:
        tm = 0.0
    elif a <= 0.0:
        tm = L / v
    elif L >= v * v / a:
        tm = L / v + v / a
    else:
        tm = 2.0 * math.sqrt(L / a)
    if tp[3] > 0.0:
        ang = abs(X[h, 5] - X[g, 4]) % (2.0 * math.pi)
        if ang > math.pi:
            ang = 2.0 * math.pi - ang
        tt = ang / tp[3]
        if tt > tm:
            tm = tt
    return tm + tp[2]


@njit
def tour_cost(t, c, P):
    m = t.shape[0]
    s = 0.0
    prev = c[t[m - 1]]
    for i in range(m):
        g = c[t[i]]
        s += cost(prev, g, P)
        prev = g
    return s


# ---------------------------------------------------------------- entry DP
@njit
def _dp_close(F, prev_a, prev_n, g_end, S, P):
    """Cheapest way from the layer of F (candidate slots prev_a..prev_a +
    prev_n) on to candidate g_end: (cost, slot)."""
    cids = S[1]
    best = np.inf
    arg = 0
    for q in range(prev_n):
        v = F[q] + cost(cids[prev_a + q], g_end, P)
        if v < best:
            best = v
            arg = q
    return best, arg


@njit
def _dp_layers(t, i0, i1, F, F2, back, want_back, S, P):
    """Advance the layered DP: ``F`` holds the cheapest cost of reaching each
    candidate of the item at position i0; afterwards it holds those of the
    item at i1.  With want_back, ``back`` records the best predecessor of
    every candidate, layer after layer.  Returns (first candidate slot and
    count of the item at i1, length of ``back`` used)."""
    cptr, cids = S[0], S[1]
    prev_a = cptr[t[i0]]
    prev_n = cptr[t[i0] + 1] - prev_a
    off = 0
    for i in range(i0 + 1, i1 + 1):
        k = t[i]
        a, nk = cptr[k], cptr[k + 1] - cptr[k]
        for j in range(nk):
            best, arg = _dp_close(F, prev_a, prev_n, cids[a + j], S, P)
            F2[j] = best
            if want_back:
                back[off + j] = arg
        for j in range(nk):
            F[j] = F2[j]
        off += nk
        prev_a, prev_n = a, nk
    return prev_a, prev_n, off


@njit
def _dp_back(t, c, i0, i1, j, off, back, S):
    """Write the DP's choice for positions i1 down to i0 into c, starting
    from slot j of the item at i1."""
    cptr, cids = S[0], S[1]
    for i in range(i1, i0 - 1, -1):
        k = t[i]
        c[k] = cids[cptr[k] + j]
        if i > i0:
            off -= cptr[k + 1] - cptr[k]
            j = back[off + j]


@njit
def _dp_from(t, c, S, P, g0, back, F, F2, want_back):
    """Layered shortest path for a fixed order starting and ending at anchor
    candidate g0; returns the closed cost; with want_back also the choice c."""
    cptr, cids = S[0], S[1]
    m = t.shape[0]
    k1 = t[1]
    for j in range(cptr[k1 + 1] - cptr[k1]):
        F[j] = cost(g0, cids[cptr[k1] + j], P)
    prev_a, prev_n, off = _dp_layers(t, 1, m - 1, F, F2, back, want_back, S, P)
    best, arg = _dp_close(F, prev_a, prev_n, g0, S, P)
    if want_back:
        c[t[0]] = g0
        _dp_back(t, c, 1, m - 1, arg, off, back, S)
    return best


@njit
def dp_full(t, c, S, P):
    """Exact best candidates for the order ``t`` (c updated); returns the
    closed-tour cost.  O(|C_anchor| * sum |C_i| |C_i+1|)."""
    cptr, cids = S[0], S[1]
    m = t.shape[0]
    if m == 1:
        best = np.inf
        for q in range(cptr[0], cptr[1]):
            v = cost(cids[q], cids[q], P)
            if v < best:
                best = v
                c[0] = cids[q]
        return best
    mx = 1
    for k in range(cptr.shape[0] - 1):
        if cptr[k + 1] - cptr[k] > mx:
            mx = cptr[k + 1] - cptr[k]
    back = np.empty(cids.shape[0], dtype=np.int64)
    F = np.empty(mx)
    F2 = np.empty(mx)
    a0, b0 = cptr[t[0]], cptr[t[0] + 1]
    if b0 - a0 == 1:
        return _dp_from(t, c, S, P, cids[a0], back, F, F2, True)
    best = np.inf
    bg = cids[a0]
    for q in range(a0, b0):
        v = _dp_from(t, c, S, P, cids[q], back, F, F2, False)
        if v < best:
            best = v
            bg = cids[q]
    return _dp_from(t, c, S, P, bg, back, F, F2, True)


@njit
def dp_window(t, c, lo, hi, S, P):
    """Re-choose the candidates at positions lo..hi exactly, the items just
    outside keeping theirs.  Returns the cost decrease (c updated)."""
    cptr, cids = S[0], S[1]
    m = t.shape[0]
    if lo < 1:
        lo = 1
    if hi > m - 1:
        hi = m - 1
    if hi < lo:
        return 0.0
    before = c[t[lo - 1]]
    after = c[t[(hi + 1) % m]]
    old = cost(before, c[t[lo]], P) + cost(c[t[hi]], after, P)
    for i in range(lo, hi):
        old += cost(c[t[i]], c[t[i + 1]], P)
    tot = 0
    mx = 1
    for i in range(lo, hi + 1):
        nk = cptr[t[i] + 1] - cptr[t[i]]
        tot += nk
        if nk > mx:
            mx = nk
    back = np.empty(tot, dtype=np.int64)
    F = np.empty(mx)
    F2 = np.empty(mx)
    k = t[lo]
    for j in range(cptr[k + 1] - cptr[k]):
        F[j] = cost(before, cids[cptr[k] + j], P)
    prev_a, prev_n, off = _dp_layers(t, lo, hi, F, F2, back, True, S, P)
    best, arg = _dp_close(F, prev_a, prev_n, after, S, P)
    if best >= old - EPS:
        return 0.0
    _dp_back(t, c, lo, hi, arg, off, back, S)
    return old - best


# ---------------------------------------------------------------- local search
@njit
def _push(x, queue, inq, qs):
    """qs = [head, size]; circular queue of capacity len(queue)."""
    if not inq[x]:
        inq[x] = True
        n = queue.shape[0]
        queue[(qs[0] + qs[1]) % n] = x
        qs[1] += 1


@njit
def _rev_internal(t, c, p, q, P):
    s = 0.0
    for k in range(p, q):
        x = c[t[k]]
        y = c[t[k + 1]]
        s += cost(y, x, P) - cost(x, y, P)
    return s


@njit
def _rev_ok(t, pos, p, q, S):
    pptr, pidx, sptr, sidx = S[4], S[5], S[6], S[7]
    for k in range(p, q + 1):
        x = t[k]
        for r in range(pptr[x], pptr[x + 1]):
            y = pos[pidx[r]]
            if p <= y <= q:
                return False
        for r in range(sptr[x], sptr[x + 1]):
            y = pos[sidx[r]]
            if p <= y <= q:
                return False
    return True


@njit
def _two_opt(a, t, c, pos, S, P, queue, inq, qs):
    near, neard, flags = S[2], S[3], S[8]
    prec = flags[0] != 0
    asym = flags[1] == 0
    m = t.shape[0]
    i = pos[a]
    K = near.shape[1]
    for side in range(2):
        if side == 0:
            d1 = cost(c[a], c[t[(i + 1) % m]], P)
        else:
            d1 = cost(c[t[(i - 1 + m) % m]], c[a], P)
        for r in range(K):
            b = near[a, r]
            if b < 0 or neard[a, r] >= d1:
                break
            j = pos[b]
            if side == 0:
                x, y = (i, j) if i < j else (j, i)
            else:
                x, y = (i - 1 + m) % m, (j - 1 + m) % m
                if x > y:
                    x, y = y, x
            if y - x < 2:
                continue
            ta, tb, te, tf = t[x], t[x + 1], t[y], t[(y + 1) % m]
            delta = (cost(c[ta], c[te], P) + cost(c[tb], c[tf], P)
                     - cost(c[ta], c[tb], P) - cost(c[te], c[tf], P))
            if delta < -EPS and asym:
                delta += _rev_internal(t, c, x + 1, y, P)
            if delta < -EPS and (not prec or _rev_ok(t, pos, x + 1, y, S)):
                lo, hi = x + 1, y
                while lo < hi:
                    tmp = t[lo]
                    t[lo] = t[hi]
                    t[hi] = tmp
                    lo += 1
                    hi -= 1
                for k in range(x + 1, y + 1):
                    pos[t[k]] = k
                _push(ta, queue, inq, qs)
                _push(tb, queue, inq, qs)
                _push(te, queue, inq, qs)
                _push(tf, queue, inq, qs)
                return -delta
    return 0.0


@njit
def _move_segment(t, pos, i, L, q, rev, buf):
    """Move t[i:i+L] (optionally reversed) to just after position q."""
    for k in range(L):
        buf[k] = t[i + L - 1 - k] if rev else t[i + k]
    if q > i + L - 1:
        for k in range(i + L, q + 1):
            t[k - L] = t[k]
        ins = q - L + 1
        lo, hi = i, q
    else:
        for k in range(i - 1, q, -1):
            t[k + L] = t[k]
        ins = q + 1
        lo, hi = q + 1, i + L - 1
    for k in range(L):
        t[ins + k] = buf[k]
    for k in range(lo, hi + 1):
        pos[t[k]] = k


@njit
def _related_in(t, pos, i, L, ptr, idx, lo, hi):
    """True when an item of t[i:i+L] has a related item (CSR ptr/idx:
    predecessors or successors) at a position in lo..hi."""
    for k in range(i, i + L):
        x = t[k]
        for r in range(ptr[x], ptr[x + 1]):
            if lo <= pos[idx[r]] <= hi:
                return True
    return False


@njit
def _or_opt(a, t, c, pos, S, P, queue, inq, qs, inseg, buf, max_seg):
    cptr, cids, near, neard = S[0], S[1], S[2], S[3]
    pptr, pidx, sptr, sidx, flags = S[4], S[5], S[6], S[7], S[8]
    prec = flags[0] != 0
    asym = flags[1] == 0
    m = t.shape[0]
    K = near.shape[1]
    i = pos[a]
    if i == 0:
        return 0.0
    for L in range(1, max_seg + 1):
        if i + L - 1 > m - 1 or L > m - 3:
            break
        s1 = t[i]
        sL = t[i + L - 1]
        p = t[i - 1]
        nx = t[(i + L) % m]
        rem = cost(c[p], c[s1], P) + cost(c[sL], c[nx], P) - cost(c[p], c[nx], P)
        if rem <= EPS:
            continue
        for k in range(i, i + L):
            inseg[t[k]] = True
        internal = _rev_internal(t, c, i, i + L - 1, P) if (asym and L > 1) else 0.0
        can_rev = True
        if prec and L > 1:
            for k in range(i, i + L):
                x = t[k]
                for r in range(pptr[x], pptr[x + 1]):
                    if inseg[pidx[r]]:
                        can_rev = False
                for r in range(sptr[x], sptr[x + 1]):
                    if inseg[sidx[r]]:
                        can_rev = False
        multi = cptr[s1 + 1] - cptr[s1] > 1
        best = EPS
        bq = -1
        brev = False
        bcand = -1
        nends = 1 if L == 1 else 2
        for e_i in range(nends):
            e = s1 if e_i == 0 else sL
            for r in range(K):
                b = near[e, r]
                if b < 0 or neard[e, r] >= rem:
                    break
                if inseg[b]:
                    continue
                q0 = pos[b]
                for qq in range(2):
                    q = q0 if qq == 0 else (q0 - 1 + m) % m
                    u = t[q]
                    v = t[(q + 1) % m]
                    if inseg[u] or inseg[v]:
                        continue
                    duv = cost(c[u], c[v], P)
                    if L == 1 and multi:
                        for z in range(cptr[s1], cptr[s1 + 1]):
                            g = cids[z]
                            gain = rem - (cost(c[u], g, P) + cost(g, c[v], P) - duv)
                            if gain > best:
                                best, bq, brev, bcand = gain, q, False, g
                        continue
                    gain = rem - (cost(c[u], c[s1], P) + cost(c[sL], c[v], P) - duv)
                    if gain > best:
                        best, bq, brev, bcand = gain, q, False, -1
                    if L > 1 and can_rev:
                        gain = rem - (cost(c[u], c[sL], P) + cost(c[s1], c[v], P) - duv + internal)
                        if gain > best:
                            best, bq, brev, bcand = gain, q, True, -1
        for k in range(i, i + L):
            inseg[t[k]] = False
        if bq < 0:
            continue
        q = bq
        if prec:
            # moving forward the segment passes items that must not be its
            # successors; moving back, items that must not be its predecessors
            if q > i + L - 1:
                if _related_in(t, pos, i, L, sptr, sidx, i + L, q):
                    continue
            elif _related_in(t, pos, i, L, pptr, pidx, q + 1, i - 1):
                continue
        u = t[q]
        v = t[(q + 1) % m]
        _move_segment(t, pos, i, L, q, brev, buf)
        if bcand >= 0:
            c[s1] = bcand
        _push(p, queue, inq, qs)
        _push(nx, queue, inq, qs)
        _push(s1, queue, inq, qs)
        _push(sL, queue, inq, qs)
        _push(u, queue, inq, qs)
        _push(v, queue, inq, qs)
        return best
    return 0.0


@njit
def local_search(t, c, pos, active, S, P, max_seg):
    """2-opt and Or-opt (segments of 1..max_seg items, either direction; a
    single item also re-picks its candidate) with neighbour lists and a work
    queue of items whose surroundings changed (don't-look bits), until no move
    helps.  Every move keeps precedence.  Returns the cost decrease."""
    m = t.shape[0]
    if m < 4:
        return 0.0
    for i in range(m):
        pos[t[i]] = i
    queue = np.empty(m, dtype=np.int64)
    inq = np.zeros(m, dtype=np.bool_)
    inseg = np.zeros(m, dtype=np.bool_)
    buf = np.empty(max_seg, dtype=np.int64)
    qs = np.zeros(2, dtype=np.int64)
    for x in active:
        _push(x, queue, inq, qs)
    total = 0.0
    while qs[1] > 0:
        a = queue[qs[0]]
        qs[0] = (qs[0] + 1) % m
        qs[1] -= 1
        inq[a] = False
        g = _two_opt(a, t, c, pos, S, P, queue, inq, qs)
        if g <= 0.0:
            g = _or_opt(a, t, c, pos, S, P, queue, inq, qs, inseg, buf, max_seg)
        if g > 0.0:
            total += g
            _push(a, queue, inq, qs)
    return total


@njit
def improve(t, c, pos, active, S, P, full_dp):
    """Local search on the order (starting from the items in ``active``)
    alternated with the entry DP -- the full DP when ``full_dp``, else
    overlapping windows of 8 positions -- until neither helps.  Returns the
    tour cost."""
    m = t.shape[0]
    buf = np.empty(2 * m, dtype=np.int64)
    n_act = min(active.shape[0], 2 * m)
    buf[:n_act] = active[:n_act]
    old_c = np.empty(m, dtype=np.int64)
    cur = tour_cost(t, c, P)
    for _ in range(50):
        local_search(t, c, pos, buf[:n_act], S, P, 3)
        cur = tour_cost(t, c, P)
        old_c[:] = c
        if full_dp:
            new = dp_full(t, c, S, P)
            if new >= cur - EPS * max(1.0, cur):
                c[:] = old_c
                return cur
        else:
            gain = 0.0
            for i in range(1, m, 6):
                gain += dp_window(t, c, i - 1, i + 6, S, P)
            if gain <= EPS * max(1.0, cur):
                return tour_cost(t, c, P)
        n_act = 0
        for i in range(m):
            k = t[i]
            if c[k] != old_c[k]:
                buf[n_act] = k
                buf[n_act + 1] = t[(i + 1) % m]
                n_act += 2
        if n_act == 0:
            return tour_cost(t, c, P)
    return tour_cost(t, c, P)


# ---------------------------------------------------------------- precedence
@njit
def repair(t, S):
    """The precedence-respecting order closest to t: repeatedly take the
    earliest (by position in t) item whose predecessors are all placed."""
    pptr, sptr, sidx = S[4], S[6], S[7]
    m = t.shape[0]
    rank = np.empty(m, dtype=np.int64)
    for i in range(m):
        rank[t[i]] = i
    missing = np.empty(m, dtype=np.int64)
    for k in range(m):
        missing[k] = pptr[k + 1] - pptr[k]
    heap = np.empty(m, dtype=np.int64)
    hn = 0
    for i in range(m):
        if missing[t[i]] == 0:
            heap[hn] = i   # ranks pushed in increasing order: already a heap
            hn += 1
    out = np.empty(m, dtype=np.int64)
    no = 0
    while hn > 0:
        r0 = heap[0]
        hn -= 1
        heap[0] = heap[hn]
        j = 0
        while True:
            l_ = 2 * j + 1
            if l_ >= hn:
                break
            s = l_
            if l_ + 1 < hn and heap[l_ + 1] < heap[l_]:
                s = l_ + 1
            if heap[s] >= heap[j]:
                break
            heap[s], heap[j] = heap[j], heap[s]
            j = s
        it = t[r0]
        out[no] = it
        no += 1
        for r in range(sptr[it], sptr[it + 1]):
            s2 = sidx[r]
            missing[s2] -= 1
            if missing[s2] == 0:
                heap[hn] = rank[s2]
                j = hn
                hn += 1
                while j > 0 and heap[(j - 1) // 2] > heap[j]:
                    par = (j - 1) // 2
                    heap[par], heap[j] = heap[j], heap[par]
                    j = par
    return out


@njit
def violations(t, S):
    pptr, pidx = S[4], S[5]
    m = t.shape[0]
    pos = np.empty(m, dtype=np.int64)
    for i in range(m):
        pos[t[i]] = i
    bad = 0
    for k in range(m):
        for r in range(pptr[k], pptr[k + 1]):
            if pos[pidx[r]] > pos[k]:
                bad += 1
    return bad


# ---------------------------------------------------------------- construction
@njit
def random_nn(S, P, st, choose_among):
    """Randomised nearest-neighbour tour from the anchor: the next item is drawn
    among the ``choose_among`` nearest allowed items of the current item's
    neighbour list (the nearest allowed item overall when none is listed)."""
    cptr, cids, near, pptr, sptr, sidx = S[0], S[1], S[2], S[4], S[6], S[7]
    m = cptr.shape[0] - 1
    t = np.empty(m, dtype=np.int64)
    c = np.empty(m, dtype=np.int64)
    visited = np.zeros(m, dtype=np.bool_)
    missing = np.empty(m, dtype=np.int64)
    for k in range(m):
        missing[k] = pptr[k + 1] - pptr[k]
    t[0] = 0
    visited[0] = True
    c[0] = cids[cptr[0] + rnd_int(st, cptr[1] - cptr[0])]
    for r in range(sptr[0], sptr[1]):
        missing[sidx[r]] -= 1
    K = near.shape[1]
    pick_item = np.empty(K, dtype=np.int64)
    pick_cand = np.empty(K, dtype=np.int64)
    pick_d = np.empty(K)
    for step in range(1, m):
        cur = t[step - 1]
        g = c[cur]
        npk = 0
        for r in range(K):
            b = near[cur, r]
            if b < 0:
                break
            if visited[b] or missing[b] > 0:
                continue
            bd = np.inf
            bc = cids[cptr[b]]
            for z in range(cptr[b], cptr[b + 1]):
                v = cost(g, cids[z], P)
                if v < bd:
                    bd = v
                    bc = cids[z]
            pick_item[npk] = b
            pick_cand[npk] = bc
            pick_d[npk] = bd
            npk += 1
        if npk == 0:
            bd = np.inf
            bi = -1
            bc = -1
            for b in range(1, m):
                if visited[b] or missing[b] > 0:
                    continue
                z = cptr[b]
                v = cost(g, cids[z], P)
                if v < bd:
                    bd = v
                    bi = b
                    bc = cids[z]
            if bi < 0:
                raise ValueError("random_nn: precedence constraints contain a cycle")
            nxt, nc = bi, bc
        else:
            # partial selection sort of the choose_among nearest
            top = min(choose_among, npk)
            for u in range(top):
                bu = u
                for w in range(u + 1, npk):
                    if pick_d[w] < pick_d[bu]:
                        bu = w
                pick_d[u], pick_d[bu] = pick_d[bu], pick_d[u]
                pick_item[u], pick_item[bu] = pick_item[bu], pick_item[u]
                pick_cand[u], pick_cand[bu] = pick_cand[bu], pick_cand[u]
            w = rnd_int(st, top)
            nxt, nc = pick_item[w], pick_cand[w]
        t[step] = nxt
        c[nxt] = nc
        visited[nxt] = True
        for r in range(sptr[nxt], sptr[nxt + 1]):
            missing[sidx[r]] -= 1
    return t, c


@njit
def order_crossover(p1, p2, st):
    """OX on orders (position 0 stays the anchor): a slice of p1 is kept in
    place, the other items follow p2's order."""
    m = p1.shape[0]
    child = p1.copy()
    if m <= 3:
        return child
    a = 1 + rnd_int(st, m - 2)
    b = a + 1 + rnd_int(st, m - 1 - a)
    if b > m - 1:
        b = m - 1
    keep = np.zeros(m, dtype=np.bool_)
    for i in range(a, b + 1):
        keep[p1[i]] = True
    j = 1
    for i in range(1, m):
        x = p2[i]
        if keep[x]:
            continue
        if j == a:
            j = b + 1
        child[j] = x
        j += 1
    return child


# ---------------------------------------------------------------- ruin and recreate
@njit
def ruin_recreate(t, c, k, kind, noise, S, P, st, touched):
    """Large-neighbourhood move: remove k items (kind 0 = random, 1 = a
    segment of the tour, 2 = related: a random item and its neighbours, 3 =
    worst: largest detour, with noise) and re-insert them one by one, in
    random order respecting precedence (an item goes after its predecessors
    and before its successors, also those reached through successors still
    waiting to be re-inserted), at the cheapest place next to one of
    their neighbours (any allowed place when none is listed), each with its
    cheapest candidate there; insertion costs are perturbed by
    ``1 + noise * u``, u uniform in [-1, 1].  Returns the tour (a new array);
    ``touched[:k]`` receives the re-inserted items."""
    cptr, cids, near = S[0], S[1], S[2]
    pptr, pidx, sptr, sidx = S[4], S[5], S[6], S[7]
    m = t.shape[0]
    if k > m - 1:
        k = m - 1
    removed = np.zeros(m, dtype=np.bool_)
    rem = np.empty(k, dtype=np.int64)
    nr = 0
    if kind == 1:
        p0 = 1 + rnd_int(st, m - k)
        for i in range(p0, p0 + k):
            rem[nr] = t[i]
            removed[t[i]] = True
            nr += 1
    elif kind == 2:
        x = t[1 + rnd_int(st, m - 1)]
        rem[0] = x
        removed[x] = True
        nr = 1
        K = near.shape[1]
        tries = 0
        while nr < k and tries < 20 * k:
            tries += 1
            y = rem[rnd_int(st, nr)]
            z = near[y, rnd_int(st, K)]
            if z <= 0 or removed[z]:
                continue
            rem[nr] = z
            removed[z] = True
            nr += 1
    elif kind == 3:
        score = np.empty(m)
        score[0] = -np.inf
        for i in range(1, m):
            a_ = c[t[i - 1]]
            b_ = c[t[i]]
            d_ = c[t[(i + 1) % m]]
            gain = cost(a_, b_, P) + cost(b_, d_, P) - cost(a_, d_, P)
            score[i] = gain * (1.0 + noise * (2.0 * rnd_float(st) - 1.0))
        idx = np.argsort(-score)
        for r in range(k):
            i = idx[r]
            if i == 0:
                continue
            rem[nr] = t[i]
            removed[t[i]] = True
            nr += 1
    while nr < k:
        x = t[1 + rnd_int(st, m - 1)]
        if removed[x]:
            continue
        rem[nr] = x
        removed[x] = True
        nr += 1
    # partial tour
    nt = np.empty(m, dtype=np.int64)
    L = 0
    for i in range(m):
        if not removed[t[i]]:
            nt[L] = t[i]
            L += 1
    pos = np.full(m, -1, dtype=np.int64)
    for i in range(L):
        pos[nt[i]] = i
    # random insertion order
    for i in range(nr - 1, 0, -1):
        j = rnd_int(st, i + 1)
        rem[i], rem[j] = rem[j], rem[i]
    seen = np.zeros(m, dtype=np.int64)
    stack = np.empty(2 * sidx.shape[0] + m, dtype=np.int64)
    stamp = 0
    done = 0
    while done < nr:
        # first item in rem[done:] whose removed predecessors are all inserted
        pick = done
        if pptr[-1] > 0:
            for w in range(done, nr):
                x = rem[w]
                ok = True
                for r in range(pptr[x], pptr[x + 1]):
                    if pos[pidx[r]] < 0:
                        ok = False
                        break
                if ok:
                    pick = w
                    break
        rem[done], rem[pick] = rem[pick], rem[done]
        x = rem[done]
        lo = 1
        hi = L
        for r in range(pptr[x], pptr[x + 1]):
            pp = pos[pidx[r]]
            if pp + 1 > lo:
                lo = pp + 1
        # successors still waiting to be re-inserted pass their own
        # successors' places on: x must come before all of them
        stamp += 1
        ns = 0
        for r in range(sptr[x], sptr[x + 1]):
            stack[ns] = sidx[r]
            ns += 1
        while ns > 0:
            ns -= 1
            y = stack[ns]
            if seen[y] == stamp:
                continue
            seen[y] = stamp
            sp = pos[y]
            if sp >= 0:
                if sp < hi:
                    hi = sp
                continue
            for r in range(sptr[y], sptr[y + 1]):
                stack[ns] = sidx[r]
                ns += 1
        best = np.inf
        bi = -1
        bg = -1
        K = near.shape[1]
        pb = 0
        for r in range(K + 1):
            if r < K:
                b = near[x, r]
                if b < 0:
                    continue
                pb = pos[b]
                if pb < 0:
                    continue
            for side in range(2):
                if r < K:
                    ins = pb if side == 0 else pb + 1
                    if ins < lo or ins > hi:
                        continue
                    rng_lo, rng_hi = ins, ins
                else:
                    if bi >= 0 or side == 1:
                        break
                    rng_lo, rng_hi = lo, hi
                for ins2 in range(rng_lo, rng_hi + 1):
                    u = nt[ins2 - 1]
                    v = nt[ins2 % L]
                    duv = cost(c[u], c[v], P)
                    for z in range(cptr[x], cptr[x + 1]):
                        g = cids[z]
                        dl = cost(c[u], g, P) + cost(g, c[v], P) - duv
                        if noise > 0.0:
                            dl *= 1.0 + noise * (2.0 * rnd_float(st) - 1.0)
                        if dl < best:
                            best = dl
                            bi = ins2
                            bg = g
        if bi < 0:
            raise ValueError("ruin_recreate: no place keeps precedence")
        for i in range(L, bi, -1):
            nt[i] = nt[i - 1]
            pos[nt[i]] = i
        nt[bi] = x
        pos[x] = bi
        c[x] = bg
        L += 1
        touched[done] = x
        done += 1
    return nt


@njit
def segment_swap(t, S, st, max_len, touched):
    """Double-bridge kick: swap two adjacent random segments (each at most
    ``max_len`` items) of a copy of t; returns (tour, number of items written
    to ``touched`` -- the ends of the moved segments), or (copy of t, 0) when
    the swap would put an item before one of its predecessors."""
    pptr, pidx = S[4], S[5]
    m = t.shape[0]
    t2 = t.copy()
    lmax = max(1, min(max_len, (m - 1) // 3))
    l1 = 1 + rnd_int(st, lmax)
    l2 = 1 + rnd_int(st, lmax)
    if l1 + l2 > m - 1:
        return t2, 0
    p1 = 1 + rnd_int(st, m - l1 - l2)
    p2 = p1 + l1
    p3 = p2 + l2
    inb = np.zeros(m, dtype=np.bool_)
    for i in range(p1, p2):
        inb[t[i]] = True
    for i in range(p2, p3):
        x = t[i]
        for r in range(pptr[x], pptr[x + 1]):
            if inb[pidx[r]]:
                return t2, 0
    k = p1
    for i in range(p2, p3):
        t2[k] = t[i]
        k += 1
    for i in range(p1, p2):
        t2[k] = t[i]
        k += 1
    touched[0] = t[p1 - 1]
    touched[1] = t[p1]
    touched[2] = t[p2 - 1]
    touched[3] = t[p2]
    touched[4] = t[p3 - 1]
    touched[5] = t[p3 % m]
    return t2, 6


# ---------------------------------------------------------------- the genetic algorithm
@njit
def _store(pop_t, pop_c, pop_cost, i, t, c, pos, S, P):
    """Entries by the DP, full improvement, then individual i := (t, c)."""
    dp_full(t, c, S, P)
    pop_cost[i] = improve(t, c, pos, t, S, P, True)
    pop_t[i] = t
    pop_c[i] = c


@njit
def init_island(pop_t, pop_c, pop_cost, seed_t, seed_c, use_seed, S, P, st, cheap_k):
    """Fill a population: individual 0 = the given seed tour (when use_seed)
    or a randomised nearest-neighbour tour, the others randomised
    nearest-neighbour tours, each fully improved by :func:`improve`.  With
    ``cheap_k > 0`` (large jobs) the others are instead individual 0 with
    ``cheap_k`` items ruined and recreated, improved around those items only."""
    npop, m = pop_t.shape
    pos = np.empty(m, dtype=np.int64)
    touched = np.empty(m, dtype=np.int64)
    for i in range(npop):
        if i == 0 and use_seed:
            t = seed_t.copy()
            c = seed_c.copy()
        elif i > 0 and cheap_k > 0:
            c = pop_c[0].copy()
            k = min(cheap_k, m - 1)
            t = ruin_recreate(pop_t[0], c, k, rnd_int(st, 4), 0.1, S, P, st, touched)
            pop_cost[i] = improve(t, c, pos, touched[:k].copy(), S, P, True)
            pop_t[i] = t
            pop_c[i] = c
            continue
        else:
            t, c = random_nn(S, P, st, 3)
        _store(pop_t, pop_c, pop_cost, i, t, c, pos, S, P)


@njit
def _tournament(pop_cost, st):
    n = pop_cost.shape[0]
    a = rnd_int(st, n)
    b = rnd_int(st, n)
    return a if pop_cost[a] <= pop_cost[b] else b


@njit
def _lns_steps(t, c, cur, steps, S, P, st, full_dp, kmax, noise, accept):
    """Iterated ruin-and-recreate (or, one step in five, a double-bridge
    kick) on (t, c), each step followed by local search and the entry DP; a
    step is kept when its tour is
    at most ``accept`` (relative) longer than the current one (threshold
    acceptance: the walk can leave a local optimum); returns the best tour
    seen and its cost (c holds its candidates)."""
    m = t.shape[0]
    pos = np.empty(m, dtype=np.int64)
    touched = np.empty(max(m, 6), dtype=np.int64)
    act = np.empty(3 * max(m, 6), dtype=np.int64)
    best_t = t.copy()
    best_c = c.copy()
    best = cur
    for _ in range(steps):
        kind = rnd_int(st, 5)
        c2 = c.copy()
        if kind == 4:
            t2, k = segment_swap(t, S, st, 30, touched)
            if k == 0:
                continue
        else:
            k = min(2 + rnd_int(st, max(1, kmax - 1)), m - 1)
            t2 = ruin_recreate(t, c2, k, kind, noise, S, P, st, touched)
        for i in range(m):
            pos[t2[i]] = i
        na = 0
        for r in range(k):
            x = touched[r]
            i = pos[x]
            act[na] = x
            act[na + 1] = t2[i - 1]
            act[na + 2] = t2[(i + 1) % m]
            na += 3
        if full_dp:
            new = improve(t2, c2, pos, act[:na], S, P, True)
        else:
            local_search(t2, c2, pos, act[:na], S, P, 3)
            for r in range(k):
                i = pos[touched[r]]
                dp_window(t2, c2, i - 2, i + 2, S, P)
            new = tour_cost(t2, c2, P)
        if new <= cur * (1.0 + accept) + EPS * max(1.0, cur):
            t = t2
            c[:] = c2
            cur = new
            if new < best - EPS * max(1.0, best):
                best = new
                best_t[:] = t2
                best_c[:] = c2
    c[:] = best_c
    return best_t, best


@njit
def evolve(pop_t, pop_c, pop_cost, stats, n_gens, S, P, st, full_dp, p_cross,
           lns_steps, kmax, noise, restart_after, accept):
    """Run ``n_gens`` generations of the memetic GA on one island (in place).
    A generation makes one child -- by order crossover of two
    tournament-selected parents (p_cross), or as a copy of one parent --
    repairs precedence, chooses entries by the DP, improves it by local search
    and ``lns_steps`` iterated ruin-and-recreate moves (threshold acceptance
    ``accept``), and lets it replace the worst individual when it is better
    and not a duplicate.  After ``restart_after`` generations without a new
    island best, all but the best are replaced by heavily perturbed copies of
    the best and fresh randomised tours.  ``stats = [generations done,
    generations since the island best improved]``."""
    npop, m = pop_t.shape
    pos = np.empty(m, dtype=np.int64)
    flags = S[8]
    for _ in range(n_gens):
        stats[0] += 1
        best_before = pop_cost.min()
        i1 = _tournament(pop_cost, st)
        if npop > 1 and rnd_float(st) < p_cross:
            i2 = _tournament(pop_cost, st)
            if i2 == i1:
                i2 = (i1 + 1 + rnd_int(st, npop - 1)) % npop
            child = order_crossover(pop_t[i1], pop_t[i2], st)
            if flags[0] != 0:
                child = repair(child, S)
            cc = pop_c[i1].copy()
            dp_full(child, cc, S, P)
            cst = improve(child, cc, pos, child, S, P, True)
        else:
            child = pop_t[i1].copy()
            cc = pop_c[i1].copy()
            cst = pop_cost[i1]
        child, cst = _lns_steps(child, cc, cst, lns_steps, S, P, st, full_dp, kmax, noise, accept)
        worst = 0
        dup = False
        for i in range(npop):
            if pop_cost[i] > pop_cost[worst]:
                worst = i
            if abs(pop_cost[i] - cst) <= 1e-9 * max(1.0, cst):
                dup = True
        if not dup and cst < pop_cost[worst]:
            pop_t[worst] = child
            pop_c[worst] = cc
            pop_cost[worst] = cst
        if pop_cost.min() < best_before - 1e-9 * max(1.0, best_before):
            stats[1] = 0
        else:
            stats[1] += 1
        if stats[1] >= restart_after and npop > 1:
            # restart around the best: half of the others are the best
            # heavily ruined and recreated (a quarter of the tour), half fresh
            # randomised nearest-neighbour tours
            stats[1] = 0
            b = np.argmin(pop_cost)
            touched = np.empty(m, dtype=np.int64)
            for i in range(npop):
                if i == b:
                    continue
                if i % 2 == 0:
                    c = pop_c[b].copy()
                    t = ruin_recreate(pop_t[b], c, max(kmax, m // 4), rnd_int(st, 4), noise, S, P,
                                      st, touched)
                else:
                    t, c = random_nn(S, P, st, 3)
                _store(pop_t, pop_c, pop_cost, i, t, c, pos, S, P)
