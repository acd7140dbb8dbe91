"""Benchmark of contour recognition (issue: contour recognition).

Run:  /work/main/.venv/bin/python bench/bench_recognise.py [--quick]

Cases (generated, known answers, checked after every run):
* N separate 40x30 parts, each with a round hole and a line lead-in (6 edges
  per part), N = 1,000 ... 10,000;
* a common-edge grid of 1,000 cells drawn three ways: single long lines
  (T-junctions and crossings), every cell as its own closed outline (shared
  edges twice), every cell side once.

Peer, same run, same edges: FreeCAD's fastest wire builder
``Part.Compound(edges).connectEdgesToWires(False, tol)`` followed by
``Part.Face`` per closed wire -- what a plain FreeCAD script would do.  It does
not find holes, lead-ins or common-edge cells (its counts are printed), so the
ratio is a speed reference only.

Prints a Markdown table: median of 3 runs, wall-clock seconds and the CPU
seconds of this process (less disturbed when other jobs load the machine), and
the load average.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
sys.path.insert(0, os.path.join(HERE, ".."))

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import recognise_shapes as S  # noqa: E402
from LeatherCutWorkbench.core.model import ArcEdge, LineEdge  # noqa: E402
from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise  # noqa: E402

V = FreeCAD.Vector
RUNS = 3


def peer(edges, tol: float = 0.01):
    """connectEdgesToWires + Part.Face: (seconds, closed wires, faces)."""
    t = time.perf_counter()
    pe = []
    for e in edges:
        if isinstance(e, LineEdge):
            pe.append(Part.LineSegment(V(*e.start, 0), V(*e.end, 0)).toShape())
        elif isinstance(e, ArcEdge):
            pe.append(Part.makeCircle(e.radius, V(*e.center, 0), V(0, 0, 1),
                                      min(e.start_angle, e.start_angle + e.sweep),
                                      max(e.start_angle, e.start_angle + e.sweep)))
    wires = Part.Compound(pe).connectEdgesToWires(False, tol).Wires
    faces = [Part.Face(w) for w in wires if w.isClosed()]
    return time.perf_counter() - t, sum(1 for w in wires if w.isClosed()), len(faces)


def timed(fn, runs: int = RUNS):
    """(median wall seconds, median CPU seconds of this process, last result)."""
    times, cpu, result = [], [], None
    for _ in range(runs):
        t, c = time.perf_counter(), time.process_time()
        result = fn()
        times.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return statistics.median(times), statistics.median(cpu), result


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="1,000 and 2,000 parts only")
    quick = ap.parse_args().quick
    sizes = [1000, 2000] if quick else [1000, 2000, 5000, 10000]
    rows = []
    load0 = os.getloadavg()
    for n in sizes:
        edges = S.many_parts(n)
        d = S.drawing(edges)
        t, tc, rec = timed(lambda: recognise(d, RecogniseOptions()))
        ok = (len(rec.parts) == n and all(len(p.holes) == 1 and len(p.lead_ins) == 1
                                          for p in rec.parts) and not rec.flags)
        tp, _, (_, closed, _) = timed(lambda: peer(edges))
        rows.append((f"{n:,} parts + hole + lead-in", len(edges), t, tc, ok,
                     f"{n} parts, {n} holes, {n} lead-ins", tp, f"{closed} closed wires"))
    for label, maker in [("grid 40x25 single lines", S.grid_lines),
                         ("grid 40x25 separate outlines", S.grid_separate),
                         ("grid 40x25 each side once", S.grid_segments)]:
        edges = maker(40, 25)
        d = S.drawing(edges)
        t, tc, rec = timed(lambda: recognise(d, RecogniseOptions()))
        ok = len(rec.active_parts()) == 1000 and not rec.flags and \
            all(abs(p.outer.area - 100.0) < 1e-6 for p in rec.parts)
        tp, _, (_, closed, _) = timed(lambda: peer(edges))
        rows.append((label, len(edges), t, tc, ok, f"{len(rec.active_parts())} cells",
                     tp, f"{closed} closed wires"))
    load1 = os.getloadavg()
    print(f"recognise benchmark, median of {RUNS} runs, FreeCAD {'.'.join(FreeCAD.Version()[:3])}, "
          f"{os.cpu_count()} CPUs, load average {load0[0]:.2f} at start / {load1[0]:.2f} at end")
    print()
    print("| case | edges | recognise wall (s) | recognise CPU (s) | correct | found | "
          "peer wall (s) | peer found | recognise/peer |")
    print("|---|---:|---:|---:|:---:|---|---:|---|---:|")
    for label, ne, t, tc, ok, found, tp, pfound in rows:
        print(f"| {label} | {ne:,} | {t:.2f} | {tc:.2f} | {'yes' if ok else 'NO'} | {found} | "
              f"{tp:.2f} | {pfound} | {t / tp:.2f} |")
    base = rows[0]
    print()
    print("Growth of recognise time with the part count (separate parts):")
    print()
    print("| parts | wall s | CPU s | CPU s per 1,000 parts | CPU x of 1,000 parts |")
    print("|---:|---:|---:|---:|---:|")
    for (label, ne, t, tc, ok, found, tp, pfound), n in zip(rows, sizes):
        print(f"| {n:,} | {t:.2f} | {tc:.2f} | {tc / n * 1000:.2f} | {tc / base[3]:.1f} |")
    return 0 if all(r[4] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
