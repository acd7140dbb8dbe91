"""The project's own nesting engine: parts + options -> Layout.

Steps: flatten parts (:mod:`shapes`), build the grid variants and the
container bins, run the bottom-left fill and the anytime search
(:mod:`search`) in worker processes, turn the best placements into a
:class:`~LeatherCutWorkbench.core.model.Layout` with container figures.
The caller (:func:`nest`) runs the validity checker on the result; on
hides the engine checks it first and, if it fails, keeps an earlier or
another worker's valid layout when that places as many copies
(:func:`_valid_or_fallback`).
"""

from __future__ import annotations

import logging
import math
import multiprocessing as mp
import os
import sys
import time
from contextlib import contextmanager
from typing import Callable, Dict, Iterator, List, Optional, Sequence, Tuple

from shapely.geometry import Polygon

from ..errors import CancelledError, LeatherCutError
from ..model import Container, Finding, Layout, Part, Placement
from ..progress import ProgressFn, report
from .blf import BinSpec
from .checker import part_polygon, placed_polygon, problem_labels
from .containers import net_area, rectangle
from .hide_regions import HideRegions
from .hide_shapes import simplify_for_hides
from .options import NestOptions
from .part_regions import nesting_grade, region_check, region_grade_levels
from .search import Budget, Problem, search, worker_main
from .shapes import PieceType, make_variants, piece_from_part
from .tail import EXIT_S, Tail, current, runnable

_log = logging.getLogger(__name__)

#: The grid resolution: the largest container or part dimension spans this many units.
GRID_UNITS = 2.0e6


def _grid_scale(types: Sequence[PieceType], options: NestOptions) -> float:
    spec = options.container
    dims = [spec.width, spec.height]
    for h in spec.hides:
        xs = [p[0] for p in h.outline]
        ys = [p[1] for p in h.outline]
        dims += [max(xs) - min(xs), max(ys) - min(ys), max(abs(v) for v in xs + ys)]
    for t in types:
        dims.append(float(abs(t.outer).max()) * 2.0)
    # at least 10 grid units per checker tolerance: the few units of rounding slack
    # the engine allows then stay well inside the tolerance
    return max(GRID_UNITS / max(max(dims), 1e-9), 10.0 / options.tolerance)


def _bins(options: NestOptions, scale: float, half_gap: float,
          grades: Sequence[int]) -> Tuple[List[BinSpec], List[Container], bool, Optional[int]]:
    spec = options.container
    m = options.margin
    if spec.kind in ("sheet", "strip"):
        w = int(round(spec.width * scale))
        h = int(round(spec.height * scale))
        # variants are inflated by half_gap + 1 unit: widen the usable rectangle alike,
        # plus one unit so an exact fit keeps a region of positive area
        lo = int(round(m * scale)) - int(round(half_gap * scale)) - 2
        rect = (lo, lo, w - lo, h - lo)
        kind = spec.kind
        bins = [BinSpec(kind, rect)]
        if spec.kind == "sheet":
            return bins, [], spec.count is None, spec.count
        return bins, [], False, 1
    # built when the fill first opens each hide (:mod:`hide_regions`)
    bins = [BinSpec("hide", prep=HideRegions(c, sorted(set(grades)), m, scale))
            for c in spec.hides]
    return bins, list(spec.hides), False, len(spec.hides)


def _workers(options: NestOptions) -> int:
    if options.workers is not None:
        return options.workers
    return max(1, min(os.cpu_count() or 1, 8))


#: seconds the parent waits after the deadline for workers to finish, then ends them
_GRACE_S = 0.3
#: on a busy machine the other workers wait for worker 0's first layout at most
#: this share of the budget (:func:`_run_pool`)
_WAIT_FIRST = 0.2


