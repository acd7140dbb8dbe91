"""Strip improvement phase: shrink the strip, then separate the overlaps.

:func:`improve_strip` takes a valid strip layout (the engine's best) and,
until the deadline, repeatedly

1. closes the strip a little shorter than a valid layout: the copies right
   of a random vertical cut move left by the difference (sparrow's shrink),
   everything is pushed back inside, which creates overlaps;
2. runs the separator (:mod:`separation`: guided local search over the
   penetration depths of :mod:`overlap`) until no pair overlaps;
3. *exploration* (the first ``1 - COMPRESSION_SHARE`` of the time,
   :func:`_explore`): each worker keeps its own infeasible layout at its
   target length.  A failed separation joins a pool of the least-overlapping
   failures at that target; the next try starts from one of them (the better
   ones more likely) with two large copies swapped, at the same target
   (sparrow's exploration: the target never moves up).  On success the
   layout is the new best and the next target lies ``EXPLORE_SHRINK`` below it.
   *Compression* (the rest, :func:`_compress`): shrinks of 0.05 % down to
   0.002 % of the best valid layout, back to it after each failure.

Several worker threads (``options.workers``, default all cores up to 8)
run this loop with their own random streams and share the best layout: a
worker drops a separation as soon as another one has reached its target
length and goes on from that layout (each compression shrink starts from the
shortest strip any of them has found).  The
result is re-checked by the independent :func:`checker.check_layout`; if it
is not valid or not shorter, the input layout is returned unchanged, so the
phase can never make a layout worse.  Before that check, each kept layout
moves every copy left where it fits (:mod:`compaction`): that can only
shorten the strip.  Only there: compacting every separated layout (the next
target then starting from the compacted strip), in all workers or in every
other one, raised fu and shirts but lost albano below spyrrow on one seed in
three (docs/BENCHMARKS.md).

Lengths: mm in the :class:`Layout`, the engine's integer grid inside.
"""

from __future__ import annotations

import copy
import dataclasses
import importlib
import importlib.util
import math
import os
import threading
import time
from concurrent.futures import ThreadPoolExecutor, wait
from typing import TYPE_CHECKING, Callable, List, Optional, Sequence, Tuple

import numpy as np

from ..model import Container, Layout, Part, Placement
from ..progress import ProgressFn, report
from . import tail
from .options import ContainerSpec, NestOptions
from .shapes import _same_shape, make_variants, piece_from_part, transform_ring

if TYPE_CHECKING:
    from .separation import Separator


def _kernels() -> bool:
    """Can the separation kernels (numba: :mod:`overlap`, :mod:`separation`,
    :mod:`compaction`) be
    imported?  (Imported here on first use, after the engine's search, so no
    nest imports numba before its first layout; False e.g. in a bare FreeCAD
    Python, where the engine runs alone.)"""
    try:
        for name in ("overlap", "separation", "compaction"):
            importlib.import_module(f".{name}", __package__)
    except ImportError:       # pragma: no cover - the project's venv always has numba
        return False
    return True

