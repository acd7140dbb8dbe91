"""The edge graph: end-point snapping, T-junction / overshoot splitting, peeling.

Written by hand in pure Python on purpose: FreeCAD has no call that snaps end
points within a tolerance *without* also merging neighbouring contours
(``connectEdgesToWires`` swallows lead-ins at corners, ``sortEdges`` is greedy at
junctions and 20x slower; see docs/notes).  A hash grid with cells of the join
tolerance finds coincident end points in O(1) per point; degree counting and
iterative peeling of degree-1 edges separate open chains (lead-ins, marks,
unclosed outlines) from the closed part of the graph in linear time.

Invariants: every :class:`Piece` has two node ids; a piece whose ends snap to
the same node is a closed curve (circle, closed spline) and counts 2 towards
that node's degree.  Lengths are mm.
"""

from __future__ import annotations

import math
from collections import defaultdict
from typing import Dict, List, Optional, Tuple

from ..geometry import ArcSeg, CurveSeg, LineSeg, Point, Segment


class Piece:
    """One edge (or part of a split edge) of the graph.

    ``src`` is the index of the drawing edge it comes from, ``seg`` its geometry
    in the drawing's direction, ``curve`` the FreeCAD edge of an unsplit ellipse
    or spline (None otherwise), ``n0``/``n1`` its end nodes."""

    __slots__ = ("src", "seg", "curve", "n0", "n1", "peeled")

    def __init__(self, src: int, seg: Segment, curve=None):
        self.src = src
        self.seg = seg
        self.curve = curve
        self.n0 = -1
        self.n1 = -1
        self.peeled = False


class NodeGrid:
    """Snaps points to nodes: a point within ``tol`` mm of an existing node is
    that node.  Cells of size ``tol`` so only the 3x3 neighbourhood is searched."""

    def __init__(self, tol: float):
        self.tol2 = tol * tol
        self.inv = 1.0 / tol
        self.cells: Dict[Tuple[int, int], List[int]] = {}
        self.pos: List[Point] = []

    def node(self, p: Point) -> int:
        x, y = p
        ix, iy = math.floor(x * self.inv), math.floor(y * self.inv)
        cells, pos, tol2 = self.cells, self.pos, self.tol2
        own = cells.get((ix, iy))
        if own:
            for n in own:
                q = pos[n]
                if (q[0] - x) ** 2 + (q[1] - y) ** 2 <= tol2:
                    return n
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                if dx == 0 and dy == 0:
                    continue
                for n in cells.get((ix + dx, iy + dy), ()):
                    q = pos[n]
                    if (q[0] - x) ** 2 + (q[1] - y) ** 2 <= tol2:
                        return n
        n = len(pos)
        pos.append((x, y))
        if own is None:
            cells[(ix, iy)] = [n]
        else:
            own.append(n)
        return n

    def find(self, p: Point) -> int:
        """The node within the tolerance of ``p``, or -1 (creates nothing)."""
        x, y = p
        ix, iy = math.floor(x * self.inv), math.floor(y * self.inv)
        for dx in (0, -1, 1):
            for dy in (0, -1, 1):
                for n in self.cells.get((ix + dx, iy + dy), ()):
                    q = self.pos[n]
                    if (q[0] - x) ** 2 + (q[1] - y) ** 2 <= self.tol2:
                        return n
        return -1


