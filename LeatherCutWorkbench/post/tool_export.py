"""Multi-tool jobs written out: one G-code file with tool changes, HP-GL with
one pen per tool, DXF with one layer per tool, and the per-tool report.

Each pass of a :class:`~.tool_jobs.ToolJob` becomes neutral moves through the
ordinary toolpath builder (lines) or as strikes (rapid, tool ``on``, tool
``off`` at each point), with a copy of the profile that carries the tool's
on/off lines and feed and no drag-knife / overcut treatment (only the main
tool gets those).  Coordinates are shifted by minus the tool's offset, so the
tool -- not the main tool -- lands on the drawn point.  Items are numbered
through the whole job, so ``(seg I:S)`` ids stay unique for the live link.
The G-code passes ``select`` lines (``T2 M6`` / profile words) between
passes, and every line of the file goes through the safety check.

A job without mapped roles is written by the single-tool writers unchanged.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Dict, List, Optional, Sequence

from ..core.geometry import ArcSeg, Point, Transform2D
from ..core.model import CutItem, CutPlan, Part
from .profiles import MachineProfile
from .tool_jobs import ToolJob, ToolPass, build_tool_job
from .toolpath import Move, Toolpath, build_toolpath, seg_id
from .tools import main_tool, tool_map

#: Preview colour of each tool kind (the main tool keeps the plan colours).
KIND_COLOURS = {"pen": "#6a1b9a", "marker": "#6a1b9a", "scribe": "#6a1b9a", "crease": "#00838f",
                "notch": "#ad1457", "punch": "#000000", "torch": "#1f5fbf", "knife": "#1f5fbf"}


def job_for(plan: CutPlan, parts: Sequence[Part], profile: MachineProfile,
            overrides: Optional[Dict[str, str]] = None,
            overrides_from: str = "--tool-map") -> ToolJob:
    """The tool job of ``plan`` and ``parts`` for ``profile`` (role map from the
    profile, ``overrides`` on top, named ``overrides_from`` in messages).
    Raises InputError for a role mapped to a tool the machine lacks."""
    return build_tool_job(plan, parts, tool_map(profile, overrides, overrides_from),
                          main_tool(profile), profile.notch_length)


def is_multi(job: ToolJob, plan: CutPlan) -> bool:
    """True when the job needs more than the plan: other tools or knife extras."""
    return len(job.passes) > 1 or len(job.main.items) != len(plan.items)


def pass_profile(p: ToolPass, profile: MachineProfile) -> MachineProfile:
    """The profile a pass is written with."""
    if p.tool.main:
        return profile
    return replace(profile, tool="pen", rotary_axis="", blade_offset=0.0, overcut=0.0,
                   knife_down=list(p.tool.on) or list(profile.knife_down),
                   knife_up=list(p.tool.off) or list(profile.knife_up),
                   tool_on=[], tool_off=[], pierce_delay=0.0, cooling_delay=0.0,
                   cut_feed=p.tool.feed, hpgl_pen=p.tool.number)


def _shift(items: Sequence[CutItem], off: Point) -> List[CutItem]:
    if off == (0.0, 0.0):
        return list(items)
    xf = Transform2D(dx=-off[0], dy=-off[1])
    return [replace(it, entry=xf.apply(it.entry), segments=[s.transformed(xf) for s in it.segments])
            for it in items]


def _strikes(p: ToolPass, prof: MachineProfile, start: Point, first: int) -> Toolpath:
    """Rapid, tool on, tool off (and a sync) at every point of ``p``; items
    numbered from ``first``."""
    tp = Toolpath()
    here = start
    dx, dy = p.tool.offset
    for i, (x, y) in enumerate(p.points, first):
        sid = seg_id(i, 1)
        tp.segment_ids.append(sid)
        tp.item_labels.append(f"{p.tool.kind} {p.tool.name} #{i - first + 1}")
        at = (x - dx, y - dy)
        tp.moves.append(Move("rapid", seg=sid, x=at[0], y=at[1], feed=prof.rapid_feed, item=i,
                             start=here))
        tp.moves.append(Move("down", seg=sid, item=i, start=at))
        tp.moves.append(Move("up", item=i, start=at))
        if prof.sync_at_items:
            tp.moves.append(Move("sync", item=i, start=at))
        here = at
    return tp


def _renumber(tp: Toolpath, offset: int) -> Toolpath:
    def sid(s: str) -> str:
        if not s:
            return s
        i, j = s.split(":")
        return f"{int(i) + offset}:{j}"
    moves = [replace(m, seg=sid(m.seg), item=m.item + offset if m.item else 0) for m in tp.moves]
    return Toolpath(moves, [sid(s) for s in tp.segment_ids], [""] * offset + tp.item_labels)


def _pass_toolpath(p: ToolPass, prof: MachineProfile, home: Point, first: bool,
                   last: bool) -> Toolpath:
    """Moves of one pass: its lines (the ordinary toolpath builder), then its
    strikes; the job's preamble (vacuum / plate on) only on the ``first``
    pass, the return home and vacuum off only on the ``last``."""
    tp = build_toolpath(CutPlan(_shift(p.items, p.tool.offset), home=home), prof)
    mv = tp.moves
    at_items = [i for i, m in enumerate(mv) if m.item]
    lo = at_items[0] if at_items else next(i for i, m in enumerate(mv) if m.kind == "rapid")
    hi = at_items[-1] + 1 if at_items else lo
    end = (mv[hi - 1].x, mv[hi - 1].y) if at_items else home
    hits = _strikes(p, prof, end, len(p.items) + 1)
    moves = (mv[:lo] if first else []) + mv[lo:hi] + hits.moves + (mv[hi:] if last else [])
    return Toolpath(moves, tp.segment_ids + hits.segment_ids, tp.item_labels + hits.item_labels)


def _pass_toolpaths(job: ToolJob, profile: MachineProfile) -> List[tuple]:
    """(pass, profile, toolpath renumbered through the job) for every pass."""
    out = []
    offset = 0
    last = len(job.passes) - 1
    for k, p in enumerate(job.passes):
        prof = pass_profile(p, profile)
        tp = _pass_toolpath(p, prof, job.home, k == 0, k == last)
        out.append((p, prof, _renumber(tp, offset)))
        offset += len(p.items) + len(p.points)
    return out


def gcode_program(job: ToolJob, profile: MachineProfile, options=None):
    """One G-code program (a :class:`~.gcode.Program`: lines with their segment
    ids, for files and the live link): every pass, ``select`` lines before
    each tool's pass."""
    from . import gcode, safety

    opts = replace(options or gcode.ExportOptions(), line_numbers=False)
    out = gcode.Program()
    parts = _pass_toolpaths(job, profile)
    for k, (p, prof, tp) in enumerate(parts):
        prof_k = replace(prof, header=list(profile.header) if k == 0 else [],
                         footer=list(profile.footer) if k == len(parts) - 1 else [],
                         vacuum_on=[] if k else prof.vacuum_on, press_on=[] if k else prof.press_on,
                         line_numbers=False)
        prog = gcode.build_program(CutPlan(p.items), prof_k, opts, toolpath=tp)
        lines, segs = prog.lines, prog.segs
        if opts.comments and lines and lines[0].startswith("(LeatherCut job"):
            lines, segs = lines[1:], segs[1:]
            out.add(safety.comment(f"LeatherCut job for {profile.name}: tool {p.tool.name} = "
                                   f"{p.tool.kind}, {len(p.points) or len(p.items)} items"))
        head = len(prof_k.header)
        select = gcode.expand([t.replace("{number}", str(p.tool.number)) for t in p.tool.select],
                              profile)
        for line, seg in list(zip(lines[:head], segs[:head])) + [(t, "") for t in select] \
                + list(zip(lines[head:], segs[head:])):
            out.add(line, seg)
        out.segment_ids.extend(tp.segment_ids)
    numbered = profile.line_numbers if (options is None or options.line_numbers is None) \
        else options.line_numbers
    if numbered:
        gcode.number_lines(out.lines)
    safety.check_lines(out.lines, profile)
    return out