#: the longest container or part dimension spans this many grid units
GRID_UNITS = 1.0e6
#: share of the time budget the engine's own search gets before this phase (:func:`nest_compacted`)
SEARCH_SHARE = 0.25
#: with more copies than this the engine's share shrinks in proportion (down to
#: ``MIN_SEARCH_SHARE``): its search slows with the number of copies while the
#: phase's moves stay local (measured: shirts, 99 copies, got a 0.9 % shorter
#: strip at 60 s from a 6 s search than from a 15 s one; albano, 24 copies, the reverse)
SHARE_COPIES = 40
MIN_SEARCH_SHARE = 0.08
#: on sheets the engine's search decides the number of sheets (the phase only
#: shortens the last one): it may use the whole budget and ends only at its
#: plateau, no fewer sheets or shorter last sheet for this share of the budget;
#: the phase gets what is left (a fixed 75 % share left WM_SLIM_TANK at T = 10
#: on 9 sheets with 2.7 s unused, because its last sheet holds one copy)
SHEET_STALL_SHARE = 0.2
#: ... and not before this share of the budget: until then the other workers
#: make their first, exact fills (``engine._deadlines``: 40 % of T), so a
#: plateau may be worker 0's quick layout alone (WM_SLIM_TANK at T = 10 in 3
#: of 4 runs of one benchmark: 9 sheets at 1.1 s, the search ended at 3.1 s
#: and 6.7 s went unused; 7 sheets when worker 1's first layout came in time)
SHEET_MIN_SEARCH_SHARE = 0.4
#: on a strip the engine's search also ends once it has not found a shorter
#: layout for this share of the budget (at least ``STALL_MIN_S``): it reaches
#: its plateau in a few seconds (measured: shirts 3.6 s, shapes0 5.2 s, fu
#: 6.8 s, albano 4.1 s of a 15 s search), the phase keeps gaining after that
#: (albano at 60 s: the phase's first 2 s shorten the engine's layout by 2.8-3.2 %;
#: 0.05 of the budget left the engine searching 4-8 s of 60 s, 0.02 ends it at 2-3 s)
STALL_SHARE = 0.02
STALL_MIN_S = 1.0
#: the phase needs the no-fit polygon of every ordered pair of orientations: it
#: skips jobs with more (e.g. 100 parts with free rotation every 30 degrees)
MAX_PAIRS = 40000
SHRINK_BACKOFF = 0.5
#: overlap-free layouts each worker keeps for the final check
KEEP = 6
COMPRESSION_SHARE = 0.2
COMPRESS_MAX = 0.0005
COMPRESS_MIN = 0.00002
SWAP_P = 0.5
#: exploration (:func:`_explore`): each target lies this share of the length
#: below the best valid layout, whatever the failures (sparrow's fixed 0.1 %;
#: measured against 0.4 % halving after two failures down to 0.02 %, 60 s, both
#: variants at the same time: albano +0.37 / +0.02 / +0.24 / -0.07 points on
#: seeds 1-4, fu +0.38, shirts +1.76 / -0.10, shapes0 -1.18 / 0.00), the failed
#: layouts kept per target, and the spread of the pick (|N(0, POOL_STDDEV)| x
#: pool size; sparrow's default 0.25)
EXPLORE_SHRINK = 0.001
POOL_SIZE = 20
POOL_STDDEV = 0.25