def _deadlines(t_start: float, budget: float, reserve: float, hides: bool = False,
               promised: Optional[float] = None, fill_reserve: Optional[float] = None
               ) -> Tuple[float, float, float, float, float]:
    """(search end, first-fill exact limit of worker 0, of the other workers,
    bounding boxes only in the first fill from the search end, and the first
    fill's last resort end).

    The search ends ``reserve`` seconds before T (:func:`_reserve`: the
    workers' shutdown, then the final build, check, outputs and exit).  The
    last resort is the promised end T + 10 % + 1 s (``promised``: that of the
    whole nest when this search has only a share of it) less 1.25
    ``fill_reserve`` (default ``reserve``; the engine leaves the outputs out of
    it, on hides all but opening the files: a first fill cut short for them
    loses copies, a late output only time) -- the placement step under way
    when it passes (the fill checks between orientations), then the tail --,
    never before the search end: only a
    machine too loaded even for box-only no-fit polygons ever leaves copies
    unplaced for lack of time (it was 1.5 T + 2 s, and Baldacci Test5 / Test6
    then took 18-19 s at T = 10 under load).

    Worker 0 switches its first
    fill to coarse no-fit polygons after max(1 s, 5 % of T) so a layout exists
    within a second or two; the others fill exactly for up to 40 % of T (hides:
    70 %: a coarse fill on hides of concave leather parts wastes whole hides)."""
    if budget <= 0:
        return math.inf, math.inf, math.inf, math.inf, math.inf
    t_end = t_start + max(budget - reserve, 0.5 * budget)
    quick = t_start + min(max(1.0, 0.05 * budget), 0.5 * budget)
    slow = t_start + (0.7 if hides else 0.4) * budget
    if promised is None:
        promised = t_start + 1.1 * budget + 1.0
    last = promised - 1.25 * (reserve if fill_reserve is None else fill_reserve)
    return t_end, quick, slow, t_end, max(last, t_end)


def _reserve_floor(budget: float) -> float:
    """The smallest :func:`_reserve` any measured tail gives: the shutdown and the exit."""
    return min(0.05 * budget, 0.5) + min(EXIT_S, 0.4 * budget)


def _reserve(budget: float, n_copies: int, tail: Tail, outputs: bool = True) -> float:
    """Seconds the search leaves free at the end of ``budget``: the workers'
    shutdown (``_GRACE_S`` and joining them: min(5 % T, 0.5 s)) and
    :meth:`Tail.reserve` (measured build and check, outputs, exit), that
    at most 40 % of the budget (so the first fill's last resort still comes
    after the search end and the tail fits in T + 10 % + 1 s)."""
    return min(0.05 * budget, 0.5) + min(tail.reserve(n_copies, outputs=outputs), 0.4 * budget)


class _Best:
    """Best layout so far over all workers (ties: the lowest worker index) and
    the live report of it: progress message, optional ``on_best`` layout."""

    def __init__(self, summary, on_best, build):
        self.per_worker: Dict[int, tuple] = {}
        self.evals: Dict[int, int] = {}      # evaluations reported so far per worker
        self.best: Optional[tuple] = None
        self.summary = summary
        self.on_best = on_best
        self.build = build
        self.shown = 0.0
        self.dirty = False
        #: ``time.monotonic()`` when the first layout arrived (None before)
        self.first_at: Optional[float] = None
        #: where each layout refused for a lost copy came from (:attr:`Budget.copies`)
        self.lost: List[str] = []
        #: the last bests replaced by better ones (:meth:`alternatives`)
        self.replaced: List[tuple] = []

    def offer(self, worker: int, cost, order, placements) -> None:
        entry = (cost, order, placements, worker)
        self.per_worker[worker] = entry
        if self.first_at is None:
            self.first_at = time.monotonic()
        if self.best is None or (cost, worker) < (self.best[0], self.best[3]):
            if self.best is not None:
                self.replaced = (self.replaced + [self.best])[-FALLBACKS:]
            self.best = entry
            self.dirty = True

    def alternatives(self) -> List[tuple]:
        """Layouts other than the best, best first, each once: each worker's
        latest best and the last ``FALLBACKS`` bests it replaced."""
        seen = {id(self.best)}
        out = []
        for c in list(self.per_worker.values()) + self.replaced:
            if id(c) not in seen:
                seen.add(id(c))
                out.append(c)
        return sorted(out, key=lambda c: (c[0], c[3]))[:FALLBACKS]

    def message(self) -> str:
        return self.summary(self.best[0], self.best[2]) if self.best else "first fill"

    def publish(self, force: bool = False) -> None:
        """Hand the best layout to ``on_best`` (at most twice a second)."""
        now = time.monotonic()
        if self.on_best is None or not self.dirty or (not force and now - self.shown < 0.5):
            return
        self.shown, self.dirty = now, False
        self.on_best(self.build(self.best[1], self.best[2]))


