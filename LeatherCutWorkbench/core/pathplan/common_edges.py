"""Common edges: an edge shared by two contours is cut once.

Recognition marks shared segments in ``Contour.shared``.  Here each marked
segment is matched by geometry (same end points either way round and the same
mid point, within ``tol`` mm) with a segment of another contour.  The contour
cut first keeps the edge; the one cut later drops it and is split into open
runs (each cut as an open path).
"""

from __future__ import annotations

import math
from typing import Dict, List, Sequence, Set, Tuple

import numpy as np

from ..geometry import Segment


def _mid(seg: Segment) -> Tuple[float, float]:
    return seg.point_at(seg.length / 2.0)


def match_shared(contours: Sequence[Tuple[str, Sequence[Segment], Sequence[int]]],
                 tol: float = 0.05) -> List[Tuple[Tuple[int, int], Tuple[int, int]]]:
    """Pairs ``((contour_index, segment_index), (contour_index, segment_index))``
    of geometrically equal segments on different contours, where at least one
    side is marked shared.  ``contours`` holds ``(id, segments, shared)``."""
    marked = [(ci, si) for ci, (_, segs, shared) in enumerate(contours)
              for si in shared if 0 <= si < len(segs)]
    if not marked:
        return []
    from scipy.spatial import cKDTree
    refs = [(ci, si) for ci, (_, segs, _) in enumerate(contours) for si in range(len(segs))]
    mids = np.array([_mid(contours[ci][1][si]) for ci, si in refs])
    tree = cKDTree(mids)
    index = {r: i for i, r in enumerate(refs)}
    pairs = set()
    for ci, si in marked:
        a = contours[ci][1][si]
        for j in tree.query_ball_point(mids[index[(ci, si)]], r=tol):
            cj, sj = refs[j]
            if cj == ci:
                continue
            b = contours[cj][1][sj]
            same = (math.dist(a.start, b.start) <= tol and math.dist(a.end, b.end) <= tol) or \
                   (math.dist(a.start, b.end) <= tol and math.dist(a.end, b.start) <= tol)
            if same and abs(a.length - b.length) <= 2 * tol:
                pairs.add(tuple(sorted([(ci, si), (cj, sj)])))
    return sorted(pairs)


def edges_to_drop(pairs: Sequence[Tuple[Tuple[int, int], Tuple[int, int]]],
                  rank: Sequence[int]) -> Dict[int, Set[int]]:
    """For each matched pair the contour with the higher ``rank`` (cut later)
    drops its copy.  Returns contour index -> dropped segment indices."""
    drop: Dict[int, Set[int]] = {}
    kept: Set[Tuple[int, int]] = set()
    for (ci, si), (cj, sj) in pairs:
        later, earlier = ((ci, si), (cj, sj)) if rank[ci] > rank[cj] else ((cj, sj), (ci, si))
        if later in kept:        # already the kept copy of another pair
            later, earlier = earlier, later
        if earlier in drop.get(earlier[0], set()):
            continue
        drop.setdefault(later[0], set()).add(later[1])
        kept.add(earlier)
    return drop


def open_runs(segments: Sequence[Segment], dropped: Set[int]) -> List[List[Segment]]:
    """The connected runs of a closed contour left after removing ``dropped``
    segment indices, each in the contour's direction."""
    n = len(segments)
    if not dropped:
        return [list(segments)]
    if len(dropped) >= n:
        return []
    start = next(i for i in range(n) if i not in dropped and (i - 1) % n in dropped)
    runs: List[List[Segment]] = []
    cur: List[Segment] = []
    for k in range(n):
        i = (start + k) % n
        if i in dropped:
            if cur:
                runs.append(cur)
                cur = []
        else:
            cur.append(segments[i])
    if cur:
        runs.append(cur)
    return runs