class _Instance:
    """Copies of a strip layout in the separator's terms (grid units)."""

    def __init__(self, layout: Layout, parts: Sequence[Part], options: NestOptions):
        spec = options.container
        self.options = options
        pieces = [piece_from_part(p, options.chord_tol, options.rotation_step,
                                  options.part_rotations(p.rotations), options.mirror_override)
                  for p in parts]
        dims = [spec.height] + [float(abs(t.outer).max()) * 2.0 for t in pieces]
        length = float(layout.metrics.get("strip_length_mm", 0.0))
        self.scale = s = max(GRID_UNITS / max(max(dims + [length]), 1e-9), 10.0 / options.tolerance)
        self.pieces = pieces
        half_gap = options.spacing / 2.0
        self.variants = make_variants(pieces, s, half_gap, options.chord_tol)
        self.choices = [[v.index for v in self.variants if v.type_index == t] for t in range(len(pieces))]
        core = [np.asarray(v.core, dtype=np.float64) for v in self.variants]
        self.cb = np.array([[c[:, 0].min(), c[:, 1].min(), c[:, 0].max(), c[:, 1].max()] for c in core])
        ob = np.array([v.bbox for v in self.variants], dtype=np.float64)
        self.pad = float(np.abs(ob - self.cb).max())       # inflated outline beyond the core box
        key = {t.key: k for k, t in enumerate(pieces)}
        m = options.margin
        self.x0, self.y0, self.y1 = m * s, m * s, (spec.height - m) * s
        # overlaps up to a quarter of the checker's tolerance are contact (the
        # engine's own rounding leaves such touching pairs)
        self.eps = 0.25 * options.tolerance * s
        n = len(layout.placements)
        self.X, self.Y = np.zeros(n), np.zeros(n)
        self.V = np.zeros(n, dtype=np.int64)
        self.types = np.zeros(n, dtype=np.int64)
        self.ok = True
        for i, pl in enumerate(layout.placements):
            t = key.get(pl.part_id)
            found = None if t is None else self._variant_of(t, pl)
            if found is None:
                self.ok = False
                return
            self.types[i], (self.V[i], self.X[i], self.Y[i]) = t, found

    def _variant_of(self, t: int, pl: Placement) -> Optional[Tuple[int, float, float]]:
        """The variant showing placement ``pl``'s shape and its reference point."""
        piece = self.pieces[t]
        s = self.scale
        ring = transform_ring(piece.outer, pl.angle, pl.mirrored)
        for vi in self.choices[t]:
            v = self.variants[vi]
            if v.mirrored == pl.mirrored and abs((v.angle - pl.angle + 180.0) % 360.0 - 180.0) < 1e-6:
                return vi, pl.x * s, pl.y * s
        for vi in self.choices[t]:          # an orientation kept once (same shape moved)
            v = self.variants[vi]
            vr = transform_ring(piece.outer, v.angle, v.mirrored)
            if _same_shape(ring, vr, max(piece.tol, 1e-6)):
                d = ring.min(axis=0) - vr.min(axis=0)
                return vi, (pl.x + d[0]) * s, (pl.y + d[1]) * s
        return None

    def right_edge(self, X: np.ndarray, V: np.ndarray) -> float:
        return float((X + self.cb[V, 2]).max())

    def to_layout(self, base: Layout, X: np.ndarray, Y: np.ndarray, V: np.ndarray) -> Layout:
        out = copy.deepcopy(base)
        s = self.scale
        for i, pl in enumerate(out.placements):
            v = self.variants[int(V[i])]
            pl.x, pl.y, pl.angle, pl.mirrored = float(X[i]) / s, float(Y[i]) / s, v.angle, v.mirrored
        return out


def _swap_large(inst: _Instance, X, Y, V, rng) -> None:
    """Disrupt a layout: two copies of different types among the larger half
    trade places (bounding-box centres), so the separator can find another
    arrangement than the one it got stuck in.  The copies whose centre a
    swapped copy will cover move by the opposite shift, into the room it
    leaves (as sparrow moves the items a swapped item would contain), so a
    large copy swapped with a small one does not land on the small one's
    neighbours."""
    cb = inst.cb
    area = (cb[V, 2] - cb[V, 0]) * (cb[V, 3] - cb[V, 1])
    big = np.nonzero(area >= np.median(area))[0]
    for _ in range(10):
        a, b = rng.choice(big, 2, replace=False) if len(big) > 1 else (0, 0)
        if inst.types[a] != inst.types[b]:
            break
    else:
        return
    cx = X + 0.5 * (cb[V, 0] + cb[V, 2])
    cy = Y + 0.5 * (cb[V, 1] + cb[V, 3])
    dx, dy = cx[b] - cx[a], cy[b] - cy[a]
    others = np.ones(len(X), dtype=bool)
    others[[a, b]] = False
    in_a = others & _covers(inst, X[a] + dx, Y[a] + dy, V[a], cx, cy)
    in_b = others & ~in_a & _covers(inst, X[b] - dx, Y[b] - dy, V[b], cx, cy)
    X[in_a] -= dx
    Y[in_a] -= dy
    X[in_b] += dx
    Y[in_b] += dy
    X[a] += dx
    Y[a] += dy
    X[b] -= dx
    Y[b] -= dy


def _covers(inst: _Instance, x: float, y: float, v: int, px, py):
    """Which points (px, py) lie in variant ``v``'s core box placed at (x, y)."""
    b = inst.cb[v]
    return (px >= x + b[0]) & (px <= x + b[2]) & (py >= y + b[1]) & (py <= y + b[3])