def prepare(parts: Sequence[Part], options: NestOptions):
    """Shapes, grid variants, bins and the worker :class:`Problem` of a nest:
    (types, variants, problem, copies, hides, scale), or None with nothing
    to nest.  (Also the entry point of the hide fill profile in ``bench/``.)"""
    types = [piece_from_part(p, options.chord_tol, options.rotation_step,
                             options.part_rotations(p.rotations), options.mirror_override)
             for p in parts]
    types = [t for t in types if t.quantity > 0]
    if not types:
        return None
    scale = _grid_scale(types, options)
    half_gap = options.spacing / 2.0
    variants = make_variants(types, scale, half_gap, options.chord_tol)
    if options.container.kind == "hide":
        variants = simplify_for_hides(variants)
    type_variants = [[v.index for v in variants if v.type_index == i] for i in range(len(types))]
    by_key = {p.id: p for p in parts}
    type_parts = [by_key[t.key] for t in types]
    grades = [nesting_grade(p) for p in type_parts]
    bins, hides, open_new, max_bins = _bins(options, scale, half_gap,
                                            grades + region_grade_levels(type_parts))
    problem = Problem(variants, type_variants, grades, [t.area for t in types], bins,
                      open_new, max_bins, scale,
                      hide_net=[net_area(h) for h in hides] if hides else None,
                      region_check=region_check(type_parts, hides, scale, options.tolerance,
                                                options.chord_tol))
    copies = [i for i, t in enumerate(types) for _ in range(t.quantity)]
    return types, variants, problem, copies, hides, scale


