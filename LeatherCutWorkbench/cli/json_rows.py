"""JSON text of a large report: indented outline, one compact line per row.

``json.dump(..., indent=2)`` always runs the pure-Python encoder (CPython
uses its C encoder only without ``indent``): 10 s for the 150 MB report of
250,000 parts.  Here the top-level object and the containers it holds are
indented as ``indent=2`` would, and every element one level below them (one
part, one flag, one finding) is written on one line by the C encoder, with
``", "`` and ``": "`` separators.  The text parses to the same value as
``json.dumps(data, indent=2)``.
"""

from __future__ import annotations

import json
from typing import Any, Callable, Optional, TextIO


def write_rows(data: Any, out: TextIO, default: Optional[Callable[[Any], Any]] = None,
               depth: int = 2) -> None:
    """Write ``data`` to ``out``: containers nested less than ``depth`` levels
    deep are indented by two spaces per level, anything deeper is one line."""
    row = json.JSONEncoder(separators=(", ", ": "), default=default).encode
    _write(data, out, row, depth, "")


def _write(value: Any, out: TextIO, row: Callable[[Any], str], depth: int, pad: str) -> None:
    if depth <= 0 or not isinstance(value, (dict, list)) or not value:
        out.write(row(value))
        return
    inner = pad + "  "
    if isinstance(value, dict):
        out.write("{")
        sep = "\n"
        for key, item in value.items():
            out.write(f"{sep}{inner}{row(str(key))}: ")
            _write(item, out, row, depth - 1, inner)
            sep = ",\n"
        out.write(f"\n{pad}}}")
        return
    out.write("[")
    sep = "\n"
    for item in value:
        out.write(sep + inner)
        _write(item, out, row, depth - 1, inner)
        sep = ",\n"
    out.write(f"\n{pad}]")