class Graph:
    """Pieces, nodes and incidence of one drawing (or one pattern piece)."""

    def __init__(self, pieces: List[Piece], tol: float):
        self.tol = tol
        self.grid = NodeGrid(tol)
        self.pieces: List[Piece] = []
        self.adj: Dict[int, List[int]] = defaultdict(list)
        self.live_degree: Dict[int, int] = {}
        for pc in pieces:
            self.add(pc)

    @property
    def pos(self) -> List[Point]:
        return self.grid.pos

    def add(self, pc: Piece) -> int:
        i = len(self.pieces)
        pc.n0 = self.grid.node(pc.seg.start)
        pc.n1 = self.grid.node(pc.seg.end)
        self.pieces.append(pc)
        self.adj[pc.n0].append(i)
        self.adj[pc.n1].append(i)
        return i

    def degree(self, n: int) -> int:
        return len(self.adj.get(n, ()))

    def replace(self, i: int, parts: List[Segment]) -> None:
        """Split piece ``i`` into consecutive segments ``parts`` (same source)."""
        old = self.pieces[i]
        self.adj[old.n0].remove(i)
        self.adj[old.n1].remove(i)
        first = Piece(old.src, parts[0])
        first.n0 = self.grid.node(first.seg.start)
        first.n1 = self.grid.node(first.seg.end)
        self.pieces[i] = first
        self.adj[first.n0].append(i)
        self.adj[first.n1].append(i)
        for seg in parts[1:]:
            self.add(Piece(old.src, seg))

    # ------------------------------------------------------------------
    def split_at_dangling_ends(self, gap_tol: float) -> Tuple[int, int]:
        """Split edges where a dangling end lies on them (T-junction) or where a
        dangling line crosses another line within ``gap_tol`` mm of its free end
        (an overshoot).  Returns (T-junctions, overshoots) split."""
        return self.split_at_nodes([n for n, inc in self.adj.items() if len(inc) == 1], gap_tol)

    def split_at_nodes(self, nodes: List[int], gap_tol: float) -> Tuple[int, int]:
        """Split edges where one of ``nodes`` lies on their interior (T-junction);
        a node that is a dangling line end may also split at an overshoot."""
        dangling = nodes
        if not dangling:
            return 0, 0
        index = _SegmentIndex(self.pieces, self.tol)
        t_count = o_count = 0
        for n in dangling:
            if not self.adj[n]:
                continue
            own = self.adj[n][0]
            p = self.pos[n]
            hit = None
            for j in index.near(p):
                if j in self.adj[n] or j >= len(self.pieces):
                    continue
                pc = self.pieces[j]
                if pc.n0 == n or pc.n1 == n:
                    continue
                split = _split_at_point(pc.seg, p, self.tol)
                if split is not None:
                    hit = (j, split)
                    break
            if hit is not None:
                j, split = hit
                # pin the split point to the dangling node so both meet exactly
                split = [_with_end(split[0], p), _with_start(split[1], p)]
                self.replace(j, split)
                index.update(self.pieces, j)
                t_count += 1
                continue
            seg = self.pieces[own].seg
            if len(self.adj[n]) != 1 or not isinstance(seg, LineSeg) or gap_tol <= 0:
                continue
            cross = self._overshoot(own, n, index, gap_tol)
            if cross is not None:
                j, x = cross
                o_count += 1
                for k in (own, j):
                    s = self.pieces[k].seg
                    self.replace(k, [LineSeg(s.start, x), LineSeg(x, s.end)])
                    index.update(self.pieces, k)
        return t_count, o_count

    def _overshoot(self, own: int, n: int, index: "_SegmentIndex",
                   gap_tol: float) -> Optional[Tuple[int, Point]]:
        seg = self.pieces[own].seg
        free = self.pos[n]
        best = None
        for j in set(index.near(free, gap_tol)):
            if j == own:
                continue
            other = self.pieces[j].seg
            if not isinstance(other, LineSeg):
                continue
            x = _line_cross(seg, other, self.tol)
            if x is None:
                continue
            d = math.hypot(x[0] - free[0], x[1] - free[1])
            if self.tol < d <= gap_tol and (best is None or d < best[0]):
                best = (d, j, x)
        return None if best is None else (best[1], best[2])

    # ------------------------------------------------------------------
    def chain_interior_nodes(self) -> List[int]:
        """Degree-2 nodes whose both edges were peeled (inside open chains)."""
        out = []
        for n, inc in self.adj.items():
            if len(inc) == 2 and all(self.pieces[i].peeled for i in inc):
                out.append(n)
        return out

    def peel(self) -> None:
        """Mark every edge that hangs on a degree-1 node (repeatedly) as peeled."""
        for pc in self.pieces:
            pc.peeled = False
        deg = {n: len(inc) for n, inc in self.adj.items()}
        stack = [n for n, d in deg.items() if d == 1]
        pieces, adj = self.pieces, self.adj
        while stack:
            n = stack.pop()
            if deg[n] != 1:
                continue
            for i in adj[n]:
                pc = pieces[i]
                if not pc.peeled:
                    break
            else:  # pragma: no cover - degree bookkeeping guarantees one
                continue
            pc.peeled = True
            deg[pc.n0] -= 1
            deg[pc.n1] -= 1
            m = pc.n1 if pc.n0 == n else pc.n0
            if deg[m] == 1:
                stack.append(m)
        self.live_degree = deg

    def components(self) -> List[List[int]]:
        """Connected groups of unpeeled pieces (lists of piece indices)."""
        seen = set()
        out = []
        pieces, adj = self.pieces, self.adj
        for i, pc in enumerate(pieces):
            if pc.peeled or i in seen:
                continue
            comp = []
            stack = [i]
            seen.add(i)
            while stack:
                k = stack.pop()
                comp.append(k)
                q = pieces[k]
                for n in (q.n0, q.n1):
                    for j in adj[n]:
                        if j not in seen and not pieces[j].peeled:
                            seen.add(j)
                            stack.append(j)
            out.append(comp)
        return out

    def is_simple_cycle(self, comp: List[int]) -> bool:
        deg = self.live_degree
        for i in comp:
            pc = self.pieces[i]
            if deg[pc.n0] != 2 or deg[pc.n1] != 2:
                return False
        return True

    def walk_cycle(self, comp: List[int]) -> List[Tuple[int, bool]]:
        """Order the pieces of a simple cycle: [(piece index, forward?)]."""
        pieces, adj = self.pieces, self.adj
        first = comp[0]
        pc = pieces[first]
        out = [(first, True)]
        if pc.n0 == pc.n1:
            return out
        node = pc.n1
        prev = first
        while node != pc.n0:
            nxt = next(j for j in adj[node] if j != prev and not pieces[j].peeled)
            q = pieces[nxt]
            fwd = q.n0 == node
            out.append((nxt, fwd))
            node = q.n1 if fwd else q.n0
            prev = nxt
            if len(out) > len(comp):  # pragma: no cover - defensive
                raise RuntimeError("cycle walk did not close")
        return out


