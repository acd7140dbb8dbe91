"""``leathercut plan``: cut order, entry points, knife lifts and idle-travel
metrics for a drawing (nested first when a container is given).
Documented in docs/CLI.md (section ``plan``)."""

from __future__ import annotations

import argparse
import os
from typing import Any, Dict

from . import Report, add_common_options
from ..core.errors import InputError
from .stages import add_stage_options, job_options, positive, positive_int, progress_bar


def _angle(text: str):
    """Degrees in 0..180, or the string "none" (no tangential knife)."""
    if text.lower() in ("none", "off"):
        return "none"
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an angle: {text!r} (degrees, or 'none')")
    if not 0 <= v <= 180:
        raise argparse.ArgumentTypeError(f"lift angle must be within 0..180 degrees: {text!r}")
    return v


def _point(text: str):
    try:
        x, y = (float(v) for v in text.split(","))
        return x, y
    except ValueError:
        raise argparse.ArgumentTypeError(f"bad point {text!r}: use X,Y in mm, e.g. 0,0")


def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    """Planning options; with ``primary`` False ``--method``/``--time`` become
    ``--plan-method``/``--plan-time``."""
    pre = "" if primary else "plan-"
    g = parser.add_argument_group("cut path planning")
    g.add_argument(f"--{pre}method", dest="plan_method", choices=("ga", "aco", "nn"), default="ga",
                   help="order search: ga = genetic algorithm (default), aco = max-min ant system, "
                        "nn = nearest neighbour (fast baseline)")
    g.add_argument(f"--{pre}time", dest="plan_time", type=positive, default=10.0, metavar="S",
                   help="planning time budget in seconds (default 10; stops earlier when converged)")
    g.add_argument(f"--{pre}iterations", dest="plan_iterations", type=positive_int, default=None,
                   metavar="N", help="stop after N GA generations / ACO iterations: with the same "
                                     "seed the plan is then the same on any machine (the time "
                                     "budget still caps the run)")
    g.add_argument("--entry-spacing", dest="plan_entry_spacing", type=positive, default=20.0,
                   metavar="MM", help="entry candidates every MM mm along edges, plus every vertex "
                                      "(default 20)")
    g.add_argument("--lift-angle", dest="plan_lift_angle", type=_angle, default=None,
                   metavar="DEG", help="tangential knife: lift where the heading turns by more than "
                                       "DEG degrees; 'none' = no tangential knife (default: none, or "
                                       "the machine profile's angle)")
    g.add_argument("--home", dest="plan_home", type=_point, default=None, metavar="X,Y",
                   help="machine zero in drawing coordinates, mm (default 0,0, or minus the "
                        "machine profile's origin)")
    g.add_argument("--rapid-speed", dest="plan_rapid_speed", type=positive, default=None,
                   metavar="MM_MIN", help="travel speed for the time estimate (default 20000 mm/min)")
    g.add_argument("--cut-speed", dest="plan_cut_speed", type=positive, default=None,
                   metavar="MM_MIN", help="cutting speed for the time estimate (default 6000 mm/min)")
    g.add_argument("--accel", dest="plan_accel", type=positive, default=None, metavar="MM_S2",
                   help="acceleration for the time estimate (default 1000 mm/s^2)")
    g.add_argument("--objective", dest="plan_objective", choices=("distance", "time"),
                   default="distance",
                   help="what the order search minimises: distance = idle travel in mm (default), "
                        "time = idle seconds with the rapid speed, acceleration, knife lift time and "
                        "(tangential knife) blade turns between contours")
    g.add_argument("--no-open-chains", dest="plan_no_open_chains", action="store_true",
                   help="do not cut open chains (lines that are neither contours nor lead-ins)")


