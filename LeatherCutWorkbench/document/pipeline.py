"""The job's stages on a FreeCAD document: read inputs, compute, store results.

Each stage is split in three so the GUI can keep the slow part off its thread:

* ``prepare(job)``  -- main thread: read options and the previous stage from the document;
* ``compute(inputs, progress)`` -- any thread: call the core stage function
  (pure Python / Part geometry, no document access);
* ``apply(job, result)`` -- main thread: create or replace the stage objects.

:func:`run_stage` does all three in the calling thread (macros, ``freecadcmd``
and tests); the workbench commands run ``compute`` in a worker thread with a
progress bar and a cancel button.  The stage functions themselves live in
``core`` and ``post``; this module only moves values between them and the
document.
"""

from __future__ import annotations

import importlib
import os
import re
from dataclasses import dataclass, replace
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import FreeCAD

from ..core import geometry, model
from ..core.decisions import apply_decisions, rerun_with_fixes
from ..core.errors import InputError
from ..core.progress import ProgressFn
from . import objects, options, part_objects, shapes
from .job_properties import add_nest_container_properties
from .objects import translate

#: stage key -> the core package that must exist for the stage's command
STAGE_PACKAGES = {
    "Import": "LeatherCutWorkbench.core.dxfimport",
    "Recognise": "LeatherCutWorkbench.core.recognition",
    "Nest": "LeatherCutWorkbench.core.nesting",
    "Plan": "LeatherCutWorkbench.core.pathplan",
    "Post": "LeatherCutWorkbench.post.profiles",
    "Send": "LeatherCutWorkbench.post.link",
}



def available(stage: str) -> bool:
    """True when the stage's package can be imported."""
    try:
        importlib.import_module(STAGE_PACKAGES[stage])
        return True
    except ImportError:
        return False


def make_job(doc, label: str = "Job", source: str = ""):
    """A new job (options from the preferences) in ``doc``."""
    job = objects.make_job(doc, label)
    add_nest_container_properties(job)
    objects.apply_preferences(job)
    if source:
        job.SourceFile = source
    return job


def stage_options(job, key: str):
    """The options dataclass of stage ``key`` built from the job's properties."""
    for st in options.STAGE_OPTIONS:
        if st.key == key:
            opts = options.read_options(job, st)
            if key == "Nest" and opts is not None:
                opts = replace(opts, container=container_spec(job))
            return opts
    raise KeyError(key)


def container_spec(job):
    """The nesting container spec of the job (None when the drawing is cut as it lies)."""
    from ..core.nesting.options import ContainerSpec
    kind = job.NestContainer
    if kind == "sheet":
        return ContainerSpec.sheet(job.NestSheetWidth, job.NestSheetHeight,
                                   job.NestSheetCount or None)
    if kind == "strip":
        return ContainerSpec.strip(job.NestStripWidth)
    if kind == "hide":
        if not job.NestHideFile:
            raise InputError("choose the hide DXF (NestHideFile) for hide nesting")
        from ..core.nesting import containers
        return ContainerSpec.hide(*_read_hides(containers, job.NestHideFile))
    return None


def _read_hides(containers, path: str):
    hides = containers.read_hide_dxf(path)
    return hides if isinstance(hides, (list, tuple)) else [hides]


# ---------------------------------------------------------------------------
# Stage definition
# ---------------------------------------------------------------------------

@dataclass
class Stage:
    key: str
    title: str
    prepare: Callable[[Any], Any]
    compute: Callable[[Any, Optional[ProgressFn]], Any]
    apply: Callable[[Any, Any], Any]


def run_stage(job, key: str, progress: Optional[ProgressFn] = None):
    """Run one stage synchronously on ``job`` and return what ``apply`` made."""
    st = STAGES[key]
    inputs = st.prepare(job)
    result = st.compute(inputs, progress)
    return st.apply(job, result)


# -- import ---------------------------------------------------------------------

