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
from ..core.errors import InputError, LeatherCutError
from ..core.progress import ProgressFn
from . import objects, options, shapes
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

CONTAINER_KINDS = ["none", "sheet", "strip", "hide"]


def available(stage: str) -> bool:
    """True when the stage's package can be imported."""
    try:
        importlib.import_module(STAGE_PACKAGES[stage])
        return True
    except ImportError:
        return False


# ---------------------------------------------------------------------------
# Job options that are not plain dataclass fields
# ---------------------------------------------------------------------------

def add_nest_container_properties(job) -> None:
    """The nesting container as separate properties (kind, sheet, strip, hide)."""
    props = [
        ("App::PropertyEnumeration", "NestContainer",
         "what to nest on: none (cut the drawing where it lies), sheet, strip or hide"),
        ("App::PropertyFloat", "NestSheetWidth", "sheet width (X), mm"),
        ("App::PropertyFloat", "NestSheetHeight", "sheet height (Y), mm"),
        ("App::PropertyInteger", "NestSheetCount", "at most this many sheets (0 = open sheets as needed)"),
        ("App::PropertyFloat", "NestStripWidth", "strip width (Y), mm; the length along X is minimised"),
        ("App::PropertyFile", "NestHideFile", "DXF with the hide outline, defects and quality zones"),
    ]
    for ptype, name, tip in props:
        if name not in job.PropertiesList:
            job.addProperty(ptype, name, "Nest", tip)
            if name == "NestContainer":
                job.NestContainer = CONTAINER_KINDS
                job.NestContainer = "none"
    if job.NestSheetWidth == 0 and job.NestSheetHeight == 0:
        job.NestSheetWidth, job.NestSheetHeight = 1000.0, 1000.0
    if job.NestStripWidth == 0:
        job.NestStripWidth = 1000.0
    if "PlanMoveToOrigin" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "PlanMoveToOrigin", "Plan",
                        "without nesting: move the drawing so its lower-left corner lies "
                        "PlanOriginOffset from machine zero (drawings often lie far from it)")
        job.addProperty("App::PropertyFloat", "PlanOriginOffset", "Plan",
                        "distance of the moved drawing's lower-left corner from machine zero, mm")
        job.PlanOriginOffset = 10.0
    if "PlanFromMachine" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "PlanFromMachine", "Plan",
                        "take speeds, acceleration and the knife lift angle from the machine profile "
                        "(PostMachine) instead of the Plan options")
        job.PlanFromMachine = True


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
    grp = objects.make_stage_group(job, objects.RecognitionProxy, "Recognition",
                                   translate("LeatherCut", "Recognition"))
    objects.store_data(grp, rec)
    build_recognition_view(grp, rec)
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
        from ..core.recognition import recognise
        out = recognise(drawing, replace(opts, close_gaps=False, accept_fixes=accept,
                                         reject_fixes=reject))
        _RERUN_CACHE[slot] = (key, out)
        return out

    return apply_decisions(rec, decisions, recognise_again)


#: (document, job) -> (key, recognition with the accepted fixes applied)
_RERUN_CACHE: Dict[Tuple[str, str], Tuple[Any, model.Recognition]] = {}


def apply_decisions(rec: model.Recognition, decisions: Dict[str, str],
                    recognise_again: Optional[Callable[[frozenset, frozenset],
                                                       model.Recognition]] = None
                    ) -> model.Recognition:
    """Apply decisions (flag id -> Include / Exclude / Accept / Reject / Undecided).

    Over-recognised: Include clears ``excluded`` on the flagged parts, Exclude
    sets it.  Under-recognised: the fixes to apply (Accept, or Undecided on a
    flag the stored run already applied, e.g. with ``close_gaps``) and to reject
    are passed to ``recognise_again(accept_ids, reject_ids)``, which returns the
    core's recognition with exactly those fixes applied; it is called only when
    the geometry must change.  Returns a new recognition."""
    from copy import deepcopy
    under = [f for f in rec.flags if f.kind == "under"]
    accept = frozenset(f.id for f in under if decisions.get(f.id) == "Accept"
                       or (decisions.get(f.id, "Undecided") == "Undecided" and f.accepted is True))
    reject = frozenset(f.id for f in under if decisions.get(f.id) == "Reject")
    if any((f.id in accept) != (f.accepted is True) for f in under):
        if recognise_again is None:
            raise LeatherCutError("accepting or rejecting a fix needs the drawing: "
                                  "recognise again")
        out = deepcopy(recognise_again(accept, reject))
        _check_same_flags(rec, out, accept | reject)
    else:
        out = deepcopy(rec)
        for f in out.flags:
            if f.kind == "under" and f.id in reject:
                f.accepted = False
    for flag in out.flags:
        d = decisions.get(flag.id, "Undecided")
        if flag.kind == "over" and d in ("Include", "Exclude"):
            flag.accepted = d == "Exclude"
            ids = set(flag.ids)
            for p in out.parts:
                if p.id in ids or p.outer.id in ids:
                    p.excluded = d == "Exclude"
    return out


