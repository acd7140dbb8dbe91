"""Child process that runs spyrrow (sparrow) on one strip instance.

Reads ``{"height", "items": [{"id", "shape", "demand", "orientations"}], "time",
"seed", "workers", "separation"}`` as JSON on stdin and writes
``{"length", "density", "placed": [{"id", "rotation", "x", "y"}]}`` on stdout.
Run as ``python -m LeatherCutWorkbench.core.nesting.sparrow_runner``; it lives
in its own process because a native abort in the library must not take the
caller (FreeCAD) down.
"""

import json
import sys


def main() -> int:
    req = json.load(sys.stdin)
    import spyrrow

    items = [spyrrow.Item(it["id"], [tuple(p) for p in it["shape"]], int(it["demand"]),
                          it["orientations"]) for it in req["items"]]
    inst = spyrrow.StripPackingInstance("leathercut", float(req["height"]), items)
    kw = dict(early_termination=False, total_computation_time=max(1, int(round(req["time"]))),
              seed=int(req["seed"]), num_workers=req.get("workers"))
    if req.get("separation"):
        kw["min_items_separation"] = float(req["separation"])
    sol = inst.solve(spyrrow.StripPackingConfig(**kw))
    out = {"length": sol.width, "density": sol.density,
           "placed": [{"id": p.id, "rotation": p.rotation, "x": p.translation[0],
                       "y": p.translation[1]} for p in sol.placed_items]}
    json.dump(out, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
