"""The recombination of single-hide packings (core/nesting/hide_patterns.py):
the set-cover master problem picks the fewest hides, then the least net
area, among the packings seen; takes surplus copies out; and answers None
when the packings give nothing better than the set the search already has."""

from LeatherCutWorkbench.core.nesting.hide_patterns import HidePatterns


def _copies(*types):
    """One copy per type, at distinct made-up positions (variant 0)."""
    return [(t, 0, 10 * i, 0) for i, t in enumerate(types)]


def test_one_hide_holding_everything_beats_two_smaller_hides():
    # nets 10, 20, 30; demand two of type 0 and one of type 1
    pats = HidePatterns([2, 1], [10.0, 20.0, 30.0], [3.0, 4.0])
    pats.add(0, _copies(0, 0))
    pats.add(1, _copies(0, 1))
    pats.add(2, _copies(0, 0, 1))
    cover = pats.best_cover((3, 60.0), time_limit=5.0)
    assert [h for h, _ in cover] == [2]
    assert sorted(c[0] for c in cover[0][1]) == [0, 0, 1]


def test_among_equal_hide_counts_the_least_net_area_wins_and_surplus_is_taken_out():
    pats = HidePatterns([2, 1], [10.0, 20.0, 30.0], [3.0, 4.0])
    pats.add(0, _copies(0, 0))            # 6 of 10 used
    pats.add(1, _copies(0, 1))            # 7 of 20 used
    pats.add(2, _copies(0, 1))
    cover = pats.best_cover((3, 60.0), time_limit=5.0)
    assert [h for h, _ in cover] == [0, 1]           # 30 net, not 0 + 2 = 40
    held = sorted(c[0] for _, cps in cover for c in cps)
    assert held == [0, 0, 1]                         # three type-0 copies cut to two
    # the surplus copy left the hide that was fuller (hide 0: 6/10 > 7/20)
    assert sorted(c[0] for c in dict(cover)[0]) == [0]
    assert dict(cover)[1] == _copies(0, 1)


def test_no_cover_better_than_the_given_set_gives_none():
    pats = HidePatterns([2, 1], [10.0, 20.0, 30.0], [3.0, 4.0])
    pats.add(0, _copies(0, 0))
    pats.add(1, _copies(0, 1))
    assert pats.best_cover((2, 30.0), time_limit=5.0) is None     # the same set is not better
    assert pats.best_cover((2, 31.0), time_limit=5.0) is not None
    pats.add(2, _copies(0))                          # no hide holds all: never one hide
    assert pats.best_cover((1, 60.0), time_limit=5.0) is None


def test_a_packing_of_the_same_types_is_kept_once_and_layouts_map_positions_to_hides():
    pats = HidePatterns([2, 1], [10.0, 20.0, 30.0], [3.0, 4.0])
    pats.add(1, _copies(0, 1))
    pats.add(1, list(reversed(_copies(1, 0))))       # same multiset, other placement
    assert len(pats) == 1 and pats.fresh == 1
    seq = [(0, None), (1, None), (0, None)]
    # sequence positions 0 and 2 on bin position 1 (hide 2), 1 on position 0 (hide 0);
    # a copy left out (bin -1) belongs to no pattern
    placements = [(0, 1, 0, 5, 5), (1, 0, 0, 1, 1), (2, 1, 1, 9, 9), (2, -1, 0, 0, 0)]
    pats.add_layout(seq, placements, [0, 2])
    assert len(pats) == 3 and pats.fresh == 3
    cover = pats.best_cover((3, 60.0), time_limit=5.0)
    assert pats.fresh == 0
    assert [h for h, _ in cover] == [0, 2]               # 40 net, not 1 + 2 = 50