def _squeeze(inst: _Instance, X, Y, V, bx1: float, x1: float, rng) -> None:
    """Close the strip from ``bx1`` to ``x1``: copies right of a random cut move
    left by the difference, then every copy is pushed back inside."""
    cb = inst.cb
    cut = rng.uniform(inst.x0, bx1)
    centre = X + 0.5 * (cb[V, 0] + cb[V, 2])
    X[centre > cut] -= bx1 - x1
    _inside(inst, X, Y, V, x1)


def _inside(inst: _Instance, X, Y, V, x1: float) -> None:
    """Push every copy back inside the strip closed at ``x1`` (the separator
    moves only overlapping copies, so one outside would stay there)."""
    cb = inst.cb
    X[:] = np.minimum(np.maximum(X, inst.x0 - cb[V, 0]), x1 - cb[V, 2])
    Y[:] = np.minimum(np.maximum(Y, inst.y0 - cb[V, 1]), inst.y1 - cb[V, 3])


class _Best:
    """The shortest valid layout any worker has found, (x1, X, Y, V); shared by
    the worker threads, so each next shrink starts from the best of all (the
    arrays are never changed once offered)."""

    def __init__(self, state):
        self._lock = threading.Lock()
        self._state = state

    def offer(self, state) -> None:
        with self._lock:
            if state[0] < self._state[0]:
                self._state = state

    def get(self):
        with self._lock:
            return self._state


def _shrink_loop(inst: _Instance, sep: Separator, shared: _Best, deadline: float, seed: int):
    """One worker's loop (see module doc): exploration (:func:`_explore`) until
    ``COMPRESSION_SHARE`` of the time is left, then compression
    (:func:`_compress`).  Returns its last ``KEEP`` overlap-free layouts
    (x1, X, Y, V), shortest last."""
    from .separation import seed_rng
    rng = np.random.default_rng(seed)
    seed_rng(seed)
    found: list = []
    squeeze_at = time.monotonic() + (1.0 - COMPRESSION_SHARE) * (deadline - time.monotonic())
    _explore(inst, sep, shared, squeeze_at, rng, found)
    _compress(inst, sep, shared, deadline, rng, found, COMPRESS_MAX, COMPRESS_MIN)
    return found


def _explore(inst: _Instance, sep: Separator, shared: _Best, until: float, rng, found: list) -> None:
    """Exploration: the worker keeps its own infeasible layout at a target
    length ``x1`` below the best valid one.  A failed separation goes into a
    pool of the least-overlapping layouts at ``x1`` (sorted by total
    overlap); the next try starts from one of them (the better ones more
    likely), disrupted by a swap of two large copies, at the same target
    (sparrow's exploration).  On success the layout is the new best and the
    next target lies ``EXPLORE_SHRINK`` of its length below it.  When another
    worker reaches ``x1`` first, this one goes on from that worker's best."""
    from .separation import colliding_total
    x0 = inst.x0
    best = None
    x1 = X = Y = V = None
    pool: list = []
    while time.monotonic() < until and not sep.stop.is_set():
        other = shared.get()
        if best is None or other[0] <= x1:
            best = other                  # first round, or another worker reached x1
            x1 = best[0] - EXPLORE_SHRINK * (best[0] - x0)
            X, Y, V = best[1].copy(), best[2].copy(), best[3].copy()
            _squeeze(inst, X, Y, V, best[0], x1, rng)
            pool = []
        new = _separate(inst, sep, shared, X, Y, V, x1, until, rng, found)
        if new is not None:
            best = new
            x1 = best[0] - EXPLORE_SHRINK * (best[0] - x0)
            X, Y, V = X.copy(), Y.copy(), V.copy()
            _squeeze(inst, X, Y, V, best[0], x1, rng)
            pool = []
            continue
        if shared.get()[0] <= x1:
            continue                      # the top of the loop takes the other's best
        total = colliding_total(sep.overlaps(X, Y, V), sep.eps)
        pool.append((total, X, Y, V))
        pool.sort(key=lambda e: e[0])
        del pool[POOL_SIZE:]
        pick = pool[int(min(abs(rng.normal(0.0, POOL_STDDEV)), 0.999) * len(pool))]
        X, Y, V = pick[1].copy(), pick[2].copy(), pick[3].copy()
        _swap_large(inst, X, Y, V, rng)
        _inside(inst, X, Y, V, x1)


