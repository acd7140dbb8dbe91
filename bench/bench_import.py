"""Benchmark: DXF import of a generated 100,000-entity drawing vs ``ezdxf.readfile``.

Generates (into a temporary directory, never committed) a drawing with LINEs,
ARCs, CIRCLEs, bulged LWPOLYLINEs and INSERTs of blocks (some nested, rotated,
mirrored and non-uniformly scaled), then times in the same run, each in a fresh
subprocess so peak memory (ru_maxrss) belongs to one operation:

* ``ezdxf.readfile`` alone (the peer),
* ``read_drawing`` (readfile + conversion + clean-up) on the same file.

Runs ``--runs`` times (default 3), alternating, and prints a Markdown table of
medians: wall time, CPU time (robust when other jobs load the machine) and the
per-run CPU-time ratio to readfile (target <= 2), peak RSS.  ``read_drawing``
pauses Python's cyclic GC while it runs, so readfile with the GC paused is
shown too: the honest comparison for the conversion work itself.

    .venv/bin/python bench/bench_import.py [--entities 100000] [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def generate(path: str, n: int, seed: int = 1) -> dict:
    """Write an ``n``-entity model space to ``path``; returns the composition."""
    import ezdxf

    rnd = random.Random(seed)
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    for k in range(20):
        b = doc.blocks.new(f"PART{k}")
        w, h = 20 + k, 10 + k / 2
        b.add_lwpolyline([(0, 0, 0), (w, 0, 0.3), (w, h, 0), (0, h, -0.2)], format="xyb", close=True)
        b.add_circle((w / 2, h / 2), h / 5)
        b.add_line((2, 2), (w - 2, 2), dxfattribs={"layer": "MARK"})
        b.add_arc((w / 2, h), w / 4, 0, 180)
        b.add_point((w / 3, h / 3), dxfattribs={"layer": "DRILL"})
        if k % 4 == 3:  # nested block
            b.add_blockref(f"PART{k - 1}", (w, 0), dxfattribs={"rotation": 90})
    msp = doc.modelspace()
    size = 5000.0
    mix = {"LINE": 0.40, "ARC": 0.15, "CIRCLE": 0.05, "LWPOLYLINE": 0.25, "INSERT": 0.15}
    counts = {k: int(round(v * n)) for k, v in mix.items()}
    counts["LINE"] += n - sum(counts.values())

    def xy():
        return (rnd.uniform(0, size), rnd.uniform(0, size))

    for _ in range(counts["LINE"]):
        x, y = xy()
        msp.add_line((x, y), (x + rnd.uniform(-50, 50), y + rnd.uniform(-50, 50)))
    for _ in range(counts["ARC"]):
        msp.add_arc(xy(), rnd.uniform(1, 40), rnd.uniform(0, 360), rnd.uniform(0, 360))
    for _ in range(counts["CIRCLE"]):
        msp.add_circle(xy(), rnd.uniform(1, 20))
    for _ in range(counts["LWPOLYLINE"]):
        x, y = xy()
        pts = [(x + rnd.uniform(0, 60), y + rnd.uniform(0, 60), rnd.choice((0, 0, 0.4, -0.3)))
               for _ in range(rnd.randint(3, 7))]
        msp.add_lwpolyline(pts, format="xyb", close=rnd.random() < 0.5)
    for i in range(counts["INSERT"]):
        sx = rnd.choice((1, 1, 1, -1, 2))
        sy = rnd.choice((1, 1, 1, 0.5))
        msp.add_blockref(f"PART{i % 20}", xy(), dxfattribs={
            "rotation": rnd.uniform(0, 360), "xscale": sx, "yscale": sy})
    doc.saveas(path)
    return counts


def child(mode: str, path: str) -> None:
    """Run one measurement in this (fresh) process and print JSON."""
    import resource

    import gc

    sys.path.insert(0, REPO)
    import ezdxf
    from LeatherCutWorkbench.core.dxfimport import ImportOptions, read_drawing

    t, c = time.perf_counter(), time.process_time()
    if mode.startswith("readfile"):
        if mode == "readfile-nogc":
            gc.disable()
        doc = ezdxf.readfile(path)
        extra = {"entities": len(doc.modelspace())}
    else:
        d = read_drawing(path, ImportOptions(cleanup=(mode == "import")))
        extra = {"edges": len(d.edges), "marks": len(d.marks),
                 "cleanup": d.stats.get("cleanup")}
    dt, dc = time.perf_counter() - t, time.process_time() - c
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(json.dumps({"seconds": dt, "cpu": dc, "peak_rss_mb": rss, **extra}))


MODES = {
    "readfile": "`ezdxf.readfile` (the peer)",
    "readfile-nogc": "`ezdxf.readfile`, cyclic GC paused (for reference)",
    "import": "`read_drawing`, clean-up on (default)",
    "import-no-cleanup": "`read_drawing --no-cleanup`",
}


def run_child(mode: str, path: str) -> dict:
    out = subprocess.run([sys.executable, __file__, "--child", mode, path],
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--entities", type=int, default=100_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--child", nargs=2, metavar=("MODE", "PATH"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(*args.child)
        return
    with tempfile.TemporaryDirectory(prefix="lc-bench-import-") as tmp:
        path = os.path.join(tmp, "bench.dxf")
        t = time.perf_counter()
        counts = generate(path, args.entities)
        gen = time.perf_counter() - t
        mb = os.path.getsize(path) / 1e6
        res = {m: [] for m in MODES}
        for _ in range(args.runs):
            for mode in MODES:
                res[mode].append(run_child(mode, path))
    med = {m: statistics.median(r["seconds"] for r in rs) for m, rs in res.items()}
    cpu = {m: statistics.median(r["cpu"] for r in rs) for m, rs in res.items()}
    rss = {m: statistics.median(r["peak_rss_mb"] for r in rs) for m, rs in res.items()}
    # ratio per run (same run, adjacent processes), then the median over runs
    ratio = {m: statistics.median(r["cpu"] / p["cpu"] for r, p in zip(rs, res["readfile"]))
             for m, rs in res.items()}
    imp = res["import"][0]
    print(f"Generated {args.entities} entities ({', '.join(f'{v} {k}' for k, v in counts.items())}), "
          f"{mb:.1f} MB, in {gen:.1f} s; {args.runs} runs, medians.\n")
    print("| step | wall (s) | CPU (s) | CPU ratio to `ezdxf.readfile` | peak RSS (MB) |")
    print("|---|---:|---:|---:|---:|")
    for m in MODES:
        print(f"| {MODES[m]} | {med[m]:.2f} | {cpu[m]:.2f} | {ratio[m]:.2f} | {rss[m]:.0f} |")
    print(f"\nImport result: {imp['edges']} edges, {imp['marks']} marks; clean-up: "
          f"{json.dumps(imp['cleanup'])}")
    runs = "; ".join(m + ": " + ", ".join(f"{r['seconds']:.2f}/{r['cpu']:.2f}" for r in rs)
                     for m, rs in res.items())
    print(f"All runs (wall/CPU s): {runs}")


if __name__ == "__main__":
    main()
