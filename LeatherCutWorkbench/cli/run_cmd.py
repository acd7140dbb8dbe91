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
    from ..post import svg_preview, tool_export
    from ..post.jobfile import write_file, write_job_file
    from ..post.profiles import load_profile

    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    profile = load_profile(args.post_machine)
    if not profile.is_gcode:
        raise InputError(f"profile {profile.name} is for {profile.dialect}, but run writes G-code "
                         f"(job.nc); use 'leathercut post --format {profile.dialect}'",
                         source=args.post_machine)
    overrides = post_cmd.tool_overrides(args)
    tool_export.tool_map(profile, overrides)       # a bad --tool-map fails before planning
    for name in ("job.nc", "preview.svg", "report.json"):
        check_output_path(os.path.join(args.outdir, name))
    result = run_job(args.file, job_options(args, before="end", machine=profile),
                     None if args.json else progress_bar())
    require_cut_items(result, args.file)
    tools = tool_export.job_for(result.plan, result.parts_to_cut, profile, overrides)
    text_nc = tool_export.render(result.plan, result.parts_to_cut, profile, "gcode", job=tools)
    outdir = args.outdir
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create output folder: {exc.strerror}", source=outdir)
    paths = {name: os.path.join(outdir, name) for name in ("job.nc", "preview.svg", "report.json")}
    data = job_report(result)
    data["machine"] = profile.name
    data["tools"] = tool_export.tool_report(tools, profile)
    data["findings"] += [f.to_json() for f in tools.findings]
    from ..post.compensation import summary
    data["tool_path"] = summary(result.plan, profile)
    data["outputs"] = paths
    # atomic writes (temp file + fsync + rename); job.nc sealed with its end marker
    write_job_file(paths["job.nc"], text_nc, gcode=True)
    write_file(paths["preview.svg"], svg_preview.render(tools.main.plan(result.plan.home),
                                                        result.parts_to_cut,
                                                        title=os.path.basename(args.file),
                                                        tools=tool_export.preview_tools(tools),
                                                        profile=profile))
    write_file(paths["report.json"], json.dumps(data, indent=2) + "\n")
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
