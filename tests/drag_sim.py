"""A drag knife simulated from a written machine file: where does the blade tip go?

The tip trails the swivel axis by the blade offset r: whenever the axis moves,
the tip is pulled along the line towards it and stays at distance r (a
tractrix follower: an ideal caster blade).  The blade keeps its direction while the knife is up.
Independent of post/drag_knife.py: it only reads the axis path back from the
HP-GL / G-code text.
"""

from __future__ import annotations

import math
from typing import List, Sequence, Tuple

import numpy as np

from LeatherCutWorkbench.core.geometry import Point

SAMPLE = 0.05           # mm between reported tip positions while the blade settles
SETTLED = 5.0           # blade offsets of travel after which the blade is settled
LONG_SAMPLE = 1.0       # mm between reported tip positions after that


def simulate(strokes: Sequence[Sequence[Point]], r: float, start_heading: float = 0.0
             ) -> List[np.ndarray]:
    """Tip positions (one array per knife-down stroke) for axis ``strokes`` (mm).

    Along a straight axis move the follower is a tractrix, solved exactly: the
    angle phi between the blade and the move obeys
    tan(phi / 2) = tan(phi0 / 2) * exp(-s / r) after s mm of travel."""
    bh = math.radians(start_heading)          # blade direction: tip -> axis
    tips: List[np.ndarray] = []
    for stroke in strokes:
        out = [(stroke[0][0] - r * math.cos(bh), stroke[0][1] - r * math.sin(bh))]
        for a, b in zip(stroke, stroke[1:]):
            length = math.dist(a, b)
            if length < 1e-12:
                continue
            e = math.atan2(b[1] - a[1], b[0] - a[0])
            phi0 = (bh - e + math.pi) % (2 * math.pi) - math.pi
            if length <= SAMPLE:          # short move: its end is enough (and fast)
                phi1 = 2.0 * math.atan(math.tan(phi0 / 2.0) * math.exp(-length / r))
                bh = e + phi1
                out.append((b[0] - r * math.cos(bh), b[1] - r * math.sin(bh)))
                continue
            near = min(length, SETTLED * r)
            s = np.linspace(near / (int(near / SAMPLE) + 1), near, int(near / SAMPLE) + 1)
            if length > near:
                s = np.concatenate([s, np.linspace(near, length, int((length - near) / LONG_SAMPLE) + 2)[1:]])
            phi = 2.0 * np.arctan(math.tan(phi0 / 2.0) * np.exp(-s / r))
            ax = a[0] + s * math.cos(e)
            ay = a[1] + s * math.sin(e)
            out.extend(zip(ax - r * np.cos(e + phi), ay - r * np.sin(e + phi)))
            bh = e + float(phi[-1])
        tips.append(np.array(out))
    return tips


def gcode_strokes(text: str, profile) -> List[List[Point]]:
    """Knife-down axis paths of a G-code program (arcs as chords within 1e-6 mm),
    traced by the project's G-code interpreter; the knife is down while the
    lift axis (``profile.lift_axis``) is below zero."""
    from LeatherCutWorkbench.post.gcode_reader import interpreter_for

    it = interpreter_for(profile)
    strokes: List[List[Point]] = []
    cur: List[Point] = []
    down = False
    lift = profile.lift_axis
    for n, line in enumerate(text.splitlines(), 1):
        for m in it.execute(line, n):
            if lift and m.kind in ("rapid", "line") and m.end.get(lift, 0.0) != m.start.get(lift, 0.0):
                down = m.end[lift] < 0.0
                if not down and cur:
                    strokes.append(cur)
                    cur = []
                continue
            if m.kind == "rapid" or not down:
                continue
            a = (m.start["X"], m.start["Y"])
            e = (m.end["X"], m.end["Y"])
            if not cur:
                cur = [a]
            if m.kind == "arc":
                cx, cy = m.center
                rad = math.hypot(a[0] - cx, a[1] - cy)
                a0 = math.atan2(a[1] - cy, a[0] - cx)
                a1 = math.atan2(e[1] - cy, e[0] - cx)
                sw = (a1 - a0) % (2 * math.pi) if m.ccw else -((a0 - a1) % (2 * math.pi))
                if abs(sw) < 1e-12:
                    sw = 2 * math.pi if m.ccw else -2 * math.pi
                k = max(2, int(math.ceil(abs(sw) / (2.0 * math.sqrt(2e-6 / rad)))))
                cur.extend((cx + rad * math.cos(a0 + sw * i / k), cy + rad * math.sin(a0 + sw * i / k))
                           for i in range(1, k + 1))
            else:
                cur.append(e)
    if cur:
        strokes.append(cur)
    return strokes


def drawn_lines(plan, chord_tol: float = 0.001):
    """The drawn paths of ``plan`` as shapely two-point lines (chords within
    ``chord_tol`` mm of arcs), which keeps nearest-distance queries fast."""
    import shapely

    from LeatherCutWorkbench.core.geometry import path_points

    chords = []
    for it in plan.items:
        for s in it.segments:
            pts = path_points([s], chord_tol)
            chords += [(a, b) for a, b in zip(pts, pts[1:])]
    return shapely.linestrings(np.asarray(chords))


def nearest_distance(lines, pts: np.ndarray) -> np.ndarray:
    """Distance (mm) from every point to the nearest of ``lines``."""
    import shapely

    tree = shapely.STRtree(lines)
    (_, _), d = tree.query_nearest(shapely.points(pts), return_distance=True, all_matches=False)
    return d


def swivel_corners(plan, swivel_angle: float) -> List[Point]:
    """Where a compensated drag knife swivels: every entry point and every
    joint of the drawn items whose heading turns by more than ``swivel_angle``."""
    from LeatherCutWorkbench.core.geometry import CurveSeg, LineSeg, turn_angle

    out: List[Point] = []
    for it in plan.items:
        pieces = []
        for s in it.segments:
            if isinstance(s, CurveSeg):
                pieces += [LineSeg(a, b) for a, b in zip(s.pts, s.pts[1:]) if math.dist(a, b) > 1e-9]
            elif s.length > 1e-9:
                pieces.append(s)
        if not pieces:
            continue
        out.append(pieces[0].start)
        for p, q in zip(pieces, pieces[1:]):
            if turn_angle(p.end_heading(), q.start_heading()) > swivel_angle + 1e-9:
                out.append(q.start)
    return out


def split_deviation(tips: Sequence[np.ndarray], drawn, corners: Sequence[Point], radius: float
                    ) -> Tuple[float, float]:
    """(largest deviation away from the swivel corners, largest within ``radius``
    mm of one), mm: tip positions near a swivel arc are measured separately."""
    import shapely

    pts = np.vstack(tips)
    d = nearest_distance(drawn, pts)
    near = np.zeros(len(pts), dtype=bool)
    if corners:
        tree = shapely.STRtree(shapely.points(pts))
        idx = tree.query(shapely.points(np.asarray(corners)), predicate="dwithin",
                         distance=radius)
        near[np.unique(idx[1])] = True
    away = d[~near]
    return (float(away.max()) if away.size else 0.0, float(d[near].max()) if near.any() else 0.0)
