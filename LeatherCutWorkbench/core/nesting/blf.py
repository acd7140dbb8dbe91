"""Constructive placement: bottom-left fill on no-fit polygons.

Pieces are placed one by one in a given order.  For each allowed variant the
feasible region is the container's inner-fit region minus the union of the
NFPs of everything already placed in that container (pyclipper, non-zero
fill).  Every vertex of that region is a candidate -- touching positions,
including the corners where two NFPs cross -- and the candidate with the
smallest right edge (then the lowest, then the leftmost) wins: gravity to the
left, so a strip stays short and a sheet or hide keeps its free material in
one piece on the right.

All coordinates are grid integers; a :class:`Bin` is one container instance
(a strip, one sheet, one hide).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pyclipper

from .hide_shapes import HullPockets, superset_rings
from .nfp import Clock, NfpCache
from .shapes import IntPath, Variant

if TYPE_CHECKING:
    from .hide_regions import HideRegions

_NZ = pyclipper.PFT_NONZERO


@dataclass
class BinSpec:
    """A container instance in grid units.

    ``rect`` (x0, y0, x1, y1) is the usable rectangle of a sheet or strip (after
    the margin; a strip's x1 is ignored: it is open).  A hide has ``regions``:
    per grade, the (outers, obstacles) rings of the material that grade may use
    (after margins), turned into inner-fit regions per variant on demand, and
    ``material``: the area of the largest region (a copy larger than what is
    left of it cannot fit, so no inner-fit region is computed for it);
    ``coarse``: per grade a subset of the region with few vertices and convex
    obstacles, used under time pressure.

    ``prep`` (hides): a :class:`hide_regions.HideRegions` that builds them
    when first needed: ``material`` and ``grade_key`` when :meth:`ready` is
    first called -- the fill calls it when it opens the hide, so a hide the
    search never tries is never prepared --, each region key's exact region
    on its first :meth:`region`, its coarse one on its first :meth:`coarse_region`
    (a fill under time pressure builds no exact region).  With ``prep`` None
    the fields are already set."""

    kind: str
    rect: Tuple[int, int, int, int] = (0, 0, 0, 0)
    regions: Dict[int, Tuple[List[IntPath], List[IntPath]]] = field(default_factory=dict)
    grade_key: Dict[int, int] = field(default_factory=dict)   # part grade -> region key
    material: float = math.inf    # hide: usable area (grid units^2) of its largest region
    coarse: Dict[int, Optional[Tuple[List[IntPath], List[IntPath]]]] = field(default_factory=dict)
    prep: Optional[HideRegions] = None
    _opened: bool = field(default=False, repr=False, compare=False)

    def ready(self) -> "BinSpec":
        """This spec with ``material`` and ``grade_key`` set (once; see ``prep``)."""
        if self.prep is not None and not self._opened:
            self.material = self.prep.material()
            self.grade_key = self.prep.keys()
            self._opened = True
        return self

    def region(self, key: int) -> Tuple[List[IntPath], List[IntPath]]:
        """The exact (outers, obstacles) of region ``key`` (built on first use)."""
        hit = self.regions.get(key)
        if hit is None and self.prep is not None:
            hit = self.regions[key] = self.prep.exact(key)
        return hit if hit is not None else ([], [])

    def coarse_region(self, key: int) -> Optional[Tuple[List[IntPath], List[IntPath]]]:
        """The coarse subset of region ``key`` (built on first use; None: empty region)."""
        if key not in self.coarse and self.prep is not None:
            self.coarse[key] = self.prep.coarse(key)
        return self.coarse.get(key)


class Placer:
    """Bottom-left fill of item sequences into bins (see module doc)."""

    def __init__(self, variants: Sequence[Variant], type_variants: Sequence[Sequence[int]],
                 type_grade: Sequence[int], bins: Sequence[BinSpec], open_new: bool,
                 max_bins: Optional[int], nfps: Optional[NfpCache] = None,
                 clock: Optional[Clock] = None, type_area: Optional[Sequence[float]] = None,
                 region_check=None):
        self.variants = variants
        self.type_variants = type_variants
        self.type_grade = type_grade
        self.bin_specs = list(bins)
        self.open_new = open_new
        self.max_bins = max_bins
        self.nfps = nfps or NfpCache(variants, clock)
        self.clock = self.nfps.clock
        self.type_area = type_area       # true part areas, grid units^2 (for the hide prune)
        #: hides: :class:`part_regions.RegionCheck` for parts with graded regions (or None)
        self.region_check = region_check
        #: default ``variant_cap`` of :meth:`place` (None: every orientation)
        self.variant_cap: Optional[int] = None
        #: "x": the candidate with the smallest right edge wins (module doc);
        #: hides only (bins are never closed by extent): "y" the lowest top edge,
        #: "-x" the right-most left edge, "-y" the highest bottom edge (the
        #: fill packs from that side of the hide; :mod:`hide_assign` picks one per hide)
        self.gravity = "x"
        #: hides: spec index per fill position (None: in the given order)
        self.bin_order: Optional[List[int]] = None
        self._ifp_cache: Dict[Tuple[int, int, bool], List[IntPath]] = {}
        self._ob_forms: Dict[tuple, list] = {}    # (bin region, exact) -> obstacle edge forms
        self._pockets: Dict[tuple, HullPockets] = {}   # (bin region, exact) -> hull and pockets
        self._region_rings: Dict[int, list] = {}  # variant -> its graded regions' (grade, ring)
        #: hides: inner-fit regions of the part's own outline against the hide
        #: outline's pockets (exact: a concave part may reach round a concave
        #: stretch of the outline) instead of its convex hull's (a subset, about
        #: half the time; see :meth:`_ifp`)
        self.concave_fit = False
        #: hides: a part with graded regions is placed as if it were wholly of
        #: its strictest region's grade (a subset of where it may lie), so no
        #: candidate needs the per-position region test (:meth:`best_position`):
        #: worker 0's quick first fill (Baldacci Test10: the tests' forbidden
        #: material took 0.3 of its 1.3 s)
        self.whole_grade = False

    # ---------------------------------------------------------------- regions
    def _spec_index(self, b: int) -> int:
        """The container spec of the bin at position ``b`` (hides: through
        ``bin_order``, the order in which the fill opens them)."""
        if self.bin_order is not None and b < len(self.bin_order):
            return self.bin_order[b]
        return min(b, len(self.bin_specs) - 1)

    def _spec(self, b: int) -> BinSpec:
        """The spec of bin position ``b``, its hide regions built (:meth:`BinSpec.ready`)."""
        return self.bin_specs[self._spec_index(b)].ready()

    def _ifp(self, b: int, v: Variant, extent: int) -> List[IntPath]:
        """Inner-fit region of ``v`` in bin ``b`` (a strip is open up to ``extent``)."""
        spec = self._spec(b)
        if spec.kind == "hide":
            from .nfp import region_ifp
            rc = self.region_check
            g = self.type_grade[v.type_index]
            if self.whole_grade and rc is not None and rc.applies(v.type_index):
                g = max(g, rc.strictest(v.type_index))
            rk = spec.grade_key.get(g, 0)
            cf = self.concave_fit
            key = (self._spec_index(b) * 100003 + rk, v.index, True, cf)
            hit = self._ifp_cache.get(key)
            if hit is None:
                # out of time: the coarse region (fewer vertices, convex defects)
                # and the part's convex hull against the defects too (one convex sum each)
                exact = self.clock.exact()
                key = key[:2] + (exact, cf)
                hit = self._ifp_cache.get(key)
                if hit is None:
                    rough = None if exact else spec.coarse_region(rk)
                    outers, obstacles = spec.region(rk) if rough is None else rough
                    # exact: the true ring against the defects; its convex hull in the
                    # hull of the hide, minus the pockets (a hide is nearly convex) --
                    # the sums with the pockets of its convex hull, or with
                    # ``concave_fit`` of its own convex pieces (exact)
                    forms, pockets = self._region_forms((key[0], rough is None), outers,
                                                        obstacles)
                    hit = region_ifp(outers, obstacles, v.core if exact else v.core_hull,
                                     forms, fits=pockets.ifp(v.core_hull,
                                                             v.core if cf and exact else None))
                    if exact and hit and rc is not None and rc.applies(v.type_index):
                        hit = self._region_fit(self._spec_index(b), hit, rc, v)
                    self._ifp_cache[key] = hit
            return hit
        x0, y0, x1, y1 = spec.rect
        if spec.kind == "strip":
            x1 = extent
        lx, hx = x0 - v.bbox[0], x1 - v.bbox[2]
        ly, hy = y0 - v.bbox[1], y1 - v.bbox[3]
        if lx > hx or ly > hy:
            return []
        return [[[lx, ly], [hx, ly], [hx, hy], [lx, hy]]]

    def hide_ifp(self, spec_index: int, vi: int, concave: bool = False) -> List[IntPath]:
        """Inner-fit region of variant ``vi`` on hide ``spec_index`` (cached;
        for :mod:`hide_separation`): its convex hull against the hide outline
        even with ``concave_fit`` (a subset of the exact region, with fewer
        vertices: on two stuck Baldacci Test2 states the separation fitted a
        left-out copy in 3 of 8 seeded tries with these regions, 1 of 8 with
        the exact ones); ``concave``: the exact region (:attr:`concave_fit`)."""
        saved = self.bin_order, self.concave_fit
        self.bin_order, self.concave_fit = [spec_index], concave
        try:
            return self._ifp(0, self.variants[vi], _OPEN_STRIP)
        finally:
            self.bin_order, self.concave_fit = saved

    def _region_forms(self, fk: tuple, outers: List[IntPath],
                      obstacles: List[IntPath]) -> Tuple[list, HullPockets]:
        """The obstacle edge forms and the hull and pockets of a hide region,
        built once per ``fk`` = (hide spec index * 100003 + region key, exact)."""
        from .nfp import obstacle_forms
        if fk not in self._ob_forms:
            self._ob_forms[fk] = [obstacle_forms(ob) for ob in obstacles]
        if fk not in self._pockets:
            self._pockets[fk] = HullPockets(outers)
        return self._ob_forms[fk], self._pockets[fk]

    def _region_fit(self, sb: int, fit: List[IntPath], rc, v: Variant) -> List[IntPath]:
        """``fit`` cut down to where each stricter region of ``v``'s part lies in
        the region of its grade on hide spec ``sb`` (exact, zone borders need no
        margin).  The region's hull, pockets and obstacle forms are kept per hide
        and grade (:class:`HullPockets` with the ring's own convex pieces instead
        of a sweep along the hide outline), and each region ring is replaced
        by a ring containing it with few vertices (:func:`hide_shapes.superset_rings`,
        as the variants' outlines are): Baldacci Test10's 200-400-vertex
        region rings (60-100 convex pieces) took ~1 s per hide and variant."""
        from .nfp import region_ifp
        from .shapes import convex_hull
        spec = self.bin_specs[sb].ready()
        rings = self._region_rings.get(v.index)
        if rings is None:
            rings = self._region_rings[v.index] = superset_rings(
                rc.grid_rings(v.type_index, v.angle, v.mirrored), v)
        for g, ring in rings:
            rk = spec.grade_key.get(g, g)
            outers, obstacles = spec.region(rk)
            forms, pockets = self._region_forms((sb * 100003 + rk, True), outers, obstacles)
            inner = region_ifp(outers, obstacles, ring, forms,
                               fits=pockets.ifp(convex_hull(ring), ring))
            if not inner:
                return []
            c = pyclipper.Pyclipper()
            c.AddPaths(fit, pyclipper.PT_SUBJECT, True)
            c.AddPaths(inner, pyclipper.PT_CLIP, True)
            fit = c.Execute(pyclipper.CT_INTERSECTION, _NZ, _NZ)
            if not fit:
                return []
        return fit

    def _may_fit(self, b: int, state: "BinState", t: int) -> bool:
        """False when a copy of type ``t`` is larger than the material left on
        hide ``b`` (exact: placed copies lie in the material, disjointly)."""
        spec = self._spec(b)
        if spec.kind != "hide" or self.type_area is None or spec.material == math.inf:
            return True
        used = sum(self.type_area[self.variants[u].type_index] for (u, _x, _y) in state.placed)
        return self.type_area[t] <= spec.material - used

    def _can_open(self, n: int) -> bool:
        """May an (n+1)-th bin be opened?"""
        if self.max_bins is not None:
            return n < self.max_bins
        return self.open_new or n < len(self.bin_specs)

    # -------------------------------------------------------------- placement
    def _new_bin(self, b: int) -> "BinState":
        return BinState(placed=(), extent=self._spec(b).rect[0], free={})

    def free_region(self, b: int, state: "BinState", vi: int) -> List[IntPath]:
        """Translations of variant ``vi`` that fit bin ``b`` next to everything
        placed so far.  Kept per variant and updated lazily: only the NFPs of
        pieces placed since the last query are cut away (one clip operation)."""
        hit = state.free.get(vi)
        if hit is None:
            region = [r for r in self._ifp(b, self.variants[vi], _OPEN_STRIP)
                      if len(r) >= 3 and pyclipper.Area(r) != 0]
            done = 0
        else:
            region, done = hit
        n = len(state.placed)
        if done < n and region:
            clips = []
            for (u, tx, ty) in state.placed[done:]:
                paths, _ = self.nfps.get(u, vi)
                off = np.array([tx, ty], dtype=np.int64)
                clips.extend((p + off) for p in paths)
            c = pyclipper.Pyclipper()
            c.AddPaths(region, pyclipper.PT_SUBJECT, True)
            c.AddPaths(clips, pyclipper.PT_CLIP, True)
            region = c.Execute(pyclipper.CT_DIFFERENCE, _NZ, _NZ)
        state.free[vi] = (region, n)
        return region

    def best_position(self, b: int, state: "BinState", vi: int) -> Optional[Tuple[int, int, int]]:
        """Best (key, x, y) candidate of variant ``vi`` in bin ``b`` or None; the
        key is the edge :attr:`gravity` minimises (lower is better; "x": the
        right edge)."""
        free = self.free_region(b, state, vi)
        if not free:
            return None
        v = self.variants[vi]
        pts = np.array([q for p in free for q in p], dtype=np.int64)
        right = pts[:, 0] + v.bbox[2]
        rc = self.region_check
        if rc is not None and rc.applies(v.type_index) and not self.whole_grade:
            # a part with graded regions: the best candidate whose stricter
            # regions lie on good enough material (at most _REGION_TRIES tested)
            sb = self._spec_index(b)
            for k in np.lexsort((pts[:, 0], pts[:, 1], right))[:_REGION_TRIES]:
                if rc.ok(sb, v.type_index, v.angle, v.mirrored, int(pts[k, 0]), int(pts[k, 1])):
                    return int(right[k]), int(pts[k, 0]), int(pts[k, 1])
            return None
        g = self.gravity
        if g == "y":                      # lowest top edge, then leftmost
            top = pts[:, 1] + v.bbox[3]
            k = np.lexsort((pts[:, 0], top))[0]
            return int(top[k]), int(pts[k, 0]), int(pts[k, 1])
        if g == "-y":                     # highest bottom edge, then rightmost
            key = -(pts[:, 1] + v.bbox[1])
            k = np.lexsort((-pts[:, 0], key))[0]
            return int(key[k]), int(pts[k, 0]), int(pts[k, 1])
        if g == "-x":                     # rightmost left edge, then highest
            key = -(pts[:, 0] + v.bbox[0])
            k = np.lexsort((-pts[:, 1], key))[0]
            return int(key[k]), int(pts[k, 0]), int(pts[k, 1])
        k = np.lexsort((pts[:, 0], pts[:, 1], right))[0]
        return int(right[k]), int(pts[k, 0]), int(pts[k, 1])

    def place(self, sequence: Sequence[Tuple[int, Optional[int]]],
              prefix: Optional["Trace"] = None, keep: int = 0,
              give_up: Optional[Tuple[float, Sequence[float]]] = None,
              abortable: bool = True, variant_cap: Optional[int] = None) -> Optional["Trace"]:
        """Place ``sequence`` (type index, forced variant or None) in order.

        Returns None when the fill is abandoned: it left out more area than
        ``give_up`` = (limit, area per type) allows, or (``abortable``) the
        clock's ``stop_at`` passed.  ``variant_cap``: a copy without a forced
        variant tries at most this many orientations of its part, evenly
        spread (a quick first fill of freely turning parts).

        With ``prefix`` (the trace of an earlier call) and ``keep`` = k, the first
        k items are taken as placed there (the search changes only later items).
        Returns the trace: placements (seq index, bin, variant, x, y; bin -1 =
        unplaced) and the bin states before each item."""
        if prefix is not None and keep > 0:
            placements = list(prefix.placements[:keep])
            states = list(prefix.states[:keep + 1])
            bins = [bs.copy() for bs in prefix.states[keep]]
        else:
            placements, states, bins = [], [], [self._new_bin(0)]
            states.append(tuple(bs.copy() for bs in bins))
        left_out = 0.0
        if give_up is not None:
            left_out = sum(give_up[1][sequence[p[0]][0]] for p in placements if p[1] < 0)
        for si in range(len(placements), len(sequence)):
            if abortable and self.clock.expired():
                return None
            t, forced = sequence[si]
            if not abortable and time.monotonic() > self.clock.give_up_at:
                placements.append((si, -1, -1, 0, 0))     # out of time: left unplaced
                states.append(tuple(bs.copy() for bs in bins))
                continue
            cands = [forced] if forced is not None else self.type_variants[t]
            cap = variant_cap if variant_cap is not None else self.variant_cap
            if forced is None and cap is not None and len(cands) > cap:
                cands = [cands[(k * len(cands)) // cap] for k in range(cap)]
            done = False
            b = 0
            while True:
                if b == len(bins):
                    if not self._can_open(len(bins)):
                        break
                    bins.append(self._new_bin(b))
                best = None
                for vi in (cands if self._may_fit(b, bins[b], t) else ()):
                    if not abortable and time.monotonic() > self.clock.give_up_at:
                        break               # out of time: the orientations tried so far
                    r = self.best_position(b, bins[b], vi)
                    if r is not None and (best is None or r < best[0]):
                        best = (r, vi)
                if best is not None:
                    (right, tx, ty), vi = best
                    bs = bins[b]
                    bins[b] = BinState(bs.placed + ((vi, tx, ty),), max(bs.extent, right), bs.free)
                    placements.append((si, b, vi, tx, ty))
                    done = True
                    break
                if not bins[b].placed and self._spec(b).kind != "hide":
                    break                   # does not fit an empty sheet: nowhere
                b += 1
            if not done:
                placements.append((si, -1, -1, 0, 0))
                if give_up is not None:
                    left_out += give_up[1][t]
                    if left_out > give_up[0] + 1e-9:
                        return None
            states.append(tuple(bs.copy() for bs in bins))
        return Trace(placements, states)


#: Candidate positions tested per variant and bin for a part with graded regions.
_REGION_TRIES = 64

#: Open strips are searched up to this x (grid units) -- far beyond any layout.
_OPEN_STRIP = 1 << 40


@dataclass
class BinState:
    """What one bin holds: placed (variant, x, y), the right-most edge, and the
    cached free regions per variant (shared between states, never mutated)."""

    placed: tuple
    extent: int
    free: Dict[int, Tuple[List[IntPath], int]]

    def copy(self) -> "BinState":
        return BinState(self.placed, self.extent, dict(self.free))


@dataclass
class Trace:
    placements: List[Tuple[int, int, int, int, int]]
    states: List[tuple]

    @property
    def unplaced(self) -> List[int]:
        return [p[0] for p in self.placements if p[1] < 0]
