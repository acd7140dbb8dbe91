"""Entry-point candidates on a closed contour.

A closed contour may be entered at any of its vertices (segment joints) and
every ``spacing`` mm of arc length along its edges; candidates closer than a
quarter spacing to a vertex are dropped (the vertex is kept).  Positions are
arc lengths in mm from the contour's first point, so the cut path for an entry
is ``rotate_closed_path(segments, s)``.
"""

from __future__ import annotations

import math
from typing import List, Sequence

import numpy as np

from ..geometry import Point, Segment

#: Most spacing points generated on one contour before thinning (bounded memory
#: whatever the contour length).
_MAX_SPACED = 100_000


def entry_positions(segments: Sequence[Segment], spacing: float,
                    max_candidates: int = 64) -> List[float]:
    """Sorted arc-length positions (mm) of the entry candidates of a closed
    contour: all vertices plus points every ``spacing`` mm; at most
    ``max_candidates`` (thinned evenly along the contour when there are more)."""
    lengths = [s.length for s in segments]
    total = float(sum(lengths))
    if total <= 0:
        return [0.0]
    verts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
    pos = list(verts)
    if spacing and spacing > 0:
        # at most _MAX_SPACED points (the result is thinned to max_candidates anyway)
        k = max(1, min(int(math.ceil(total / spacing)), _MAX_SPACED))
        step = total / k
        along = np.arange(k) * step
        if len(verts):
            # distance (along the loop) to the nearest vertex: verts are sorted, so
            # only the neighbours either side (and the wrap-around) can be nearest
            j = np.searchsorted(verts, along)
            before = verts[np.clip(j - 1, 0, len(verts) - 1)]
            after = verts[np.clip(j, 0, len(verts) - 1)]
            dv = np.minimum(np.abs(along - before), np.abs(after - along))
            dv = np.minimum(dv, np.minimum(total - along + verts[0], along + total - verts[-1]))
            along = along[dv > 0.25 * step]
        pos.extend(along.tolist())
    pos = np.unique(np.round(np.asarray(pos), 9))
    if len(pos) > max_candidates:
        idx = np.unique(np.round(np.linspace(0, len(pos) - 1, max_candidates)).astype(int))
        pos = pos[idx]
    return [float(p) for p in pos]


def locate(segments: Sequence[Segment], p: Point, chord_tol: float = 0.01) -> float:
    """Arc length (mm) along a path of the point nearest to ``p``."""
    best_d, best_s, acc = math.inf, 0.0, 0.0
    for seg in segments:
        pts = np.asarray(seg.points(chord_tol), dtype=float)
        a, b = pts[:-1], pts[1:]
        ab = b - a
        ll = np.einsum("ij,ij->i", ab, ab)
        t = np.clip(np.einsum("ij,ij->i", np.asarray(p) - a, ab) / np.where(ll > 0, ll, 1.0), 0, 1)
        proj = a + ab * t[:, None]
        dd = np.hypot(proj[:, 0] - p[0], proj[:, 1] - p[1])
        i = int(dd.argmin())
        if dd[i] < best_d:
            piece = np.sqrt(ll)
            poly_s = float(piece[:i].sum() + t[i] * piece[i])
            poly_len = float(piece.sum())
            scale = seg.length / poly_len if poly_len > 0 else 0.0
            best_d, best_s = float(dd[i]), acc + poly_s * scale
        acc += seg.length
    return best_s
