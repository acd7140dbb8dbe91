"""Benchmark: honest large drawings through ``inspect`` and ``recognise`` (issue #16 item 8).

Generates (into a temporary directory, never committed) R12 drawings of
``--squares`` 5 mm squares on a 10 mm grid, drawn either as four LINEs each
(``lines``: 250,000 squares = 1 M LINEs) or as one closed LWPOLYLINE each
(``lwpoly``: 100,000 squares), then runs the console script's ``main`` in a
fresh subprocess per call so the peak memory (``ru_maxrss``) belongs to that
call alone, and prints wall / CPU seconds and peak RSS, plus
``ezdxf.readfile`` alone (the floor of the ezdxf path; plain drawings like these
are read by core/dxfimport/plain_reader.py instead) and ``stages``: the CPU
seconds of each step of ``recognise --json`` run one after the other.

    .venv/bin/python bench/bench_hostile_or_scale.py [--lines-squares 250000]
                                                     [--lwpoly-squares 100000]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)

CHILD = r"""
import json, resource, sys, time
sys.path.insert(0, {repo!r})
what, path = sys.argv[1], sys.argv[2]
t0, c0 = time.monotonic(), time.process_time()
stages = {{}}
if what == "readfile":
    import ezdxf
    ezdxf.readfile(path)
    code = 0
elif what == "stages":
    # where recognise --json spends its time: the same calls as the CLI, one at a time
    import io
    from LeatherCutWorkbench.cli import _json_default
    from LeatherCutWorkbench.cli.json_rows import write_rows
    from LeatherCutWorkbench.cli.recognise_cmd import recognition_json
    from LeatherCutWorkbench.core.dxfimport import read_drawing
    from LeatherCutWorkbench.core.job import JobOptions, chosen_parts
    from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise
    def lap(name, c=[c0]):
        now = time.process_time()
        stages[name] = round(now - c[0], 2)
        c[0] = now
    lap("start-up and imports")
    d = read_drawing(path); lap("import (read_drawing)")
    r = recognise(d, RecogniseOptions()); lap("recognition (recognise)")
    c = chosen_parts(d, r, JobOptions()); lap("part choices (chosen_parts)")
    data = recognition_json(c, path); lap("report dict (recognition_json)")
    write_rows(data, io.StringIO(), default=_json_default); lap("JSON text (write_rows)")
    stages["reader"] = d.stats["file"].get("reader")
    code = 0
else:
    import io, contextlib
    from LeatherCutWorkbench.cli import main
    with contextlib.redirect_stdout(io.StringIO()):
        code = main([what, path, "--json"])
print(json.dumps({{"code": code, "wall": time.monotonic() - t0, "cpu": time.process_time() - c0,
                  "cpu_process": sum(resource.getrusage(resource.RUSAGE_SELF)[:2]),
                  "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "stages": stages}}))
"""


def write_squares(path: str, n: int, lwpoly: bool, pitch: float = 10.0, size: float = 5.0) -> None:
    """``n`` squares of ``size`` mm on a ``pitch`` grid (R12 ENTITIES, $INSUNITS mm)."""
    side = int(n ** 0.5) + 1
    h = 0x100
    with open(path, "w") as out:
        out.write("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n4\n"
                  "0\nENDSEC\n"
                  "0\nSECTION\n2\nENTITIES\n")
        for k in range(n):
            x0, y0 = (k // side) * pitch, (k % side) * pitch
            pts = [(x0, y0), (x0 + size, y0), (x0 + size, y0 + size), (x0, y0 + size)]
            if lwpoly:
                out.write(f"0\nLWPOLYLINE\n5\n{h:X}\n100\nAcDbEntity\n8\nCUT\n"
                          f"100\nAcDbPolyline\n90\n4\n70\n1\n")
                out.write("".join(f"10\n{x}\n20\n{y}\n" for x, y in pts))
                h += 1
                continue
            for a in range(4):
                (x1, y1), (x2, y2) = pts[a], pts[(a + 1) % 4]
                out.write(f"0\nLINE\n5\n{h:X}\n8\nCUT\n10\n{x1}\n20\n{y1}\n11\n{x2}\n21\n{y2}\n")
                h += 1
        out.write("0\nENDSEC\n0\nEOF\n")


def run(what: str, path: str) -> dict:
    """One call in a fresh interpreter; ``wall_process`` / ``cpu_process`` include
    the interpreter's start-up (``wall`` / ``cpu``: from the child's first line)."""
    t0 = time.monotonic()
    proc = subprocess.run([sys.executable, "-c", CHILD.format(repo=REPO), what, path],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        return {"code": proc.returncode, "error": proc.stderr.strip()[-300:]}
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["wall_process"] = time.monotonic() - t0
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines-squares", type=int, default=250_000)
    ap.add_argument("--lwpoly-squares", type=int, default=100_000)
    args = ap.parse_args()
    print(f"load average at start: {os.getloadavg()[0]:.2f}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, n, lw in ((f"{4 * args.lines_squares:,} LINEs", args.lines_squares, False),
                             (f"{args.lwpoly_squares:,} LWPOLYLINE squares",
                              args.lwpoly_squares, True)):
            if n <= 0:
                continue
            path = os.path.join(tmp, "drawing.dxf")
            write_squares(path, n, lw)
            mb = os.path.getsize(path) / 2 ** 20
            for what in ("readfile", "inspect", "recognise", "stages"):
                r = run(what, path)
                rows.append((label, f"{mb:.0f}", what, r))
                print(label, what, json.dumps(r), flush=True)
    print(f"load average at end: {os.getloadavg()[0]:.2f}\n")
    print("| drawing | file MiB | call | exit | wall s | CPU s | peak RSS MiB |")
    print("|---|---|---|---|---|---|---|")
    for label, mb, what, r in rows:
        print(f"| {label} | {mb} | {what} | {r.get('code')} | {r.get('wall_process', 0):.1f} | "
              f"{r.get('cpu_process', 0):.1f} | {r.get('rss_mb', 0):.0f} |")
    print("(wall and CPU of the whole process, interpreter start-up included)")
    print("\nCPU s per stage of recognise --json (the 'stages' call):")
    for label, mb, what, r in rows:
        if what == "stages":
            print(label, json.dumps(r.get("stages")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