def run_own(parts: Sequence[Part], options: NestOptions,
            progress: Optional[ProgressFn] = None,
            on_best: Optional[Callable[[Layout], None]] = None,
            stop: Optional[Callable[[], bool]] = None) -> Layout:
    """Nest with the project's engine (see module doc); unchecked result.

    The time budget counts from this call (shapes, no-fit polygons, first
    fill and search).  ``on_best(layout)`` receives each better layout (at
    most twice a second); ``stop()`` returning True ends the search and keeps
    the best layout so far (``progress`` returning False cancels)."""
    t_start = options.started_at if options.started_at is not None else time.monotonic()
    report(progress, 0.0, "preparing part shapes")
    prepared = prepare(parts, options)
    if prepared is None:
        return Layout(containers=[], placements=[], unplaced=[], metrics={"placed_count": 0},
                      findings=[Finding("warning", "nothing-to-nest", "no parts to nest")])
    types, variants, problem, copies, hides, scale = prepared
    findings: List[Finding] = []
    report(progress, 0.02, f"nesting {len(copies)} copies of {len(types)} parts")

    n_workers = _workers(options)
    budget = options.time_budget
    tail = current(parts, options)
    tail.note_load(1)              # a visibly loaded machine: a larger prior tail
    on_hides = options.container.kind == "hide"
    # hides (heavy checks and outputs): the last resort also keeps the outputs' files free
    t_end, quick, slow, boxes, hard = _deadlines(t_start, budget,
                                                 _reserve(budget, len(copies), tail), on_hides,
                                                 tail.promised_end(),
                                                 _reserve(budget, len(copies), tail, outputs=False)
                                                 + (tail.files_s() if on_hides else 0.0))
    # the searches themselves may run until the latest end any measured tail allows
    # (the shutdown and the exit only); this process ends them at ``measured_end``,
    # before the first layout at ``t_end`` (the prior tail): a measured tail cheaper
    # than the prior one gives the search its time back
    latest = _deadlines(t_start, budget, _reserve_floor(budget))[0]
    max_eval = options.max_evaluations if budget > 0 else 4
    net = problem.hide_net or []            # (net areas cost 7 ms a Test10 hide)

    def summary(cost, placements) -> str:
        return _summary(problem, options, scale, net, cost, placements, len(copies))

    def build(order, placements) -> Layout:
        return _to_layout(parts, types, variants, order, placements, options, scale, hides)

    timed: List[bool] = []          # [True] once the tail was timed on the first layout

    # worker processes that search on while the parent times the tail (one worker:
    # the search runs in this process and waits for the measurement)
    searching = n_workers if n_workers > 1 and budget > 0 and len(copies) >= 2 else 0

    def measured_end(first_best) -> float:
        """The search end once a layout exists: the tail's build and check
        timed on the first one (while the workers search on) and the
        contention expected at the end (:meth:`Tail.note_load`, sampled all
        along), so earlier or later than ``t_end``, never after ``latest``.
        A first layout that comes after ``t_end`` leaves the end there."""
        if not timed:
            timed.append(budget > 0 and time.monotonic() < t_end)
            if timed[0] and tail.per_copy is None:
                tail.busy = searching
                t, c = time.monotonic(), time.thread_time()
                layout = build(first_best[1], first_best[2])
                tail.note_build(time.monotonic() - t, len(layout.placements),
                                time.thread_time() - c)
                tail.check(parts, layout, options)
            if searching:
                tail.preload()      # the outputs' libraries, while the workers search
        if not timed[0]:
            return t_end
        return min(latest, _deadlines(t_start, budget, _reserve(budget, len(copies), tail))[0])

    best = _Best(summary, on_best, build)

    def frac() -> float:
        if budget <= 0:
            return 0.5
        return 0.05 + 0.9 * min(1.0, (time.monotonic() - t_start) / budget)

    if n_workers == 1 or budget <= 0 or len(copies) < 2:
        def tick(_cost) -> bool:
            best.publish()
            return progress is None or progress(frac(), best.message()) is not False

        end = [t_end]

        def offer(c, o, p) -> None:
            best.offer(0, c, o, p)
            report(progress, frac(), best.message())      # each better layout, live
            end[0] = measured_end(best.best)

        def stop_now() -> bool:
            if best.best is not None:
                tail.note_load(1)
                end[0] = measured_end(best.best)
            return (stop is not None and stop()) or time.monotonic() > end[0]

        b = Budget(latest, quick, max_eval, stop_now, offer, tick, hard_stop=boxes,
                   give_up_at=hard, copies=sorted(copies), on_lost=lambda w: best.lost.append(w))
        evaluations = search(problem, copies, options.seed, 0, b)[3]
        workers_used = 1
    else:
        evaluations = _run_pool(problem, copies, options.seed, n_workers, (t_end, latest),
                                (quick, slow, boxes, hard), max_eval, best, progress, frac, stop,
                                measured_end, tail)
        workers_used = n_workers
    best.publish(force=True)
    cost, order, placements, _ = best.best
    report(progress, 0.97, "building the layout")
    layout = build(order, placements)
    if on_hides:
        layout = _valid_or_fallback(parts, options, tail, layout, best, build)
    if layout.unplaced and budget > 0 and time.monotonic() > hard:
        findings.append(Finding("warning", "time-budget-short",
                                f"the time budget of {budget:g} s ended during the first fill: "
                                "copies it did not reach are unplaced; give more time"))
    layout.findings.extend(findings)
    layout.metrics.update({"engine": "own", "workers": workers_used, "evaluations": evaluations,
                           "time_s": round(time.monotonic() - t_start, 3),
                           "first_layout_s": round(best.first_at - t_start, 3), "seed": options.seed,
                           "stopped": bool(stop is not None and stop())})
    if best.lost:
        # a search defect, not the user's: the layout returned holds every copy
        layout.metrics["refused_layouts"] = len(best.lost)
        _log.warning("nesting: %d layouts that lost a copy were refused; first from %s",
                     len(best.lost), best.lost[0])
    return layout


