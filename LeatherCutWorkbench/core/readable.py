"""Numbers as people read them in messages (the CLI, the gate, the workbench)."""

from __future__ import annotations


def readable_number(value: float) -> str:
    """``41410.3`` -> ``41 410``; below 100 three significant digits (``2.41``)."""
    if abs(value) >= 100.0:
        return f"{value:,.0f}".replace(",", " ")
    return f"{value:.3g}"


def readable_area(value: float) -> str:
    """An area in mm² as people write it: ``41 410 mm²``, ``2.41 mm²``."""
    return f"{readable_number(value)} mm²"
