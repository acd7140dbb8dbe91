"""The whole job as one call: import -> recognise -> (nest) -> plan.

The CLI's ``run`` verb, the later verbs that re-run earlier stages, the
workbench's *Run job* command and the ``freecadcmd`` end-to-end test all use
:func:`run_job`, so a headless run and a toolbar run give the same result.
Stages are imported lazily: importing this module costs nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, List, Optional, Tuple

from .geometry import Transform2D, bbox
from .model import CutPlan, Drawing, Finding, Layout, OpenChain, Part, Recognition
from .progress import ProgressFn, report


@dataclass
class JobOptions:
    """Options of every stage.  ``nest`` is None when the drawing is cut where
    it lies (no container given); ``move_to_origin`` (mm) then optionally moves
    the whole drawing so its lower-left corner sits that far from machine zero
    (drawings often lie at negative or far-away coordinates)."""

    import_: Any = None
    recognise: Any = None
    nest: Any = None
    plan: Any = None
    move_to_origin: Optional[float] = None
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


def _scaled(progress: Optional[ProgressFn], lo: float, hi: float) -> Optional[ProgressFn]:
    """A progress callback mapping a stage's [0, 1] onto [lo, hi] of the job."""
    if progress is None:
        return None
    return lambda f, msg: progress(lo + (hi - lo) * f, msg)


def load_and_recognise(path: str, options: JobOptions,
                       progress: Optional[ProgressFn] = None) -> "tuple[Drawing, Recognition]":
    """Import ``path`` and recognise its parts."""
    from .dxfimport import ImportOptions, read_drawing
    from .recognition import RecogniseOptions, recognise

    report(progress, 0.0, f"reading {path}")
    drawing = read_drawing(path, options.import_ or ImportOptions(), _scaled(progress, 0.0, 0.2))
    report(progress, 0.2, "recognising contours")
    recognition = recognise(drawing, options.recognise or RecogniseOptions(),
                            _scaled(progress, 0.2, 0.4))
    return drawing, recognition


def arrange(recognition: Recognition, options: JobOptions,
            progress: Optional[ProgressFn] = None
            ) -> "tuple[Optional[Layout], List[Part], List[OpenChain]]":
    """Decide where the parts are cut: nested into a container when one is
    given, else where they lie (optionally moved to the origin).  Returns the
    layout (or None), the parts to cut and the open chains to cut.  Open chains
    are only cut with an un-nested drawing: nesting moves parts, and stray
    lines have no part to travel with."""
    parts = recognition.active_parts()
    if options.nest is not None:
        from .nesting import nest, placed_parts

        layout = nest(parts, options.nest, _scaled(progress, 0.4, 0.7))
        return layout, placed_parts(parts, layout), []
    chains = list(recognition.open_chains)
    if options.move_to_origin is not None:
        parts, chains = moved_to_origin(parts, chains, options.move_to_origin)
    return None, parts, chains


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
    from .pathplan import PlanOptions, plan

    options = options or JobOptions()
    drawing, recognition = load_and_recognise(path, options, progress)
    layout, parts, chains = arrange(recognition, options, progress)
    report(progress, 0.7, "planning the cut path")
    # the parts as the machine's tool follows them (kerf, direction, leads)
    tool_parts, tool_findings = options.prepare(parts, layout) if options.prepare else (parts, [])
    cut_plan = plan(tool_parts, chains, options.plan or PlanOptions(), _scaled(progress, 0.7, 1.0))
    cut_plan.findings[:0] = tool_findings
    findings = list(drawing.findings) + list(recognition.findings)
    if layout is not None:
        findings += layout.findings
    findings += cut_plan.findings
    report(progress, 1.0, "job planned")
    return JobResult(path, drawing, recognition, layout, parts, cut_plan, findings)