#: hides: earlier or other workers' layouts tried when the best fails the final check
FALLBACKS = 3


def _valid_or_fallback(parts: Sequence[Part], options: NestOptions, tail: Tail, layout: Layout,
                       best: _Best, build: Callable) -> Layout:
    """``layout`` (the best), or when the final check finds invalid
    placements in it -- a search defect; :func:`nest`'s safety net would
    take those copies out -- the first of :meth:`_Best.alternatives` that
    passes the check and places at least as many copies as the best keeps
    without them (a warning names what was replaced).  The check is
    remembered (:meth:`Tail.check`): :func:`nest` does not repeat it."""
    problems = tail.check(parts, layout, options)
    if not problems:
        return layout
    bad = problem_labels(problems)
    keeps = len(layout.placements) - len(bad)
    for _cost, order, placements, worker in best.alternatives():
        alt = build(order, placements)
        if len(alt.placements) >= keeps and not tail.check(parts, alt, options):
            alt.findings.append(Finding(
                "warning", "invalid-layout-replaced",
                f"the best layout found had {len(bad)} invalid placements "
                f"({', '.join(sorted(bad)[:5])}: {problems[0]}); kept instead the valid layout "
                f"of worker {worker} with {len(alt.placements)} copies placed"))
            return alt
    return layout


def _summary(problem: Problem, options: NestOptions, scale: float, net: Sequence[float],
             cost, placements, n_copies: int) -> str:
    """One line on a layout in grid units: placed copies and the figure of merit."""
    placed = [(si, b) for (si, b, vi, tx, ty) in placements if b >= 0]
    area = n_copies and sum(problem.type_area[problem.variants[vi].type_index]
                            for (si, b, vi, tx, ty) in placements if b >= 0)
    head = f"best: {len(placed)}/{n_copies} placed"
    spec = options.container
    used = cost[1]
    if spec.kind == "strip":
        length = cost[2] / scale
        dens = area / (length * spec.height) if length > 0 else 0.0
        return f"{head}, length {length:.1f} mm, density {100 * dens:.1f} %"
    if spec.kind == "sheet":
        util = area / (used * spec.width * spec.height) if used else 0.0
        return f"{head} on {used} sheet(s), utilisation {100 * util:.1f} %"
    total = sum(net[b] for b in {b for (_si, b) in placed})   # b: hide index
    util = area / total if total else 0.0
    return f"{head} on {used} hide(s), utilisation {100 * util:.1f} %"


@contextmanager
def _closable_stdin() -> Iterator[None]:
    """Give worker processes a stdin they can close.

    A starting ``multiprocessing`` worker first calls ``sys.stdin.close()``.
    FreeCAD's GUI replaces ``sys.stdin`` with an object that has no
    ``close()``: the worker would die with AttributeError and the pool respawn
    it forever (the search would hang).  While the workers live, ``sys.stdin``
    is then a read-only handle on the null device."""
    original = sys.stdin
    if original is None or callable(getattr(original, "close", None)):
        yield
        return
    sys.stdin = open(os.devnull, "r", encoding="utf-8")
    try:
        yield
    finally:
        replacement, sys.stdin = sys.stdin, original
        replacement.close()


