"""The clean-up's vectorised pre-filter (``cleanup._may_overlap``) skips only
collinear runs without overlaps: ``clean`` gives the same edges and counts with
and without it, on random collinear lines that overlap, touch, nearly touch
and lie within the tolerance of each other."""

import random

import numpy as np

from LeatherCutWorkbench.core.dxfimport import cleanup
from LeatherCutWorkbench.core.model import EdgeSource, LineEdge


def _lines(rng):
    out = []
    for k in range(rng.randrange(2, 60)):
        y = rng.choice((0.0, 0.004, 1.0, 2.0, 2.0 + 1e-7))
        x = rng.uniform(0, 50)
        n = rng.uniform(0.001, 10)
        gap = rng.choice((0.0, 0.005, 0.0101, -0.5, 1.0))
        for _ in range(rng.randrange(1, 4)):
            p, q = (x, y), (x + n, y + rng.choice((0.0, 0.0, 0.003)))
            out.append(LineEdge(p, q, EdgeSource("CUT", 256, str(k), "LINE")) if rng.random() < 0.5
                       else LineEdge(q, p, EdgeSource("CUT", 256, str(k), "LINE")))
            x += n + gap
    rng.shuffle(out)
    return out


def test_the_overlap_prefilter_changes_nothing(monkeypatch):
    rng = random.Random(16)
    for _ in range(200):
        lines = _lines(rng)
        fast, fast_counts = cleanup.clean(lines, 0.01)
        with monkeypatch.context() as m:
            m.setattr(cleanup, "_may_overlap",
                      lambda xy, order, starts, ends, tol: np.ones(len(starts), dtype=bool))
            slow, slow_counts = cleanup.clean(lines, 0.01)
        assert fast == slow and fast_counts == slow_counts
