"""``leathercut nest``: nest recognised parts (or an ESICUP instance) on sheets,
a strip or leather hides.  Documented in docs/CLI.md (section ``nest``)."""

from __future__ import annotations

import argparse
import os
from typing import Any, Dict, List, Optional

from . import Report, add_common_options
from ..core.errors import InputError
from .stages import add_stage_options, job_options, non_negative, positive, positive_int, progress_bar

def _size(text: str):
    try:
        w, h = (float(v) for v in text.lower().replace("*", "x").split("x"))
        if w <= 0 or h <= 0:
            raise ValueError
        return w, h
    except ValueError:
        raise argparse.ArgumentTypeError(f"bad sheet size {text!r}: use WxH in mm, e.g. 1000x600")


def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    """Nesting options; with ``primary`` False the clashing ones get ``--nest-``."""
    pre = "" if primary else "nest-"
    g = parser.add_argument_group("nesting")
    box = g.add_mutually_exclusive_group()
    box.add_argument("--sheet", dest="nest_sheet", type=_size, metavar="WxH",
                     help="nest on rectangular sheets W x H mm (new sheets as needed)")
    box.add_argument("--strip", dest="nest_strip", type=positive, metavar="W",
                     help="nest on a strip W mm wide with open length (minimise the length)")
    box.add_argument("--hide", dest="nest_hide", metavar="HIDE.dxf",
                     help="nest on the hide(s) in this DXF: layers HIDE (outline), DEFECT, ZONE_<grade>")
    if primary:
        box.add_argument("--esicup", dest="nest_esicup", metavar="FILE.json",
                         help="nest a benchmark instance instead of a DXF: ESICUP strip packing "
                              "or jagua-rs bin packing with hides (bins, zones, min_quality)")
    g.add_argument("--sheets", dest="nest_sheets", type=int, metavar="N",
                   help="with --sheet: use at most N sheets and report what does not fit")
    g.add_argument("--spacing", dest="nest_spacing", type=non_negative, default=0.0, metavar="MM",
                   help="minimum gap between parts in mm (knife width / kerf; default 0)")
    g.add_argument("--margin", dest="nest_margin", type=non_negative, default=0.0, metavar="MM",
                   help="minimum distance from parts to the container edge and defects in mm (default 0)")
    g.add_argument("--rotations", dest="nest_rotations", metavar="any|LIST|step:S|A+-T",
                   help="allowed rotations for every part: any, a list like 0,180, step:90, "
                        "or a grain direction with a tolerance like 0+-5 "
                        "(default: each part's own setting; ESICUP: the instance's)")
    g.add_argument("--rotation-step", dest="nest_rotation_step", type=positive, default=30.0,
                   metavar="DEG", help="angle step tried for parts that may turn freely (default 30)")
    g.add_argument("--mirror", dest="nest_mirror", action="store_true",
                   help="allow mirrored copies of every part")
    g.add_argument("--grade", dest="nest_grades", action="append", default=[], metavar="PART=G",
                   help="grade of a part (id or name; repeatable): a letter A-D (A best) or a "
                        "number; on a hide it lies only on material of that grade or better")
    g.add_argument("--copies", dest="nest_copies", type=int, default=None, metavar="N",
                   help="nest N copies of every recognised part (default: each part's quantity)")
    g.add_argument(f"--{pre}time", dest="nest_time", type=non_negative, default=10.0, metavar="S",
                   help="time budget in seconds for the whole nest: reading, shapes, no-fit polygons, "
                        "first layout and search (default 10; 0 = first layout only)")
    g.add_argument(f"--{pre}evaluations", dest="nest_evaluations", type=positive_int, default=None, metavar="N",
                   help="stop each worker after N layouts: same seed, same result on any machine")
    g.add_argument(f"--{pre}workers", dest="nest_workers", type=positive_int, default=None, metavar="N",
                   help="worker processes (default: all cores)")
    g.add_argument(f"--{pre}engine", dest="nest_engine", choices=["own", "sparrow"], default="own",
                   help="own (default; every container and constraint) or sparrow "
                        "(spyrrow, strips only, no part-in-part)")
    g.add_argument("--layout-out", dest="nest_layout_out", metavar="FILE.json",
                   help="write the placed outlines as layout JSON")
    g.add_argument(f"--{pre}dxf-out", dest="nest_dxf_out", metavar="FILE.dxf",
                   help="write the nested drawing as DXF")
    g.add_argument(f"--{pre}svg-out", dest="nest_svg_out", metavar="FILE.svg",
                   help="write a picture of the layout as SVG")
    if primary:
        g.add_argument("--remnant-out", dest="nest_remnant_out", metavar="HIDE.dxf",
                       help="with hides: write the unused material (defects, zones kept) as a "
                            "hide DXF for the next job's --hide")


