"""The project's own nesting engine: parts + options -> Layout.

Steps: flatten parts (:mod:`shapes`), build the grid variants and the
container bins, run the bottom-left fill and the anytime search
(:mod:`search`) in worker processes, turn the best placements into a
:class:`~LeatherCutWorkbench.core.model.Layout` with container figures.
The caller (:func:`nest`) runs the validity checker on the result.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import sys
import time
from contextlib import contextmanager
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

from shapely.geometry import Polygon

from ..errors import CancelledError
from ..model import Container, Finding, Layout, Part, Placement
from ..progress import ProgressFn, report
from .blf import BinSpec
from .checker import part_polygon, placed_polygon
from .containers import net_area, rectangle, shrink_for_margin
from .options import NestOptions
from .search import Problem, _worker_entry, search
from .shapes import PieceType, make_variants, piece_from_part, to_grid

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
    bins = []
    for c in spec.hides:
        regions: Dict[int, Tuple[list, list]] = {}
        for g in sorted(set(grades)):
            outers, holes, _ = shrink_for_margin(c, g, m)
            regions[g] = ([to_grid(_arr(o), scale) for o in outers],
                          [to_grid(_arr(r), scale) for r in holes])
        bins.append(BinSpec("hide", regions=regions, grade_key={g: g for g in grades}))
    return bins, list(spec.hides), False, len(spec.hides)


def _arr(ring):
    import numpy as np
    return np.asarray(ring, dtype=float)


def _workers(options: NestOptions) -> int:
    if options.workers is not None:
        return options.workers
    return max(1, min(os.cpu_count() or 1, 8))


def run_own(parts: Sequence[Part], options: NestOptions,
            progress: Optional[ProgressFn] = None) -> Layout:
    """Nest with the project's engine (see module doc); unchecked result."""
    t_start = time.monotonic()
    report(progress, 0.0, "preparing part shapes")
    types = [piece_from_part(p, options.chord_tol, options.rotation_step,
                             options.part_rotations(p.rotations), options.mirror_override)
             for p in parts]
    types = [t for t in types if t.quantity > 0]
    findings: List[Finding] = []
    if not types:
        return Layout(containers=[], placements=[], unplaced=[], metrics={"placed_count": 0},
                      findings=[Finding("warning", "nothing-to-nest", "no parts to nest")])
    scale = _grid_scale(types, options)
    half_gap = options.spacing / 2.0
    variants = make_variants(types, scale, half_gap, options.chord_tol)
    type_variants = [[v.index for v in variants if v.type_index == i] for i in range(len(types))]
    grades = [t.grade for t in types]
    bins, hides, open_new, max_bins = _bins(options, scale, half_gap, grades)
    problem = Problem(variants, type_variants, grades, [t.area for t in types], bins,
                      open_new, max_bins)
    copies = [i for i, t in enumerate(types) for _ in range(t.quantity)]
    report(progress, 0.02, f"nesting {len(copies)} copies of {len(types)} parts")

    n_workers = _workers(options)
    budget = options.time_budget
    results = []
    if n_workers == 1 or budget <= 0 or len(copies) < 2:
        results.append(search(problem, copies, options.seed, 0, budget,
                                  options.max_evaluations if budget > 0 else 4,
                                  tick=_tick(progress, t_start, budget)))
    else:
        results = _run_pool(problem, copies, options, n_workers, progress, t_start)
    best_i = min(range(len(results)), key=lambda i: (results[i][0], i))
    cost, order, placements, _ = results[best_i]
    evaluations = sum(r[3] for r in results)
    report(progress, 0.97, "building the layout")
    layout = _to_layout(parts, types, variants, order, placements, options, scale, hides)
    layout.findings.extend(findings)
    layout.metrics.update({"engine": "own", "workers": len(results), "evaluations": evaluations,
                           "time_s": round(time.monotonic() - t_start, 3), "seed": options.seed})
    return layout


def _tick(progress: Optional[ProgressFn], t0: float, budget: float):
    if progress is None:
        return None

    def tick(best_cost) -> bool:
        frac = 0.05 + 0.9 * min(1.0, (time.monotonic() - t0) / max(budget, 1e-9))
        return progress(frac, f"searching: best {best_cost}") is not False
    return tick


@contextmanager
def _closable_stdin() -> Iterator[None]:
    """Give worker processes a stdin they can close.

    A starting ``multiprocessing`` worker first calls ``sys.stdin.close()``.
    FreeCAD's GUI replaces ``sys.stdin`` with an object that has no
    ``close()``: the worker would die with AttributeError and the pool respawn
    it forever (the search would hang).  While the pool lives, ``sys.stdin`` is
    then a read-only handle on the null device."""
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


def _run_pool(problem: Problem, copies: List[int], options: NestOptions, n: int,
              progress: Optional[ProgressFn], t0: float):
    """One search per worker process; progress is polled here, cancel terminates."""
    with _closable_stdin():
        return _run_workers(problem, copies, options, n, progress, t0)


def _run_workers(problem: Problem, copies: List[int], options: NestOptions, n: int,
                 progress: Optional[ProgressFn], t0: float):
    ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else mp.get_context()
    budget = options.time_budget
    args = [(problem, copies, options.seed, i, budget, options.max_evaluations) for i in range(n)]
    pool = ctx.Pool(n)
    try:
        pending = [pool.apply_async(_worker_entry, (a,)) for a in args]
        while not all(p.ready() for p in pending):
            frac = 0.05 + 0.9 * min(1.0, (time.monotonic() - t0) / max(budget, 1e-9))
            report(progress, frac, f"searching with {n} workers")
            time.sleep(0.1)
        results = [p.get() for p in pending]
    except CancelledError:
        pool.terminate()
        raise
    finally:
        pool.close()
        pool.join()
    return results


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
    else:
        for b, c in enumerate(hides):
            names[b] = c.id
            containers.append(c)
    for b, pl in rows:
        pl.container = names[b]
    layout = Layout(containers=containers, placements=[pl for _, pl in rows], unplaced=unplaced,
                    metrics={}, findings=[])
    fill_metrics(parts, layout, options)
    return layout


def fill_metrics(parts: Sequence[Part], layout: Layout, options: NestOptions) -> None:
    """(Re)compute the layout's figures from its placements: strip length and
    density (the strip outline is set to the used length), sheet and hide
    utilisation, per-container figures, counts; an ``unplaced-parts`` warning."""
    spec = options.container
    polys = {p.id: part_polygon(p, options.chord_tol) for p in parts}
    area: Dict[str, float] = {c.id: 0.0 for c in layout.containers}
    extent: Dict[str, float] = {c.id: 0.0 for c in layout.containers}
    count: Dict[str, int] = {c.id: 0 for c in layout.containers}
    for pl in layout.placements:
        g = placed_polygon(polys[pl.part_id], pl.x, pl.y, pl.angle, pl.mirrored)
        area[pl.container] += g.area
        extent[pl.container] = max(extent[pl.container], g.bounds[2])
        count[pl.container] += 1
    metrics = layout.metrics
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
        metrics.update({"hides": len(layout.containers),
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
