"""core.part_choice: which parts go to the cut and how many (plain pytest, no FreeCAD)."""
import os

import pytest

from conftest import SAMPLES_DIR
from LeatherCutWorkbench.core.errors import InputError

from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.model import Contour, Part, Recognition
from LeatherCutWorkbench.core.part_choice import (PartChoice, apply_choices, block_names, default_choices,
                                                  display_name, sizes)


def _square(pid, size="", name="", layer="CUT", x=0.0):
    pts = [(x, 0.0), (x + 10, 0.0), (x + 10, 10.0), (x, 10.0)]
    segs = [LineSeg(a, b) for a, b in zip(pts, pts[1:] + pts[:1])]
    return Part(pid, Contour("C" + pid[1:], segs, layer), name=name, size=size)


def _graded(n_pieces=10, n_sizes=15):
    sz = [str(34 + 2 * k) for k in range(n_sizes)]
    return [_square(f"P{i * n_pieces + j + 1}", s, f"PIECE{j} size {s}")
            for i, s in enumerate(sz) for j in range(n_pieces)]


def test_a_graded_set_cuts_one_size_by_default():
    parts = _graded()
    assert len(sizes(parts)) == 15
    chosen = default_choices(parts)
    assert sum(c.include for c in chosen.values()) == 10
    assert {p.size for p in parts if chosen[p.id].include} == {"34"}       # the first size
    chosen = default_choices(parts, sample="50")
    assert {p.size for p in parts if chosen[p.id].include} == {"50"}       # the file's sample size
    chosen = default_choices(parts, sample="99")                          # not a size of the set
    assert {p.size for p in parts if chosen[p.id].include} == {"34"}


def test_a_plain_drawing_cuts_every_part_with_its_quantity():
    parts = [_square("P1"), _square("P2", x=20)]
    parts[1].quantity = 3
    chosen = default_choices(parts)
    assert chosen == {"P1": PartChoice(True, 1), "P2": PartChoice(True, 3)}


def test_choices_exclude_and_multiply_but_never_include_a_flag_exclusion():
    parts = [_square("P1"), _square("P2", x=20), _square("P3", x=40)]
    parts[2].excluded = True                      # e.g. an over-recognised region
    rec = Recognition(parts=parts)
    out = apply_choices(rec, {"P1": PartChoice(False, 1), "P2": PartChoice(True, 4),
                              "P3": PartChoice(True, 2)})
    assert [p.id for p in out.active_parts()] == ["P2"]
    assert out.parts[1].quantity == 4
    assert [p.excluded for p in rec.parts] == [False, False, True]    # input untouched


def test_display_names_come_from_the_drawing():
    assert display_name(_square("P3", "42", "BACK size 42")) == "BACK size 42 (P3)"
    assert display_name(_square("P7", layer="LEATHER")) == "layer LEATHER (P7)"
    assert display_name(_square("P8", layer="")) == "P8"


def test_block_names_from_the_edges_on_the_outline():
    from LeatherCutWorkbench.core.model import Drawing, EdgeSource, LineEdge
    parts = [_square("P1"), _square("P2", x=20), _square("P3", name="BACK size 42", x=40)]
    edges = [LineEdge((0.0, 0.0), (10.0, 0.0), EdgeSource(block="SHEET/FRONT")),
             LineEdge((10.0, 0.0), (10.0, 10.0), EdgeSource(block="SHEET/FRONT")),
             LineEdge((20.0, 0.0), (30.0, 0.0), EdgeSource()),           # not from a block
             LineEdge((40.0, 0.0), (50.0, 0.0), EdgeSource(block="BACK"))]
    names = block_names(Drawing("x.dxf", edges=edges), parts)
    assert names == {"P1": "FRONT"}        # P2 drawn in model space, P3 has its AAMA name
    assert display_name(parts[0], names["P1"]) == "block FRONT (P1)"


# -- the same choices on the command line and in core.job (one source of truth) --

def _aama_recognition(**kw):
    from LeatherCutWorkbench.core.job import JobOptions, load_and_recognise
    path = os.path.join(SAMPLES_DIR, "GMX1016S18_AAMA.DXF")
    return load_and_recognise(path, JobOptions(**kw))[1]


def test_job_cuts_only_the_sample_size_of_a_graded_set_by_default():
    rec = _aama_recognition()
    cut = rec.active_parts()
    assert {p.size for p in cut} == {"50"}                  # the file's Sample Size
    assert len({p.size for p in rec.parts}) == 15           # every size is still recognised


def test_job_sizes_and_quantities_choose_the_parts():
    rec = _aama_recognition(sizes=["42", "44"])
    assert {p.size for p in rec.active_parts()} == {"42", "44"}
    every = _aama_recognition(sizes=["all"])
    assert len(every.active_parts()) == len(every.parts) == 150
    first = every.parts[0].id
    rec = _aama_recognition(sizes=["all"], quantities={first: 3})
    assert next(p for p in rec.parts if p.id == first).quantity == 3
    with pytest.raises(InputError, match="size 99 is not in the drawing"):
        _aama_recognition(sizes=["99"])
    with pytest.raises(InputError, match="names part P9999"):
        _aama_recognition(quantities={"P9999": 2})


def test_workbench_choices_replace_the_defaults():
    every = _aama_recognition(sizes=["all"])
    keep = every.parts[0].id
    choices = {p.id: PartChoice(include=p.id == keep, quantity=2) for p in every.parts}
    rec = _aama_recognition(part_choices=choices)
    assert [(p.id, p.quantity) for p in rec.active_parts()] == [(keep, 2)]
    assert len(_aama_recognition(part_choices={}).active_parts()) == 150   # {} = as recognised