def _compress(inst: _Instance, sep: Separator, shared: _Best, until: float, rng, found: list,
              hi: float, lo: float) -> None:
    """Shrink the best valid layout by ``hi`` of its length, halving the
    shrink on every failure down to ``lo`` (then ``hi`` again); a failure
    goes back to the best (often with two large copies swapped)."""
    x0 = inst.x0
    best = shared.get()
    frac = hi
    fails = 0
    while time.monotonic() < until and not sep.stop.is_set():
        other = shared.get()
        if other[0] < best[0]:
            best = other                  # another worker got further: go on from there
        bx1, X, Y, V = best[0], best[1].copy(), best[2].copy(), best[3].copy()
        x1 = bx1 - frac * (bx1 - x0)
        if fails and rng.random() < SWAP_P:
            _swap_large(inst, X, Y, V, rng)
        _squeeze(inst, X, Y, V, bx1, x1, rng)
        new = _separate(inst, sep, shared, X, Y, V, x1, until, rng, found)
        if new is not None:
            best = new
            frac = min(hi, frac * 1.5)
            fails = 0
        elif shared.get()[0] <= x1:
            continue                      # not a failure: go on from the new best
        else:
            fails += 1
            frac *= SHRINK_BACKOFF
            if frac < lo:
                frac = hi


def _separate(inst: _Instance, sep: Separator, shared: _Best, X, Y, V, x1: float, until: float,
              rng, found: list):
    """Separate (X, Y, V) in the strip closed at ``x1``; on success the new
    best (length, X, Y, V), offered to the other workers and kept in
    ``found`` (its last ``KEEP``), else None.  The separation is dropped as
    soon as another worker has reached ``x1`` (its work could not be kept)."""
    if not sep.separate(X, Y, V, x1, until, rng=rng, give_up=lambda: shared.get()[0] <= x1):
        return None
    best = (inst.right_edge(X, V), X, Y, V)
    shared.offer(best)
    found[:] = (found + [best])[-KEEP:]
    return best


def _compact(sep: Separator, X, Y, V) -> None:
    """Move the copies of the overlap-free (X, Y, V) left where they fit
    (:func:`compaction.compact_left`, the separator's overlap test)."""
    from .compaction import compact_left
    compact_left(X, Y, V, sep.cb, sep.x0, sep.y0, sep.y1, sep.eps, sep.table.n, *sep.arrs)


