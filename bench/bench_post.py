"""Post-processing and live-link benchmark.

Run:  /work/main/.venv/bin/python bench/bench_post.py

Prints Markdown tables:

1. writers: time to write a 30-part leather job (120 items: round holes,
   slotted holes with arcs, outlines with lead-ins, rounded corners, spline
   curves, crease lines; 2400 x 1500 mm on the 2500 x 1600 table) for every
   shipped profile and format, with output size, and the time to trace the
   G-code back with the project's interpreter;
2. link: lines per second streamed through pyserial into the fake controller
   on a pseudo-terminal, send-response vs character counting, with a
   controller that needs 0 ms and 1 ms per line (a machine busy moving).
   Peer: send-response is the GRBL documentation's recommended default; the
   ratio char-count / send-response is what buffering buys.

CPU seconds (time.process_time) are given next to wall seconds: the machine
is shared, CPU is the comparable figure for the writers.
"""

from __future__ import annotations

import datetime
import os
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))

from post_helpers import sample_plan  # noqa: E402

from LeatherCutWorkbench.core.model import CutPlan  # noqa: E402
from LeatherCutWorkbench.post import dxf_out, gcode, hpgl  # noqa: E402
from LeatherCutWorkbench.post.emulator import FakeController  # noqa: E402
from LeatherCutWorkbench.post.gcode_reader import interpreter_for  # noqa: E402
from LeatherCutWorkbench.post.link import GrblLink, Journal, job_from_program  # noqa: E402
from LeatherCutWorkbench.post.profiles import load_profile  # noqa: E402


def big_plan() -> CutPlan:
    plan = CutPlan(home=(0.0, 0.0))
    for i in range(6):
        for j in range(5):
            plan.items += sample_plan(dx=i * 400.0, dy=j * 300.0 - 30.0).items
    return plan


def timed(fn, repeat=3):
    walls, cpus, out = [], [], None
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return statistics.median(walls), statistics.median(cpus), out


def writers_table(plan: CutPlan) -> str:
    rows = ["| profile | format | wall s | CPU s | lines | KiB | trace back s |",
            "|---|---|---|---|---|---|---|"]
    for name in ("grblhal_tangential", "grbl11_knife_z_servo", "linuxcnc_tangential",
                 "flame_plasma"):
        prof = load_profile(name)
        if name == "grbl11_knife_z_servo":
            prof.table_size = (2500.0, 1600.0)     # same job on the small GRBL table's profile
        w, c, text = timed(lambda: gcode.export(plan, prof))

        def trace():
            it = interpreter_for(prof)
            for n, line in enumerate(text.splitlines(), 1):
                it.execute(line, n)
        tw, _, _ = timed(trace, 1)
        rows.append(f"| {name} | gcode | {w:.3f} | {c:.3f} | {text.count(chr(10))} | "
                    f"{len(text) / 1024:.0f} | {tw:.3f} |")
    prof = load_profile("hpgl_plotter")
    prof.table_size = (2500.0, 20000.0)
    w, c, text = timed(lambda: hpgl.export(plan, prof))
    rows.append(f"| hpgl_plotter | hpgl | {w:.3f} | {c:.3f} | {text.count(chr(10))} | "
                f"{len(text) / 1024:.0f} | – |")
    prof = load_profile("grblhal_tangential")
    w, c, text = timed(lambda: dxf_out.export(plan, prof))
    rows.append(f"| grblhal_tangential | dxf (R12) | {w:.3f} | {c:.3f} | {text.count(chr(10))} | "
                f"{len(text) / 1024:.0f} | – |")
    return "\n".join(rows)


def stream_rate(job, mode: str, line_time: float) -> float:
    with FakeController(flavour="grblhal", axes="XYZC", line_time=line_time) as emu:
        with GrblLink(emu.port, status_interval=0.2, link_timeout=3.0) as link:
            link.greet()
            with tempfile.TemporaryDirectory() as d:
                j = Journal.open(os.path.join(d, "j"), job, mode)
                t = time.perf_counter()
                res = link.stream(job, j, mode)
                dt = time.perf_counter() - t
                j.close()
    assert res.status == "done", res
    assert emu.executed == job.blocks
    return len(job.blocks) / dt


def link_table(plan: CutPlan) -> str:
    prof = load_profile("grblhal_tangential")
    small = CutPlan(plan.items[:40], home=plan.home)
    job = job_from_program("bench.nc", gcode.build_program(small, prof))
    rows = [f"Job: {len(job.blocks)} lines (first 40 items), journal on a temporary folder.",
            "",
            "| controller time per line | send-response lines/s | char-count lines/s | ratio |",
            "|---|---|---|---|"]
    for lt in (0.0, 0.001):
        sr = stream_rate(job, "send-response", lt)
        cc = stream_rate(job, "char-count", lt)
        rows.append(f"| {lt * 1000:.0f} ms | {sr:,.0f} | {cc:,.0f} | {cc / sr:.2f} |")
    return "\n".join(rows)


def main() -> int:
    plan = big_plan()
    segs = sum(len(i.segments) for i in plan.items)
    print(f"Post-processing benchmark, {datetime.date.today()}, command: "
          f"`.venv/bin/python bench/bench_post.py`")
    print()
    print(f"Job: {len(plan.items)} items, {segs} plan segments, "
          f"{sum(i.length for i in plan.items) / 1000:.1f} m of cut.")
    print()
    print(writers_table(plan))
    print()
    print(link_table(plan))
    return 0


if __name__ == "__main__":
    sys.exit(main())