def _run_pool(problem: Problem, copies: List[int], seed: int, n: int, ends: Tuple[float, float],
              fill_limits: Tuple[float, float, float, float], max_eval: Optional[int], best: _Best,
              progress: Optional[ProgressFn], frac, stop,
              measured_end: Callable[[tuple], float], tail: Tail) -> int:
    """One search process per worker.  The parent collects every new best,
    reports it live, and ends the workers itself ``_GRACE_S`` after the
    deadline (or on Stop): the wall time holds whatever a worker is doing.
    ``ends`` = (the deadline, the latest end the workers are given); the
    deadline moves to ``measured_end(first best)`` once a layout exists;
    ``tail`` samples the machine's load meanwhile (:meth:`Tail.note_load`).
    On a machine with fewer free cores than workers (:func:`_busy`) the
    workers other than 0 wait for the first layout (at most ``_WAIT_FIRST``
    of the search): worker 0's quick first fill gets the cores first
    (Baldacci Test10 at load ~2 on 2 cores: its 2 s CPU took 4 s wall next
    to worker 1).
    Returns the evaluations the workers reported."""
    t_end, latest = ends
    with _closable_stdin():
        ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else mp.get_context()
        queue = ctx.Queue()
        stop_event = ctx.Event()
        first = ctx.Event()
        now = time.monotonic()
        wait = (first, now + _WAIT_FIRST * (latest - now)) if _busy(n) else None
        # hides: each worker hears of the others' complete layouts (Budget.shared);
        # not with an evaluation limit, whose result depends on the seed alone
        inboxes = [ctx.Queue() for _ in range(n)] \
            if problem.hide_net is not None and max_eval is None else None
        procs = [ctx.Process(target=worker_main, daemon=True,
                             args=(problem, copies, seed, i, latest,
                                   fill_limits[0] if i == 0 else fill_limits[1],
                                   max_eval, queue, stop_event, fill_limits[2], fill_limits[3],
                                   wait if i > 0 else None,
                                   inboxes[i] if inboxes is not None else None))
                 for i in range(n)]
        sent = None                         # the best layout last handed to the workers
        for p in procs:
            p.start()
        done: Dict[int, int] = {}
        errors: List[str] = []
        try:
            while len(done) + len(errors) < n:
                _drain(queue, best, done, errors, timeout=0.05)
                if inboxes is not None and best.best is not None and best.best is not sent \
                        and best.best[0][0] == 0:
                    sent = best.best
                    for i, box in enumerate(inboxes):
                        if i != sent[3]:
                            box.put(sent[:3])
                best.publish()              # shown first, then the tail measured on it
                report(progress, frac(), best.message())
                tail.note_load(1 + sum(p.is_alive() for p in procs))
                if best.best is not None:
                    first.set()
                    t_end = measured_end(best.best)
                if stop is not None and stop() and best.best is not None:
                    stop_event.set()
                if time.monotonic() > t_end:
                    stop_event.set()
                if stop_event.is_set() and best.best is not None:
                    t_grace = time.monotonic() + _GRACE_S
                    while len(done) + len(errors) < n and time.monotonic() < t_grace:
                        _drain(queue, best, done, errors, timeout=0.02)
                    break
                if not any(p.is_alive() for p in procs) and queue.empty():
                    break
        except CancelledError:
            stop_event.set()
            raise
        finally:
            for p in procs:
                if p.is_alive():
                    p.terminate()
            for p in procs:
                p.join(1.0)
            queue.close()
            for box in inboxes or ():
                box.cancel_join_thread()    # a worker ended may leave layouts unread
                box.close()
    if best.best is None:
        raise LeatherCutError("nesting workers failed: " + ("; ".join(errors) or "no layout"))
    return sum(max(done.get(i, 0), best.evals.get(i, 0)) for i in range(n))


def _busy(n_workers: int) -> bool:
    """Would ``n_workers`` busy processes and the tasks running now (this one
    left out) be more than the cores?  (False when unknown.)"""
    from .tail import _cores
    running = runnable()
    return running is not None and running - 1 + n_workers > _cores()


def _drain(queue, best: _Best, done: Dict[int, int], errors: List[str], timeout: float) -> None:
    """Read every waiting worker message (waiting up to ``timeout`` for the first)."""
    import queue as _q
    wait = timeout
    while True:
        try:
            msg = queue.get(timeout=wait) if wait > 0 else queue.get_nowait()
        except _q.Empty:
            return
        wait = 0
        if msg[0] == "best":
            best.offer(msg[1], msg[2], msg[3], msg[4])
        elif msg[0] == "done":
            done[msg[1]] = msg[2]
        elif msg[0] == "evals":
            best.evals[msg[1]] = msg[2]
        elif msg[0] == "lost":
            best.lost.append(f"worker {msg[1]}: {msg[2]}")
        else:
            errors.append(msg[2])


