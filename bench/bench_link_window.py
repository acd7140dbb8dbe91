"""What the link's cut window and receive-buffer bound cost while streaming.

Run:  .venv/bin/python bench/bench_link_window.py [BLOCK_TIME_S]

Streams the sample job of the link tests (4 parts, 16 items: outlines of
lines and arcs, holes, slots) through pyserial into the fake controller with its planner model (GRBL: 15
blocks, 128-byte receive buffer; grblHAL: 100 blocks, 1024 bytes), every
queued block taking ``block_time`` to execute, in character-counting mode,
with cut window 0 (no limit, the default), 1 and 2.  The ideal time is blocks executed x
``block_time``; *starved* is how much longer the stream took (the planner
ran empty waiting for lines), and *polls* how many status reports the link
asked for.  The fake controller has no acceleration, so a starved planner
costs only the wait, not the deceleration a real machine adds.
"""

from __future__ import annotations

import datetime
import inspect
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))
sys.path.insert(0, HERE)

from link_helpers import make_job  # noqa: E402

from LeatherCutWorkbench.post.emulator import FakeController  # noqa: E402
from LeatherCutWorkbench.post.link import GrblLink, Journal  # noqa: E402
from LeatherCutWorkbench.post.profiles import load_profile  # noqa: E402

#: s per queued line; the sample job's lines are 5-30 mm long (0.03-0.15 s at
#: 200 mm/s): 0.02 s is a fast machine, 0.005 s flattened curves at speed,
#: 0.002 s a stress case (argument 1)
BLOCK_TIME = float(sys.argv[1]) if len(sys.argv) > 1 else 0.02


def stream(job, profile, flavour: str, window: int):
    """(wall s, ideal s, polls, buffer resyncs) of one char-count stream."""
    axes = "XYZ" if flavour == "grbl" else "XYZC"
    blocks = 15 if flavour == "grbl" else 100
    opts = dict(status_interval=0.2, link_timeout=3.0)
    if "cut_window" in inspect.signature(GrblLink).parameters:    # before/after the window
        opts["cut_window"] = window
    with FakeController(flavour=flavour, axes=axes, planner_blocks=blocks,
                        block_time=BLOCK_TIME) as emu:
        with GrblLink(emu.port, **opts) as link:
            link.use_profile(profile)
            link.greet()
            polls0 = [0]
            real = link._poll

            def counted():
                polls0[0] += 1
                real()
            link._poll = counted
            with tempfile.TemporaryDirectory() as d:
                j = Journal.open(os.path.join(d, "j"), job, "char-count", profile)
                t = time.perf_counter()
                res = link.stream(job, j, "char-count")
                while emu._queue:
                    time.sleep(0.001)
                dt = time.perf_counter() - t
                j.close()
        assert res.status == "done", res
        moves = sum(1 for r in emu.results if r[3] and any(a in r[1] for a in "XYZC"))
    return dt, moves * BLOCK_TIME, polls0[0], getattr(res, "buffer_resyncs", 0)


def main() -> int:
    print(f"Cut window benchmark, {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC, load "
          f"{os.getloadavg()[0]:.1f}, block time {BLOCK_TIME:g} s, command: "
          f"`.venv/bin/python bench/bench_link_window.py {BLOCK_TIME:g}`")
    print()
    print("| profile | window | lines | wall s | ideal s | starved s | polls | resyncs |")
    print("|---|---|---|---|---|---|---|---|")
    for name, flavour in (("grbl11_knife_z_servo", "grbl"), ("grblhal_tangential", "grblhal")):
        prof = load_profile(name)
        job = make_job(prof, copies=4)
        for window in (0, 1, 2):
            dt, ideal, polls, resyncs = stream(job, prof, flavour, window)
            print(f"| {name} | {window} | {len(job.blocks)} | {dt:.2f} | {ideal:.2f} | "
                  f"{max(0.0, dt - ideal):.2f} | {polls} | {resyncs} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