def improve_strip(layout: Layout, parts: Sequence[Part], options: NestOptions,
                  deadline: float, progress: Optional[ProgressFn] = None,
                  user_stop: Optional[Callable[[], bool]] = None) -> Layout:
    """A valid strip layout no longer than ``layout`` (see module doc).

    ``layout`` is a strip layout of ``parts`` under ``options``; ``deadline``
    a ``time.monotonic()`` value.  Another container kind, an incomplete or
    invalid layout, more than ``MAX_PAIRS`` orientation pairs or too little
    time return ``layout`` itself.  ``progress`` is polled about every 0.1 s
    (CancelledError when it asks to stop; the workers stop within a sweep).
    ``user_stop()`` returning True (the workbench's *Stop*) ends the phase early
    and keeps the best layout found so far."""
    if options.container.kind != "strip" or layout.unplaced or len(layout.placements) < 2 \
            or not _kernels():
        return layout
    if time.monotonic() > deadline - 0.2 or _problems(parts, layout, options):
        return layout
    inst = _Instance(layout, parts, options)
    if not inst.ok or len(inst.variants) ** 2 > MAX_PAIRS:
        return layout
    from .overlap import PairTable
    from .separation import Separator
    table = PairTable(inst.variants, deadline)
    if not table.complete:
        return layout
    n = options.workers or max(1, min(os.cpu_count() or 1, 8))
    stop = threading.Event()
    seps = [Separator(table, inst.cb, inst.choices, inst.types, inst.y0, inst.y1, inst.x0,
                      inst.eps, stop=stop, pad=inst.pad) for _ in range(n)]
    seps[0].warm_up(inst.X, inst.Y, inst.V, inst.right_edge(inst.X, inst.V))
    _compact(seps[0], inst.X.copy(), inst.Y.copy(), inst.V)     # compile it before the clock runs
    # threads, not processes: the kernels release the GIL (nogil), so the workers
    # run in parallel without pickling, forking or FreeCAD's stdin quirks
    t0 = time.monotonic()
    span = max(deadline - t0, 1e-9)
    with ThreadPoolExecutor(n) as ex:
        shared = _Best((inst.right_edge(inst.X, inst.V), inst.X, inst.Y, inst.V))
        futs = [ex.submit(_shrink_loop, inst, sep, shared, deadline, options.seed * 7919 + k)
                for k, sep in enumerate(seps)]
        try:
            while not all(f.done() for f in futs):
                if user_stop is not None and user_stop():
                    break
                report(progress, 0.05 + 0.9 * min(1.0, (time.monotonic() - t0) / span),
                       f"compacting the strip ({n} workers)")
                wait(futs, timeout=0.1)
        finally:
            stop.set()
        found = sorted((st for f in futs for st in f.result()), key=lambda st: st[0])
    # the shortest layout the checker passes, each first compacted, then as
    # found (the penalty model is exact up to rounding; the checker has the
    # last word and a shorter rejected layout falls back to the next one)
    for _, X, Y, V in found[:KEEP]:
        Xc, Yc = X.copy(), Y.copy()
        _compact(seps[0], Xc, Yc, V)
        for cx, cy in ((Xc, Yc), (X, Y)):
            new = _accept(layout, parts, options, inst.to_layout(layout, cx, cy, V))
            if new is not layout:
                return new
    return layout


def improve_last_sheet(layout: Layout, parts: Sequence[Part], options: NestOptions,
                       deadline: float, progress: Optional[ProgressFn] = None,
                       user_stop: Optional[Callable[[], bool]] = None) -> Layout:
    """Sheets: shorten the used length (along X) of the last sheet with the
    strip phase (the sheet's height is the strip's width); the other sheets
    stay as they are.  Returns ``layout`` unless the checker passes a shorter
    last sheet."""
    if options.container.kind != "sheet" or not layout.containers or layout.unplaced:
        return layout
    from .engine import fill_metrics
    last = layout.containers[-1].id
    strip = dataclasses.replace(options, container=ContainerSpec.strip(options.container.height))
    sub = Layout(containers=[Container(id="strip", kind="strip", outline=[])],
                 placements=[dataclasses.replace(pl, container="strip")
                             for pl in layout.placements if pl.container == last])
    fill_metrics(parts, sub, strip)
    better = improve_strip(sub, parts, strip, deadline, progress, user_stop)
    if better is sub:
        return layout
    new = copy.deepcopy(layout)
    new.placements = [pl for pl in new.placements if pl.container != last] + \
        [dataclasses.replace(pl, container=last) for pl in better.placements]
    fill_metrics(parts, new, options)
    return layout if _problems(parts, new, options) else new


