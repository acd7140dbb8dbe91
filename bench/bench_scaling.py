"""Scaling of the GA against the same search given 20x the time.

Run:  .venv/bin/python bench/bench_scaling.py 1000,5000

Synthetic jobs as in bench_plan.py (tests/plan_shapes.leather_job, ~20 entry
candidates per contour, no holes); GA budget max(2 s, 2 s x contours / 1000),
the reference is run_ga with 20x that budget; peak RSS of this process so far.
Prints Markdown table rows: contours | candidates | NN | GA | wall s | CPU s |
generations | 20x time (generations) | GA vs 20x | peak RSS MB.
"""

import math
import os
import resource
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))
sys.path.insert(0, HERE)

from bench_plan import instance_for  # noqa: E402
from plan_shapes import leather_job  # noqa: E402
from LeatherCutWorkbench.core.pathplan.ga import run_ga  # noqa: E402
from LeatherCutWorkbench.core.pathplan.nn import nearest_neighbour  # noqa: E402

print(f"load average {os.getloadavg()[0]:.1f}", flush=True)
for m in [int(x) for x in sys.argv[1].split(",")]:
    size = 1000.0 * math.sqrt(m / 62.0)
    parts = leather_job(seed=m, n_parts=m, n_holes=0, size=size)
    inst = instance_for(parts, 25.0)
    tl = max(2.0, 2.0 * m / 1000.0)
    nn = inst.tour_cost(*nearest_neighbour(inst))
    w = time.perf_counter(); c = time.process_time()
    r = run_ga(inst, time_limit=tl, seed=1)
    w, c = time.perf_counter() - w, time.process_time() - c
    r20 = run_ga(inst, time_limit=20 * tl, seed=1)
    print(f"| {m} | {inst.n - 1} | {nn:.0f} | {r.cost:.0f} | {w:.1f} | {c:.1f} | {r.iterations} ({r.stopped_by}) | {r20.cost:.0f} ({r20.iterations}, {r20.stopped_by}) | {100 * (r.cost / r20.cost - 1):+.2f} % | {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} |", flush=True)
