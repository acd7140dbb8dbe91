"""The whole job as one call: import -> recognise -> decisions -> (nest | kept
layout, gated) -> plan.

The CLI's ``run`` verb, the later verbs that re-run earlier stages, the
workbench's *Run job* command and the ``freecadcmd`` end-to-end test all use
:func:`run_job`; the workbench's *Plan path* uses :func:`plan_arranged` on the
stored recognition with the same options, so a headless run, a toolbar run and
the stages one by one give the same result.  Stages are imported lazily:
importing this module costs nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Callable, Dict, List, Optional, Tuple

from .geometry import Transform2D, bbox
from .model import CutPlan, Drawing, Finding, Layout, OpenChain, Part, Recognition
from .progress import ProgressFn, report


@dataclass
class JobOptions:
    """Options of every stage.  ``nest`` is None when the drawing is cut where
    it lies (no container given); ``move_to_origin`` (mm) then optionally moves
    the whole drawing so its lower-left corner sits that far from machine zero
    (drawings often lie at negative or far-away coordinates).

    ``decisions`` (flag id -> Include / Exclude / Accept / Reject / Undecided,
    see :mod:`core.decisions`) are applied after recognition.  ``layout`` is a
    layout to cut as it stands (hand-placed in the workbench, or a layout JSON)
    instead of nesting again; every layout passes the gate
    (:mod:`core.layout_gate`) against ``nest``'s spacing and margin unless
    ``allow_invalid_layout``; ``log(message)`` is told of every override."""

    import_: Any = None
    recognise: Any = None
    nest: Any = None
    plan: Any = None
    move_to_origin: Optional[float] = None
    decisions: Optional[Dict[str, str]] = None
    layout: Optional[Layout] = None
    allow_invalid_layout: bool = False
    log: Optional[Callable[[str], None]] = None
    #: part id -> PartChoice (include, quantity; :mod:`core.part_choice`); None =
    #: the defaults (a graded AAMA / ASTM set cuts only its sample size), {} = as recognised
    part_choices: Optional[Dict[str, Any]] = None
    #: with the defaults: the pattern sizes to cut (["all"] = every size)
    sizes: Optional[List[str]] = None
    #: with the defaults: part id -> quantity to cut (copies when nested)
    quantities: Optional[Dict[str, int]] = None
    #: parts, layout -> (parts as the tool follows them, findings); set from the
    #: machine profile (kerf, cut direction, lead-ins: post/compensation.py)
    prepare: Optional[Callable[[List[Part], Optional[Layout]], Tuple[List[Part], List[Finding]]]] = None


@dataclass
class JobResult:
    """Everything a job produced, stage by stage."""

    path: str
    drawing: Drawing
    recognition: Recognition
    layout: Optional[Layout]
    parts_to_cut: List[Part]
    plan: CutPlan
    findings: List[Finding] = field(default_factory=list)
    #: the recognition as recognised, before the person's decisions and part choices
    proposal: Optional[Recognition] = None


def _scaled(progress: Optional[ProgressFn], lo: float, hi: float) -> Optional[ProgressFn]:
    """A progress callback mapping a stage's [0, 1] onto [lo, hi] of the job."""
    if progress is None:
        return None
    return lambda f, msg: progress(lo + (hi - lo) * f, msg)


def load_and_recognise(path: str, options: JobOptions,
                       progress: Optional[ProgressFn] = None) -> "tuple[Drawing, Recognition]":
    """Import ``path`` and recognise its parts (the person's decisions applied)."""
    drawing, _proposal, recognition = _load(path, options, progress)
    return drawing, recognition


def _load(path: str, options: JobOptions, progress: Optional[ProgressFn]
          ) -> "tuple[Drawing, Optional[Recognition], Recognition]":
    """(drawing, the recognition as recognised, recognition to cut: decisions and
    part choices applied)."""
    from .dxfimport import ImportOptions, read_drawing
    from .recognition import RecogniseOptions, recognise

    report(progress, 0.0, f"reading {path}")
    drawing = read_drawing(path, options.import_ or ImportOptions(), _scaled(progress, 0.0, 0.2))
    report(progress, 0.2, "recognising contours")
    rec_opts = options.recognise or RecogniseOptions()
    recognition = recognise(drawing, rec_opts, _scaled(progress, 0.2, 0.4))
    if not options.decisions:
        return drawing, recognition, chosen_parts(drawing, recognition, options)
    from .decisions import apply_decisions, rerun_with_fixes
    decided = apply_decisions(recognition, options.decisions, rerun_with_fixes(drawing, rec_opts))
    return drawing, recognition, chosen_parts(drawing, decided, options)