def program(plan: CutPlan, parts: Sequence[Part], profile: MachineProfile,
            overrides: Optional[Dict[str, str]] = None):
    """The G-code Program of the whole job (what ``send`` streams): the
    single-tool program when no role is mapped."""
    from . import gcode

    job = job_for(plan, parts, profile, overrides)
    if not is_multi(job, plan):
        return gcode.build_program(plan, profile)
    return gcode_program(job, profile)


def hpgl_text(job: ToolJob, profile: MachineProfile, options=None) -> str:
    """HP-GL: ``SPn`` before each tool's pass (n = the tool's number), its
    lines as ``PU``/``PD``, its strikes as ``PUx,y;PD;PU;``."""
    from . import hpgl, safety

    out: List[str] = []
    k_mm = profile.hpgl_units_per_mm
    ox, oy = profile.origin
    for p, prof, tp in _pass_toolpaths(job, profile):
        safety.check_moves(tp, prof)
        body = hpgl.export(CutPlan(_shift(p.items, p.tool.offset), home=job.home), prof,
                           options).splitlines()
        out += (body[:4] if not out else body[3:4]) + body[4:-1]
        dx, dy = p.tool.offset
        out += [f"PU{int(round((x - dx + ox) * k_mm))},{int(round((y - dy + oy) * k_mm))};PD;PU;"
                for x, y in p.points]
    out.append("SP0;")
    text = "\n".join(out) + "\n"
    hpgl.check_instructions(text)
    return text