def _to_layout(parts: Sequence[Part], types: Sequence[PieceType], variants, order,
               placements, options: NestOptions, scale: float,
               hides: List[Container]) -> Layout:
    """Placements in grid units -> Layout with containers and figures."""
    spec = options.container
    copy_no: Dict[int, int] = {}
    rows: List[Tuple[int, Placement]] = []
    unplaced: List[Tuple[str, int]] = []
    for (si, b, vi, tx, ty) in placements:
        t = order[si][0]
        k = copy_no.get(t, 0)
        copy_no[t] = k + 1
        key = types[t].key
        if b < 0:
            unplaced.append((key, k))
            continue
        v = variants[vi]
        rows.append((b, Placement(part_id=key, copy=k, container="", x=tx / scale, y=ty / scale,
                                  angle=v.angle, mirrored=v.mirrored)))
    containers: List[Container] = []
    names: Dict[int, str] = {}
    if spec.kind == "strip":
        containers.append(Container(id="strip", kind="strip", outline=rectangle(0, 0, 0, spec.height)))
        names[0] = "strip"
    elif spec.kind == "sheet":
        for n, b in enumerate(sorted({b for b, _ in rows})):
            names[b] = f"sheet{n + 1}"
            containers.append(Container(id=names[b], kind="sheet",
                                        outline=rectangle(0.0, 0.0, spec.width, spec.height)))
    else:                                   # the hides that hold parts, in order
        for b in sorted({b for b, _ in rows}):
            names[b] = hides[b].id
            containers.append(hides[b])
    for b, pl in rows:
        pl.container = names[b]
    layout = Layout(containers=containers, placements=[pl for _, pl in rows], unplaced=unplaced,
                    metrics={}, findings=[])
    fill_metrics(parts, layout, options)
    return layout


def material_grades(layout: Layout, placed: Sequence[Polygon], grade: Dict[str, int],
                    tol: float, cache: Dict[tuple, tuple]) -> List[Dict[str, object]]:
    """Per placement on a hide: the part's grade and the grade of the material
    it lies on (:func:`part_regions.material_grade`; ``cache`` keeps the
    hides' graded regions)."""
    from .part_regions import material_grade
    conts = {c.id: c for c in layout.containers}
    return [{"part": pl.part_id, "copy": pl.copy, "container": pl.container,
             "part_grade": grade.get(pl.part_id, 0),
             "material_grade": material_grade(g, conts[pl.container], tol, cache)}
            for pl, g in zip(layout.placements, placed)]


def _add_region_grades(parts: Sequence[Part], layout: Layout, rows: List[Dict[str, object]],
                       options: NestOptions, cache: Dict[tuple, tuple]) -> None:
    """Rows of ``material_grades`` for parts with graded regions get ``regions``:
    per piece (``region k`` / ``rest``) the grade it needs and the grade it lies on."""
    from .part_regions import pieces, region_grades
    by_id = {p.id: p for p in parts if p.grade_regions}
    if not by_id:
        return
    conts = {c.id: c for c in layout.containers}
    split = {pid: pieces(p, options.chord_tol) for pid, p in by_id.items()}
    for pl, row in zip(layout.placements, rows):
        if pl.part_id not in by_id:
            continue
        placed = [(g, placed_polygon(sh, pl.x, pl.y, pl.angle, pl.mirrored), lab)
                  for g, sh, lab in split[pl.part_id]]
        row["regions"] = region_grades(by_id[pl.part_id], placed, conts[pl.container],
                                       options.tolerance, cache)


