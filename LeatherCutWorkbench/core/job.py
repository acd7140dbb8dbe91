"""The whole job as one call: import -> recognise -> (nest) -> plan.

The CLI's ``run`` verb, the later verbs that re-run earlier stages, the
workbench's *Run job* command and the ``freecadcmd`` end-to-end test all use
:func:`run_job`, so a headless run and a toolbar run give the same result.
Stages are imported lazily: importing this module costs nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, List, Optional

from .model import CutPlan, Drawing, Finding, Layout, Part, Recognition
from .progress import ProgressFn, report


@dataclass
class JobOptions:
    """Options of every stage.  ``nest`` is None when the drawing is cut where
    it lies (no container given)."""

    import_: Any = None
    recognise: Any = None
    nest: Any = None
    plan: Any = None


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


def nest_if_asked(recognition: Recognition, options: JobOptions,
                  progress: Optional[ProgressFn] = None) -> "tuple[Optional[Layout], List[Part]]":
    """Nest the active parts when a container is given; otherwise the parts are
    cut where they lie.  Returns the layout (or None) and the parts to cut."""
    parts = recognition.active_parts()
    if options.nest is None:
        return None, parts
    from .nesting import nest, placed_parts

    layout = nest(parts, options.nest, _scaled(progress, 0.4, 0.7))
    return layout, placed_parts(parts, layout)


def run_job(path: str, options: Optional[JobOptions] = None,
            progress: Optional[ProgressFn] = None) -> JobResult:
    """Run import, recognition, optional nesting and path planning on ``path``.

    Raises :class:`~LeatherCutWorkbench.core.errors.InputError` for unusable
    input; every stage's findings are collected in ``JobResult.findings``."""
    from .pathplan import PlanOptions, plan

    options = options or JobOptions()
    drawing, recognition = load_and_recognise(path, options, progress)
    layout, parts = nest_if_asked(recognition, options, progress)
    report(progress, 0.7, "planning the cut path")
    # Open chains are only cut where the drawing is cut as it lies: a nested job
    # moves parts, and stray lines have no part to travel with.
    chains = recognition.open_chains if layout is None else []
    cut_plan = plan(parts, chains, options.plan or PlanOptions(), _scaled(progress, 0.7, 1.0))
    findings = list(drawing.findings) + list(recognition.findings)
    if layout is not None:
        findings += layout.findings
    findings += cut_plan.findings
    report(progress, 1.0, "job planned")
    return JobResult(path, drawing, recognition, layout, parts, cut_plan, findings)
