"""Whole-process wall time of ``leathercut nest`` against its time budget.

    .venv/bin/python bench/bench_budget.py [--time 10] [--cases deepnest,wm,...|all] [--repeat 1]
                                           [--outputs] [--load N] [--root DIR]

Each case runs the real CLI under ``/usr/bin/time -v`` (through
``bench/leathercut_first_layout.py``, which starts like the installed
``leathercut`` script, so the budget counts from the process start, and
reports when the first valid layout reached the parent process) and prints
one Markdown row: wall s, the limit T + 10 % + 1 s, the margin (limit -
wall), the first layout's time (s since the process start), the engine's
``metrics.time_s``, max RSS, the result and the 1-minute load average at
the start.  ``--outputs`` also writes the layout JSON and the DXF (part of
the tail the budget must cover); ``--load N`` starts N busy CPU processes
for the runs and ends them afterwards; ``--root DIR`` runs another checkout's
code with its own ``.venv`` (e.g. ``/work/main`` for a before/after table;
read only).  ``--cases all``: every case below.  The DXF samples are read
from ``/work/shared/samples/dxf/`` (cases whose file is missing are skipped).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
from typing import Dict, List, Optional

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SAMPLES = "/work/shared/samples/dxf"
HIDES = os.path.join(HERE, "data", "hides")

#: case name -> (label, arguments after ``leathercut nest``)
CASES: Dict[str, tuple] = {
    "deepnest": ("deepnest 700x400", [f"{SAMPLES}/deepnest_ReadMeExampleSmall.dxf", "--sheet", "700x400"]),
    "deepnest-sp3": ("deepnest 700x400, spacing 3, 1 worker",
                     [f"{SAMPLES}/deepnest_ReadMeExampleSmall.dxf", "--sheet", "700x400",
                      "--spacing", "3", "--workers", "1"]),
    "wm": ("WM_SLIM_TANK 1600x1000 --sizes all",
           [f"{SAMPLES}/WM_SLIM_TANK.DXF", "--sheet", "1600x1000", "--sizes", "all"]),
    "wm-rot": ("WM_SLIM_TANK --sizes all --rotations 0,180",
               [f"{SAMPLES}/WM_SLIM_TANK.DXF", "--sheet", "1600x1000", "--sizes", "all",
                "--rotations", "0,180"]),
    "gmx": ("GMX1016S18_AAMA 1600x1000 --sizes all",
            [f"{SAMPLES}/GMX1016S18_AAMA.DXF", "--sheet", "1600x1000", "--sizes", "all"]),
    "test1": ("Baldacci Test1 (hides)", ["--esicup", f"{HIDES}/Test1.json"]),
    "test2": ("Baldacci Test2 (hides)", ["--esicup", f"{HIDES}/Test2.json"]),
    "test10": ("Baldacci Test10 (hides)", ["--esicup", f"{HIDES}/Test10.json"]),
}
CASES.update({f"test{k}": (f"Baldacci Test{k} (hides)", ["--esicup", f"{HIDES}/Test{k}.json"])
              for k in range(3, 10)})
CASES["scarpa"] = ("Baldacci Scarpa (hides)", ["--esicup", f"{HIDES}/Scarpa.json"])
#: the order of ``--cases all``
ALL = ["deepnest", "deepnest-sp3", "wm", "wm-rot", "gmx", "test1", "test2", "test3", "test4",
       "test5", "test6", "test7", "test8", "test9", "test10", "scarpa"]
WRAPPER = os.path.join(HERE, "leathercut_first_layout.py")


def load_average() -> float:
    with open("/proc/loadavg", encoding="ascii") as fh:
        return float(fh.read().split()[0])


def _time_field(text: str, name: str) -> Optional[str]:
    m = re.search(rf"^\s*{re.escape(name)}: (.*)$", text, re.M)
    return m.group(1).strip() if m else None


def _seconds(clock: str) -> float:
    parts = [float(p) for p in clock.split(":")]
    s = 0.0
    for p in parts:
        s = s * 60.0 + p
    return s


def run_case(name: str, budget: float, outputs: bool, root: str = ROOT) -> Dict[str, object]:
    label, args = CASES[name]
    exe = os.path.join(root, ".venv", "bin", "python")
    env = dict(os.environ, PYTHONPATH=root)
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [exe, WRAPPER, "nest", *args, "--time", f"{budget:g}", "--json"]
        if outputs:
            cmd += ["--layout-out", os.path.join(tmp, "l.json"), "--dxf-out", os.path.join(tmp, "l.dxf")]
        load = load_average()
        r = subprocess.run(["/usr/bin/time", "-v", *cmd], capture_output=True, text=True,
                           cwd=root, env=env)
    wall = _seconds(_time_field(r.stderr, "Elapsed (wall clock) time (h:mm:ss or m:ss)") or "nan")
    rss = int(_time_field(r.stderr, "Maximum resident set size (kbytes)") or 0)
    first = re.search(r"^first-layout-s (\S+)$", r.stderr, re.M)
    row: Dict[str, object] = {"case": label, "load": load, "wall": wall, "rss_mb": rss / 1024.0,
                              "rc": r.returncode, "first": float(first.group(1)) if first else None}
    try:
        d = json.loads(r.stdout)
        m = d["metrics"]
        row["time_s"] = m.get("time_s")
        n = m.get("sheets", m.get("hides"))
        kind = "sheets" if "sheets" in m else "hides"
        row["result"] = (f"{m.get('placed_count')}/{m.get('placed_count', 0) + m.get('unplaced_count', 0)}"
                         f" placed, {n} {kind}, {100 * m.get('utilisation', 0):.2f} %")
    except (ValueError, KeyError):
        row["time_s"] = None
        row["result"] = f"exit {r.returncode}: {r.stderr.strip().splitlines()[:1]}"
    return row


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--time", type=float, default=10.0)
    ap.add_argument("--cases", default="deepnest,deepnest-sp3,wm,wm-rot,gmx,test1,test2")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--outputs", action="store_true", help="also write layout JSON and DXF")
    ap.add_argument("--load", type=int, default=0, help="busy CPU processes during the runs")
    ap.add_argument("--root", default=ROOT, help="checkout whose code and .venv run (default: this one)")
    a = ap.parse_args(argv)
    names = ALL if a.cases == "all" else a.cases.split(",")
    limit = 1.1 * a.time + 1.0
    busy = [subprocess.Popen([sys.executable, "-c", "while 1: pass"]) for _ in range(a.load)]
    try:
        print(f"T = {a.time:g} s, limit {limit:.1f} s, background busy processes: {a.load}"
              f"{', outputs written' if a.outputs else ''}, code: {a.root}\n")
        print("| case | load | wall s | limit s | margin s | first layout s | engine time_s "
              "| max RSS MB | result |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name in names:
            label, args = CASES[name]
            if args[0].startswith(SAMPLES) and not os.path.exists(args[0]):
                print(f"| {label} | - | skipped: {args[0]} missing | | | | | | |")
                continue
            for _ in range(a.repeat):
                r = run_case(name, a.time, a.outputs, a.root)
                first = "-" if r["first"] is None else f"{r['first']:.2f}"
                print(f"| {r['case']} | {r['load']:.1f} | {r['wall']:.2f} | {limit:.1f} | "
                      f"{limit - r['wall']:+.2f} | {first} | {r['time_s']} | {r['rss_mb']:.0f} "
                      f"| {r['result']} |", flush=True)
    finally:
        for p in busy:
            p.kill()
            p.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
