"""The compiled kernel of :func:`convex_sums.sum_all` (numba): every pairwise
Minkowski sum of two packed sets of convex rings in one call.

Inputs are the flat arrays of two :class:`convex_sums.FormSet` (base
vertices, edge vectors, edge angles, per-ring edge offsets; grid integers,
angles in radians); the output is every sum's vertices, A-major, and their
offsets -- vertex for vertex :func:`convex.sum_forms`.  Imported only by
:func:`convex_sums.warm_up` (importing numba costs a few tenths of a second).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def pair_sums(ba, ea, aa, oa, bb, eb, ab, ob):  # pragma: no cover - compiled
    na = len(oa) - 1
    nb = len(ob) - 1
    out = np.empty((nb * oa[-1] + na * ob[-1], 2), np.int64)
    offs = np.empty(na * nb + 1, np.int64)
    k = 0
    p = 0
    for i in range(na):
        for j in range(nb):
            offs[p] = k
            p += 1
            x = ba[i, 0] + bb[j, 0]
            y = ba[i, 1] + bb[j, 1]
            ia, iae, ib, ibe = oa[i], oa[i + 1], ob[j], ob[j + 1]
            for _s in range((iae - ia) + (ibe - ib)):
                out[k, 0] = x
                out[k, 1] = y
                k += 1
                # merge by edge angle; ties take A's edge first (a stable sort)
                if ib >= ibe or (ia < iae and aa[ia] <= ab[ib]):
                    x += ea[ia, 0]
                    y += ea[ia, 1]
                    ia += 1
                else:
                    x += eb[ib, 0]
                    y += eb[ib, 1]
                    ib += 1
    offs[p] = k
    return out, offs