def _import_prepare(job):
    path = job.SourceFile
    if not path:
        raise InputError("the job has no DXF file (SourceFile)")
    if not os.path.isfile(path):
        raise InputError("no such file", source=path)
    return path, stage_options(job, "Import")


def _import_compute(inputs, progress):
    from ..core.dxfimport import read_drawing
    path, opts = inputs
    return read_drawing(path, opts, progress)


def _import_apply(job, drawing: model.Drawing):
    grp = objects.make_stage_group(job, objects.DrawingProxy, "Drawing",
                                   translate("LeatherCut", "Drawing"))
    objects.store_data(grp, drawing)
    by_layer: Dict[str, List[Any]] = {}
    for e in drawing.edges:
        pe = shapes.drawing_edge(e)
        if pe is not None:
            by_layer.setdefault(e.src.layer or "0", []).append(pe)
    for layer in sorted(by_layer):
        objects.make_shape(grp, "Layer", f"{translate('LeatherCut', 'Layer')} {layer}", "layer",
                           shapes.compound(by_layer[layer]))
    if drawing.marks:
        objects.make_shape(grp, "Marks", translate("LeatherCut", "Marks"), "marks",
                           shapes.marker_points([m.position for m in drawing.marks]))
    grp.OutOfDate = False
    objects.mark_out_of_date(job, "Import", include_self=False)
    return grp


# -- recognise ------------------------------------------------------------------

def _recognise_prepare(job):
    drawing = objects.load_data(objects.stage_object(job, "Drawing"))
    if drawing is None:
        raise InputError("import a drawing first (Import DXF)")
    return drawing, stage_options(job, "Recognise")


def _recognise_compute(inputs, progress):
    from ..core.recognition import recognise
    drawing, opts = inputs
    return recognise(drawing, opts, progress)


def _recognise_apply(job, rec: model.Recognition):
    # a person's decisions survive re-recognition when the same flag comes back
    kept = {(o.Kind, tuple(sorted(o.Ids))): o.Decision for o in flag_objects(job)
            if o.Decision != "Undecided"}
    kept_parts = part_objects.current_choices(job)
    grp = objects.make_stage_group(job, objects.RecognitionProxy, "Recognition",
                                   translate("LeatherCut", "Recognition"))
    objects.store_data(grp, rec)
    build_recognition_view(grp, rec)
    part_objects.build(grp, rec, kept_parts, lambda p: part_shape(p, False),
                       objects.load_data(objects.stage_object(job, "Drawing")))
    fgrp = job.Document.addObject("App::DocumentObjectGroup", "Flags")
    fgrp.Label = translate("LeatherCut", "Flags")
    grp.addObject(fgrp)
    contours = _contours_by_id(rec)
    for flag in rec.flags:
        fobj = objects.make_flag(fgrp, flag, flag_shape(flag, contours))
        decision = kept.get((flag.kind, tuple(sorted(flag.ids))))
        if decision is not None:
            fobj.Decision = decision
    grp.OutOfDate = False
    objects.mark_out_of_date(job, "Recognise", include_self=False)
    return grp


def _contours_by_id(rec: model.Recognition) -> Dict[str, List[geometry.Segment]]:
    out: Dict[str, List[geometry.Segment]] = {}
    for p in rec.parts:
        out[p.id] = p.outer.segments
        out[p.outer.id] = p.outer.segments
        for h in p.holes:
            out[h.id] = h.segments
        for li in p.lead_ins:
            out[li.id] = li.segments
    for c in rec.open_chains:
        out[c.id] = c.segments
    return out


def flag_shape(flag: model.Flag, contours: Dict[str, List[geometry.Segment]]):
    segs: List[geometry.Segment] = []
    for i in flag.ids:
        segs.extend(contours.get(i, []))
    segs.extend(flag.fix)
    return shapes.compound(shapes.path_edges(segs))


