"""Which recognised parts go to the cut, and how many of each.

A person chooses per part (include / exclude, quantity) and, in a graded
pattern set (AAMA / ASTM files hold every size of every piece, often stacked
on top of each other), per size.  By default a graded set does **not** go to
the cut whole: only the sample size the file names (``Sample Size:``), else
the first size, is included; the person picks the others.  Nesting places
``quantity`` copies of each included part; cutting a drawing where it lies
cuts each included part once.

Part names come from the drawing: the AAMA piece name and size, the block
name, else the layer (:func:`display_name`).
"""

from __future__ import annotations

from copy import deepcopy
from dataclasses import dataclass
from typing import Dict, Iterable, List, Sequence

from .model import Drawing, Part, Recognition


@dataclass
class PartChoice:
    """A person's choice for one part: cut it or not, and how many copies (>= 1)."""

    include: bool = True
    quantity: int = 1


def display_name(part: Part) -> str:
    """What a person calls the part: its drawing name (AAMA piece and size, block
    name) or its layer, with the part id: ``"BACK size 42 (P3)"``, ``"layer CUT (P7)"``."""
    if part.name:
        return f"{part.name} ({part.id})"
    if part.outer.layer:
        return f"layer {part.outer.layer} ({part.id})"
    return part.id


def sizes(parts: Iterable[Part]) -> List[str]:
    """The distinct pattern sizes of ``parts`` in drawing order ("" not counted)."""
    out: List[str] = []
    for p in parts:
        if p.size and p.size not in out:
            out.append(p.size)
    return out


def sample_size(drawing: Drawing) -> str:
    """The ``Sample Size:`` an AAMA / ASTM file states in a model-space text, or ""."""
    from .dxfimport.aama import style_value
    texts = [t.text for t in drawing.texts if not t.src.piece]
    return (style_value(texts, "sample size") or "").strip()


def default_choices(parts: Sequence[Part], sample: str = "") -> Dict[str, PartChoice]:
    """Every part with its drawn quantity, included -- except in a graded set
    (more than one size): there only the parts of ``sample`` (when it is one of
    the sizes) or else of the first size.  (Whether recognition or a flag
    decision excluded a part is not a person's part choice: that stays.)"""
    graded = sizes(parts)
    keep = (sample if sample in graded else graded[0]) if len(graded) > 1 else None
    return {p.id: PartChoice(include=keep is None or p.size == keep,
                             quantity=max(1, int(p.quantity)))
            for p in parts}


def apply_choices(rec: Recognition, choices: Dict[str, PartChoice]) -> Recognition:
    """A copy of ``rec`` with the choices applied: a part not included becomes
    excluded (a part excluded by a flag decision stays excluded); the quantity
    is the chosen one.  Parts without a choice are left as they are."""
    out = deepcopy(rec)
    for p in out.parts:
        c = choices.get(p.id)
        if c is None:
            continue
        if not c.include:
            p.excluded = True
        p.quantity = max(1, int(c.quantity))
    return out
