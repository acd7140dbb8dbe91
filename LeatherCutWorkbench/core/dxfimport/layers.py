"""Which layers of a plain (non-pattern) drawing are cut.

Designers keep stitch lines, seam allowances, dimensions, text frames and
engraving on layers of their own; cutting them would ruin the part.  A layer is
cut unless its name matches one of the ``not_cut`` patterns (case-insensitive
shell patterns, default :data:`DEFAULT_NOT_CUT`); when ``cut`` patterns are
given, only matching layers are cut.  Edges on other layers keep role
``"internal"`` (drawn, not cut) and every such layer is reported as a finding,
so nothing disappears silently.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from fnmatch import fnmatchcase
from typing import Iterable, List, Optional, Sequence, Tuple

from ..model import Finding

#: Layer-name patterns that are drawn but not cut, unless the user says otherwise.
DEFAULT_NOT_CUT: Tuple[str, ...] = ("*stitch*", "*sew*", "*seam*", "*dim*", "*text*",
                                    "*annot*", "*engrav*", "*marking*", "defpoints")


def _matching(layer: str, patterns: Iterable[str]) -> Optional[str]:
    name = layer.strip().lower()
    for pat in patterns:
        if fnmatchcase(name, pat.strip().lower()):
            return pat
    return None


@dataclass(frozen=True)
class LayerSelection:
    """Cut / not-cut decision per layer name (see module docstring)."""

    cut: Optional[Tuple[str, ...]] = None
    not_cut: Tuple[str, ...] = DEFAULT_NOT_CUT

    def role_of(self, layer: str) -> str:
        """``"cut"`` or ``"internal"`` for an edge on ``layer``."""
        if self.cut is not None:
            return "cut" if _matching(layer, self.cut) else "internal"
        return "internal" if _matching(layer, self.not_cut) else "cut"

    def findings(self, edge_layers: Sequence[str], path: str) -> List[Finding]:
        """One warning per layer whose edges are not cut because of its name."""
        out: List[Finding] = []
        for layer, n in sorted(Counter(edge_layers).items()):
            if self.role_of(layer) == "cut":
                continue
            if self.cut is not None:
                why = f"it matches none of --cut-layers {','.join(self.cut)}"
            else:
                why = f"its name matches '{_matching(layer, self.not_cut)}' (--not-cut-layers)"
            out.append(Finding("warning", "layer-not-cut",
                               f"layer '{layer}': {n} edge(s) drawn but not cut because {why}; "
                               f"use --cut-layers / --not-cut-layers to change this",
                               f"{path} layer {layer}"))
        return out
