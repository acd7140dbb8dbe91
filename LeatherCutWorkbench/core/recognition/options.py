"""Options of the recognition stage."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import FrozenSet

from ..errors import InputError


@dataclass
class RecogniseOptions:
    """How edges are joined into contours and which doubts are resolved how.

    * ``join_tol`` (mm): end points closer than this are the same point; edges
      shorter than this are dropped.
    * ``gap_tol`` (mm): an open outline whose missing pieces are all at most this
      long is flagged as under-recognised with bridging segments as the fix.
    * ``close_gaps``: apply those fixes (the bridges become cut segments).
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
    include: FrozenSet[str] = field(default_factory=frozenset)
    exclude: FrozenSet[str] = field(default_factory=frozenset)
    chord_tol: float = 0.01
    fuzzy: float = 1e-4
    unfold: bool = True

    def validate(self) -> None:
        """Raise :class:`InputError` for unusable values."""
        if not self.join_tol > 0:
            raise InputError(f"join tolerance must be > 0 mm, got {self.join_tol}", "--join-tol")
        if self.gap_tol < 0:
            raise InputError(f"gap tolerance must be >= 0 mm, got {self.gap_tol}", "--gap-tol")
        if not self.chord_tol > 0:
            raise InputError(f"chord tolerance must be > 0 mm, got {self.chord_tol}", "--chord-tol")
        both = set(self.include) & set(self.exclude)
        if both:
            raise InputError("ids both included and excluded: " + ", ".join(sorted(both)),
                             "--include/--exclude")