def build_recognition_view(grp, rec: model.Recognition) -> None:
    """One object per contour kind: outer contours, holes, lead-ins, open chains,
    excluded contours, marks."""
    kinds: Dict[str, List[Any]] = {"outer": [], "hole": [], "lead_in": [], "open": [],
                                   "excluded": []}
    marks: List[geometry.Point] = []
    for p in rec.parts:
        if p.excluded:
            for c in p.contours():
                kinds["excluded"].extend(shapes.path_edges(c.segments))
            continue
        kinds["outer"].append(shapes.contour_shape(p.outer))
        for h in p.holes:
            kinds["hole"].append(shapes.contour_shape(h))
        for li in p.lead_ins:
            kinds["lead_in"].extend(shapes.path_edges(li.segments))
        marks.extend(m.position for m in p.marks)
    for c in rec.open_chains:
        kinds["open"].extend(shapes.path_edges(c.segments))
    labels = {"outer": translate("LeatherCut", "Outer contours"),
              "hole": translate("LeatherCut", "Holes"),
              "lead_in": translate("LeatherCut", "Lead-ins"),
              "open": translate("LeatherCut", "Open chains"),
              "excluded": translate("LeatherCut", "Excluded")}
    for kind, items in kinds.items():
        if not items:
            continue
        objects.make_shape(grp, kind.title().replace("_", ""), labels[kind], kind,
                           shapes.compound(items))
    if marks:
        objects.make_shape(grp, "Marks", translate("LeatherCut", "Marks"), "marks",
                           shapes.marker_points(marks))


def flag_objects(job) -> List[Any]:
    rec = objects.stage_object(job, "Recognition")
    if rec is None:
        return []
    return [o for o in objects.walk(rec) if objects.role(o) == "Flag"]


def effective_recognition(job) -> model.Recognition:
    """The stored recognition with every person's flag decision applied.

    Accepted under-recognition fixes come from the core: recognition runs again
    on the stored drawing with the accepted flag ids (``accept_fixes``; flag ids
    do not change when fixes are applied).  The result is cached per job until
    the stored data, the options or the decisions change."""
    rec_obj = objects.stage_object(job, "Recognition")
    rec = objects.load_data(rec_obj)
    if rec is None:
        raise InputError("recognise the drawing first (Recognise)")
    decisions = {o.FlagId: o.Decision for o in flag_objects(job)}

    def recognise_again(accept, reject):
        drawing_obj = objects.stage_object(job, "Drawing")
        opts = stage_options(job, "Recognise")
        key = (hash(rec_obj.Data), hash(getattr(drawing_obj, "Data", "")), repr(opts),
               accept, reject)
        slot = (job.Document.Name, job.Name)
        hit = _RERUN_CACHE.get(slot)
        if hit is not None and hit[0] == key:
            return hit[1]
        drawing = objects.load_data(drawing_obj)
        if drawing is None:
            raise InputError("import the drawing first (Import DXF)")
        out = rerun_with_fixes(drawing, opts)(accept, reject)
        _RERUN_CACHE[slot] = (key, out)
        return out

    return part_objects.apply_to(job, apply_decisions(rec, decisions, recognise_again))


#: (document, job) -> (key, recognition with the accepted fixes applied)
_RERUN_CACHE: Dict[Tuple[str, str], Tuple[Any, model.Recognition]] = {}


def set_flag_decision(flag_obj, decision: str) -> None:
    """Record a person's decision on a flag (call inside a transaction)."""
    if decision not in objects.FlagProxy.DECISIONS:
        raise ValueError(f"unknown decision {decision!r}")
    flag_obj.Decision = decision


# -- nest -----------------------------------------------------------------------

def _nest_prepare(job):
    import time
    pressed = time.monotonic()       # the budget counts from the user's Nest (reading the hide too)
    rec = effective_recognition(job)
    opts = stage_options(job, "Nest")
    if opts.container is None:
        raise InputError("choose what to nest on (sheet, strip or hide) in the Auto-nest panel")
    parts = rec.active_parts()
    if not parts:
        raise InputError("no parts to nest: every part is excluded")
    prof = job_profile(job)
    if prof is not None:
        from ..post.compensation import reserve_in_nesting
        reserve_in_nesting(opts, prof)
    opts.started_at = pressed
    return parts, opts


