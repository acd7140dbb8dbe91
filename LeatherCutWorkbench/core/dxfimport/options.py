"""Options of the import stage."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Tuple

from ..errors import InputError
from .extents import HUGE_COORDINATE_MM
from .layers import DEFAULT_NOT_CUT, LayerSelection
from .units import parse_units

PATTERN_MODES = ("auto", "aama", "off")


@dataclass
class ImportOptions:
    """How :func:`read_drawing` reads a DXF.

    * ``units``: drawing unit (mm, cm, m, inch, foot, ... see ``units.ALIASES``).
      When given it always wins (the file's own statement is reported in a
      finding); when None the header ``$INSUNITS``, then an AAMA ``Units:`` text
      is used, else mm is assumed with a warning.
    * ``pattern_mode``: ``"auto"`` detects AAMA / ASTM D6673 pattern files,
      ``"aama"`` forces that reading, ``"off"`` reads every file as a plain drawing.
    * ``cleanup``: remove zero-length edges, duplicates, collinear overlaps and
      split T-junctions (see :mod:`.cleanup`).
    * ``tolerance``: clean-up tolerance in mm (duplicate grid, collinearity,
      T-junction distance, zero length).
    * ``cut_layers`` / ``not_cut_layers``: layer-name patterns (case-insensitive,
      shell style) deciding which layers of a plain drawing are cut; see
      :mod:`.layers`.  Pattern files use the AAMA layer numbers instead.
    * ``local_origin``: move drawings whose coordinates exceed
      ``huge_coordinate_mm`` to a local origin (``Drawing.offset``).
    """

    units: Optional[str] = None
    pattern_mode: str = "auto"
    cleanup: bool = True
    tolerance: float = 0.01
    local_origin: bool = True
    huge_coordinate_mm: float = HUGE_COORDINATE_MM
    cut_layers: Optional[Tuple[str, ...]] = None
    not_cut_layers: Tuple[str, ...] = DEFAULT_NOT_CUT

    def layer_selection(self) -> LayerSelection:
        """The cut / not-cut rule for plain drawings."""
        return LayerSelection(self.cut_layers, self.not_cut_layers)

    def validated(self) -> "ImportOptions":
        """Self, after checking values; InputError names the bad option."""
        if self.units is not None:
            try:
                parse_units(self.units)
            except ValueError as exc:
                raise InputError(str(exc), "--units") from exc
        if self.pattern_mode not in PATTERN_MODES:
            raise InputError(f"pattern mode must be one of {', '.join(PATTERN_MODES)}, "
                             f"not {self.pattern_mode!r}", "--pattern-mode")
        if not self.tolerance > 0.0:
            raise InputError(f"tolerance must be > 0 mm, not {self.tolerance}", "--cleanup-tol")
        return self
