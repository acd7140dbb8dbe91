"""The GTSP machinery against brute force on small instances: exact entry DP,
solve_gtsp optimality, certified lower bounds, precedence repair, determinism."""

import itertools
import math
import random

import numpy as np
import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.pathplan import solve_gtsp
from LeatherCutWorkbench.core.pathplan.bounds import (held_karp_bound, item_min_matrix,
                                                      lower_bound, two_neighbour_bound)
from LeatherCutWorkbench.core.pathplan.dp import optimal_entries
from LeatherCutWorkbench.core.pathplan.ga import run_ga
from LeatherCutWorkbench.core.pathplan.instance import EuclidInstance, MatrixInstance
from LeatherCutWorkbench.core.pathplan.localsearch import improve
from LeatherCutWorkbench.core.pathplan.nn import nearest_neighbour
from LeatherCutWorkbench.core.pathplan.precedence import repair, violations


def random_gtsp(seed, n_clusters=6, per=3, asym=False):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 100, (n_clusters * per, 2))
    D = np.hypot(pts[:, None, 0] - pts[None, :, 0], pts[:, None, 1] - pts[None, :, 1])
    if asym:
        D = D + rng.uniform(0, 20, D.shape)
        np.fill_diagonal(D, 0)
    clusters = [list(range(k * per, (k + 1) * per)) for k in range(n_clusters)]
    return D, clusters


def tour_len(D, tour):
    return sum(D[a, b] for a, b in zip(tour, tour[1:] + tour[:1]))


def brute_force(D, clusters):
    best = math.inf
    for perm in itertools.permutations(range(1, len(clusters))):
        for pick in itertools.product(*[clusters[k] for k in (0,) + perm]):
            best = min(best, tour_len(D, list(pick)))
    return best


@pytest.mark.parametrize("asym", [False, True])
def test_dp_is_exact_for_a_fixed_order(asym):
    D, clusters = random_gtsp(3, n_clusters=6, per=3, asym=asym)
    inst = MatrixInstance(D, clusters)
    order = [0, 3, 1, 5, 2, 4]
    choice, cost = optimal_entries(inst, order)
    best = min(tour_len(D, list(p)) for p in itertools.product(*[clusters[k] for k in order]))
    assert cost == pytest.approx(best)
    assert tour_len(D, [choice[k] for k in order]) == pytest.approx(best)


@pytest.mark.parametrize("seed,asym", [(1, False), (2, False), (3, True)])
def test_solve_gtsp_finds_the_optimum_of_small_instances(seed, asym):
    D, clusters = random_gtsp(seed, n_clusters=6, per=3, asym=asym)
    tour = solve_gtsp(D, clusters, time_limit=5, seed=1)
    assert len(tour) == len(clusters)
    assert tour[0] in clusters[0]
    assert sorted(next(k for k, c in enumerate(clusters) if v in c) for v in tour) == list(range(6))
    assert tour_len(D, tour) == pytest.approx(brute_force(D, clusters), rel=1e-9)


def test_solve_gtsp_rejects_bad_input():
    D, clusters = random_gtsp(1)
    with pytest.raises(InputError):
        solve_gtsp(D[:, :5], clusters, time_limit=1, seed=1)
    with pytest.raises(InputError):
        solve_gtsp(D, clusters + [[0]], time_limit=1, seed=1)
    with pytest.raises(InputError):
        solve_gtsp(D, [[]], time_limit=1, seed=1)


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_lower_bounds_never_exceed_the_optimum(seed):
    D, clusters = random_gtsp(seed, n_clusters=6, per=3)
    inst = MatrixInstance(D, clusters)
    opt = brute_force(D, clusters)
    assert two_neighbour_bound(inst) <= opt + 1e-9
    hk = held_karp_bound(item_min_matrix(inst), opt)
    assert 0 < hk <= opt + 1e-9
    lb, parts = lower_bound(inst, opt)
    assert lb == max(parts.values()) <= opt + 1e-9


def test_euclid_bounds_below_a_good_tour():
    # compact clusters (like contours): 4 points within 10 mm of a centre
    rng = np.random.default_rng(5)
    centres = rng.uniform(0, 1000, (99, 2))
    pts = np.vstack([[0.0, 0.0]] + [c + rng.uniform(-10, 10, (4, 2)) for c in centres])
    clusters = [[0]] + [list(range(1 + 4 * k, 5 + 4 * k)) for k in range(99)]
    inst = EuclidInstance(clusters, pts)
    res = run_ga(inst, time_limit=3, seed=1)
    lb, parts = lower_bound(inst, res.cost)
    assert 0 < parts["two_neighbour"] <= res.cost
    assert 0 < parts["held_karp"] <= res.cost
    # Held-Karp is a real bound, not a trivial one
    assert parts["held_karp"] > 0.5 * res.cost


