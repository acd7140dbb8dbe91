"""The optional ``sparrow`` engine: spyrrow 0.9 (MIT) run in a child process.

Only strip jobs: sparrow minimises the length of a strip; it ignores holes
(no part-in-part), knows no sheets, hides, defects, quality zones or
mirroring.  Spacing is passed as sparrow's ``min_items_separation``; the
margin is applied by narrowing the strip and shifting the result.  The
child is killed when the user cancels or when it overruns the budget by more
than 120 s.  Its layout goes through the same validity checker as ours.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from typing import Dict, List, Optional, Sequence


from ..errors import CancelledError, InputError, LeatherCutError
from ..model import Container, Finding, Layout, Part, Placement
from ..progress import ProgressFn, report
from .containers import rectangle
from .options import NestOptions


def python_for_child() -> str:
    """A Python interpreter for the child (inside FreeCAD sys.executable is FreeCAD)."""
    exe = sys.executable or ""
    if "python" in os.path.basename(exe).lower():
        return exe
    for cand in (os.path.join(sys.prefix, "bin", "python3"), shutil.which("python3")):
        if cand and os.path.exists(cand):
            return cand
    raise LeatherCutError("no Python interpreter found to run the sparrow engine")


def run_sparrow(parts: Sequence[Part], options: NestOptions,
                progress: Optional[ProgressFn] = None) -> Layout:
    spec = options.container
    if spec.kind != "strip":
        raise InputError("the sparrow engine only nests on a strip (--strip W); "
                         "use --engine own for sheets and hides")
    findings: List[Finding] = []
    height = spec.height - 2.0 * options.margin
    if height <= 0:
        raise InputError(f"margin {options.margin} mm leaves no strip width")
    items = []
    for p in parts:
        if p.quantity <= 0:
            continue
        rots = options.part_rotations(p.rotations)
        pts = p.outer.points(options.chord_tol)
        items.append({"id": p.id, "shape": [list(q) for q in pts], "demand": p.quantity,
                      "orientations": None if rots is None else [float(a) for a in rots]})
        if p.holes:
            findings.append(Finding("info", "sparrow-no-holes",
                                    f"part {p.id}: sparrow does not use holes for part-in-part",
                                    p.id))
    if not items:
        return Layout(findings=[Finding("warning", "nothing-to-nest", "no parts to nest")])
    req = {"height": height, "items": items, "time": max(options.time_budget, 1.0),
           "seed": options.seed, "workers": options.workers,
           "separation": options.spacing or None}
    report(progress, 0.02, "starting sparrow")
    env = dict(os.environ)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    # the child sees the same packages as this process (inside FreeCAD the
    # interpreter differs from the one spyrrow was installed for)
    paths = [root] + [p for p in sys.path if p and os.path.isdir(p)]
    env["PYTHONPATH"] = os.pathsep.join(paths + [env.get("PYTHONPATH", "")])
    t0 = time.monotonic()
    proc = subprocess.Popen([python_for_child(), "-m", "LeatherCutWorkbench.core.nesting.sparrow_runner"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=env, text=True)
    assert proc.stdin is not None
    proc.stdin.write(json.dumps(req))
    proc.stdin.close()
    limit = req["time"] + 120.0
    try:
        while proc.poll() is None:
            el = time.monotonic() - t0
            if el > limit:
                proc.kill()
                raise LeatherCutError(f"sparrow overran its {req['time']:.0f} s budget by 120 s; stopped")
            report(progress, 0.05 + 0.9 * min(1.0, el / req["time"]), "sparrow searching")
            time.sleep(0.1)
    except CancelledError:
        proc.kill()
        proc.wait()
        raise
    out, err = proc.stdout.read(), proc.stderr.read()  # type: ignore[union-attr]
    if proc.returncode != 0:
        last = (err.strip().splitlines() or ["no message"])[-1]
        raise LeatherCutError(f"sparrow engine failed (exit {proc.returncode}): {last}")
    res = json.loads(out)
    copies: Dict[str, int] = {}
    placements: List[Placement] = []
    for it in res["placed"]:
        pid = it["id"]
        k = copies.get(pid, 0)
        copies[pid] = k + 1
        placements.append(Placement(part_id=pid, copy=k, container="strip",
                                    x=float(it["x"]) + options.margin,
                                    y=float(it["y"]) + options.margin,
                                    angle=float(it["rotation"]) % 360.0, mirrored=False))
    unplaced = [(p.id, k) for p in parts for k in range(copies.get(p.id, 0), p.quantity)]
    layout = Layout(containers=[Container(id="strip", kind="strip", outline=rectangle(0, 0, 0, spec.height))],
                    placements=placements, unplaced=unplaced, metrics={}, findings=findings)
    from .engine import fill_metrics
    fill_metrics(parts, layout, options)
    layout.metrics.update({"engine": "sparrow", "time_s": round(time.monotonic() - t0, 3),
                           "seed": options.seed})
    return layout
