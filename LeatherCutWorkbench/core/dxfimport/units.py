"""Drawing units: names, ``$INSUNITS`` codes and the factor to millimetres.

Policy (see docs/CLI.md ``inspect``): an explicit ``--units`` wins; otherwise the
header ``$INSUNITS``; otherwise the AAMA/ASTM ``Units:`` text; otherwise mm is
assumed and a warning says so.  :func:`plausibility_warning` flags unit choices
that make the drawing implausibly large or small for a cutting table.
"""

from __future__ import annotations

from typing import Dict, Optional, Tuple

#: Millimetres per unit, by canonical unit name.
MM_PER_UNIT: Dict[str, float] = {
    "mm": 1.0,
    "cm": 10.0,
    "dm": 100.0,
    "m": 1000.0,
    "km": 1.0e6,
    "inch": 25.4,
    "foot": 304.8,
    "yard": 914.4,
    "mile": 1609344.0,
    "micron": 1.0e-3,
    "microinch": 25.4e-6,
    "mil": 25.4e-3,
    "nm": 1.0e-6,
    "um": 1.0e-3,
    "decameter": 1.0e4,
    "hectometer": 1.0e5,
}

#: Spellings a person may type for ``--units`` -> canonical name.
ALIASES: Dict[str, str] = {
    "mm": "mm", "millimeter": "mm", "millimetre": "mm", "millimeters": "mm", "millimetres": "mm",
    "cm": "cm", "centimeter": "cm", "centimetre": "cm", "centimeters": "cm", "centimetres": "cm",
    "dm": "dm", "decimeter": "dm", "decimetre": "dm",
    "m": "m", "meter": "m", "metre": "m", "meters": "m", "metres": "m",
    "km": "km", "kilometer": "km", "kilometre": "km",
    "in": "inch", "inch": "inch", "inches": "inch", '"': "inch",
    "ft": "foot", "foot": "foot", "feet": "foot",
    "yd": "yard", "yard": "yard", "yards": "yard",
    "mi": "mile", "mile": "mile", "miles": "mile",
    "micron": "micron", "microns": "micron", "um": "micron", "µm": "micron",
    "microinch": "microinch", "mil": "mil", "thou": "mil",
}

#: ``$INSUNITS`` code -> canonical unit name (0 = unitless is not listed).
INSUNITS: Dict[int, str] = {
    1: "inch", 2: "foot", 3: "mile", 4: "mm", 5: "cm", 6: "m", 7: "km",
    8: "microinch", 9: "mil", 10: "yard", 13: "micron", 14: "dm",
    15: "decameter", 16: "hectometer",
}

#: A drawing whose larger side in mm falls outside this range gets a warning.
PLAUSIBLE_SIZE_MM = (1.0, 20_000.0)


def parse_units(name: str) -> str:
    """Canonical unit name for a user-typed ``name``; ValueError if unknown."""
    key = name.strip().lower()
    if key not in ALIASES:
        known = ", ".join(sorted({v for v in ALIASES.values()}))
        raise ValueError(f"unknown unit {name!r} (known: {known})")
    return ALIASES[key]


def header_units(code: Optional[int]) -> Optional[str]:
    """Unit named by a ``$INSUNITS`` value, None for absent / 0 (unitless) / unknown."""
    if code is None:
        return None
    try:
        return INSUNITS.get(int(code))
    except (TypeError, ValueError):
        return None


def aama_units(text_value: str) -> Optional[str]:
    """Unit from the value of an AAMA ``Units:`` text: ENGLISH -> inch, METRIC -> mm.

    METRIC is ambiguous in the wild (mm and cm both occur); the caller checks
    plausibility and may switch to cm."""
    v = text_value.strip().upper()
    if v.startswith("ENG") or v.startswith("INCH") or v.startswith("IMPERIAL"):
        return "inch"
    if v.startswith("MET") or v == "MM":
        return "mm"
    if v == "CM":
        return "cm"
    return None


def plausibility_warning(size_units: Tuple[float, float], unit: str) -> Optional[str]:
    """A warning text when a drawing of ``size_units`` (width, height in drawing
    units) read as ``unit`` is implausible for a cutting table, else None."""
    big = max(size_units)
    if big <= 0.0:
        return None
    size_mm = big * MM_PER_UNIT[unit]
    lo, hi = PLAUSIBLE_SIZE_MM
    if lo <= size_mm <= hi:
        return None
    guesses = [u for u in ("mm", "cm", "inch", "m")
               if u != unit and lo * 10 <= big * MM_PER_UNIT[u] <= hi / 2]
    hint = f"; if it is drawn in {' or '.join(guesses)}, use --units {guesses[0]}" if guesses else ""
    return (f"read as {unit}, the drawing is {size_mm:.6g} mm across, which is implausible "
            f"for a cutting table{hint}")
