"""All pairwise Minkowski sums of two sets of convex rings in one compiled call.

A no-fit polygon of two leather parts is the union of the sums of their
convex pieces: 5-15 pieces each, so 25-200 convex sums per pair, and the
inner-fit region of a part in a hide adds one sum per piece of every defect
and hull pocket.  Done one by one with numpy (:func:`convex.sum_forms`) each
sum costs ~40 us of call overhead for a few dozen vertices: on Baldacci
Test2 a first fill made 209,000 of them (9 of its 15 s in a profile).  The
kernel here (numba: a plain merge loop, no library does it) makes all the
sums of two :class:`FormSet` in one call, vertex for vertex the same rings
as :func:`convex.sum_forms`.
"""

from __future__ import annotations

from typing import List, Sequence

import numpy as np
from numba import njit

from .convex import Form

IntPath = List[List[int]]


class FormSet:
    """A list of edge forms (:func:`convex.edge_form`) packed into flat arrays
    for :func:`sum_all`; indexing, ``len`` and iteration give the forms."""

    __slots__ = ("forms", "base", "edges", "ang", "off")

    def __init__(self, forms: Sequence[Form]):
        self.forms = list(forms)
        n = len(self.forms)
        self.base = np.array([f[0] for f in self.forms], dtype=np.int64).reshape(n, 2)
        self.edges = (np.concatenate([f[1] for f in self.forms]).astype(np.int64)
                      if n else np.zeros((0, 2), np.int64))
        self.ang = (np.concatenate([f[2] for f in self.forms]).astype(np.float64)
                    if n else np.zeros(0))
        self.off = np.zeros(n + 1, dtype=np.int64)
        if n:
            self.off[1:] = np.cumsum([len(f[1]) for f in self.forms])

    def __len__(self) -> int:
        return len(self.forms)

    def __iter__(self):
        return iter(self.forms)

    def __getitem__(self, i: int) -> Form:
        return self.forms[i]


def as_set(forms) -> FormSet:
    """``forms`` as a :class:`FormSet` (packed once; a FormSet is returned as is)."""
    return forms if isinstance(forms, FormSet) else FormSet(forms)


@njit(cache=True)
def _sums(ba, ea, aa, oa, bb, eb, ab, ob):  # pragma: no cover - compiled
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


def sum_all(a, b) -> List[IntPath]:
    """Minkowski sums of every ring of ``a`` with every ring of ``b`` (edge
    forms or :class:`FormSet`), A-major: ``[a0+b0, a0+b1, ..., a1+b0, ...]``;
    exact integers, CCW."""
    sa, sb = as_set(a), as_set(b)
    if not len(sa) or not len(sb):
        return []
    out, offs = _sums(sa.base, sa.edges, sa.ang, sa.off, sb.base, sb.edges, sb.ang, sb.off)
    pts = out.tolist()
    o = offs.tolist()
    return [pts[o[p]:o[p + 1]] for p in range(len(o) - 1)]


def warm_up() -> None:
    """Compile (or load the cached compilation of) the kernel now: called
    before the worker processes fork, so each of them has it ready."""
    from .convex import edge_form
    tri = edge_form([[0, 0], [1, 0], [0, 1]])
    sum_all([tri], [tri])
