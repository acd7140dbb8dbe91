"""AAMA-DXF / ASTM D6673 pattern files: detection, layer roles, piece texts.

Convention (see /work/shared/notes/dxf.md section 5 and ASTM D6673): model space
holds one INSERT per piece (one block per piece and size) plus style TEXTs such
as ``Units: METRIC`` and ``TOLERANCE: .152``; inside a block the layer number
says what a curve is.  Layer names are compared after stripping spaces.
"""

from __future__ import annotations

import re
from typing import Dict, Iterable, Optional, Tuple

#: AAMA layer number -> EdgeSource.role.  Layers not listed are "internal"
#: (drawn, never cut).
LAYER_ROLES: Dict[int, str] = {
    1: "cut",        # piece boundary
    11: "cut",       # internal cut-outs
    4: "mark",       # notches
    80: "mark", 81: "mark", 82: "mark", 83: "mark",   # T, castle, check, U notch shapes
    13: "mark",      # drill holes
    7: "grain",      # grain line
    6: "mirror",     # mirror / fold line
    8: "internal",   # internal lines
    14: "internal",  # sew line
    9: "internal", 10: "internal",   # stripe / plaid reference
    2: "ignore", 3: "ignore",        # grade-rule turn / curve points
    5: "ignore",     # grade reference line
    15: "annotation",
    84: "ignore", 85: "ignore", 86: "ignore", 87: "ignore",   # validation copies
}

#: Mark kind of POINTs by AAMA layer.
MARK_KINDS: Dict[int, str] = {4: "notch", 80: "notch", 81: "notch", 82: "notch", 83: "notch",
                              13: "drill", 2: "turn", 3: "curve"}

_STYLE_KEYS = re.compile(r"^\s*(units|style name|sample size|tolerance|grading rule table)\s*:", re.I)
_PIECE_KEYS = re.compile(r"^\s*(piece name|size|quantity|category|annotation|material|"
                         r"rule table|style name)\s*:\s*(.*?)\s*$", re.I)


def layer_number(layer: str) -> Optional[int]:
    """AAMA layer number of a layer name (``' 1'`` -> 1), None if not numeric."""
    s = layer.strip()
    return int(s) if s.isdigit() else None


def layer_role(layer: str) -> str:
    """EdgeSource.role of an edge on ``layer`` in an AAMA file."""
    n = layer_number(layer)
    if n is None:
        return "internal"
    return LAYER_ROLES.get(n, "internal")


def mark_kind(layer: str) -> str:
    n = layer_number(layer)
    return MARK_KINDS.get(n, "point") if n is not None else "point"


def looks_like_aama(modelspace_texts: Iterable[str], block_texts: Iterable[str]) -> bool:
    """True when the style TEXTs in model space or a ``Piece Name:`` inside a
    block say this is an AAMA / ASTM pattern file."""
    if sum(1 for t in modelspace_texts if _STYLE_KEYS.match(t)) >= 2:
        return True
    return any(re.match(r"^\s*piece name\s*:", t, re.I) for t in block_texts)


def key_value(text: str) -> Optional[Tuple[str, str]]:
    """``('piece name', 'FR')`` for ``'Piece Name: FR'``; None for other texts."""
    m = _PIECE_KEYS.match(text)
    if not m:
        return None
    return m.group(1).lower(), m.group(2)


def style_value(texts: Iterable[str], key: str) -> Optional[str]:
    """Value of a model-space style text ``key: value`` (case-insensitive)."""
    rx = re.compile(r"^\s*" + re.escape(key) + r"\s*:\s*(.*?)\s*$", re.I)
    for t in texts:
        m = rx.match(t)
        if m:
            return m.group(1)
    return None


def parse_number(value: Optional[str]) -> Optional[float]:
    """``'.152'`` -> 0.152; None when absent or not a number."""
    if value is None:
        return None
    try:
        return float(value.strip().replace(",", "."))
    except ValueError:
        return None


def parse_quantity(value: Optional[str]) -> int:
    """Piece quantity from a ``QUANTITY:`` text value; 1 when absent or unreadable."""
    if not value:
        return 1
    m = re.search(r"\d+", value)
    return max(int(m.group()), 1) if m else 1
