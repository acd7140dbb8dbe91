"""Left compaction of overlap-free strip layouts (core/nesting/compaction.py)
on real geometry: the ESICUP instances fu (concave pieces, four rotations) and
albano (garment pieces, two rotations).  Every compacted layout is re-checked
with the independent checker."""

import os

import numpy as np
import pytest

from LeatherCutWorkbench.core.model import Container, Layout, Placement
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout
from LeatherCutWorkbench.core.nesting.compaction import compact_left
from LeatherCutWorkbench.core.nesting.engine import fill_metrics
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.overlap import PairTable
from LeatherCutWorkbench.core.nesting.separation import Separator, colliding_total
from LeatherCutWorkbench.core.nesting.strip_shrink import _compact, _Instance

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")


def _instance(name):
    inst = read_esicup(os.path.join(DATA, f"{name}.json"))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), seed=1, workers=1)
    return inst.parts, opts


def _loose_row(parts, opts, gap):
    """Every copy at angle 0 in one row along the strip, ``gap`` mm apart and 1 mm
    off the strip's edges: valid, loose."""
    placements, x = [], 0.0
    for p in parts:
        x0, y0, x1, y1 = p.outer.bbox
        for k in range(p.quantity):
            placements.append(Placement(part_id=p.id, copy=k, container="strip",
                                        x=x - x0 + opts.margin + 1.0, y=opts.margin + 1.0 - y0,
                                        angle=0.0))
            x += (x1 - x0) + gap
    lay = Layout(containers=[Container(id="strip", kind="strip", outline=[])],
                 placements=placements)
    fill_metrics(parts, lay, opts)
    return lay


def _setup(name, gap=5.0):
    parts, opts = _instance(name)
    inst = _Instance(_loose_row(parts, opts, gap), parts, opts)
    assert inst.ok
    sep = Separator(PairTable(inst.variants), inst.cb, inst.choices, inst.types, inst.y0,
                    inst.y1, inst.x0, inst.eps)
    return parts, opts, inst, sep


def _inside(inst, X, Y, V):
    cb = inst.cb
    return bool(np.all(X + cb[V, 0] >= inst.x0 - 1e-6) and np.all(Y + cb[V, 1] >= inst.y0 - 1e-6)
                and np.all(Y + cb[V, 3] <= inst.y1 + 1e-6))


@pytest.mark.parametrize("name", ["fu", "albano"])
def test_a_loose_row_closes_up_and_stays_valid(name):
    parts, opts, inst, sep = _setup(name)
    X, Y, V = inst.X.copy(), inst.Y.copy(), inst.V.copy()
    before = inst.right_edge(X, V)
    moved = compact_left(X, Y, V, sep.cb, sep.x0, sep.y0, sep.y1, sep.eps, sep.table.n, *sep.arrs)
    after = inst.right_edge(X, V)
    # a row with 5 mm gaps between the copies, all on the bottom edge: the copies
    # close up (diagonal slides fill the rows above), the strip gets much shorter
    assert moved > 0.0
    assert after < 0.9 * before
    assert colliding_total(sep.overlaps(X, Y, V), sep.eps) == 0.0
    assert _inside(inst, X, Y, V)
    lay = inst.to_layout(_loose_row(parts, opts, 5.0), X, Y, V)
    assert check_layout(parts, lay, spacing=opts.spacing, margin=opts.margin) == []


def test_a_tight_layout_is_left_alone_and_a_second_compaction_moves_nothing():
    parts, opts, inst, sep = _setup("fu")
    X, Y, V = inst.X.copy(), inst.Y.copy(), inst.V.copy()
    _compact(sep, X, Y, V)
    X2, Y2 = X.copy(), Y.copy()
    again = compact_left(X2, Y2, V, sep.cb, sep.x0, sep.y0, sep.y1, sep.eps, sep.table.n,
                         *sep.arrs)
    # compaction ends when no copy can move left any more (within its floor):
    # a second call moves at most a sliver, and never lengthens the strip
    assert again < 1e-3 * (inst.right_edge(X, V) - inst.x0)
    assert inst.right_edge(X2, V) <= inst.right_edge(X, V) + 1e-9