def options_from_args(args: argparse.Namespace):
    """NestOptions from parsed arguments, or None when no container was given."""
    from ..core.nesting import ContainerSpec, NestOptions, parse_rotations, read_hide_dxf

    if getattr(args, "nest_sheet", None):
        w, h = args.nest_sheet
        spec = ContainerSpec.sheet(w, h, args.nest_sheets)
    elif getattr(args, "nest_strip", None):
        spec = ContainerSpec.strip(args.nest_strip)
    elif getattr(args, "nest_hide", None):
        if not os.path.isfile(args.nest_hide):
            raise InputError("no such file", source=args.nest_hide)
        spec = ContainerSpec.hide(*read_hide_dxf(args.nest_hide))
    elif getattr(args, "nest_esicup", None):
        spec = ContainerSpec.strip(1.0)       # replaced by the instance's strip height
    else:
        return None
    if args.nest_sheets is not None and not args.nest_sheet:
        raise InputError("--sheets needs --sheet WxH")
    rots_override: Optional[List[float]] = None
    step = args.nest_rotation_step
    free = False
    if args.nest_rotations:
        rots_override, st = parse_rotations(args.nest_rotations)
        free = rots_override is None
        if st is not None:
            step = st
    grades: Dict[str, str] = {}
    for item in getattr(args, "nest_grades", None) or []:
        part, sep, grade = item.rpartition("=")
        if not sep or not part.strip() or not grade.strip():
            raise InputError(f"bad --grade {item!r}: use PART=G, e.g. P3=A or 'Vamp size 38=2'")
        grades[part.strip()] = grade.strip()
    opts = NestOptions(container=spec, spacing=args.nest_spacing, margin=args.nest_margin,
                       rotation_step=step, rotations_override=rots_override, free_rotation=free,
                       mirror_override=True if args.nest_mirror else None,
                       time_budget=args.nest_time, max_evaluations=args.nest_evaluations,
                       seed=getattr(args, "seed", 1), workers=args.nest_workers,
                       engine=args.nest_engine, grades=grades)
    opts.validate()
    return opts


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "nest", help="nest parts on sheets, a strip or hides (true shapes, holes, defects)",
        description="Nest the recognised parts of FILE (or an ESICUP instance) on sheets, "
                    "a strip or leather hides with defects and quality zones.")
    p.add_argument("file", metavar="FILE", nargs="?", help="DXF drawing with the parts "
                   "(not needed with --esicup)")
    add_common_options(p)
    add_stage_options(p, before="nest_cmd")
    add_options(p, primary=True)
    p.set_defaults(func=run)


def _parts_from_args(args, opts):
    """(parts, source label, findings) from a DXF or an ESICUP instance."""
    from ..core.nesting import ContainerSpec
    if getattr(args, "nest_esicup", None):
        from ..core.nesting.esicup import read_esicup
        if args.file:
            raise InputError("give either FILE or --esicup, not both")
        inst = read_esicup(args.nest_esicup)
        opts.container = ContainerSpec.hide(*inst.hides) if inst.hides else \
            ContainerSpec.strip(inst.strip_height)
        return inst.parts, args.nest_esicup, list(inst.findings)
    if not args.file:
        raise InputError("no drawing given: leathercut nest FILE.dxf --sheet WxH (or --esicup FILE.json)")
    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    from ..core.job import load_and_recognise
    drawing, rec = load_and_recognise(args.file, job_options(args, before="nest_cmd"))
    parts = rec.active_parts()
    if not parts:
        raise InputError("no closed parts recognised in the drawing", source=args.file)
    return parts, args.file, list(drawing.findings) + list(rec.findings)


def run(args: argparse.Namespace) -> Report:
    from ..core.nesting import nest
    from ..core.nesting import outputs
    from ..core.nesting.tail import writing

    t_start = _process_start()          # --time covers start-up and reading the drawing too
    opts = options_from_args(args)
    if opts is None:
        raise InputError("no container: give --sheet WxH, --strip W, --hide HIDE.dxf or --esicup FILE.json")
    parts, source, findings = _parts_from_args(args, opts)
    opts.started_at = t_start
    if args.nest_copies is not None:
        if args.nest_copies < 1:
            raise InputError(f"--copies must be >= 1, got {args.nest_copies}")
        for p in parts:
            p.quantity = args.nest_copies
    kinds = [k for k, path in (("layout", args.nest_layout_out), ("dxf", args.nest_dxf_out),
                               ("svg", args.nest_svg_out)) if path]
    with writing(kinds):               # the budget keeps their time free too
        layout = nest(parts, opts, progress_bar() if not args.json else None)
    written: Dict[str, str] = {}
    for key, path, fn in (("layout", args.nest_layout_out, outputs.write_layout_json),
                          ("dxf", args.nest_dxf_out, outputs.write_dxf),
                          ("svg", args.nest_svg_out, outputs.write_svg)):
        if path:
            try:
                fn(path, parts, layout)
            except OSError as exc:
                raise InputError(f"cannot write: {exc.strerror}", source=path) from None
            written[key] = path
    if getattr(args, "nest_remnant_out", None):
        if opts.container.kind != "hide":
            raise InputError("--remnant-out needs hides (--hide or a bin-packing --esicup)")
        rem = outputs.remnants(parts, layout, opts.spacing)
        try:
            outputs.write_hide_dxf(args.nest_remnant_out, rem)
        except OSError as exc:
            raise InputError(f"cannot write: {exc.strerror}", source=args.nest_remnant_out) from None
        written["remnant"] = args.nest_remnant_out
        layout.metrics["remnants"] = [{"id": h.id, "area_mm2": round(abs(_area(h.outline)), 3),
                                       "defects": len(h.defects), "zones": len(h.zones)}
                                      for h in rem]
    data = report_dict(source, opts, layout, findings)
    data["outputs"] = written
    # the interpreter's clean-up of a nest's heap took 0.25-0.4 s of the budget
    return Report(data=data, text=report_text(data), quick_exit=True)