def chosen_parts(drawing: Drawing, recognition: Recognition, options: JobOptions) -> Recognition:
    """``recognition`` with the person's part choices applied (``options.part_choices``,
    as the workbench's part objects hold them), else the defaults of
    :func:`core.part_choice.default_choices` with ``options.sizes`` /
    ``options.quantities`` (the CLI's ``--sizes`` / ``--quantity``)."""
    from .part_choice import apply_choices, default_choices, sample_size

    choices = options.part_choices
    if choices is None:
        choices = default_choices(recognition.parts, sample_size(drawing), options.sizes)
        for pid, n in (options.quantities or {}).items():
            if pid not in choices:
                from .errors import InputError
                raise InputError(f"--quantity names part {pid}, which the drawing does not have "
                                 f"(parts: {', '.join(sorted(choices)) or 'none'})")
            choices[pid].quantity = n
    return apply_choices(recognition, choices) if choices else recognition


def arrange(recognition: Recognition, options: JobOptions,
            progress: Optional[ProgressFn] = None
            ) -> "tuple[Optional[Layout], List[Part], List[OpenChain]]":
    """Decide where the parts are cut: on the given layout, nested into a
    container when one is given, else where they lie (optionally moved to the
    origin).  Returns the layout (or None), the parts to cut and the open chains
    to cut.  Open chains are only cut with an un-nested drawing: nesting moves
    parts, and stray lines have no part to travel with.  A layout must pass the
    gate (raises InputError naming the parts, unless overridden)."""
    parts = recognition.active_parts()
    if options.layout is not None or options.nest is not None:
        from .nesting import nest, placed_parts

        layout = options.layout if options.layout is not None else \
            nest(parts, options.nest, _scaled(progress, 0.4, 0.7))
        layout = replace(layout, findings=list(layout.findings) + gated(parts, layout, options))
        return layout, placed_parts(parts, layout), []
    chains = list(recognition.open_chains)
    if options.move_to_origin is not None:
        parts, chains = moved_to_origin(parts, chains, options.move_to_origin)
    return None, parts, chains


def gated(parts: List[Part], layout: Layout, options: JobOptions) -> List[Finding]:
    """Pass ``layout`` through the gate with the job's spacing and margin; returns
    the override warnings (each also given to ``options.log``)."""
    from .layout_gate import gate_layout

    nest = options.nest
    found = gate_layout(parts, layout, spacing=getattr(nest, "spacing", 0.0),
                        margin=getattr(nest, "margin", 0.0),
                        tol=max(getattr(nest, "tolerance", 1e-3), 1e-3),
                        chord_tol=getattr(nest, "chord_tol", 0.05),
                        allow_invalid=options.allow_invalid_layout)
    for f in found:
        if options.log is not None:
            options.log(f.message)
    return found


def plan_arranged(recognition: Recognition, options: JobOptions,
                  progress: Optional[ProgressFn] = None
                  ) -> "tuple[Optional[Layout], List[Part], CutPlan]":
    """Arrange (:func:`arrange`) and plan the recognition to cut: the one
    composition behind ``leathercut run`` / ``plan`` / ``post`` / ``send``, the
    workbench's *Run job* and its *Plan path*.  ``progress`` runs 0.4 -> 1.0."""
    from .pathplan import PlanOptions, plan

    layout, parts, chains = arrange(recognition, options, progress)
    report(progress, 0.7, "planning the cut path")
    # the parts as the machine's tool follows them (kerf, direction, leads)
    tool_parts, tool_findings = options.prepare(parts, layout) if options.prepare else (parts, [])
    cut_plan = plan(tool_parts, chains, options.plan or PlanOptions(), _scaled(progress, 0.7, 1.0))
    cut_plan.findings[:0] = tool_findings
    return layout, parts, cut_plan


def moved_to_origin(parts: List[Part], chains: List[OpenChain], offset: float
                    ) -> "tuple[List[Part], List[OpenChain]]":
    """Copies of ``parts`` and ``chains`` moved together so the lower-left corner
    of their bounding box lies ``offset`` mm from machine zero in X and Y
    (shapes and distances between them unchanged)."""
    if not parts and not chains:
        return parts, chains
    pts = [p for part in parts for p in part.outer.points(0.1)]
    pts += [p for ch in chains for s in ch.segments for p in s.points(0.1)]
    xmin, ymin, _, _ = bbox(pts)
    xf = Transform2D(dx=offset - xmin, dy=offset - ymin)
    return [p.transformed(xf) for p in parts], [c.transformed(xf) for c in chains]


def run_job(path: str, options: Optional[JobOptions] = None,
            progress: Optional[ProgressFn] = None) -> JobResult:
    """Run import, recognition, optional nesting and path planning on ``path``.

    Raises :class:`~LeatherCutWorkbench.core.errors.InputError` for unusable
    input; every stage's findings are collected in ``JobResult.findings``."""
    options = options or JobOptions()
    drawing, proposal, recognition = _load(path, options, progress)
    layout, parts, cut_plan = plan_arranged(recognition, options, progress)
    findings = list(drawing.findings) + list(recognition.findings)
    if layout is not None:
        findings += layout.findings
    findings += cut_plan.findings
    report(progress, 1.0, "job planned")
    return JobResult(path, drawing, recognition, layout, parts, cut_plan, findings, proposal)