def oriented(seg: Segment, forward: bool) -> Segment:
    return seg if forward else seg.reversed()


# ----------------------------------------------------------------------
# Geometry helpers (pure Python: exact for lines and arcs)
# ----------------------------------------------------------------------

class _SegmentIndex:
    """Uniform grid over segment bounding boxes (cell about the median size);
    boxes are kept as tuples so a point query filters without geometry."""

    def __init__(self, pieces: List[Piece], tol: float):
        self.tol = tol
        self.boxes: List[Tuple[float, float, float, float]] = [_seg_bbox(p.seg) for p in pieces]
        step = max(1, len(self.boxes) // 1000)
        sizes = sorted(max(b[2] - b[0], b[3] - b[1]) for b in self.boxes[::step])
        med = sizes[len(sizes) // 2] if sizes else 1.0
        self.cell = max(med, 10 * tol, 1e-6)
        self.cells: Dict[Tuple[int, int], List[int]] = defaultdict(list)
        for i in range(len(self.boxes)):
            self._insert(i)
        self._indexed = len(pieces)

    def _insert(self, i: int) -> None:
        x0, y0, x1, y1 = self.boxes[i]
        t, c = self.tol, self.cell
        ix0, ix1 = math.floor((x0 - t) / c), math.floor((x1 + t) / c)
        iy0, iy1 = math.floor((y0 - t) / c), math.floor((y1 + t) / c)
        cells = self.cells
        if ix0 == ix1 and iy0 == iy1:
            cells[(ix0, iy0)].append(i)
            return
        for ix in range(ix0, ix1 + 1):
            for iy in range(iy0, iy1 + 1):
                cells[(ix, iy)].append(i)

    def update(self, pieces: List[Piece], i: int) -> None:
        """Piece ``i`` was replaced by its first part and the rest appended.
        Stale entries of ``i`` stay (callers re-test geometry anyway)."""
        self.boxes[i] = _seg_bbox(pieces[i].seg)
        self._insert(i)
        for k in range(self._indexed, len(pieces)):
            self.boxes.append(_seg_bbox(pieces[k].seg))
            self._insert(k)
        self._indexed = len(pieces)

    def near(self, p: Point, radius: float = 0.0) -> List[int]:
        """Pieces whose box (grown by the tolerance + ``radius``) holds ``p``."""
        c = self.cell
        x, y = p
        r = self.tol + radius
        out = []
        boxes = self.boxes
        if radius <= 0:
            keys = [(math.floor(x / c), math.floor(y / c))]
        else:
            keys = [(ix, iy) for ix in range(math.floor((x - r) / c), math.floor((x + r) / c) + 1)
                    for iy in range(math.floor((y - r) / c), math.floor((y + r) / c) + 1)]
        for key in keys:
            for j in self.cells.get(key, ()):
                b = boxes[j]
                if b[0] - r <= x <= b[2] + r and b[1] - r <= y <= b[3] + r:
                    out.append(j)
        return out


def _seg_bbox(seg: Segment) -> Tuple[float, float, float, float]:
    if isinstance(seg, LineSeg):
        (ax, ay), (bx, by) = seg.start, seg.end
        return (min(ax, bx), min(ay, by), max(ax, bx), max(ay, by))
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        r = seg.radius
        return (cx - r, cy - r, cx + r, cy + r)
    xs = [p[0] for p in seg.pts]
    ys = [p[1] for p in seg.pts]
    return (min(xs), min(ys), max(xs), max(ys))


def _with_end(seg: Segment, p: Point) -> Segment:
    if isinstance(seg, LineSeg):
        return LineSeg(seg.start, p)
    if isinstance(seg, CurveSeg):
        return CurveSeg(seg.pts[:-1] + (p,), seg.kind)
    return seg


def _with_start(seg: Segment, p: Point) -> Segment:
    if isinstance(seg, LineSeg):
        return LineSeg(p, seg.end)
    if isinstance(seg, CurveSeg):
        return CurveSeg((p,) + seg.pts[1:], seg.kind)
    return seg


def _split_at_point(seg: Segment, p: Point, tol: float) -> Optional[List[Segment]]:
    """Two pieces of ``seg`` split where ``p`` lies on its interior (within
    ``tol`` mm, and farther than ``tol`` from both ends), else None."""
    x, y = p
    if isinstance(seg, LineSeg):
        (ax, ay), (bx, by) = seg.start, seg.end
        dx, dy = bx - ax, by - ay
        n2 = dx * dx + dy * dy
        if n2 <= 0:
            return None
        t = ((x - ax) * dx + (y - ay) * dy) / n2
        n = math.sqrt(n2)
        if t * n <= tol or (1 - t) * n <= tol:
            return None
        if abs((x - ax) * dy - (y - ay) * dx) / n > tol:
            return None
        q = (ax + t * dx, ay + t * dy)
        return [LineSeg(seg.start, q), LineSeg(q, seg.end)]
    if isinstance(seg, ArcSeg):
        cx, cy = seg.center
        if abs(math.hypot(x - cx, y - cy) - seg.radius) > tol:
            return None
        ang = math.degrees(math.atan2(y - cy, x - cx))
        rel = (ang - seg.start_angle) % 360.0 if seg.sweep > 0 else (seg.start_angle - ang) % 360.0
        s = math.radians(rel) * seg.radius
        if s <= tol or seg.length - s <= tol:
            return None
        a, b = seg.split_at(s)
        return [a, b]
    best = None
    pts = seg.pts
    acc = 0.0
    for i in range(len(pts) - 1):
        (ax, ay), (bx, by) = pts[i], pts[i + 1]
        dx, dy = bx - ax, by - ay
        n2 = dx * dx + dy * dy
        n = math.sqrt(n2)
        t = 0.0 if n2 == 0 else min(1.0, max(0.0, ((x - ax) * dx + (y - ay) * dy) / n2))
        d = math.hypot(ax + t * dx - x, ay + t * dy - y)
        if d <= tol and (best is None or d < best[0]):
            best = (d, acc + t * n)
        acc += n
    if best is None or best[1] <= tol or acc - best[1] <= tol:
        return None
    a, b = seg.split_at(best[1])
    return [a, b]


def _line_cross(a: LineSeg, b: LineSeg, tol: float) -> Optional[Point]:
    """Proper crossing point of two lines (interior of both, not at an end)."""
    (x1, y1), (x2, y2) = a.start, a.end
    (x3, y3), (x4, y4) = b.start, b.end
    d = (x2 - x1) * (y4 - y3) - (y2 - y1) * (x4 - x3)
    la = math.hypot(x2 - x1, y2 - y1)
    lb = math.hypot(x4 - x3, y4 - y3)
    if la == 0 or lb == 0 or abs(d) <= 1e-12 * la * lb:
        return None
    t = ((x3 - x1) * (y4 - y3) - (y3 - y1) * (x4 - x3)) / d
    u = ((x3 - x1) * (y2 - y1) - (y3 - y1) * (x2 - x1)) / d
    if t * la <= tol or (1 - t) * la <= tol or u * lb <= tol or (1 - u) * lb <= tol:
        return None
    return (x1 + t * (x2 - x1), y1 + t * (y2 - y1))