def nest_compacted(parts: Sequence[Part], options: NestOptions,
                   progress: Optional[ProgressFn] = None,
                   on_best: Optional[Callable[[Layout], None]] = None,
                   stop: Optional[Callable[[], bool]] = None) -> Layout:
    """The own engine with this phase: on a strip its search runs for
    ``SEARCH_SHARE`` of the time budget, less with many copies (:func:`_search_share`),
    and ends sooner once it has found no shorter layout for ``STALL_SHARE`` of the
    budget (sheets: the whole budget, ending at a ``SHEET_STALL_SHARE`` plateau), then
    :func:`improve_strip` (:func:`improve_last_sheet`) until the budget ends.  Hides, a reproducible
    run (``max_evaluations``) or no budget get the engine alone: this phase is
    driven by the clock.  Without numba the engine also runs alone.  ``on_best``
    and ``stop`` are the engine's (best layout so far; *Stop* keeps it)."""
    from .engine import run_own
    t0 = options.started_at if options.started_at is not None else time.monotonic()
    kind = options.container.kind
    if kind not in ("strip", "sheet") or options.max_evaluations is not None \
            or options.time_budget <= 0 or importlib.util.find_spec("numba") is None:
        # (numba itself is imported only after the engine: :func:`_kernels`)
        return run_own(parts, options, progress, on_best, stop)
    share = 1.0 if kind == "sheet" else _search_share(parts)
    # the share splits the time left after reading the drawing (counted from t0)
    spent = min(max(time.monotonic() - t0, 0.0), options.time_budget)
    first = dataclasses.replace(options, started_at=t0,
                                time_budget=spent + (options.time_budget - spent) * share)
    stall_share = STALL_SHARE if kind == "strip" else SHEET_STALL_SHARE
    not_before = t0 + (0.0 if kind == "strip" else SHEET_MIN_SEARCH_SHARE * options.time_budget)
    stall = _Stall(max(STALL_MIN_S, stall_share * options.time_budget), on_best, stop, not_before)
    layout = run_own(parts, first, progress, stall.on_best, stall.stop)
    layout.metrics["stopped"] = bool(stop is not None and stop())
    if stop is not None and stop():
        return layout
    phase = improve_strip if kind == "strip" else improve_last_sheet
    # the phase leaves the tail's time free: its own check of the result (two
    # rounds of build and check on sheets), then the outputs and the exit
    copies = len(layout.placements) + len(layout.unplaced)
    end = t0 + options.time_budget - tail.current(parts, options).reserve(copies, rounds=2)
    better = phase(layout, parts, options, end, progress, stop)
    better.metrics["time_s"] = round(time.monotonic() - t0, 3)
    if better is not layout and on_best is not None:
        on_best(better)
    return better


class _Stall:
    """Ends the engine's search once no shorter layout came for ``stall_s``
    seconds, not before ``not_before`` (``time.monotonic()``), or on the
    user's *Stop*; passes each better layout on."""

    def __init__(self, stall_s: float, on_best: Optional[Callable[[Layout], None]],
                 user_stop: Optional[Callable[[], bool]], not_before: float = -math.inf):
        self.stall_s, self._on_best, self._user_stop = stall_s, on_best, user_stop
        self.not_before = not_before
        self._last: Optional[float] = None

    def on_best(self, layout: Layout) -> None:
        self._last = time.monotonic()
        if self._on_best is not None:
            self._on_best(layout)

    def stop(self) -> bool:
        if self._user_stop is not None and self._user_stop():
            return True
        now = time.monotonic()
        return self._last is not None and now >= self.not_before and now - self._last > self.stall_s


def _search_share(parts: Sequence[Part]) -> float:
    """The engine's share of a strip's time budget (see ``SHARE_COPIES``)."""
    n = sum(max(p.quantity, 0) for p in parts)
    return max(MIN_SEARCH_SHARE, SEARCH_SHARE * min(1.0, SHARE_COPIES / max(n, 1)))


def _problems(parts: Sequence[Part], layout: Layout, options: NestOptions) -> List[str]:
    """The checker's verdict (:meth:`tail.Tail.check`: :func:`nest` reuses it)."""
    return tail.current(parts, options).check(parts, layout, options)


def _accept(old: Layout, parts: Sequence[Part], options: NestOptions, new: Layout) -> Layout:
    """``new`` if the checker passes it and its strip is shorter, else ``old``."""
    from .engine import fill_metrics
    fill_metrics(parts, new, options)
    if new.metrics["strip_length_mm"] >= old.metrics.get("strip_length_mm", float("inf")):
        return old
    if _problems(parts, new, options):
        return old
    new.metrics["strip_improved_from_mm"] = old.metrics.get("strip_length_mm")
    return new
