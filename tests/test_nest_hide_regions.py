"""Hide regions are built when the fill first needs them (core/nesting/hide_regions.py):
a hide the fill never opens is never prepared, a coarse fill builds no exact
region, grades of the same material share a region, and the layouts are those
of regions built up front; the first layout is timed and reported live."""

import math
import os
from dataclasses import replace

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, nest
from LeatherCutWorkbench.core.nesting import engine
from LeatherCutWorkbench.core.nesting.checker import part_polygon
from LeatherCutWorkbench.core.nesting.engine import prepare
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.hide_regions import HideRegions
from LeatherCutWorkbench.core.nesting.hide_choice import (as_hide_indices, initial_order,
                                                            used_positions)
from LeatherCutWorkbench.core.nesting.search import start_orders

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
ANGLES = [0.0, 90.0, 180.0, 270.0]


def _small_job():
    """Baldacci Test1's six smallest item types, one copy each (grades 1 and
    full), on its first two hides (holes, quality-1 zones): the first hide holds all."""
    inst = read_esicup(os.path.join(DATA, "Test1_first2hides.json"))
    parts = sorted(inst.parts, key=lambda p: part_polygon(p).area)[:6]
    parts = [replace(p, quantity=1) for p in parts]
    assert {p.grade for p in parts} != {parts[0].grade}      # two grades: two regions per hide
    return inst.hides, parts


def _fill(problem, copies, coarse=False):
    placer = problem.placer()
    placer.bin_order = initial_order(problem.hide_net)
    if coarse:                          # past the exact deadline: coarse regions and NFPs
        placer.clock.exact_until = 0.0
    return placer.place(start_orders(problem, copies)[0], abortable=False).placements


def _build_all(spec):
    spec.ready()
    for k in set(spec.grade_key.values()):
        spec.region(k)
        spec.coarse_region(k)


def test_a_hide_the_fill_never_opens_is_never_prepared():
    hides, parts = _small_job()
    opts = NestOptions(container=ContainerSpec.hide(*hides), rotations_override=ANGLES)
    _types, _variants, problem, copies, _hides, _scale = prepare(parts, opts)
    assert all(not b.regions and not b.coarse for b in problem.bins)   # nothing built yet
    placements = _fill(problem, copies)
    assert all(b >= 0 for (_si, b, _vi, _x, _y) in placements)
    assert used_positions(placements) == [0]
    first = initial_order(problem.hide_net)[0]
    for i, spec in enumerate(problem.bins):
        if i == first:
            assert len(spec.regions) == 2 and spec.material > 0 and not spec.coarse
        else:                           # never opened: never built
            assert not spec.regions and not spec.coarse and spec.material == math.inf


def test_a_coarse_first_fill_builds_no_exact_region_and_is_valid():
    """Past the exact deadline (worker 0's quick first fill) the fill asks
    only for coarse regions: no hide gets an exact one, and the layout passes
    the independent checker."""
    hides, parts = _small_job()
    opts = NestOptions(container=ContainerSpec.hide(*hides), rotations_override=ANGLES)
    types, variants, problem, copies, used, scale = prepare(parts, opts)
    order = start_orders(problem, copies)[0]
    placements = as_hide_indices(_fill(problem, copies, coarse=True),
                                 initial_order(problem.hide_net))
    assert all(b >= 0 for (_si, b, _vi, _x, _y) in placements)
    assert all(not spec.regions for spec in problem.bins)
    assert any(spec.coarse for spec in problem.bins)
    layout = engine._to_layout(parts, types, variants, order, placements, opts, scale, used)
    assert layout.placements and check_layout(parts, layout, rotations_override=ANGLES) == []


def test_grades_that_may_use_the_same_material_share_one_region():
    """A hide of base grade 3 with grade-1 zones: grades 2 and 3 may both use
    the grade-3 material only, so they get one region key, and its region is
    the one built for grade 3 itself."""
    hide = _small_job()[0][0]
    assert {g for g, _z in hide.zones} == {1} and hide.base_grade == 2
    hide = replace(hide, base_grade=3)
    prep = HideRegions(hide, [1, 2, 3], 0.0, 1.0)
    assert prep.keys() == {1: 1, 2: 2, 3: 2}
    assert prep.exact(2) == HideRegions(hide, [3], 0.0, 1.0).exact(3)


def test_lazy_regions_give_the_layout_of_regions_built_up_front():
    hides, parts = _small_job()
    opts = NestOptions(container=ContainerSpec.hide(*hides), rotations_override=ANGLES)
    lazy = prepare(parts, opts)[2]
    eager = prepare(parts, opts)[2]
    for spec in eager.bins:
        _build_all(spec)
    copies = prepare(parts, opts)[3]
    assert _fill(lazy, copies) == _fill(eager, copies)
    assert _fill(lazy, copies, coarse=True) == _fill(eager, copies, coarse=True)
    for a, b in zip(lazy.bins, eager.bins):
        _build_all(a)
        assert a.regions == b.regions and a.coarse == b.coarse and a.material == b.material


def test_nest_with_lazy_regions_equals_the_eager_nest(monkeypatch):
    """The whole engine (two workers, a fixed number of evaluations: the
    search is deterministic) lays out the same with every hide built first."""
    hides, parts = _small_job()
    opts = NestOptions(container=ContainerSpec.hide(*hides), rotations_override=ANGLES,
                       time_budget=0, workers=2, seed=4)
    lazy = nest(parts, opts)
    real = engine._bins

    def eager_bins(*a, **k):
        bins, *rest = real(*a, **k)
        for spec in bins:
            _build_all(spec)
        return (bins, *rest)

    monkeypatch.setattr(engine, "_bins", eager_bins)
    eager = nest(parts, opts)
    key = [(p.part_id, p.copy, p.container, p.x, p.y, p.angle) for p in lazy.placements]
    assert key == [(p.part_id, p.copy, p.container, p.x, p.y, p.angle) for p in eager.placements]
    assert check_layout(parts, lazy, rotations_override=ANGLES) == []


def test_the_first_layout_is_timed_and_reported_live_with_one_worker():
    """One worker: the search runs in the caller's process, and the bar heard
    of the best layout only every 10 evaluations -- never, in a search of
    fewer.  Now each better layout is reported when it is found."""
    hides, parts = _small_job()
    opts = NestOptions(container=ContainerSpec.hide(*hides), rotations_override=ANGLES,
                       time_budget=20, max_evaluations=3, workers=1)
    seen = []
    lay = nest(parts, opts, lambda f, msg: seen.append(msg) or True)
    assert any(m.startswith("best: 6/6 placed on 1 hide(s)") for m in seen)
    m = lay.metrics
    assert 0 < m["first_layout_s"] <= m["time_s"]
