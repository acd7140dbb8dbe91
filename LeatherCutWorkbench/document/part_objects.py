"""One object per recognised part (*Recognition ▸ Parts*) carrying a person's
choice: ``Include`` and ``Quantity`` (see :mod:`..core.part_choice`).

The objects are made with the recognition; a choice survives re-recognition
when the same part (id and drawing name) comes back.  :func:`apply_to` puts
the choices into the recognition every later stage uses.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

import FreeCAD

from ..core import model
from ..core.part_choice import (PartChoice, apply_choices, block_names, default_choices, display_name,
                                sample_size, sizes)
from . import objects
from .objects import translate

#: (part id, drawing name) -> choice; what survives re-recognition
Kept = Dict[Tuple[str, str], PartChoice]


def part_objects(job) -> List[Any]:
    """The job's part objects in recognition order (empty before recognition)."""
    rec = objects.stage_object(job, "Recognition")
    return [o for o in objects.walk(rec) if objects.role(o) == "Part"] if rec is not None else []


def current_choices(job) -> Kept:
    return {(o.PartId, o.PartName): PartChoice(bool(o.Include), int(o.Quantity))
            for o in part_objects(job)}


def choices_of(job) -> Dict[str, PartChoice]:
    return {o.PartId: PartChoice(bool(o.Include), int(o.Quantity)) for o in part_objects(job)}


def apply_to(job, rec: model.Recognition) -> model.Recognition:
    """``rec`` with the job's part choices applied (unchanged without part objects)."""
    choices = choices_of(job)
    return apply_choices(rec, choices) if choices else rec


def build(grp, rec: model.Recognition, kept: Kept, shape_of: Callable[[model.Part], Any],
          drawing: Optional[model.Drawing] = None) -> Optional[Any]:
    """The *Parts* group in the recognition group ``grp``: one object per part
    that recognition did not exclude (excluded regions are the flags' business).
    ``drawing`` (the imported drawing) gives the graded set's sample size and the
    block names of parts drawn in blocks."""
    parts = [p for p in rec.parts if not p.excluded]
    if not parts:
        return None
    doc = grp.Document
    pgrp = doc.addObject("App::DocumentObjectGroup", "Parts")
    pgrp.Label = translate("LeatherCut", "Parts")
    grp.addObject(pgrp)
    sample = sample_size(drawing) if drawing is not None and len(sizes(parts)) > 1 else ""
    blocks = block_names(drawing, parts) if drawing is not None else {}
    defaults = default_choices(parts, sample)
    for p in parts:
        choice = kept.get((p.id, p.name), defaults[p.id])
        obj = doc.addObject("Part::FeaturePython", "Part")
        objects.PartProxy(obj)
        obj.PartId, obj.PartName, obj.Size = p.id, p.name, p.size
        obj.Area = float(p.net_area)
        obj.Shape = shape_of(p)
        obj.Include = choice.include
        obj.Quantity = max(1, choice.quantity)
        obj.Label = display_name(p, blocks.get(p.id, ""))
        pgrp.addObject(obj)
        if FreeCAD.GuiUp:
            from . import style, viewproviders
            viewproviders.PartViewProvider(obj.ViewObject)
            style.style_part(obj)
    return pgrp


def set_included(objs, include: bool) -> None:
    """Include or exclude several parts (call inside a transaction)."""
    for o in objs:
        if bool(o.Include) != include:
            o.Include = include


def by_size(job) -> Dict[str, List[Any]]:
    """Part objects grouped by pattern size, in drawing order ("" = no size)."""
    out: Dict[str, List[Any]] = {}
    for o in part_objects(job):
        out.setdefault(o.Size, []).append(o)
    return out

