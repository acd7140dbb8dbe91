"""What the verbs share: earlier-stage options, job options, argument types, progress.

A verb that needs earlier stages (``plan`` needs import + recognition +
optional nesting) adds their options with :func:`add_stage_options` and turns
the parsed arguments into :class:`~LeatherCutWorkbench.core.job.JobOptions`
with :func:`job_options`, so every verb accepts and interprets a stage's
options identically.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from typing import Any, Callable, List, Optional

from ..core.job import JobOptions

#: Stage CLI modules in pipeline order and the JobOptions field each fills.
STAGES = (("inspect_cmd", "import_"), ("recognise_cmd", "recognise"),
          ("nest_cmd", "nest"), ("plan_cmd", "plan"))


def _stage_modules(before: str) -> List[Any]:
    """CLI modules of the stages before ``before`` (``"end"``: all)."""
    names = [name for name, _ in STAGES]
    upto = len(names) if before == "end" else names.index(before)
    return [importlib.import_module(f".{name}", __package__) for name in names[:upto]]


def add_stage_options(parser: argparse.ArgumentParser, before: str) -> None:
    """Add the options of every stage before ``before`` (e.g. ``"plan_cmd"``,
    or ``"end"`` for all of them) with their non-primary names."""
    for mod in _stage_modules(before):
        mod.add_options(parser, primary=False)
    if before in ("plan_cmd", "end"):
        parser.add_argument(
            "--move-to-origin", dest="job_move_to_origin", type=non_negative, default=None,
            metavar="MM", help="without nesting: move the drawing so its lower-left corner lies "
                               "MM mm from machine zero (default: cut where it lies)")
        gate = parser.add_argument_group("layout gate")
        gate.add_argument(
            "--layout-in", dest="job_layout_in", metavar="FILE.json", default=None,
            help="cut this layout (layout JSON as written by --layout-out, e.g. edited by hand) "
                 "instead of nesting; checked against --spacing/--margin")
        gate.add_argument(
            "--allow-invalid-layout", dest="job_allow_invalid_layout", action="store_true",
            help="experts: cut a layout with overlaps, spacing or margin violations, parts "
                 "outside the container or on a defect anyway (logged on stderr and in the report)")


def job_options(args: argparse.Namespace, before: str, machine: Any = None) -> JobOptions:
    """JobOptions of every stage before ``before`` (``"end"`` = all) from ``args``;
    a machine profile gives the planner its speeds and lift angle."""
    opts = JobOptions()
    for mod, (name, field) in zip(_stage_modules(before), STAGES):
        if name == "plan_cmd":
            setattr(opts, field, mod.options_from_args(args, machine))
        else:
            setattr(opts, field, mod.options_from_args(args))
    opts.move_to_origin = getattr(args, "job_move_to_origin", None)
    if getattr(args, "job_layout_in", None):
        from ..core.layout_json import read_layout_json
        opts.layout = read_layout_json(args.job_layout_in)
    opts.allow_invalid_layout = bool(getattr(args, "job_allow_invalid_layout", False))
    opts.sizes = getattr(args, "recognise_sizes", None)
    opts.quantities = getattr(args, "recognise_quantities", None)
    opts.log = _warn
    if machine is not None:
        from ..post.compensation import apply_to_job
        apply_to_job(opts, machine)
    return opts


def _warn(message: str) -> None:
    """Overrides of the layout gate, on stderr as they happen."""
    sys.stderr.write(f"warning: {message}\n")


def _number(text: str, ok: Callable[[float], bool], rule: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}")
    if not ok(v):
        raise argparse.ArgumentTypeError(f"must be {rule}: {text!r}")
    return v


def positive(text: str) -> float:
    """argparse type: a number > 0."""
    return _number(text, lambda v: v > 0, "> 0")


def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1."""
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}")
    if v < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1: {text!r}")
    return v


def non_negative(text: str) -> float:
    """argparse type: a number >= 0."""
    return _number(text, lambda v: v >= 0, ">= 0")


def progress_bar() -> Optional[Callable[[float, str], bool]]:
    """A terminal progress bar on stderr, or None when stderr is not a terminal
    (logs and pipes stay clean)."""
    if not sys.stderr.isatty():
        return None
    state = {"last": -1}

    def bar(frac: float, msg: str) -> bool:
        pct = int(frac * 100)
        if pct != state["last"]:
            state["last"] = pct
            sys.stderr.write(f"\r[{'#' * (pct // 4):<25}] {pct:3d}% {msg[:50]:<50}")
            if pct >= 100:
                sys.stderr.write("\n")
            sys.stderr.flush()
        return True
    return bar