def test_local_search_keeps_precedence_and_improves():
    rng = np.random.default_rng(7)
    pts = rng.uniform(0, 500, (61, 2))
    clusters = [[k] for k in range(61)]
    preds = [[] for _ in range(61)]
    r = random.Random(3)
    for k in range(1, 61):
        if r.random() < 0.4:
            preds[k] = [r.randrange(1, 61)]
            if preds[k][0] == k:
                preds[k] = []
    # drop cycles: keep only edges from lower to higher index
    preds = [[p for p in ps if p < k] for k, ps in enumerate(preds)]
    inst = EuclidInstance(clusters, pts, preds=preds)
    t, c = nearest_neighbour(inst)
    assert violations(t, inst.preds) == 0
    before = inst.tour_cost(t, c)
    near, nd = inst.neighbours(10)
    after = improve(inst, t, c, near, nd)
    assert violations(t, inst.preds) == 0
    assert sorted(t) == list(range(61)) and t[0] == 0
    assert after < before
    res = run_ga(inst, time_limit=3, seed=2)
    assert violations(res.order, inst.preds) == 0
    assert res.cost <= after + 1e-9


def test_repair_gives_closest_valid_order():
    preds = [[], [2], [], [1]]
    succs = [[], [3], [1], []]
    assert repair([0, 1, 2, 3], preds, succs) == [0, 2, 1, 3]
    assert repair([0, 2, 1, 3], preds, succs) == [0, 2, 1, 3]
    assert violations([0, 1, 2, 3], preds) == 1


@pytest.mark.slow
def test_ga_is_deterministic_per_seed():
    # the budget is generous: the GA stops by convergence, not by the clock
    D, clusters = random_gtsp(11, n_clusters=15, per=4)
    a = solve_gtsp(D, clusters, time_limit=120, seed=5)
    b = solve_gtsp(D, clusters, time_limit=120, seed=5)
    assert a == b


@pytest.mark.slow
def test_ga_beats_nearest_neighbour_on_random_gtsp():
    rng = np.random.default_rng(2)
    pts = rng.uniform(0, 1000, (1 + 150 * 5, 2))
    clusters = [[0]] + [list(range(1 + 5 * k, 6 + 5 * k)) for k in range(150)]
    inst = EuclidInstance(clusters, pts)
    t, c = nearest_neighbour(inst)
    nn = inst.tour_cost(t, c)
    # a fixed amount of work (not a time budget): the machine may be loaded
    res = run_ga(inst, time_limit=600, seed=1, max_iterations=5)
    assert res.iterations == 5
    assert res.cost < 0.9 * nn
    assert res.nn_cost == pytest.approx(nn)


def test_window_dp_is_exact_inside_the_window():
    from LeatherCutWorkbench.core.pathplan.dp import window_entries
    D, clusters = random_gtsp(8, n_clusters=7, per=3, asym=True)
    inst = MatrixInstance(D, clusters)
    t = [0, 4, 2, 6, 1, 5, 3]
    c = [cl[0] for cl in clusters]
    lo, hi = 2, 4
    best = math.inf
    for pick in itertools.product(*[clusters[t[i]] for i in range(lo, hi + 1)]):
        cc = list(c)
        for i, g in zip(range(lo, hi + 1), pick):
            cc[t[i]] = g
        best = min(best, inst.tour_cost(t, cc))
    before = inst.tour_cost(t, c)
    gain = window_entries(inst, t, c, lo, hi)
    assert inst.tour_cost(t, c) == pytest.approx(best)
    assert gain == pytest.approx(before - best)
    # items outside the window keep their candidates
    assert all(c[t[i]] == clusters[t[i]][0] for i in (0, 1, 5, 6))


def test_dp_with_a_single_home_candidate_is_exact():
    D, clusters = random_gtsp(4, n_clusters=6, per=3, asym=True)
    # home = node 0 alone; the other clusters keep three nodes each
    nodes = [0] + [v for cl in clusters[1:] for v in cl]
    cl_ids, off = [[0]], 1
    for cl in clusters[1:]:
        cl_ids.append(list(range(off, off + len(cl))))
        off += len(cl)
    inst = MatrixInstance(D, cl_ids, start_node=np.array(nodes))
    order = [0, 2, 5, 1, 4, 3]
    choice, cost = optimal_entries(inst, order)
    real = [[0]] + clusters[1:]
    best = min(tour_len(D, list(p)) for p in itertools.product(*[real[k] for k in order]))
    assert cost == pytest.approx(best)
    assert tour_len(D, [nodes[choice[k]] for k in order]) == pytest.approx(best)
