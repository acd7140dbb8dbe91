"""The gate before the machine: a layout is checked before it is planned or cut.

One function decides for every path to a machine file (the CLI's ``plan``,
``post``, ``run`` and ``send``, the workbench's *Plan path*, *Post-process*,
*Run job* and *Send to cutter*): :func:`gate_layout` runs the independent
layout checker (:func:`core.nesting.checker.check_layout`, shapely) and refuses
a layout in which a placed part

* overlaps another placed part (parts in a hole of another part are fine),
* is closer to another part than the set spacing, or to the container edge or a
  defect than the set margin,
* lies (partly) outside its container, or covers a defect or material below its
  grade,
* is unknown, placed twice or both placed and unplaced.

Rotations and mirroring are not restricted here: a person may turn a part to
any angle by hand (the part's own rotation limits bind automatic nesting only).

Each finding names the parts (``P2#0 overlaps P1#0 by 41 410 mm²``).  An
expert may cut such a layout anyway with an explicit override (CLI
``--allow-invalid-layout``, job property ``AllowInvalidLayout``): the findings
then come back as ``layout-override`` warnings that the caller logs (stderr,
``report.json``, FreeCAD's report view).  Lengths mm, areas mm².
"""

from __future__ import annotations

import re
from typing import List, Optional, Sequence

from .errors import InputError
from .model import Finding, Layout, Part
from .readable import readable_area

_AREA = re.compile(r"(-?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?) ?mm2")
#: at most this many findings are quoted in the refusal (all are in the findings)
QUOTED = 5


def layout_findings(parts: Sequence[Part], layout: Layout, spacing: float = 0.0,
                    margin: float = 0.0, tol: float = 1e-3,
                    chord_tol: float = 0.05) -> List[str]:
    """Everything that makes ``layout`` unsafe to cut, one line per problem naming
    the parts (``<part>#<copy>``); empty when the layout may be cut.
    ``spacing`` / ``margin`` are the nesting options the layout must keep (mm);
    ``tol`` the length tolerance of the checker (mm)."""
    from .nesting.checker import check_layout

    problems = check_layout(parts, layout, spacing=spacing, margin=margin,
                            tol=max(tol, 1e-6), chord_tol=chord_tol,
                            rotations_override=None, mirror_override=True,
                            free_rotation=True)
    return [_AREA.sub(lambda m: readable_area(float(m.group(1))), p) for p in problems]


def gate_layout(parts: Sequence[Part], layout: Layout, spacing: float = 0.0,
                margin: float = 0.0, tol: float = 1e-3, chord_tol: float = 0.05,
                allow_invalid: bool = False, source: Optional[str] = None) -> List[Finding]:
    """Refuse an unsafe layout (:class:`InputError` quoting the first problems),
    or, with ``allow_invalid``, return every problem as a ``layout-override``
    warning for the caller to log.  An empty list: the layout is safe."""
    problems = layout_findings(parts, layout, spacing, margin, tol, chord_tol)
    if not problems:
        return []
    if not allow_invalid:
        more = len(problems) - QUOTED
        raise InputError(
            "the layout is not safe to cut: " + "; ".join(problems[:QUOTED])
            + (f"; and {more} more" if more > 0 else "")
            + ". Move the parts apart or nest again; to cut it anyway (experts only, "
              "logged) use --allow-invalid-layout", source=source)
    return [Finding("warning", "layout-override", f"cut despite the layout gate: {p}", source)
            for p in problems]
