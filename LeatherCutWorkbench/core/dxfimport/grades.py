"""Leather grades of parts as drawn in the DXF.

A part's grade is the lowest material quality it may be cut from: on a hide,
a part of grade g may only lie where the hide's grade is >= g (see
:mod:`LeatherCutWorkbench.core.nesting.containers`; 0 = anywhere).

Convention (case-insensitive), first match wins:

1. a TEXT / MTEXT inside the part's outer contour reading ``Grade: A``,
   ``GRADE=B``, ``Quality: 2`` or ``Qualität: 3`` (AAMA pattern files carry
   such a text in the piece block, next to ``Piece Name:``); when the text
   lies inside several parts (a part in the hole of another), the smallest
   one gets it;
2. the outer contour's layer named ``GRADE_<g>`` or ``QUALITY_<g>``.

``<g>`` is a whole number >= 0 (higher = better) or a letter: ``A`` = 4 (best),
``B`` = 3, ``C`` = 2, ``D`` = 1 -- the same scale as the hide layers
``ZONE_<g>`` / ``HIDE_<g>``, which accept the letters too.

Part regions (a shoe upper's visible zone needs grade A, the rest of the
part grade B): a closed contour *inside* a part drawn on a layer
``GRADE_<g>`` / ``QUALITY_<g>`` is not a hole but a region of that part with
grade g (``Part.grade_regions``): it is drawn, not cut, and on a hide it may
only lie on material of grade >= g (grade 0: anywhere, e.g. a window that is
cut away later); the rest of the part keeps the part's grade.  Recognition
first sees such a contour as a hole; :func:`assign_grades` turns it into a
region (one info finding each).
"""

from __future__ import annotations

import re
from typing import Iterable, List, Optional, Sequence

from ..errors import InputError
from ..model import Finding, Part, TextNote

#: grade letters, best first: A = 4 ... D = 1
LETTERS = {"A": 4, "B": 3, "C": 2, "D": 1}

_TEXT = re.compile(r"^\s*(?:grade|quality|qualit[aä]t)\s*[:=]\s*([A-Za-z]|\d+)\s*$", re.I)
_LAYER = re.compile(r"^(?:GRADE|QUALITY)_([A-Za-z]|\d+)$", re.I)


def parse_grade(value: object, source: str = "") -> int:
    """A grade from ``4``, ``"4"`` or ``"A"`` (see module doc); InputError
    naming ``source`` otherwise."""
    text = str(value).strip().upper()
    if text in LETTERS:
        return LETTERS[text]
    if text.isdigit():
        return int(text)
    raise InputError(f"bad grade {value!r}: use a letter A-D (A best) or a whole number >= 0",
                     source or None)


def grade_of_text(text: str) -> Optional[int]:
    """The grade a text announces, or None when it is no grade text."""
    m = _TEXT.match(text or "")
    if not m or (m.group(1).isalpha() and m.group(1).upper() not in LETTERS):
        return None
    return parse_grade(m.group(1))


def grade_of_texts(texts: Iterable[str]) -> Optional[int]:
    """The grade the first grade text among ``texts`` announces (a pattern
    piece's own texts), or None."""
    for t in texts:
        g = grade_of_text(t)
        if g is not None:
            return g
    return None


def grade_of_layer(layer: str) -> Optional[int]:
    """The grade a layer name announces (``GRADE_A``, ``QUALITY_2``), or None."""
    m = _LAYER.match(layer or "")
    if not m or (m.group(1).isalpha() and m.group(1).upper() not in LETTERS):
        return None
    return parse_grade(m.group(1))


def assign_grades(parts: Sequence[Part], texts: Sequence[TextNote]) -> List[Finding]:
    """Set ``Part.grade`` of the parts not graded yet (a pattern piece's part
    takes the grade of its piece's own texts, see :func:`grade_of_texts`)
    from grade texts and layers (see module doc); one info finding per part."""
    from shapely.geometry import Point, Polygon

    graded = [(t, g) for t, g in ((t, grade_of_text(t.text)) for t in texts) if g is not None]
    polys = []
    for p in parts if graded else ():     # outlines only when a grade text needs them
        try:
            poly = Polygon(p.outer.points(0.5))
        except (ValueError, TypeError):
            poly = None
        polys.append(poly if poly is not None and poly.is_valid else None)
    found: dict = {}
    for t, g in graded:
        pt = Point(t.position)
        inside = [i for i, poly in enumerate(polys) if poly is not None and poly.contains(pt)]
        if inside:
            found.setdefault(min(inside, key=lambda i: polys[i].area), g)
    findings: List[Finding] = list(_regions_from_holes(parts))
    for i, p in enumerate(parts):
        if p.grade:
            continue
        g = found.get(i)
        how = "text"
        if g is None:
            g, how = grade_of_layer(p.outer.layer), "layer"
        if g is None:
            continue
        p.grade = g
        findings.append(Finding("info", "part-grade", f"part {p.id}: grade {g} from its {how}"))
    return findings


def _regions_from_holes(parts: Sequence[Part]) -> List[Finding]:
    """Holes drawn on a grade layer become part regions (see module doc)."""
    findings: List[Finding] = []
    for p in parts:
        keep = []
        for h in p.holes:
            g = grade_of_layer(h.layer)
            if g is None:
                keep.append(h)
                continue
            p.grade_regions.append((g, h))
            p.lead_ins = [li for li in p.lead_ins if li.contour_id != h.id]
            findings.append(Finding("info", "part-region",
                                    f"part {p.id}: contour {h.id} on layer {h.layer} is a region "
                                    f"of grade {g} (drawn, not cut)"))
        p.holes = keep
    return findings
