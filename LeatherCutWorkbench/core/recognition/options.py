"""Options of the recognition stage."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import FrozenSet, Optional

from ..errors import InputError


@dataclass
class RecogniseOptions:
    """How edges are joined into contours and which doubts are resolved how.

    * ``join_tol`` (mm): end points closer than this are the same point; edges
      shorter than this are dropped.
    * ``gap_tol`` (mm): an open outline whose missing pieces are all at most this
      long is flagged as under-recognised with bridging segments as the fix.
    * ``close_gaps``: apply those fixes (the bridges become cut segments).
    * ``accept_fixes``: ids of under-recognition flags (``F4``, as reported by a run
      with the same drawing and options) whose fix is applied -- bridges for
      ``close`` and ``join`` flags, removal of the stub for ``trim`` flags; the
      flags come back accepted, the others stay proposals.  Flag ids do not
      change when fixes are applied.
    * ``reject_fixes``: ids of under-recognition flags whose fix a person
      rejected: nothing is applied (not even with ``close_gaps``) and the flag
      comes back with ``accepted`` False.
    * ``include`` / ``exclude``: contour ids (``C3``) or part ids (``P2``) a person
      decided about; they override the automatic over-recognition flags.
    * ``chord_tol`` (mm): ellipses and splines are flattened into polylines whose
      chords deviate at most this much from the curve.
    * ``fuzzy`` (mm): fuzzy value of FreeCAD's ``generalFuse`` when splitting
      common-edge clusters into cells.
    * ``unfold``: pattern pieces drawn as a half against a fold (mirror) line
      are unfolded into the whole piece to cut.
    """

    join_tol: float = 0.01
    gap_tol: float = 0.5
    close_gaps: bool = False
    accept_fixes: Optional[FrozenSet[str]] = None
    reject_fixes: Optional[FrozenSet[str]] = None
    include: FrozenSet[str] = field(default_factory=frozenset)
    exclude: FrozenSet[str] = field(default_factory=frozenset)
    chord_tol: float = 0.01
    fuzzy: float = 1e-4
    unfold: bool = True

    def validate(self) -> None:
        """Raise :class:`InputError` for unusable values."""
        if not 0 < self.join_tol < math.inf:
            raise InputError(f"join tolerance must be > 0 mm, got {self.join_tol}", "--join-tol")
        if not 0 <= self.gap_tol < math.inf:
            raise InputError(f"gap tolerance must be >= 0 mm, got {self.gap_tol}", "--gap-tol")
        if not 0.001 <= self.chord_tol <= 10.0:     # finer flattening never ends on big curves
            raise InputError(f"chord tolerance must lie in 0.001 .. 10 mm, got {self.chord_tol}",
                             "--chord-tol")
        both = set(self.accept_fixes or ()) & set(self.reject_fixes or ())
        if both:
            raise InputError("fixes both accepted and rejected: " + ", ".join(sorted(both)),
                             "--accept-fix")
        both = set(self.include) & set(self.exclude)
        if both:
            raise InputError("ids both included and excluded: " + ", ".join(sorted(both)),
                             "--include/--exclude")

    def fix_decision(self, flag_id: str) -> Optional[bool]:
        """Whether the fix of under-recognition flag ``flag_id`` is applied (True),
        rejected (False) or left a proposal (None)."""
        if self.reject_fixes and flag_id in self.reject_fixes:
            return False
        if self.close_gaps or (self.accept_fixes and flag_id in self.accept_fixes):
            return True
        return None
