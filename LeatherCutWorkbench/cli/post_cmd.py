"""``leathercut post``: write the machine file of a drawing's cut job.

Runs import, recognition, nesting (when a container is given) and planning
with the same options as the earlier verbs, then writes G-code, HP-GL or DXF
for a machine profile.  The safety check runs before anything is written: a
refused job leaves no output file.  Documented in docs/CLI.md (``post``).
"""

from __future__ import annotations

import argparse
import os
from typing import Any

from . import Report, add_common_options
from ..core.errors import InputError
from .outputs import check_output_path, require_cut_items
from .stages import add_stage_options, job_options, non_negative

DEFAULT_MACHINE = "grblhal_tangential"
FORMATS = ("gcode", "hpgl", "dxf")
def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    """Post-processing options (``--machine`` is shared with ``send``)."""
    g = parser.add_argument_group("post-processing")
    g.add_argument("--machine", dest="post_machine", default=DEFAULT_MACHINE,
                   metavar="NAME_OR_FILE",
                   help=f"machine profile name or JSON file (default {DEFAULT_MACHINE}; "
                        "see docs/MACHINES.md)")
    g.add_argument("--tool-map", dest="post_tool_map", default="", metavar="ROLE=TOOL,...",
                   help="which tool does which role, on top of the profile's tool_map: roles "
                        "drill, notch, point, internal, stitch or layer:NAME; tools as declared in "
                        "the profile (e.g. stitch=pen,drill=punch4,notch=knife; none = not done)")
    if not primary:
        return
    g.add_argument("--format", dest="post_format", choices=FORMATS, default="gcode",
                   help="output format (default gcode)")
    g.add_argument("-o", "--output", dest="post_output", required=True, metavar="OUT",
                   help="file to write (not created when the safety check refuses the job)")
    g.add_argument("--line-numbers", dest="post_line_numbers", action="store_true",
                   default=None, help="G-code: N word on every block")
    g.add_argument("--overcut", dest="post_overcut", type=non_negative, metavar="MM",
                   help="cut this many mm past the start of closed contours "
                        "(default: the profile's overcut)")


def options_from_args(args: argparse.Namespace):
    from ..post.gcode import ExportOptions

    return ExportOptions(line_numbers=getattr(args, "post_line_numbers", None),
                         overcut=getattr(args, "post_overcut", None))


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("post", help="write G-code, HP-GL or DXF of a drawing's cut job",
                       description="Import, recognise, nest (if a container is given) and plan "
                                   "FILE, then write the job for a machine profile. The job is "
                                   "checked against the table limits, feeds and the dialect's "
                                   "words first; a refused job writes nothing.")
    p.add_argument("file", metavar="FILE", help="DXF drawing to cut")
    add_common_options(p)
    add_stage_options(p, before="end")
    add_options(p, primary=True)
    p.set_defaults(func=run)


def plan_drawing(args: argparse.Namespace, profile) -> Any:
    """Run the earlier stages on ``args.file`` with their CLI options; returns
    the JobResult (``.plan`` is the CutPlan)."""
    from ..core.job import run_job

    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    opts = job_options(args, before="end", machine=profile)
    result = run_job(args.file, opts)
    require_cut_items(result, args.file)
    return result


def tool_overrides(args: argparse.Namespace):
    """``--tool-map`` as a role -> tool dict (checked against the profile later)."""
    from ..post.tools import parse_tool_map

    return parse_tool_map(getattr(args, "post_tool_map", "") or "")


def run(args: argparse.Namespace) -> Report:
    from ..post import tool_export
    from ..post.profiles import load_profile
    from ..post.tools import tool_map

    profile = load_profile(args.post_machine)
    fmt = args.post_format
    if fmt == "gcode" and not profile.is_gcode:
        raise InputError(f"profile {profile.name} is for {profile.dialect}; use --format "
                         f"{'hpgl' if profile.dialect == 'hpgl' else 'dxf'}", source=args.file)
    if fmt == "hpgl" and profile.dialect != "hpgl":
        raise InputError(f"profile {profile.name} is for {profile.dialect}, not HP-GL",
                         source=args.file)
    check_output_path(args.post_output)
    tool_map(profile, tool_overrides(args))        # a bad --tool-map fails before planning
    result = plan_drawing(args, profile)
    tools = tool_export.job_for(result.plan, result.parts_to_cut, profile, tool_overrides(args))
    text = tool_export.render(result.plan, result.parts_to_cut, profile, fmt,
                              options_from_args(args), job=tools)
    out = args.post_output
    from ..post.jobfile import write_job_file
    write_job_file(out, text, gcode=fmt == "gcode")      # atomic; G-code sealed
    plan = result.plan
    n_lines = text.count("\n")
    data = {
        "file": args.file, "machine": profile.name, "dialect": profile.dialect,
        "format": fmt, "output": out, "bytes": len(text.encode("ascii")), "lines": n_lines,
        "items": len(plan.items), "segments": sum(len(i.segments) for i in plan.items),
        "cut_length_mm": round(sum(i.length for i in plan.items), 3),
        "tools": tool_export.tool_report(tools, profile),
        "findings": [f.to_json() for f in result.findings + tools.findings],
    }
    text_out = (f"{args.file}: {data['items']} items, {data['segments']} segments, "
                f"cut {data['cut_length_mm']:.1f} mm -> {out} ({fmt}, {profile.name}, "
                f"{n_lines} lines)")
    return Report(data=data, text=text_out)