def _nest_compute(inputs, progress):
    from ..core.nesting import nest
    parts, opts = inputs
    return parts, nest(parts, opts, progress), opts


def _nest_apply(job, result):
    parts, layout, opts = result
    grp = objects.make_stage_group(job, objects.LayoutProxy, "Layout",
                                   translate("LeatherCut", "Layout"))
    objects.store_data(grp, layout)
    for c in layout.containers:
        outline = shapes.path_edges(_ring_segments(c.outline))
        objects.make_shape(grp, "Container", f"{translate('LeatherCut', 'Container')} {c.id}",
                           "container", shapes.compound(outline))
        if c.defects:
            edges = []
            for d in c.defects:
                edges.extend(shapes.path_edges(_ring_segments(d)))
            objects.make_shape(grp, "Defects", f"{translate('LeatherCut', 'Defects')} {c.id}",
                               "defect", shapes.compound(edges))
    by_id = {p.id: p for p in parts}
    for pl in layout.placements:
        part = by_id[pl.part_id]
        objects.make_placed(grp, "Placed", part_shape(part, pl.mirrored), placement_of(pl),
                            pl.part_id, pl.copy, pl.container, pl.mirrored)
    grp.OutOfDate = False
    objects.mark_out_of_date(job, "Nest", include_self=False)
    update_collisions(job)
    return grp


def _ring_segments(ring: Sequence[geometry.Point]) -> List[geometry.Segment]:
    pts = list(ring)
    if pts and pts[0] != pts[-1]:
        pts.append(pts[0])
    return [geometry.LineSeg(tuple(a), tuple(b)) for a, b in zip(pts, pts[1:])]


def part_shape(part: model.Part, mirrored: bool):
    """A face of the part (outer minus holes) in part coordinates, mirrored about Y if asked."""
    import Part as P
    xf = geometry.Transform2D(mirrored=True) if mirrored else None

    def wire(c: model.Contour):
        segs = [s.transformed(xf) for s in c.segments] if xf else c.segments
        return shapes.contour_shape(model.Contour(c.id, segs))

    outer = wire(part.outer)
    try:
        face = P.Face(outer)
        for h in part.holes:
            hw = wire(h)
            if isinstance(hw, P.Wire) and hw.isClosed():
                face = face.cut(P.Face(hw))
        return face
    except Exception:  # an outline OCC cannot face (self-touching): show its edges
        return outer


def placement_of(pl: model.Placement):
    return FreeCAD.Placement(FreeCAD.Vector(pl.x, pl.y, 0.0),
                             FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), pl.angle))


def _angle_of(placement) -> float:
    a = placement.Rotation.toEuler()[0]
    return round(a % 360.0, 9)


def placed_objects(job) -> List[Any]:
    lay = objects.stage_object(job, "Layout")
    return [o for o in objects.walk(lay) if objects.role(o) == "PlacedPart"] if lay else []


def current_layout(job) -> Optional[model.Layout]:
    """The stored layout with the placements as the placed objects now stand
    (a person may have moved or rotated them by hand)."""
    lay_obj = objects.stage_object(job, "Layout")
    layout = objects.load_data(lay_obj)
    if layout is None:
        return None
    layout.placements = [
        model.Placement(part_id=o.PartId, copy=o.Copy, container=o.ContainerId,
                        x=float(o.Placement.Base.x), y=float(o.Placement.Base.y),
                        angle=_angle_of(o.Placement), mirrored=bool(o.Mirrored))
        for o in placed_objects(job)]
    return layout


def layout_problems(job) -> List[str]:
    """Problems of the current layout that the gate refuses (overlaps, spacing
    and margin, outside the container, defects), naming the parts."""
    from ..core.layout_gate import layout_findings
    layout = current_layout(job)
    if layout is None:
        return []
    rec = effective_recognition(job)
    opts = stage_options(job, "Nest")
    return layout_findings(rec.active_parts(), layout, spacing=opts.spacing, margin=opts.margin,
                           tol=max(opts.tolerance, 1e-3), chord_tol=opts.chord_tol)


