"""The copy-to-hide search (core/nesting/hide_assign.py) on real Baldacci
geometry: it moves copies from an over-full hide to another until every copy
is placed, the layout it reports passes the independent checker, and a
finished set is shrunk to smaller hides."""

import os
import random
import time
from dataclasses import replace

import numpy as np

from LeatherCutWorkbench.core.model import Container
from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, check_layout, placed_parts
from LeatherCutWorkbench.core.nesting.engine import _to_layout, prepare
from LeatherCutWorkbench.core.nesting.esicup import read_esicup
from LeatherCutWorkbench.core.nesting.hide_assign import AssignmentSearch, as_layout, from_placed
from LeatherCutWorkbench.core.nesting.hide_choice import as_hide_indices
from LeatherCutWorkbench.core.nesting.hide_patterns import HidePatterns
from LeatherCutWorkbench.core.nesting.search import _mutate

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
ANGLES = [0.0, 90.0, 180.0, 270.0]


def _setup(scales):
    """Test8's hide outline at the given scales; a third of Test8's copies
    (0.46 M units^2: more than a 0.45-scale hide of 0.5 M can hold)."""
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    o = inst.hides[0].outline
    hides = [Container(id=f"h{k}", kind="hide", outline=[(s * x, s * y) for x, y in o],
                       base_grade=1) for k, s in enumerate(scales)]
    parts = [replace(p, grade=1, grade_regions=[], quantity=max(1, p.quantity // 3))
             for p in inst.parts]
    opts = NestOptions(container=ContainerSpec.hide(*hides), time_budget=60, workers=1,
                       rotations_override=ANGLES, seed=1)
    return parts, hides, opts, prepare(parts, opts)


def _search(problem, seconds):
    t_end = time.monotonic() + seconds
    return AssignmentSearch(problem, problem.placer(), random.Random(4), _mutate,
                            lambda: time.monotonic() > t_end)


def test_copies_move_off_an_over_full_hide_until_all_are_placed():
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.45, 0.55])
    s = _search(problem, 40.0)
    genes = [[(t, None) for t in sorted(copies, key=lambda t: -problem.type_area[t])], []]
    st = s.start([0, 1], genes)
    # everything was queued on the small hide: what it left out went on to the
    # other hide (first fit across the set, ``_spill``), out of its own sequence
    assert st.genes[1] and len(st.genes[0]) + len(st.genes[1]) == len(copies)
    assert len(st.traces[0].unplaced) == 0 and st.lost[0] == 0
    seen = []
    s.run(st, problem.hide_net, lambda state: seen.append(state.copy()),
          sum(problem.type_area[t] for t in copies))
    done = [x for x in seen if x.total == 0]
    assert done, "every copy placed on the two hides"
    seq, placements, order = as_layout(done[0])
    assert sorted(g[0] for g in seq) == sorted(copies)
    lay = _to_layout(parts, types, variants, seq, as_hide_indices(placements, order), opts,
                     scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0 and lay.metrics["hides"] == 2


def test_a_finished_set_is_shrunk_to_a_smaller_unused_hide():
    """Three hides, the copies all on the two largest: once every copy is
    placed the search swaps the larger one for the unused smaller hide."""
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.7, 0.8, 0.6])
    s = _search(problem, 8.0)
    order = sorted(copies, key=lambda t: -problem.type_area[t])
    genes = [[(t, None) for t in order[0::2]], [(t, None) for t in order[1::2]]]
    st = s.start([1, 0], genes)
    assert st.total == 0
    seen = []
    s.run(st, problem.hide_net, lambda state: seen.append(state.copy()),
          sum(problem.type_area[t] for t in copies))
    net = problem.hide_net
    done = [x for x in seen if x.total == 0]
    assert min(sum(net[h] for h in x.hides) for x in done) < net[0] + net[1]