def _check_same_flags(old: model.Recognition, new: model.Recognition, decided) -> None:
    """The decided flags must be the same flags in the new run (else the stored
    recognition no longer matches the drawing or the options)."""
    got = {f.id: f for f in new.flags}
    for f in old.flags:
        if f.id not in decided:
            continue
        g = got.get(f.id)
        if g is None or (g.kind, g.action) != (f.kind, f.action) or \
                abs((g.gap or 0.0) - (f.gap or 0.0)) > 1e-9:
            raise InputError(f"flag {f.id} is not the same after recognising again: the "
                             "recognition is out of date, run Recognise again")


def set_flag_decision(flag_obj, decision: str) -> None:
    """Record a person's decision on a flag (call inside a transaction)."""
    if decision not in objects.FlagProxy.DECISIONS:
        raise ValueError(f"unknown decision {decision!r}")
    flag_obj.Decision = decision


# -- nest -----------------------------------------------------------------------

def _nest_prepare(job):
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
    """Problems of the current layout (overlaps, outside the container, defects)."""
    from ..core.nesting.checker import check_layout
    layout = current_layout(job)
    if layout is None:
        return []
    rec = effective_recognition(job)
    opts = stage_options(job, "Nest")
    return check_layout(rec.active_parts(), layout, spacing=opts.spacing, margin=opts.margin,
                        tol=max(opts.tolerance, 1e-3), chord_tol=opts.chord_tol,
                        rotations_override=None, mirror_override=True)


def update_collisions(job) -> List[str]:
    """Set ``Collides`` on every placed part named in a layout problem; returns the problems.

    Rotations are not restricted here: a person may turn a part to any angle
    by hand (the part's own rotation limits apply to automatic nesting)."""
    problems = [p for p in layout_problems(job) if "not allowed" not in p]
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

def parts_to_cut(job) -> Tuple[List[model.Part], List[model.OpenChain]]:
    """Parts (placed in container coordinates when nested) and open chains to cut."""
    rec = effective_recognition(job)
    parts = rec.active_parts()
    layout = current_layout(job)
    if layout is not None and job.NestContainer != "none":
        from ..core.nesting import placed_parts
        return placed_parts(parts, layout), []
    chains = list(rec.open_chains)
    if getattr(job, "PlanMoveToOrigin", False):
        from ..core.job import moved_to_origin
        return moved_to_origin(parts, chains, job.PlanOriginOffset)
    return parts, chains


def _plan_prepare(job):
    parts, chains = parts_to_cut(job)
    opts = stage_options(job, "Plan")
    prof = job_profile(job)
    if prof is not None:
        # kerf, cut direction and lead-ins of the machine (post/compensation.py)
        from ..post.compensation import job_hook
        hook = job_hook(prof, opts.entry_spacing)
        if hook is not None:
            parts, findings = hook(parts, current_layout(job) if job.NestContainer != "none" else None)
            return parts, chains, with_machine(opts, job), findings
    return parts, chains, with_machine(opts, job), []


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
    from ..core.pathplan import plan
    parts, chains, opts, findings = inputs
    cut_plan = plan(parts, chains, opts, progress)
    cut_plan.findings[:0] = findings
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
    objects.mark_out_of_date(job, "Plan", include_self=False)
    return obj


def stored_plan(job) -> model.CutPlan:
    obj = objects.stage_object(job, "CutPath")
    plan = objects.load_data(obj)
    if plan is None:
        raise InputError("plan the cut path first (Plan path)")
    return plan


# -- post -----------------------------------------------------------------------

POST_EXTENSIONS = {"gcode": ".nc", "hpgl": ".plt", "dxf": ".dxf"}


def default_output(job) -> str:
    base = os.path.splitext(job.SourceFile or job.Document.FileName or "job")[0] or "job"
    return base + POST_EXTENSIONS.get(job.PostFormat, ".nc")


def _post_prepare(job):
    from ..post.profiles import load_profile
    plan = stored_plan(job)
    path = job.PostOutputFile or default_output(job)
    return plan, load_profile(job.PostMachine), job.PostFormat, path


def _post_compute(inputs, progress):
    plan, profile, fmt, path = inputs
    writer = importlib.import_module(f"LeatherCutWorkbench.post.{'dxf_out' if fmt == 'dxf' else fmt}")
    text = writer.export(plan, profile)
    return text, path


def _post_apply(job, result):
    text, path = result
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)
    job.PostLastOutput = path
    return path


# -- run job (the lead's core.job.run_job, then every stage's apply) --------------

def _run_prepare(job):
    from ..core.job import JobOptions
    path, import_opts = _import_prepare(job)
    nest_opts = stage_options(job, "Nest") if job.NestContainer != "none" else None
    opts = JobOptions(import_=import_opts, recognise=stage_options(job, "Recognise"),
                      nest=nest_opts, plan=with_machine(stage_options(job, "Plan"), job))
    prof = job_profile(job)
    if prof is not None:
        from ..post.compensation import apply_to_job
        apply_to_job(opts, prof)
    return path, opts


def _run_compute(inputs, progress):
    from ..core.job import run_job
    path, opts = inputs
    return run_job(path, opts, progress), opts


def _run_apply(job, result):
    res, opts = result
    _import_apply(job, res.drawing)
    _recognise_apply(job, res.recognition)
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
