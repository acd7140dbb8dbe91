"""Clean-up of imported edges: zero-length edges, exact duplicates, collinear
overlaps and T-junctions.

Runs per group of edges that may interact: (piece, role).  In AAMA/ASTM files
every piece is its own group, so graded sizes stacked at one origin (identical
outlines in different blocks) are never merged; cut edges are never merged with
marks or internal lines.

* zero-length: edges shorter than :data:`ZERO_LENGTH` (1e-6 mm).  Short but
  real edges (a 0.003 mm closing segment is common in pattern exports) are
  kept: removing them would open gaps;
* duplicates: same geometry in either direction, coordinates compared on a
  ``tol`` grid (first edge kept);
* collinear overlaps: lines on one carrier line (within ``tol``) whose
  intervals overlap by more than ``tol``; the union is kept, each piece owned by
  the earliest line covering it (common-edge layouts draw shared edges twice);
* T-junctions: a line is split where an edge end point lies on its interior
  (within ``tol``); the split point is that end point, so the graph meets exactly.
  Only lines are split (arcs are left whole).

Line geometry is handled with numpy (vectorised); T-junction candidates come
from a shapely STRtree of the line boxes (envelope test, then exact distance
with numpy: ~3x faster than the STRtree's own ``dwithin`` predicate).  The
per-carrier interval sweep is hand-written because no library offers it.
"""

from __future__ import annotations

import math
from collections import defaultdict
from itertools import chain
from operator import attrgetter
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import shapely

from ..model import ArcEdge, EllipseEdge, LineEdge, SplineEdge

_START_END = attrgetter("start", "end")
#: Edges shorter than this (mm) are zero-length and removed.
ZERO_LENGTH = 1e-6
#: Direction difference (radians) below which two lines may share a carrier.
_ANGLE_TOL = 1e-6


@dataclass
class CleanupCounts:
    """What the clean-up changed (``overlap_length`` in mm)."""

    zero_length: int = 0
    duplicates: int = 0
    overlaps: int = 0
    overlap_length: float = 0.0
    t_junctions: int = 0
    edges_before: int = 0
    edges_after: int = 0
    by_type: Dict[str, int] = field(default_factory=dict)

    def to_json(self) -> Dict[str, Any]:
        return {"zero_length_removed": self.zero_length, "duplicates_removed": self.duplicates,
                "overlaps_removed": self.overlaps,
                "overlap_length_mm": round(self.overlap_length, 6),
                "t_junction_splits": self.t_junctions, "edges_before": self.edges_before,
                "edges_after": self.edges_after, "removed_by_entity_type": dict(self.by_type)}


