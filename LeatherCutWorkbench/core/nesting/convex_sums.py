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

The kernel lives in :mod:`convex_kernel`, loaded by :func:`warm_up`: numba's
import and its cached machine code cost 0.6-0.9 s, which a worker's first
fill on hides need not wait for (its coarse inner-fit regions make a few
thousand sums: Baldacci Test10 4,800, +0.03 s pair by pair).  Until then
:func:`sum_all` sums pair by pair with numpy -- the same rings.
"""

from __future__ import annotations

from typing import Callable, List, Optional, Sequence

import numpy as np

from .convex import Form, sum_forms

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


#: the compiled kernel once :func:`warm_up` loaded it (None: numpy pair by pair)
_kernel: Optional[Callable] = None


def sum_all(a, b) -> List[IntPath]:
    """Minkowski sums of every ring of ``a`` with every ring of ``b`` (edge
    forms or :class:`FormSet`), A-major: ``[a0+b0, a0+b1, ..., a1+b0, ...]``;
    exact integers, CCW (the kernel's or, before :func:`warm_up`, numpy's)."""
    sa, sb = as_set(a), as_set(b)
    if not len(sa) or not len(sb):
        return []
    if _kernel is None:
        return [sum_forms(fa, fb) for fa in sa.forms for fb in sb.forms]
    out, offs = _kernel(sa.base, sa.edges, sa.ang, sa.off, sb.base, sb.edges, sb.ang, sb.off)
    pts = out.tolist()
    o = offs.tolist()
    return [pts[o[p]:o[p + 1]] for p in range(len(o) - 1)]


def warm_up() -> None:
    """Load the kernel (compile it, or load its cached compilation) and run
    it once; later calls do nothing."""
    global _kernel
    if _kernel is not None:
        return
    from .convex import edge_form
    from .convex_kernel import pair_sums
    _kernel = pair_sums
    tri = edge_form([[0, 0], [1, 0], [0, 1]])
    sum_all([tri], [tri])