def test_a_search_takes_over_a_better_complete_set_of_another_worker():
    """``run``'s ``adopt``: a search on the two larger hides takes over another
    worker's complete layout on the smallest hide (a bottom-up fill, which
    this search's left-to-right fills do not make), as
    :func:`hide_assign.from_placed` rebuilt it -- the very placements,
    checker-valid -- and ends there: no smaller set is left."""
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.7, 0.8, 0.6])
    order = sorted(copies, key=lambda t: -problem.type_area[t])
    theirs = problem.placer()
    theirs.gravity = "y"
    other = AssignmentSearch(problem, theirs, random.Random(1), _mutate,
                             lambda: False).start([2], [[(t, None) for t in order]])
    assert other.total == 0
    seq, placements, hide_order = as_layout(other)
    taken = from_placed(problem.placer(), seq, as_hide_indices(placements, hide_order))
    assert taken.hides == [2] and taken.total == 0 and as_layout(taken)[1:] == (placements, [2])
    s = _search(problem, 30.0)
    st = s.start([1, 0], [[(t, None) for t in order[0::2]], [(t, None) for t in order[1::2]]])
    assert st.total == 0 and st.traces[0].placements != placements
    offered, seen = [taken], []
    t0 = time.monotonic()
    s.run(st, problem.hide_net, lambda state: seen.append(state.copy()),
          sum(problem.type_area[t] for t in copies), adopt=lambda: offered.pop() if offered else None)
    assert time.monotonic() - t0 < 30.0             # ended: nothing smaller than hide 2
    assert seen[-1].hides == [2] and seen[-1].traces[0].placements == placements
    seq, placements, hide_order = as_layout(seen[-1])
    lay = _to_layout(parts, types, variants, seq, as_hide_indices(placements, hide_order), opts,
                     scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0 and lay.metrics["hides"] == 1


def test_a_search_recombines_a_hide_packing_it_saw_into_a_smaller_complete_set():
    """``patterns`` (:mod:`hide_patterns`): a bottom-up fill that held every
    copy on the smallest hide is among the packings seen; a search on the two
    larger hides recombines it into that one-hide layout -- the very
    placements, checker-valid -- instead of finding it by its own fills."""
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.7, 0.8, 0.6])
    order = sorted(copies, key=lambda t: -problem.type_area[t])
    patterns = HidePatterns(np.bincount(copies, minlength=len(problem.type_area)),
                            problem.hide_net, problem.type_area)
    theirs = problem.placer()
    theirs.gravity = "y"
    other = AssignmentSearch(problem, theirs, random.Random(1), _mutate, lambda: False,
                             patterns=patterns).start([2], [[(t, None) for t in order]])
    assert other.total == 0 and len(patterns) == 1
    placements = as_layout(other)[1]
    t_end = time.monotonic() + 4.0
    s = AssignmentSearch(problem, problem.placer(), random.Random(4), _mutate,
                         lambda: time.monotonic() > t_end, t_end, patterns=patterns)
    st = s.start([1, 0], [[(t, None) for t in order[0::2]], [(t, None) for t in order[1::2]]])
    assert st.total == 0
    seen = []
    s.run(st, problem.hide_net, lambda state: seen.append(state.copy()),
          sum(problem.type_area[t] for t in copies))
    assert s.recombined >= 1
    one = [x for x in seen if x.hides == [2]]
    assert one and one[0].total == 0
    seq, got, hide_order = as_layout(one[0])
    assert sorted(got) == sorted(placements)
    lay = _to_layout(parts, types, variants, seq, as_hide_indices(got, hide_order), opts,
                     scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0 and lay.metrics["hides"] == 1


def test_odd_worker_searches_the_smallest_hides_right_after_its_first_fill():
    """Worker 1 on hides: after its first fill (largest hide first, every copy
    on hide 0) its next layout already lies on the smallest hide -- the
    copy-to-hide search starts on the k smallest hides, k the hides the first
    fill used -- passes the checker, and the worker ends after a few fills
    when no smaller set exists (it used to repeat worker 0's order search
    for a third of the budget first)."""
    from LeatherCutWorkbench.core.nesting.search import Budget, run_search
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.8, 0.7, 0.75])
    seen = []
    t0 = time.monotonic()
    budget = Budget(t0 + 120.0, on_best=lambda c, order, pl: seen.append((c, order, pl)))
    cost, order, placements, evals = run_search(problem, copies, 1, 1, budget)
    assert evals < 100          # no order search first (it made thousands of fills)
    assert len(seen) >= 2
    assert {b for (_si, b, _v, _x, _y) in seen[0][2]} == {0}     # first fill: the largest hide
    assert {b for (_si, b, _v, _x, _y) in seen[1][2]} == {1}     # then the smallest one
    assert {b for (_si, b, _v, _x, _y) in placements} == {1} and cost[0] == 0
    lay = _to_layout(parts, types, variants, order, placements, opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0 and lay.metrics["hides"] == 1


def test_order_search_worker_hands_over_once_it_stalls_on_a_complete_layout():
    """Worker 0 on hides: its order search places every copy on one hide and
    then finds nothing better; it hands over to the copy-to-hide search on
    that hide (which finds no smaller set and ends) instead of repeating
    fills until the deadline -- the layout stays on the smallest hide and
    passes the checker."""
    from LeatherCutWorkbench.core.nesting import search
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.8, 0.7, 0.75])
    calls = []
    real = search._assign_hides

    def spy(*args, **kw):
        calls.append(args[-1])                     # the hides it searches
        return real(*args, **kw)
    search._assign_hides = spy
    try:
        t0 = time.monotonic()
        budget = search.Budget(t0 + 40.0)
        cost, order, placements, evals = search.run_search(problem, copies, 1, 0, budget)
    finally:
        search._assign_hides = real
    assert calls == [[1]]                          # handed over on the smallest hide
    assert time.monotonic() < budget.t_end         # and ended there, before the deadline
    assert {b for (_si, b, _v, _x, _y) in placements} == {1} and cost[0] == 0
    lay = _to_layout(parts, types, variants, order, placements, opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert lay.metrics["unplaced_count"] == 0 and lay.metrics["hides"] == 1


def test_copy_to_hide_worker_starts_on_the_fewest_loosely_filled_smallest_hides():
    """Baldacci Test6 (43 copies, 380.0 M units^2, 15 hides): the copies fill
    46.5 % of the 14 smallest hides and 50.6 % of the 13 smallest, so the
    copy-to-hide worker starts on at most 14 hides (its quick first fill used
    all 15)."""
    from LeatherCutWorkbench.core.nesting.search import LOOSE_FILL, _fewest_loose
    inst = read_esicup(os.path.join(os.path.dirname(__file__), "..", "bench", "data", "hides",
                                    "Test6.json"))
    full = inst.hides[0].base_grade
    parts = [replace(p, grade=full, grade_regions=[]) for p in inst.parts]
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=60, workers=1,
                       rotations_override=[0.0])
    _types, _variants, problem, copies, _h, _s = prepare(parts, opts)
    items = sum(problem.type_area[c] for c in copies)
    net = sorted(problem.hide_net)
    k = _fewest_loose(problem.hide_net, items)
    assert k == 14
    assert items <= LOOSE_FILL * sum(net[:k]) and items > LOOSE_FILL * sum(net[:k - 1])


