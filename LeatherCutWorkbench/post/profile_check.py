"""Hostile-value checks of a machine profile, run when it is loaded.

:func:`check_profile` completes ``profiles._validate`` (kinds, dialects, axes)
with what makes a profile dangerous rather than merely wrong; each refusal is
an :class:`InputError` naming the profile file and the field:

* every number finite (``NaN``/``Infinity`` are valid JSON for Python) and in
  the range of :data:`RANGES` (units in docs/MACHINES.md);
* ``z_up`` above ``z_down`` when a lift axis moves the knife;
* text fields (``name``, templates, ``header``, ``footer``) without control
  characters or line breaks, printable ASCII only: one template entry is one
  output line, it can never smuggle in a second one; ``name`` also without
  ``(``, ``)``, ``;`` (it is written into comments);
* G-code profiles: every expanded template, header and footer line passes the
  output safety check (:func:`.safety.check_lines`: words of the dialect, line
  length, line form, motion traced from machine zero inside the table);
  templates that run at every item (knife, vacuum, press, tool) contain no X/Y
  words at all.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Dict, List, Tuple

from ..core.errors import InputError, SafetyError

#: field -> (lowest, highest) allowed value (inclusive), units as in docs/MACHINES.md.
RANGES: Dict[str, Tuple[float, float]] = {
    "table_size": (1.0, 100_000.0),          # mm
    "origin": (-1.0e6, 1.0e6),                # mm
    "rapid_feed": (1e-3, 1.0e6), "cut_feed": (1e-3, 1.0e6),
    "plunge_feed": (1e-3, 1.0e6), "max_feed": (1e-3, 1.0e6),   # mm/min
    "acceleration": (1e-3, 1.0e6),            # mm/s^2
    "units_per_turn": (1e-3, 1.0e6),          # axis units per turn
    "heading_offset": (-360.0, 360.0),        # degrees
    "z_up": (-1000.0, 1000.0), "z_down": (-1000.0, 1000.0),   # mm
    "settle_dwell": (0.0, 600.0), "pierce_delay": (0.0, 600.0),
    "cooling_delay": (0.0, 600.0),            # s
    "chord_tol": (0.001, 1.0),                # mm
    "max_line_length": (16, 256),             # characters
    "baud": (300, 10_000_000),
    "rx_buffer_size": (16, 1 << 20),          # bytes
    "hpgl_units_per_mm": (1.0, 1000.0),
    "hpgl_pen": (0, 255),
    "hpgl_velocity": (0.01, 1000.0),          # cm/s
    "hpgl_force": (0.0, 10_000.0),            # g
    "overcut": (0.0, 100.0),                  # mm
}

#: Template fields emitted at every item: no X/Y motion allowed in them.
ITEM_TEMPLATES = ("knife_up", "knife_down", "vacuum_on", "vacuum_off", "press_on",
                  "press_off", "tool_on", "tool_off")


def _numbers(value: Any) -> List[float]:
    if isinstance(value, bool):
        return []
    if isinstance(value, (int, float)):
        return [value]
    if isinstance(value, (tuple, list)) and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        return list(value)
    return []


def _bad_text(text: str) -> str:
    """Description of the first forbidden character of ``text``, or ''."""
    for ch in text:
        if ch in "\r\n":
            return "a line break"
        if ord(ch) < 32 or ord(ch) == 127:
            return f"the control character {ch!r}"
        if ord(ch) > 126:
            return f"the non-ASCII character {ch!r}"
    return ""


def check_profile(p: Any, source: str) -> None:
    """Refuse hostile values of profile ``p`` (see the module docstring)."""
    def fail(field: str, msg: str) -> None:
        raise InputError(f"field {field!r}: {msg}", source=source)

    for f in dataclasses.fields(p):
        value = getattr(p, f.name)
        for v in _numbers(value):
            if not math.isfinite(v):
                fail(f.name, f"{v} is not a finite number")
            lo, hi = RANGES.get(f.name, (None, None))
            if lo is not None and not lo <= v <= hi:
                fail(f.name, f"{v:g} is outside the allowed range {lo:g} .. {hi:g}")
        if f.name == "source":
            continue
        lines = value if isinstance(value, list) else [value] if isinstance(value, str) else []
        for k, line in enumerate(lines):
            if not isinstance(line, str):
                continue
            bad = _bad_text(line)
            if bad:
                where = f" line {k + 1}" if isinstance(value, list) else ""
                fail(f.name, f"{where.strip() + ' ' if where else ''}contains {bad}: one entry is "
                             f"exactly one output line of printable ASCII")
    if any(ch in p.name for ch in "();"):
        fail("name", f"{p.name!r} contains '(', ')' or ';': the name is written into G-code "
                     f"comments, which these would end")
    if p.lift_axis and p.is_gcode and not p.z_up > p.z_down:
        fail("z_up", f"z_up {p.z_up:g} must lie above z_down {p.z_down:g} (mm on the lift axis "
                     f"{p.lift_axis})")
    if p.is_gcode:
        _check_gcode_lines(p, source)


def _check_gcode_lines(p: Any, source: str) -> None:
    from . import safety
    from .gcode import expand

    groups = [(name, getattr(p, name)) for name in ITEM_TEMPLATES] + \
        [("header", p.header), ("footer", p.footer)]
    for name, templates in groups:
        if not templates:
            continue
        lines = expand(templates, p)
        try:
            safety.check_lines(lines, p)       # words, line form, motion from machine zero
            if name in ITEM_TEMPLATES:
                for k, line in enumerate(lines, 1):
                    if any(letter in "XY" for letter, _ in safety.words(line)):
                        raise SafetyError("X/Y motion is not allowed in a template that runs at "
                                          "every item", source=f"line {k} {line!r}")
        except SafetyError as exc:
            raise InputError(f"field {name!r}: {exc}", source=source) from None