def update_collisions(job) -> List[str]:
    """Set ``Collides`` on every placed part named in a layout problem; returns the problems.

    Rotations are not restricted here: a person may turn a part to any angle
    by hand (the part's own rotation limits apply to automatic nesting)."""
    problems = layout_problems(job)
    placed = placed_objects(job)
    labels = {f"{o.PartId}#{o.Copy}": o for o in placed}
    bad = set()
    for text in problems:
        for token in re.findall(r"[^\s:]+#\d+", text):
            if token in labels:
                bad.add(token)
    for lab, o in labels.items():
        want = lab in bad
        if o.Collides != want:
            o.Collides = want
    return problems


# -- plan -----------------------------------------------------------------------

def job_options(job, nest_again: bool = False):
    """The core's JobOptions for ``job`` as the document stands: every stage's
    options, the flag decisions, move-to-origin, the current (maybe hand-placed)
    layout unless ``nest_again``, the gate override; overrides are logged in the
    report view.  The one reading of the document behind *Plan path* and *Run
    job* (and what ``leathercut run`` gets from the equivalent options)."""
    from ..core.job import JobOptions
    nested = job.NestContainer != "none"
    layout = current_layout(job) if nested and not nest_again else None
    opts = JobOptions(
        import_=stage_options(job, "Import"), recognise=stage_options(job, "Recognise"),
        nest=stage_options(job, "Nest") if nested else None,
        plan=with_machine(stage_options(job, "Plan"), job),
        move_to_origin=job.PlanOriginOffset if getattr(job, "PlanMoveToOrigin", False) else None,
        decisions={o.FlagId: o.Decision for o in flag_objects(job)},
        layout=layout, allow_invalid_layout=bool(getattr(job, "AllowInvalidLayout", False)),
        log=_log_override, part_choices=part_objects.choices_of(job))
    prof = job_profile(job)
    if prof is not None:
        # kerf, cut direction and lead-ins of the machine (post/compensation.py)
        from ..post.compensation import apply_to_job
        apply_to_job(opts, prof)
    return opts


def _log_override(message: str) -> None:
    FreeCAD.Console.PrintWarning(f"LeatherCut: {message}\n")


def _kept_layout_options(job):
    """JobOptions of a stage that cuts the current layout and never nests."""
    opts = job_options(job)
    if opts.nest is not None and opts.layout is None:
        raise InputError("nest the parts first (Auto-nest), or choose no container to cut "
                         "the drawing where it lies")
    return opts


def parts_to_cut(job) -> Tuple[List[model.Part], List[model.OpenChain]]:
    """Parts (placed in container coordinates when nested) and open chains to cut;
    a layout must pass the gate (InputError naming the parts)."""
    from ..core.job import arrange
    _layout, parts, chains = arrange(effective_recognition(job), _kept_layout_options(job))
    return parts, chains


def check_gate(job) -> None:
    """Refuse (InputError) a current layout the gate does not pass; *Post-process*
    and *Send to cutter* call it, since parts may have moved since *Plan path*."""
    from ..core.job import gated
    opts = job_options(job)
    if opts.layout is not None:
        gated(effective_recognition(job).active_parts(), opts.layout, opts)


def _plan_prepare(job):
    return effective_recognition(job), _kept_layout_options(job)


def job_profile(job):
    """The job's machine profile, or None (no machine chosen, post not available)."""
    if not getattr(job, "PostMachine", "") or not available("Post"):
        return None
    from ..post.profiles import load_profile
    return load_profile(job.PostMachine)


def with_machine(opts, job):
    """Plan options with speeds, acceleration and knife lift angle taken from the
    job's machine profile (when ``PlanFromMachine`` is set)."""
    if opts is None or not getattr(job, "PlanFromMachine", False) or not job.PostMachine \
            or not available("Post"):
        return opts
    from ..post.profiles import load_profile
    prof = load_profile(job.PostMachine)
    return replace(opts, rapid_speed=prof.rapid_feed, cut_speed=prof.cut_feed,
                   accel=prof.acceleration,
                   lift_angle=prof.lift_angle if prof.tangential else None)