def test_worker_0_first_layout_turns_each_part_one_way_then_fills_with_four():
    """Worker 0 on hides answers first with one orientation per part
    (``FIRST_CAP_HIDES``: a quarter of the inner-fit regions), a valid
    layout; its next fill tries four orientations and is kept only when
    better, so the layouts it reports improve."""
    from LeatherCutWorkbench.core.nesting.search import Budget, run_search
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.8, 0.7, 0.75])
    seen = []
    budget = Budget(time.monotonic() + 120.0, max_evaluations=2,
                    on_best=lambda c, order, pl: seen.append((c, order, pl)))
    run_search(problem, copies, 1, 0, budget)
    one_way = {problem.type_variants[t][0] for t in range(len(types))}
    _cost, order, first = seen[0]
    assert {vi for (_si, b, vi, _x, _y) in first if b >= 0} <= one_way
    lay = _to_layout(parts, types, variants, order, first, opts, scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    assert [c for c, _o, _p in seen] == sorted((c for c, _o, _p in seen), reverse=True)
    if len(seen) > 1:                     # the four-orientation fill was better
        assert not {vi for (_si, b, vi, _x, _y) in seen[1][2] if b >= 0} <= one_way


def test_each_hide_is_filled_from_its_own_side_and_stays_valid():
    """One hide per gravity: the same few copies on Test8's outline packed from
    the left, the bottom, the right and the top.  Each fill lies against its
    side (its copies' mean centre is off the hide's centre that way) and every
    layout passes the independent checker."""
    parts, hides, opts, (_t, _v, problem, copies, _h, _s) = _setup([0.6] * 4)
    big = sorted(set(copies), key=lambda t: -problem.type_area[t])[:3]
    parts = [replace(parts[t], quantity=4) for t in big]       # each hide: one copy of each
    types, variants, problem, copies, _h, scale = prepare(parts, opts)
    s = _search(problem, 30.0)
    st = s.start([0, 1, 2, 3], [[(t, None) for t in range(3)] for _ in range(4)],
                 gravity=["x", "y", "-x", "-y"])
    assert st.total == 0
    seq, placements, order = as_layout(st)
    lay = _to_layout(parts, types, variants, seq, as_hide_indices(placements, order), opts,
                     scale, hides)
    assert check_layout(parts, lay, rotations_override=ANGLES) == []
    xs = [x for x, _ in hides[0].outline]
    ys = [y for _, y in hides[0].outline]
    cx, cy = (min(xs) + max(xs)) / 2.0, (min(ys) + max(ys)) / 2.0
    centres = {}
    for pl, part in zip(lay.placements, placed_parts(parts, lay)):
        x0, y0, x1, y1 = part.outer.bbox
        centres.setdefault(pl.container, []).append(((x0 + x1) / 2.0, (y0 + y1) / 2.0))
    mean = {c: (sum(x for x, _ in v) / len(v), sum(y for _, y in v) / len(v))
            for c, v in centres.items()}
    assert len(mean) == 4
    assert mean["h0"][0] < cx and mean["h2"][0] > cx        # from the left, from the right
    assert mean["h1"][1] < cy and mean["h3"][1] > cy        # from the bottom, from the top
    assert mean["h2"][0] > mean["h0"][0] and mean["h3"][1] > mean["h1"][1]


def test_a_layout_that_lost_a_copy_is_refused_and_reported_with_its_call_chain():
    """``cost_of`` counts only the copies left out, so a layout whose order
    lost a copy would look complete (and on fewer hides) and win; the
    worker's budget refuses it and says where it came from."""
    from LeatherCutWorkbench.core.nesting.search import Budget, cost_of
    parts, hides, opts, (types, variants, problem, copies, _h, scale) = _setup([0.45, 0.55])
    placer = problem.placer()
    order = [(t, None) for t in copies]
    tr = placer.place(order)
    full = tr.placements
    reported, lost = [], []
    b = Budget(time.monotonic() + 5, copies=sorted(copies), on_lost=lost.append,
               on_best=lambda c, o, p: reported.append(len(o)))
    short = [pl for pl in full if pl[0] != len(order) - 1]      # the last copy's placement gone
    b.improved(cost_of(problem, order[:-1], short), order[:-1], short)
    assert reported == [] and len(lost) == 1
    assert lost[0].startswith("test_a_layout_that_lost_a_copy") and lost[0].count(" < ") <= 7
    b.improved(cost_of(problem, order, full), order, full)
    assert reported == [len(copies)] and len(lost) == 1