def _process_start() -> float:
    """``time.monotonic()`` when this ``leathercut`` process started (Linux:
    /proc/self/stat, whose start time counts clock ticks since boot like
    CLOCK_MONOTONIC), so ``--time`` covers Python's start-up too.  Now when
    the CLI runs inside another program (tests, scripts) or the start is
    unknown or implausible."""
    import sys
    import time
    now = time.monotonic()
    if not os.path.basename(sys.argv[0] if sys.argv else "").startswith("leathercut"):
        return now
    try:
        with open("/proc/self/stat", encoding="ascii") as fh:
            ticks = float(fh.read().rsplit(")", 1)[1].split()[19])
        start = ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return now
    return start if now - 30.0 < start <= now else now


def _area(ring) -> float:
    from ..core.geometry import signed_area
    return signed_area(list(ring))


def report_dict(source: str, opts, layout, findings) -> Dict[str, Any]:
    m = dict(layout.metrics)
    spec = opts.container
    cont: Dict[str, Any] = {"kind": spec.kind}
    if spec.kind == "sheet":
        cont.update({"width_mm": spec.width, "height_mm": spec.height, "count": spec.count})
    elif spec.kind == "strip":
        cont.update({"width_mm": spec.height})
    else:
        cont.update({"hides": [c.id for c in spec.hides]})
    return {
        "file": source,
        "container": cont,
        "engine": opts.engine,
        "spacing_mm": opts.spacing,
        "margin_mm": opts.margin,
        "time_budget_s": opts.time_budget,
        "seed": opts.seed,
        "metrics": {k: v for k, v in m.items() if k != "per_container"},
        "containers": m.get("per_container", []),
        "placements": [{"part": p.part_id, "copy": p.copy, "container": p.container,
                        "x": round(p.x, 6), "y": round(p.y, 6), "angle": p.angle,
                        "mirrored": p.mirrored} for p in layout.placements],
        "unplaced": [{"part": pid, "copy": k} for pid, k in layout.unplaced],
        "findings": [f.to_json() for f in list(findings) + list(layout.findings)],
    }


def report_text(d: Dict[str, Any]) -> str:
    m = d["metrics"]
    lines = [f"{d['file']}: {m.get('placed_count', 0)} placed, {m.get('unplaced_count', 0)} unplaced "
             f"({d['engine']} engine, {m.get('time_s', 0):.1f} s)"]
    kind = d["container"]["kind"]
    if kind == "strip":
        lines.append(f"strip {m['strip_width_mm']:g} mm wide: length {m['strip_length_mm']:.3f} mm, "
                     f"density {100 * m['density']:.2f} %")
    else:
        lines.append(f"utilisation {100 * m.get('utilisation', 0):.2f} %"
                     + (f" (gross {100 * m['utilisation_gross']:.2f} %)" if "utilisation_gross" in m else ""))
        for c in d["containers"]:
            lines.append(f"  {c['id']}: {c['parts']} parts, utilisation {100 * c['utilisation']:.2f} %")
            on: Dict[int, List[str]] = {}
            for g in m.get("grades", []):
                if g["container"] == c["id"]:
                    on.setdefault(g["material_grade"], []).append(
                        f"{g['part']}#{g['copy']}" + (f" (grade {g['part_grade']})" if g["part_grade"] else ""))
            for lv in sorted(on, reverse=True):
                lines.append(f"    on grade {lv}: " + ", ".join(on[lv][:30])
                             + (" ..." if len(on[lv]) > 30 else ""))
    if d["unplaced"]:
        lines.append("unplaced: " + ", ".join(f"{u['part']}#{u['copy']}" for u in d["unplaced"][:20]))
    for f in d["findings"]:
        if f["level"] != "info":
            lines.append(f"{f['level']}: {f['message']}")
    for k, v in d.get("outputs", {}).items():
        lines.append(f"wrote {k}: {v}")
    return "\n".join(lines)
