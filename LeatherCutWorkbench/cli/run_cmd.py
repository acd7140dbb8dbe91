"""``leathercut run``: the whole job from DXF to machine file.

Writes ``OUTDIR/job.nc`` (G-code for the chosen machine profile),
``OUTDIR/preview.svg`` (parts, cut order, idle moves dashed) and
``OUTDIR/report.json`` (counts, cut length, idle travel, warnings).
Nests only when a container (``--sheet``, ``--strip`` or ``--hide``) is given;
otherwise the drawing is cut where it lies.
"""

from __future__ import annotations

import argparse
import json
import os

from . import Report, add_common_options, post_cmd
from ..core.errors import InputError
from ..core.job import run_job
from ..core.job_report import job_report
from .outputs import check_output_path, require_cut_items
from .stages import add_stage_options, job_options, progress_bar


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run", help="import, recognise, nest (if a container is given), plan and post a job",
        description="Run the whole job on FILE and write OUTDIR/job.nc, OUTDIR/preview.svg "
                    "and OUTDIR/report.json.")
    p.add_argument("file", metavar="FILE", help="DXF drawing to cut")
    p.add_argument("-o", "--output", dest="outdir", required=True, metavar="OUTDIR",
                   help="folder for job.nc, preview.svg and report.json (created if missing)")
    add_common_options(p)
    add_stage_options(p, before="end")
    post_cmd.add_options(p, primary=False)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> Report:
    from ..post import gcode, svg_preview
    from ..post.profiles import load_profile

    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    profile = load_profile(args.post_machine)
    if not profile.is_gcode:
        raise InputError(f"profile {profile.name} is for {profile.dialect}, but run writes G-code "
                         f"(job.nc); use 'leathercut post --format {profile.dialect}'",
                         source=args.post_machine)
    for name in ("job.nc", "preview.svg", "report.json"):
        check_output_path(os.path.join(args.outdir, name))
    result = run_job(args.file, job_options(args, before="end", machine=profile),
                     None if args.json else progress_bar())
    require_cut_items(result, args.file)
    text_nc = gcode.export(result.plan, profile)
    outdir = args.outdir
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create output folder: {exc.strerror}", source=outdir)
    paths = {name: os.path.join(outdir, name) for name in ("job.nc", "preview.svg", "report.json")}
    data = job_report(result)
    data["machine"] = profile.name
    data["outputs"] = paths
    with open(paths["job.nc"], "w", encoding="ascii", newline="\n") as fh:
        fh.write(text_nc)
    with open(paths["preview.svg"], "w", encoding="utf-8") as fh:
        fh.write(svg_preview.render(result.plan, result.parts_to_cut,
                                    title=os.path.basename(args.file)))
    with open(paths["report.json"], "w", encoding="utf-8") as fh:
        json.dump(data, fh, indent=2)
        fh.write("\n")
    c = data["counts"]
    lines = [
        f"{args.file}: {c['parts']} parts ({c['parts_excluded']} excluded), {c['holes']} holes, "
        f"{c['lead_ins']} lead-ins, {c['open_chains']} open chains, {c['flags']} flags",
        f"cut {data['cut_length_mm']:.1f} mm in {c['cut_items']} items, idle travel "
        f"{data['idle_travel_mm']:.1f} mm, {data['lifts']} knife lifts ({result.plan.method})",
    ]
    if data["nesting"]:
        n = data["nesting"]
        lines.append(f"nested: {n['placed']} placed, {len(n['unplaced'])} unplaced")
    lines += [f"warning: {w['message']}" + (f" ({w['source']})" if w.get("source") else "")
              for w in data["warnings"][:20]]
    if len(data["warnings"]) > 20:
        lines.append(f"... {len(data['warnings']) - 20} more warnings in report.json")
    lines.append("wrote " + ", ".join(paths.values()))
    return Report(data=data, text="\n".join(lines))
