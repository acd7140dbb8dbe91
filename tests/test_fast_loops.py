"""Loops made only of lines are measured in one pass (``Loop.__init__``,
``Loop.sample_point``): the same signed area, box and sample point, bit for
bit, as ``signed_path_area``, ``path_bbox`` and the longest-segment midpoint,
on random loops (ties of equal lengths, -0.0, tiny and huge coordinates)."""

import random

from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.recognition.from_part import signed_path_area
from LeatherCutWorkbench.core.recognition.loops import Loop, path_bbox


def _loops():
    rng = random.Random(16)
    for trial in range(300):
        n = rng.randrange(1, 10)
        scale = rng.choice((1e-6, 1.0, 1e3, 1e9))
        if trial % 5 == 0:      # a square: four equal longest sides, the first must win
            pts = [(0.0, 0.0), (scale, 0.0), (scale, scale), (-0.0, scale)]
        else:
            pts = [(rng.uniform(-1, 1) * scale, rng.uniform(-1, 1) * scale) for _ in range(n)]
        yield [LineSeg(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]


def test_line_loop_measures_equal_the_general_code():
    for segs in _loops():
        lp = Loop(segs, set(), set())
        assert lp.signed_area == signed_path_area(segs)
        assert lp.bbox == path_bbox(segs)
        longest = max(segs, key=lambda s: s.length)
        assert lp.sample_point() == longest.point_at(longest.length / 2.0)