def _plan_compute(inputs, progress):
    from ..core.job import plan_arranged
    rec, opts = inputs
    layout, _parts, cut_plan = plan_arranged(rec, opts, progress)
    if layout is not None:  # the stored plan says it was cut past the gate
        cut_plan.findings += [f for f in layout.findings if f.code == "layout-override"]
    return cut_plan


def _plan_apply(job, cut_plan: model.CutPlan):
    obj = objects.make_cut_path(job)
    objects.store_data(obj, cut_plan)
    edges = []
    for it in cut_plan.items:
        edges.extend(shapes.path_edges(it.segments))
    obj.Shape = shapes.compound(edges)
    m = cut_plan.metrics or {}
    obj.IdleTravel = float(m.get("idle_mm", 0.0))
    obj.CutLength = float(m.get("cut_mm", sum(it.length for it in cut_plan.items)))
    obj.Lifts = int(m.get("lifts", sum(len(it.lifts) for it in cut_plan.items)))
    obj.EstimatedTime = float(m.get("est_time_s", 0.0))
    obj.Items = len(cut_plan.items)
    obj.Method = cut_plan.method
    obj.OutOfDate = False
    _show_tools(job, cut_plan)
    objects.mark_out_of_date(job, "Plan", include_self=False)
    return obj


def tool_job(job, cut_plan: model.CutPlan):
    """The multi-tool job (post/tool_jobs.py) of ``cut_plan`` for the job's
    machine and ``PostToolMap``; None when the machine has no further tools
    in use or the profile / map would be refused by Post-process."""
    from ..post import tool_export
    from ..post.profiles import load_profile
    from ..post.tools import parse_tool_map
    try:
        prof = load_profile(job.PostMachine)
        tools = tool_export.job_for(cut_plan, parts_to_cut(job)[0], prof,
                                    parse_tool_map(getattr(job, "PostToolMap", "") or "",
                                                   "PostToolMap"), "PostToolMap")
    except InputError:
        return None
    return tools if tool_export.is_multi(tools, cut_plan) else None


def _show_tools(job, cut_plan: model.CutPlan) -> None:
    """The passes of the further tools of the job's machine (pen lines, punch
    points, ...), one shape per tool in its colour (post/tool_export.py), in a
    *Tool paths* group replaced with the cut path.  Nothing when the machine
    has no tool map; a map the Post stage would refuse shows no tools."""
    from ..post import tool_export
    old = objects.stage_object(job, objects.ToolPathsProxy.ROLE)
    if old is not None:
        objects.remove_tree(old)
    tools = tool_job(job, cut_plan)
    if tools is None or len(tools.passes) < 2:
        return
    grp = objects.make_stage_group(job, objects.ToolPathsProxy, "ToolPaths",
                                   translate("LeatherCut", "Tool paths"))
    for name, colour, items, points in tool_export.preview_tools(tools):
        shape = shapes.compound([e for it in items for e in shapes.path_edges(it.segments)]
                                + list(shapes.marker_points(points).Vertexes))
        obj = objects.make_shape(grp, "Tool", translate("LeatherCut", "Tool {0}").format(name),
                                 "tool", shape)
        if FreeCAD.GuiUp:
            rgb = tuple(int(colour[i:i + 2], 16) / 255.0 for i in (1, 3, 5))
            obj.ViewObject.LineColor = obj.ViewObject.PointColor = rgb
            obj.ViewObject.PointSize = 5.0


def stored_plan(job) -> model.CutPlan:
    obj = objects.stage_object(job, "CutPath")
    plan = objects.load_data(obj)
    if plan is None:
        raise InputError("plan the cut path first (Plan path)")
    return plan


# -- post -----------------------------------------------------------------------

POST_EXTENSIONS = {"gcode": ".nc", "hpgl": ".plt", "dxf": ".dxf"}