def options_from_args(args: argparse.Namespace, machine: Any = None):
    """PlanOptions from parsed arguments; a machine profile (``run``) supplies
    speeds, acceleration, lift angle and home unless given explicitly."""
    from ..core.pathplan import PlanOptions

    o = PlanOptions(method=args.plan_method, time_limit=args.plan_time,
                    max_iterations=args.plan_iterations,
                    seed=getattr(args, "seed", 1), entry_spacing=args.plan_entry_spacing,
                    cut_open_chains=not args.plan_no_open_chains,
                    objective=getattr(args, "plan_objective", "distance"))
    if machine is not None:
        o.rapid_speed = float(getattr(machine, "rapid_feed", o.rapid_speed))
        o.cut_speed = float(getattr(machine, "cut_feed", o.cut_speed))
        o.accel = float(getattr(machine, "acceleration", o.accel))
        if getattr(machine, "tool", "") == "tangential_knife":
            o.lift_angle = float(getattr(machine, "lift_angle", 15.0))
        ox, oy = getattr(machine, "origin", (0.0, 0.0))
        o.home = (-float(ox), -float(oy))
    if args.plan_lift_angle is not None:
        o.lift_angle = None if args.plan_lift_angle == "none" else args.plan_lift_angle
    if args.plan_home is not None:
        o.home = args.plan_home
    for name in ("rapid_speed", "cut_speed", "accel"):
        v = getattr(args, f"plan_{name}")
        if v is not None:
            setattr(o, name, v)
    return o


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "plan", help="cut order, entry points, knife lifts and idle travel for a drawing",
        description="Recognise the parts of FILE (nest them first when --sheet/--strip/--hide is "
                    "given), then plan the cut: order, entry points, knife lifts; report idle "
                    "travel against the drawing order, nearest neighbour and a lower bound.")
    p.add_argument("file", metavar="FILE", help="DXF drawing")
    add_common_options(p)
    add_stage_options(p, before="plan_cmd")
    add_options(p, primary=True)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> Report:
    from ..core.job import run_job

    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    jo = job_options(args, before="plan_cmd")
    jo.plan = options_from_args(args)
    result = run_job(args.file, jo, None if args.json else progress_bar())
    data = report_dict(args.file, result)
    return Report(data=data, text=report_text(data))


def _pt(p):
    return [round(float(p[0]), 3), round(float(p[1]), 3)]


def report_dict(source: str, result) -> Dict[str, Any]:
    plan = result.plan
    order = []
    for i, it in enumerate(plan.items):
        order.append({"order": i + 1, "contour": it.contour_id, "part": it.part_id, "kind": it.kind,
                      "start": _pt(it.start), "entry": _pt(it.entry), "end": _pt(it.end),
                      "lead_in": it.lead_in_count > 0, "lifts": len(it.lifts),
                      "length_mm": round(it.length, 3)})
    return {
        "file": source,
        "method": plan.method,
        "home": _pt(plan.home),
        "nested": result.layout is not None,
        "order": order,
        "metrics": dict(plan.metrics),
        "findings": [f.to_json() for f in result.findings],
    }


def report_text(d: Dict[str, Any]) -> str:
    m = d["metrics"]
    lines = [f"{d['file']}: {len(d['order'])} cut items, method {d['method']}"
             f"{' (nested)' if d['nested'] else ''}"]
    if d["order"]:
        def pct(x):
            return "-" if x is None else f"{100 * x:.1f} %"
        lines += [
            f"idle travel {m['idle_mm']:.1f} mm (drawing order {m['drawing_order_idle_mm']:.1f} mm, "
            f"saving {pct(m.get('idle_saving_vs_drawing_order'))}; nearest neighbour "
            f"{m['nn_idle_mm']:.1f} mm; lower bound {m['lower_bound_mm']:.1f} mm)",
            f"cut {m['cut_mm']:.1f} mm, {m['lifts']} knife lifts, estimated time {m['est_time_s']:.1f} s; "
            f"planned in {m['time_s']:.2f} s ({m['cpu_s']:.2f} s CPU, {m['iterations']} iterations)",
        ]
        for o in d["order"][:30]:
            extra = ("  lead-in" if o["lead_in"] else "") + (f"  {o['lifts']} lifts" if o["lifts"] else "")
            lines.append(f"  {o['order']:4d}. {o['contour']:<20} part {o['part'] or '-':<12} "
                         f"entry ({o['entry'][0]:.1f}, {o['entry'][1]:.1f}){extra}")
        if len(d["order"]) > 30:
            lines.append(f"  ... {len(d['order']) - 30} more (use --json for all)")
    for f in d["findings"]:
        if f["level"] != "info":
            lines.append(f"{f['level']}: {f['message']}" + (f" ({f['source']})" if f.get("source") else ""))
    return "\n".join(lines)