def clean(edges: Sequence[Any], tol: float,
          step: Optional[Callable[[float, str], None]] = None) -> Tuple[List[Any], CleanupCounts]:
    """Cleaned copy of ``edges`` and the counts.  Edges are grouped by
    (``src.piece``, ``src.role``); within a group lines come first, then arcs,
    ellipses and splines, each in their original order.  ``step(fraction,
    message)`` is called as groups and stages complete."""
    def tick(done: int, what: str) -> None:
        if step is not None:
            step(done / max(len(edges), 1), what)

    counts = CleanupCounts(edges_before=len(edges))
    groups: Dict[Tuple[str, str], Tuple[list, list, list, list]] = {}
    for e in edges:
        src = e.src
        key = (src.piece, src.role)
        g = groups.get(key)
        if g is None:
            g = groups[key] = ([], [], [], [])
        t = type(e)
        g[0 if t is LineEdge else 1 if t is ArcEdge else 2 if t is EllipseEdge else 3].append(e)
    result: List[Any] = []
    done = 0
    for lines, arcs, ellipses, others in groups.values():
        size = len(lines) + len(arcs) + len(ellipses) + len(others)
        others = _drop_zero_and_duplicates(others, tol, counts)
        ends = [np.empty((0, 2))]
        if arcs:
            arcs, arc_ends = _dedupe_arcs(arcs, tol, counts)
            ends.append(arc_ends)
        if ellipses:
            ellipses, ell_ends = _dedupe_ellipses(ellipses, tol, counts)
            ends.append(ell_ends)
        if lines:
            lines, xy = _dedupe_lines(lines, tol, counts)
            tick(done + size // 4, "clean-up: duplicates removed")
            if len(lines) > 1:
                lines, xy = _merge_overlaps(lines, xy, tol, counts)
            tick(done + size // 2, "clean-up: collinear overlaps merged")
            extra = [p for e in others for p in _end_points(e)]
            if extra:
                ends.append(np.asarray(extra, dtype=float))
            lines = _split_t_junctions(lines, xy, np.vstack(ends), tol, counts)
        result.extend(lines)
        result.extend(arcs)
        result.extend(ellipses)
        result.extend(others)
        done += size
        tick(done, "clean-up: T-junctions split")
    counts.edges_after = len(result)
    return result, counts


def _count(counts: CleanupCounts, dxftype: str, n: int = 1) -> None:
    counts.by_type[dxftype] = counts.by_type.get(dxftype, 0) + n


def _rows(rows: Any, n: int, width: int) -> np.ndarray:
    """(n, width) float array from an iterable of flat tuples (``np.fromiter``:
    several times faster than ``np.array`` on nested tuples)."""
    return np.fromiter(chain.from_iterable(rows), float, count=n * width).reshape(n, width)


def _line_array(lines: Sequence[LineEdge]) -> np.ndarray:
    """(n, 4) array of x1, y1, x2, y2."""
    return _rows(chain.from_iterable(map(_START_END, lines)), len(lines), 4)


def _unique_first(rows: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Boolean mask keeping the first (lowest index) of equal integer ``rows``
    among the ``valid`` ones."""
    idx = np.flatnonzero(valid)
    keep = np.zeros(len(rows), dtype=bool)
    if len(idx) == 0:
        return keep
    sub = rows[idx]
    order = np.lexsort(sub.T[::-1])          # stable: equal rows keep index order
    srt = sub[order]
    first = np.ones(len(order), dtype=bool)
    first[1:] = (srt[1:] != srt[:-1]).any(axis=1)
    keep[idx[order[first]]] = True
    return keep


def _unique_points(pts: np.ndarray) -> np.ndarray:
    """Rows of ``pts`` without exact repeats."""
    order = np.lexsort((pts[:, 1], pts[:, 0]))
    srt = pts[order]
    first = np.ones(len(srt), dtype=bool)
    first[1:] = (srt[1:] != srt[:-1]).any(axis=1)
    return srt[first]


def _apply_keep(edges: List[Any], keep: np.ndarray, zero: np.ndarray,
                counts: CleanupCounts) -> List[Any]:
    if keep.all():
        return edges
    for i in np.flatnonzero(~keep).tolist():
        if zero[i]:
            counts.zero_length += 1
        else:
            counts.duplicates += 1
        _count(counts, edges[i].src.dxftype)
    return [edges[i] for i in np.flatnonzero(keep).tolist()]


def _dedupe_arcs(arcs: List[ArcEdge], tol: float, counts: CleanupCounts
                 ) -> Tuple[List[ArcEdge], np.ndarray]:
    """Drop zero-length arcs and duplicates in either direction (vectorised);
    also returns the end points (k, 2) of the kept open arcs."""
    a = _rows(((*e.center, e.radius, e.start_angle, e.sweep) for e in arcs), len(arcs), 5)
    cx, cy, r, a0, sw = a.T
    full = np.abs(sw) >= 360.0 - 1e-9
    zero = r * np.radians(np.abs(sw)) <= ZERO_LENGTH
    ang = np.radians(np.stack([a0, a0 + sw, a0 + 0.5 * sw], axis=1))
    px = cx[:, None] + r[:, None] * np.cos(ang)
    py = cy[:, None] + r[:, None] * np.sin(ang)
    q = np.round(np.stack([cx, cy, r, px[:, 0], py[:, 0], px[:, 1], py[:, 1], px[:, 2], py[:, 2]],
                          axis=1) / tol).astype(np.int64)
    q[full, 3:] = 0
    swap = (q[:, 3] > q[:, 5]) | ((q[:, 3] == q[:, 5]) & (q[:, 4] > q[:, 6]))
    q[swap, 3:7] = q[swap][:, [5, 6, 3, 4]]
    rows = np.hstack([full[:, None].astype(np.int64), q])
    keep = _unique_first(rows, ~zero)
    ends_mask = keep & ~full
    ends = np.vstack([np.stack([px[ends_mask, 0], py[ends_mask, 0]], axis=1),
                      np.stack([px[ends_mask, 1], py[ends_mask, 1]], axis=1)])
    return _apply_keep(arcs, keep, zero, counts), ends


def _dedupe_ellipses(ells: List[EllipseEdge], tol: float, counts: CleanupCounts
                     ) -> Tuple[List[EllipseEdge], np.ndarray]:
    """Drop zero-length and duplicate elliptical arcs (vectorised; params always
    run counter-clockwise, so equal curves have equal end and middle points);
    also returns the end points (k, 2) of the kept open arcs."""
    a = _rows(((*e.center, *e.major_axis, e.ratio, e.start_param, e.end_param) for e in ells),
              len(ells), 7)
    cx, cy, mx, my, ratio, s0, s1 = a.T
    span = s1 - s0
    full = span >= 2 * math.pi - 1e-12
    length = np.hypot(mx, my)
    zero = length * span <= ZERO_LENGTH
    nx, ny = -my * ratio, mx * ratio
    s = np.stack([s0, s1, 0.5 * (s0 + s1)], axis=1)
    px = cx[:, None] + mx[:, None] * np.cos(s) + nx[:, None] * np.sin(s)
    py = cy[:, None] + my[:, None] * np.cos(s) + ny[:, None] * np.sin(s)
    flip = (mx < 0) | ((mx == 0) & (my < 0))        # full ellipse: M and -M are the same
    amx, amy = np.where(full & flip, -mx, mx), np.where(full & flip, -my, my)
    q = np.round(np.stack([cx, cy, length, length * ratio, px[:, 0], py[:, 0], px[:, 1], py[:, 1],
                           px[:, 2], py[:, 2], amx, amy], axis=1) / tol).astype(np.int64)
    q[full, 4:10] = 0
    q[~full, 10:] = 0
    rows = np.hstack([full[:, None].astype(np.int64), q])
    keep = _unique_first(rows, ~zero)
    m = keep & ~full
    ends = np.vstack([np.stack([px[m, 0], py[m, 0]], axis=1), np.stack([px[m, 1], py[m, 1]], axis=1)])
    return _apply_keep(ells, keep, zero, counts), ends


def _dedupe_lines(lines: List[LineEdge], tol: float, counts: CleanupCounts
                  ) -> Tuple[List[LineEdge], np.ndarray]:
    """Drop zero-length lines and duplicates in either direction (vectorised);
    returns the kept lines and their (n, 4) coordinate array."""
    xy = _line_array(lines)
    d = xy[:, 2:] - xy[:, :2]
    zero = np.hypot(d[:, 0], d[:, 1]) <= ZERO_LENGTH
    q = np.round(xy / tol).astype(np.int64)
    a, b = q[:, :2], q[:, 2:]
    swap = (a[:, 0] > b[:, 0]) | ((a[:, 0] == b[:, 0]) & (a[:, 1] > b[:, 1]))
    key = np.where(swap[:, None], np.hstack([b, a]), q)
    keep = _unique_first(key, ~zero)
    return _apply_keep(lines, keep, zero, counts), xy[keep]


# ---------------------------------------------------------------- zero / duplicates (other curves)

def _q(p: Sequence[float], inv: float) -> Tuple[int, int]:
    return (round(p[0] * inv), round(p[1] * inv))


def _drop_zero_and_duplicates(edges: List[Any], tol: float, counts: CleanupCounts) -> List[Any]:
    inv = 1.0 / tol
    seen = set()
    kept = []
    for e in edges:
        key = _key(e, tol, inv)
        if key is None:
            counts.zero_length += 1
            _count(counts, e.src.dxftype)
            continue
        if key in seen:
            counts.duplicates += 1
            _count(counts, e.src.dxftype)
            continue
        seen.add(key)
        kept.append(e)
    return kept


def _key(e: Any, tol: float, inv: float):
    """Direction-free geometric key of a spline (or any other edge kind) on a
    ``tol`` grid; None for zero-length edges."""
    t = type(e)
    if t is SplineEdge:
        if max(math.hypot(p[0] - e.poles[0][0], p[1] - e.poles[0][1]) for p in e.poles) <= ZERO_LENGTH:
            return None
        poles = [_q(p, inv) for p in e.poles]
        w = tuple(round(x, 9) for x in e.weights)
        fwd = (tuple(poles), w)
        rev = (tuple(reversed(poles)), tuple(reversed(w)))
        return ("S", e.degree, min(fwd, rev))
    return ("?", id(e))


def _merge_overlaps(lines: List[LineEdge], xy: np.ndarray, tol: float, counts: CleanupCounts
                    ) -> Tuple[List[LineEdge], np.ndarray]:
    """Replace collinear overlapping lines by their union; returns lines and
    their coordinate array."""
    n = len(lines)
    d = xy[:, 2:] - xy[:, :2]
    theta = np.arctan2(d[:, 1], d[:, 0]) % math.pi
    theta[theta > math.pi - _ANGLE_TOL] -= math.pi
    length = np.hypot(d[:, 0], d[:, 1])
    normal = np.stack([-np.sin(theta), np.cos(theta)], axis=1)
    rho = np.einsum("ij,ij->i", normal, xy[:, :2])
    order = np.lexsort((rho, theta))
    th_sorted = theta[order]
    new_run = np.empty(n, dtype=bool)
    new_run[0] = True
    new_run[1:] = np.diff(th_sorted) > _ANGLE_TOL
    run_id = np.cumsum(new_run)
    # inside each angle run, sort by rho and cut where rho jumps by more than tol
    order = order[np.lexsort((rho[order], run_id))]
    rho_sorted = rho[order]
    run_sorted = np.cumsum(np.r_[True, np.diff(theta[order]) > _ANGLE_TOL])
    brk = np.r_[True, (np.diff(rho_sorted) > tol) | (np.diff(run_sorted) != 0)]
    starts = np.flatnonzero(brk)
    ends = np.r_[starts[1:], n]
    multi = np.flatnonzero(ends - starts > 1)
    multi = multi[_may_overlap(xy, order, starts[multi], ends[multi], tol)]
    replace: Dict[int, List[LineEdge]] = {}
    for k in multi:
        idx = order[starts[k]:ends[k]]
        _resolve_carrier(lines, sorted(idx.tolist()), length, tol, counts, replace)
    if not replace:
        return lines, xy
    out: List[LineEdge] = []
    for i, e in enumerate(lines):
        out.extend(replace.get(i, (e,)))
    return out, _line_array(out)


def _may_overlap(xy: np.ndarray, order: np.ndarray, starts: np.ndarray, ends: np.ndarray,
                 tol: float) -> np.ndarray:
    """Mask over the carrier runs ``order[starts[k]:ends[k]]``: False only where
    :func:`_resolve_carrier` would surely find no overlap, so it is not called
    (on a drawing of many separate parts nearly every run; 1.6 s of 7 s on 100k
    lines).  The same projection onto the run's first line as there, all lines
    of the run, sorted: the first overlap of sorted intervals is always between
    neighbours, and dropping lines (those off the carrier) adds none.  A margin
    of 1e-6 mm covers rounding differences to the exact code."""
    sizes = ends - starts
    if len(sizes) == 0:
        return np.zeros(0, dtype=bool)
    gid = np.repeat(np.arange(len(sizes)), sizes)
    first = np.r_[0, np.cumsum(sizes)[:-1]]
    members = order[np.repeat(starts, sizes) + np.arange(len(gid)) - np.repeat(first, sizes)]
    ref = np.minimum.reduceat(members, first)
    ox, oy = xy[ref, 0], xy[ref, 1]
    ln = np.hypot(xy[ref, 2] - ox, xy[ref, 3] - oy)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux, uy = (xy[ref, 2] - ox) / ln, (xy[ref, 3] - oy) / ln
    px, py, ux, uy = ox[gid], oy[gid], ux[gid], uy[gid]
    a = (xy[members, 0] - px) * ux + (xy[members, 1] - py) * uy
    b = (xy[members, 2] - px) * ux + (xy[members, 3] - py) * uy
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    srt = np.lexsort((lo, gid))
    lo, hi, gid = lo[srt], hi[srt], gid[srt]
    hit = (gid[1:] == gid[:-1]) & ~(lo[1:] >= hi[:-1] - tol + 1e-6)   # NaN: checked
    out = np.zeros(len(sizes), dtype=bool)
    out[gid[1:][hit]] = True
    return out


def _resolve_carrier(lines: List[LineEdge], idx: List[int], length: np.ndarray, tol: float,
                     counts: CleanupCounts, replace: Dict[int, List[LineEdge]]) -> None:
    """Keep the union of collinear lines ``idx`` (original order = ownership)."""
    ref = lines[idx[0]]
    ox, oy = ref.start
    dx, dy = ref.end[0] - ox, ref.end[1] - oy
    ln = math.hypot(dx, dy)
    ux, uy = dx / ln, dy / ln

    def s_of(p):
        return (p[0] - ox) * ux + (p[1] - oy) * uy

    iv = []
    for i in idx:
        e = lines[i]
        a, b = s_of(e.start), s_of(e.end)
        # the line must really lie on the carrier (the sort only bounds rho)
        off = max(abs((p[0] - ox) * uy - (p[1] - oy) * ux) for p in (e.start, e.end))
        if off > tol:
            continue
        iv.append((min(a, b), max(a, b), i, e.start if a <= b else e.end, e.end if a <= b else e.start))
    iv.sort()
    if len(iv) < 2 or not _any_overlap(iv, tol):
        return
    # breakpoints with the original points that define them
    bps: List[Tuple[float, Tuple[float, float]]] = []
    for lo, hi, _, p, q in iv:
        bps.append((lo, p))
        bps.append((hi, q))
    bps.sort(key=lambda x: x[0])
    merged = [bps[0]]
    for s, p in bps[1:]:
        if s - merged[-1][0] > tol:
            merged.append((s, p))
    pieces: Dict[int, List[LineEdge]] = defaultdict(list)
    run_owner, run_start = None, None
    for k in range(len(merged) - 1):
        s0, s1 = merged[k][0], merged[k + 1][0]
        owner = min((i for lo, hi, i, _, _ in iv if lo <= s0 + tol and hi >= s1 - tol), default=None)
        if owner != run_owner:
            if run_owner is not None:
                pieces[run_owner].append(_piece(lines[run_owner], run_start, merged[k][1]))
            run_owner, run_start = owner, merged[k][1]
    if run_owner is not None:
        pieces[run_owner].append(_piece(lines[run_owner], run_start, merged[-1][1]))
    for lo, hi, i, _, _ in iv:
        new = pieces.get(i, [])
        kept = sum(math.hypot(e.end[0] - e.start[0], e.end[1] - e.start[1]) for e in new)
        removed = float(length[i]) - kept
        if removed > tol:
            counts.overlaps += 1
            counts.overlap_length += removed
            _count(counts, lines[i].src.dxftype)
            replace[i] = new


def _any_overlap(iv: List[tuple], tol: float) -> bool:
    """True when sorted intervals overlap by more than ``tol`` somewhere."""
    reach = iv[0][1]
    for lo, hi, *_ in iv[1:]:
        if lo < reach - tol:
            return True
        reach = max(reach, hi)
    return False


def _piece(e: LineEdge, a: Tuple[float, float], b: Tuple[float, float]) -> LineEdge:
    return LineEdge(a, b, e.src)


# ---------------------------------------------------------------- T-junctions

def _split_t_junctions(lines: List[LineEdge], seg: np.ndarray, extra_ends: np.ndarray,
                       tol: float, counts: CleanupCounts) -> List[LineEdge]:
    """Split lines (coordinates ``seg``) where an end point of a line or of
    ``extra_ends`` lies inside them (distance <= ``tol``, more than ``tol`` from
    both ends)."""
    ends = np.vstack([seg.reshape(-1, 2), extra_ends]) if len(extra_ends) else seg.reshape(-1, 2)
    pts = _unique_points(ends)
    lo = np.minimum(seg[:, :2], seg[:, 2:]) - tol
    hi = np.maximum(seg[:, :2], seg[:, 2:]) + tol
    tree = shapely.STRtree(shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1]))
    pi, li = tree.query(shapely.points(pts))     # envelope test only (fast)
    if len(pi) == 0:
        return lines
    px, py = pts[pi, 0], pts[pi, 1]
    x1, y1, x2, y2 = (seg[:, k][li] for k in range(4))
    dx, dy = x2 - x1, y2 - y1
    ln = np.sqrt(dx * dx + dy * dy)
    rx, ry = px - x1, py - y1
    t = (rx * dx + ry * dy) / (ln * ln)
    off = np.abs(rx * dy - ry * dx) / ln
    margin = tol / ln
    inner = (t > margin) & (t < 1.0 - margin) & (off <= tol)
    if not inner.any():
        return lines
    splits: Dict[int, List[Tuple[float, Tuple[float, float]]]] = defaultdict(list)
    for p, l, tt in zip(pi[inner].tolist(), li[inner].tolist(), t[inner].tolist()):
        splits[l].append((tt, (float(pts[p][0]), float(pts[p][1]))))
    out: List[LineEdge] = []
    done = 0
    for i in sorted(splits):
        out.extend(lines[done:i])
        done = i + 1
        e = lines[i]
        cuts = splits[i]
        cuts.sort()
        prev = e.start
        for _, p in cuts:
            if math.hypot(p[0] - prev[0], p[1] - prev[1]) <= tol:
                continue
            out.append(LineEdge(prev, p, e.src))
            counts.t_junctions += 1
            prev = p
        out.append(LineEdge(prev, e.end, e.src))
    out.extend(lines[done:])
    return out


def _end_points(e: Any) -> List[Tuple[float, float]]:
    t = type(e)
    if t is SplineEdge and not e.closed and e.poles:
        return [tuple(e.poles[0]), tuple(e.poles[-1])]
    return []