def default_output(job) -> str:
    """Where Post-process writes when the job names no file: ``<job label>.<ext>``
    in the user's output folder preference (``OutputFolder``), else beside the
    saved document, else in the home folder -- never next to the source DXF
    (often a read-only or shared folder)."""
    folder = options.preferences().GetString("OutputFolder", "").strip()
    if not folder:
        saved = job.Document.FileName
        folder = os.path.dirname(saved) if saved else os.path.expanduser("~")
    stem = re.sub(r"[^\w.-]+", "_", job.Label).strip("._") or "job"
    return os.path.join(os.path.expanduser(folder), stem + POST_EXTENSIONS.get(job.PostFormat, ".nc"))


def _post_prepare(job):
    from ..post.profiles import load_profile
    from ..post.tools import parse_tool_map, tool_map
    plan = stored_plan(job)
    check_gate(job)
    path = job.PostOutputFile or default_output(job)
    profile = load_profile(job.PostMachine)
    overrides = parse_tool_map(getattr(job, "PostToolMap", "") or "", "PostToolMap")
    tool_map(profile, overrides, "PostToolMap")   # a bad map is refused before anything is written
    return plan, parts_to_cut(job)[0], profile, job.PostFormat, overrides, path


def _post_compute(inputs, progress):
    from ..post import tool_export
    plan, parts, profile, fmt, overrides, path = inputs
    text = tool_export.render(plan, parts, profile, fmt, overrides=overrides,
                              overrides_from="PostToolMap")
    return text, path, fmt


def _post_apply(job, result):
    from ..post.jobfile import write_job_file
    text, path, fmt = result
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    write_job_file(path, text, gcode=fmt == "gcode")     # atomic; G-code sealed
    job.PostLastOutput = path
    return path


# -- run job (core.job.run_job with the document's decisions, then every stage's apply) --

def _run_prepare(job):
    path, _import_opts = _import_prepare(job)
    nest_again = bool(getattr(job, "RunNestAgain", False))
    opts = job_options(job, nest_again=nest_again)
    rec = objects.stage_object(job, "Recognition")
    if rec is not None and rec.OutOfDate and any(d != "Undecided" for d in opts.decisions.values()):
        raise InputError("the recognition is out of date and has flag decisions (flag ids may "
                         "name other contours now): recognise again first, decisions are kept")
    lay = objects.stage_object(job, "Layout")
    if opts.layout is not None and lay.OutOfDate:
        raise InputError("the layout is out of date (an earlier stage changed since it was "
                         "nested): nest again (Auto-nest), or set RunNestAgain to let Run job "
                         "replace it")
    return path, opts


def _run_compute(inputs, progress):
    from ..core.job import run_job
    path, opts = inputs
    return run_job(path, opts, progress), opts


def _run_apply(job, result):
    res, opts = result
    _import_apply(job, res.drawing)
    _recognise_apply(job, res.proposal or res.recognition)
    if res.layout is not None:
        _nest_apply(job, (res.recognition.active_parts(), res.layout, opts.nest))
    else:
        old = objects.stage_object(job, "Layout")
        if old is not None:
            objects.remove_tree(old)
    _plan_apply(job, res.plan)
    return run_stage(job, "Post")


STAGES: Dict[str, Stage] = {
    "Import": Stage("Import", "Import DXF", _import_prepare, _import_compute, _import_apply),
    "Recognise": Stage("Recognise", "Recognise", _recognise_prepare, _recognise_compute,
                       _recognise_apply),
    "Nest": Stage("Nest", "Auto-nest", _nest_prepare, _nest_compute, _nest_apply),
    "Plan": Stage("Plan", "Plan path", _plan_prepare, _plan_compute, _plan_apply),
    "Post": Stage("Post", "Post-process", _post_prepare, _post_compute, _post_apply),
    "RunJob": Stage("RunJob", "Run job", _run_prepare, _run_compute, _run_apply),
}


def run_all(job, progress: Optional[ProgressFn] = None) -> str:
    """The whole job (import to machine file) on ``job``; returns the file written."""
    return run_stage(job, "RunJob", progress)
