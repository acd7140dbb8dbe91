"""The ``leathercut`` command line: one verb per pipeline stage plus ``run``.

Each verb lives in its own module (``<verb>_cmd.py``) exposing
``register(subparsers)``; the parser it creates sets ``func(args) -> Report``.
Stage modules also expose ``add_options(parser, primary)`` and
``options_from_args(args)`` so later verbs (which re-run earlier stages) take
the same options.  This module only wires verbs together, prints reports and
turns errors into one clear line on stderr with a non-zero exit code:

* 0  success
* 1  the job ran but found problems it was asked to fail on
* 2  bad input (missing file, not a DXF, bad option value): nothing usable
* 3  internal error (a bug): the traceback is shown only with ``--debug``
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional

from ..core.errors import LeatherCutError

#: Verb modules in pipeline order; each must define ``register(subparsers)``.
VERB_MODULES = ["inspect", "recognise", "nest", "plan", "post", "send", "run"]


@dataclass
class Report:
    """What a verb returns: a JSON-able dict and the human-readable text."""

    data: Dict[str, Any]
    text: str
    exit_code: int = 0
    extra: List[str] = field(default_factory=list)
    rows: bool = False    # JSON: one line per part / flag (cli/json_rows.py), for large reports
    #: the console script ends with ``os._exit`` once the report is printed (every
    #: file the verb wrote is closed): no interpreter clean-up of a large heap
    quick_exit: bool = False


def add_common_options(p: argparse.ArgumentParser) -> None:
    """Options every verb takes."""
    p.add_argument("--json", action="store_true",
                   help="print a machine-readable JSON report on stdout")
    p.add_argument("--seed", type=int, default=1,
                   help="random seed for every randomised search (default 1); same seed, same result")
    p.add_argument("--debug", action="store_true",
                   help="show Python tracebacks for internal errors")


def build_parser() -> argparse.ArgumentParser:
    """The full ``leathercut`` parser with every verb registered."""
    import importlib

    parser = argparse.ArgumentParser(
        prog="leathercut",
        description="Turn a DXF drawing into a cut job for a CNC leather or flame cutter.")
    from .. import __version__
    parser.add_argument("--version", action="version", version=f"leathercut {__version__}")
    sub = parser.add_subparsers(dest="verb", metavar="VERB")
    sub.required = True
    for name in VERB_MODULES:
        mod = importlib.import_module(f".{name}_cmd", __name__)
        mod.register(sub)
    return parser


def print_report(report: Report, as_json: bool) -> None:
    if as_json and report.rows:
        from .json_rows import write_rows
        write_rows(report.data, sys.stdout, default=_json_default)
        sys.stdout.write("\n")
    elif as_json:
        json.dump(report.data, sys.stdout, indent=2, sort_keys=False, default=_json_default)
        sys.stdout.write("\n")
    elif report.text:
        print(report.text)


def _json_default(o: Any) -> Any:
    if hasattr(o, "to_json"):
        return o.to_json()
    if isinstance(o, (set, tuple)):
        return list(o)
    try:
        import numpy as np
        if isinstance(o, np.generic):
            return o.item()
        if isinstance(o, np.ndarray):
            return o.tolist()
    except ImportError:  # pragma: no cover - numpy is a dependency
        pass
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def main(argv: Optional[List[str]] = None) -> int:
    """Console entry point.  Returns (and exits with) the exit code."""
    code = _main(argv, quick_exit=argv is None)
    if argv is None:
        sys.exit(code)
    return code


def _main(argv: Optional[List[str]], quick_exit: bool = False) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    func: Callable[[argparse.Namespace], Report] = args.func
    try:
        report = func(args)
    except LeatherCutError as exc:
        # one line, whatever the message quotes (file content, library errors)
        print(f"leathercut {args.verb}: error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"leathercut {args.verb}: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # a bug: one line unless --debug
        if getattr(args, "debug", False):
            raise
        print(f"leathercut {args.verb}: internal error: {type(exc).__name__}: "
              f"{' '.join(str(exc).split())} "
              f"(re-run with --debug for the traceback)", file=sys.stderr)
        return 3
    print_report(report, getattr(args, "json", False))
    for line in report.extra:
        print(line, file=sys.stderr)
    if quick_exit and report.quick_exit:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(report.exit_code)
    return report.exit_code