def fill_metrics(parts: Sequence[Part], layout: Layout, options: NestOptions) -> None:
    """(Re)compute the layout's figures from its placements: strip length and
    density (the strip outline is set to the used length), sheet and hide
    utilisation, per-container figures, counts; an ``unplaced-parts`` warning."""
    spec = options.container
    polys = {p.id: part_polygon(p, options.chord_tol) for p in parts}
    area: Dict[str, float] = {c.id: 0.0 for c in layout.containers}
    extent: Dict[str, float] = {c.id: 0.0 for c in layout.containers}
    count: Dict[str, int] = {c.id: 0 for c in layout.containers}
    grade = {p.id: p.grade for p in parts}
    placed = []
    for pl in layout.placements:
        g = placed_polygon(polys[pl.part_id], pl.x, pl.y, pl.angle, pl.mirrored)
        area[pl.container] += g.area
        extent[pl.container] = max(extent[pl.container], g.bounds[2])
        count[pl.container] += 1
        placed.append(g)
    metrics = layout.metrics
    if spec.kind == "hide":
        regions: Dict[tuple, tuple] = {}        # (hide, grade) -> usable region, prepared
        metrics["grades"] = material_grades(layout, placed, grade, options.tolerance, regions)
        _add_region_grades(parts, layout, metrics["grades"], options, regions)
    per: List[Dict[str, object]] = []
    if spec.kind == "strip":
        c = layout.containers[0]
        length = extent[c.id] + options.margin if count[c.id] else 0.0
        c.outline = rectangle(0.0, 0.0, length, spec.height)
        dens = area[c.id] / (length * spec.height) if length > 0 else 0.0
        metrics.update({"strip_width_mm": spec.height, "strip_length_mm": round(length, 6),
                        "density": round(dens, 6), "item_area_mm2": round(area[c.id], 3)})
        per.append({"id": c.id, "length_mm": round(length, 6), "parts": count[c.id],
                    "density": round(dens, 6)})
    elif spec.kind == "sheet":
        sa = spec.width * spec.height
        for c in layout.containers:
            per.append({"id": c.id, "parts": count[c.id], "part_area_mm2": round(area[c.id], 3),
                        "utilisation": round(area[c.id] / sa, 6),
                        "used_length_mm": round(extent[c.id] + options.margin, 3)})
        n = len(layout.containers)
        total = sum(area.values())
        metrics.update({"sheets": n, "sheet_size_mm": [spec.width, spec.height],
                        "utilisation": round(total / (n * sa), 6) if n else 0.0,
                        "item_area_mm2": round(total, 3)})
    else:
        total_used = total_net = total_gross = 0.0
        for c in layout.containers:
            na, ga = net_area(c), Polygon(c.outline).area
            total_used += area[c.id]
            total_net += na
            total_gross += ga
            per.append({"id": c.id, "parts": count[c.id], "part_area_mm2": round(area[c.id], 3),
                        "net_area_mm2": round(na, 3), "gross_area_mm2": round(ga, 3),
                        "utilisation": round(area[c.id] / na, 6) if na else 0.0,
                        "utilisation_gross": round(area[c.id] / ga, 6) if ga else 0.0,
                        "defects": len(c.defects), "zones": len(c.zones)})
        metrics.update({"hides": len(layout.containers), "hides_available": len(spec.hides),
                        "utilisation": round(total_used / total_net, 6) if total_net else 0.0,
                        "utilisation_gross": round(total_used / total_gross, 6) if total_gross else 0.0,
                        "item_area_mm2": round(total_used, 3)})
    metrics.update({"per_container": per, "placed_count": len(layout.placements),
                    "unplaced_count": len(layout.unplaced)})
    layout.findings = [f for f in layout.findings if f.code != "unplaced-parts"]
    if layout.unplaced:
        layout.findings.append(Finding(
            "warning", "unplaced-parts",
            f"{len(layout.unplaced)} part copies found no place: "
            + ", ".join(f"{k}#{c}" for k, c in layout.unplaced[:10])
            + (" ..." if len(layout.unplaced) > 10 else "")))