def dxf_layers(job: ToolJob) -> Dict[str, tuple]:
    """DXF layer per non-main tool: ``TOOL_<NAME>`` -> (segments, points);
    strikes of a tool with a diameter are also drawn as circles."""
    layers: Dict[str, tuple] = {}
    for p in job.passes[:-1]:
        segs = [s for it in p.items for s in it.segments]
        if p.tool.diameter > 0:
            segs += [ArcSeg(pt, p.tool.diameter / 2.0, 0.0, 360.0) for pt in p.points]
        layers[f"TOOL_{p.tool.name.upper()}"] = (segs, list(p.points))
    return layers


def render(plan: CutPlan, parts: Sequence[Part], profile: MachineProfile, fmt: str,
           options=None, overrides: Optional[Dict[str, str]] = None,
           job: Optional[ToolJob] = None, overrides_from: str = "--tool-map") -> str:
    """The machine file of a whole job in ``fmt`` (gcode | hpgl | dxf): the
    single-tool writers when no role is mapped, else every tool's pass
    (``job``: the tool job when already built with :func:`job_for`)."""
    from . import dxf_out, gcode, hpgl

    job = job or job_for(plan, parts, profile, overrides, overrides_from)
    marks = [m for part in parts for m in part.marks]
    if fmt == "dxf":
        return dxf_out.export(job.main.plan(plan.home), profile,
                              dxf_out.DxfOptions(marks=marks, tool_layers=dxf_layers(job)))
    if not is_multi(job, plan):
        return gcode.export(plan, profile, options) if fmt == "gcode" else \
            hpgl.export(plan, profile, options)
    if fmt == "gcode":
        return gcode_program(job, profile, options).text()
    return hpgl_text(job, profile, options)


def tool_report(job: ToolJob, profile: MachineProfile) -> List[Dict[str, Any]]:
    """Per tool: name, kind, number, roles done, length (mm) drawn or cut,
    count (strikes for punches / notch tools, items otherwise), idle travel
    (mm) and estimated time (s: the planner's trapezoid model at the tool's
    feed for lines; travel at rapid_feed plus one lift time, 0.3 s, per strike)."""
    from ..core.geometry import dist
    from ..core.pathplan import PlanOptions
    from ..core.pathplan.metrics import plan_metrics

    lift = PlanOptions().lift_time_s
    out = []
    for p in job.passes:
        feed = profile.cut_feed if p.tool.main else p.tool.feed
        if p.points:
            here, idle = job.home, 0.0
            for pt in p.points:
                idle += dist(here, pt)
                here = pt
            idle += dist(here, job.home)
            t = idle / profile.rapid_feed * 60.0 + len(p.points) * lift
            out.append({"tool": p.tool.name, "kind": p.tool.kind, "number": p.tool.number,
                        "roles": dict(p.roles), "length_mm": 0.0, "count": len(p.points),
                        "idle_mm": round(idle, 3), "time_s": round(t, 2)})
            continue
        m = plan_metrics(p.plan(job.home), profile.rapid_feed, feed, profile.acceleration, lift)
        out.append({"tool": p.tool.name, "kind": p.tool.kind, "number": p.tool.number,
                    "roles": dict(p.roles), "length_mm": round(m["cut_mm"], 3),
                    "count": len(p.items), "idle_mm": round(m["idle_mm"], 3),
                    "time_s": round(m["est_time_s"], 2)})
    return out


def preview_tools(job: ToolJob) -> List[tuple]:
    """(name, colour, items, points) of every non-main pass, for svg_preview."""
    return [(p.tool.name, KIND_COLOURS.get(p.tool.kind, "#6a1b9a"), p.items, p.points)
            for p in job.passes[:-1]]
