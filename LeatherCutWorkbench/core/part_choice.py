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

from copy import copy
from dataclasses import dataclass, replace
from typing import Dict, Iterable, List, Optional, Sequence

from .gc_pause import collector_paused
from .model import Drawing, Part, Recognition


@dataclass
class PartChoice:
    """A person's choice for one part: cut it or not, and how many copies (>= 1)."""

    include: bool = True
    quantity: int = 1


def display_name(part: Part, block: str = "") -> str:
    """What a person calls the part: its drawing name (AAMA piece and size), the
    block it was drawn in, or its layer, with the part id: ``"BACK size 42 (P3)"``,
    ``"block FRONT (P5)"``, ``"layer CUT (P7)"``."""
    if part.name:
        return f"{part.name} ({part.id})"
    if block:
        return f"block {block} ({part.id})"
    if part.outer.layer:
        return f"layer {part.outer.layer} ({part.id})"
    return part.id


def block_names(drawing: Drawing, parts: Sequence[Part], tol: float = 0.05) -> Dict[str, str]:
    """Part id -> name of the block its outline was drawn in, for parts without
    a drawing name whose outline edges come from a block INSERT (the block that
    holds the geometry: the last of a nested ``A/B/C`` path).  An edge belongs
    to a part when its start point lies within ``tol`` mm of the part's outline;
    the block most of those edges come from wins."""
    from collections import Counter
    from shapely.geometry import LineString, Point as SPoint
    from shapely.strtree import STRtree

    todo = [p for p in parts if not p.name]
    starts = [(_edge_start(e), e.src.block.split("/")[-1]) for e in drawing.edges
              if e.src.block and e.src.role == "cut"]
    starts = [(pt, b) for pt, b in starts if pt is not None]
    if not todo or not starts:
        return {}
    rings = [LineString(list(p.outer.points()) + [p.outer.points()[0]]) for p in todo]
    tree = STRtree(rings)
    votes: Dict[int, Counter] = {}
    for pt, block in starts:
        q = SPoint(pt)
        for k in tree.query(q.buffer(tol)):
            k = int(k)
            if rings[k].distance(q) <= tol:
                votes.setdefault(k, Counter())[block] += 1
    return {todo[k].id: c.most_common(1)[0][0] for k, c in votes.items()}


def _edge_start(edge):
    """A point on a drawing edge (mm): its start, or None for an unknown kind."""
    import math
    if hasattr(edge, "start"):
        return tuple(edge.start)
    if hasattr(edge, "radius"):
        a = math.radians(edge.start_angle)
        return (edge.center[0] + edge.radius * math.cos(a), edge.center[1] + edge.radius * math.sin(a))
    poles = getattr(edge, "poles", None)
    return tuple(poles[0]) if poles else None


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


def default_choices(parts: Sequence[Part], sample: str = "",
                    wanted: Optional[Sequence[str]] = None) -> Dict[str, PartChoice]:
    """Every part with its drawn quantity, included -- except in a graded set
    (more than one size): there only the parts of ``sample`` (when it is one of
    the sizes) or else of the first size.  ``wanted`` names the sizes to cut
    instead (``["all"]``: every size; a size the set lacks raises InputError).
    (Whether recognition or a flag decision excluded a part is not a person's
    part choice: that stays.)"""
    graded = sizes(parts)
    if wanted is not None and [w.lower() for w in wanted] != ["all"]:
        missing = [w for w in wanted if w not in graded]
        if missing:
            from .errors import InputError
            raise InputError(f"size {', '.join(missing)} is not in the drawing "
                             f"(sizes: {', '.join(graded) or 'none'})")
        keep = set(wanted)
    elif wanted is not None or len(graded) <= 1:
        keep = None
    else:
        keep = {sample if sample in graded else graded[0]}
    with collector_paused():
        return {p.id: PartChoice(include=keep is None or p.size in keep,
                                 quantity=max(1, int(p.quantity)))
                for p in parts}


def apply_choices(rec: Recognition, choices: Dict[str, PartChoice]) -> Recognition:
    """A copy of ``rec`` with the choices applied: a part not included becomes
    excluded (a part excluded by a flag decision stays excluded); the quantity
    is the chosen one.  Parts without a choice are left as they are.

    The copy is of the recognition, its lists and its parts (so setting a
    part's fields never changes ``rec``); contours, segments, marks and flags
    are shared, as no later stage changes them in place (a deep copy took as
    long as recognition itself on 250k parts)."""
    with collector_paused():
        out = replace(rec, parts=[_part_copy(p) for p in rec.parts],
                      open_chains=list(rec.open_chains), flags=list(rec.flags),
                      findings=list(rec.findings))
    for p in out.parts:
        c = choices.get(p.id)
        if c is None:
            continue
        if not c.include:
            p.excluded = True
        p.quantity = max(1, int(c.quantity))
    return out


def _part_copy(p: Part) -> Part:
    """``p`` with its own lists (the geometry in them is shared); ``copy.copy``
    rather than ``dataclasses.replace``, which re-runs ``__init__`` (5x slower)."""
    q = copy(p)
    q.holes, q.lead_ins, q.marks, q.lines = (list(p.holes), list(p.lead_ins), list(p.marks),
                                             list(p.lines))
    if p.rotations is not None:
        q.rotations = list(p.rotations)
    return q
