"""Path planning on real geometry: every constraint of a cut job is checked by
code independent of the planner (order of contour ids, segment geometry)."""

import math

import pytest

from LeatherCutWorkbench.core.geometry import turn_angle
from LeatherCutWorkbench.core.pathplan import PlanOptions, plan
from plan_shapes import leather_job, nested_job, shared_edge_job

TOL = 1e-6


def _close(a, b, tol=TOL):
    return math.dist(a, b) <= tol


def index_of(p):
    """contour id -> positions in the plan."""
    out = {}
    for i, it in enumerate(p.items):
        out.setdefault(it.contour_id, []).append(i)
    return out


def assert_real_job(p, parts, chains=()):
    """Connected items starting at their entry / lead-in, closed contours
    returning to the entry, every contour of every active part cut once."""
    for it in p.items:
        segs = it.segments
        assert segs, it.contour_id
        for a, b in zip(segs, segs[1:]):
            assert _close(a.end, b.start), f"{it.contour_id}: gap between segments"
        body = segs[it.lead_in_count:]
        assert _close(body[0].start, it.entry), it.contour_id
        if it.kind in ("hole", "outer"):
            # closed contour: back to the entry (a lead-out may follow)
            ends = [s.end for s in body]
            assert any(_close(e, it.entry) for e in ends), f"{it.contour_id} does not close"
    ids = index_of(p)
    for part in parts:
        for c in part.contours():
            if part.excluded:
                assert c.id not in ids, f"excluded {c.id} was cut"
            else:
                assert len(ids.get(c.id, [])) == 1, f"{c.id} cut {len(ids.get(c.id, []))} times"
    for ch in chains:
        assert len(ids.get(ch.id, [])) == 1


@pytest.mark.parametrize("method", ["nn", "ga", "aco"])
def test_nested_job_respects_every_precedence(method):
    parts, chains = nested_job()
    p = plan(parts, chains, PlanOptions(method=method, time_limit=5, seed=2, lift_angle=30))
    assert_real_job(p, parts, chains)
    pos = {k: v[0] for k, v in index_of(p).items()}
    # holes before their outline
    for part in parts:
        if part.excluded:
            continue
        for h in part.holes:
            assert pos[h.id] < pos[part.outer.id], f"hole {h.id} after outline"
    # part I lies in frame F's hole: all of I before that hole, and before F
    assert pos["I.h0"] < pos["I.outer"] < pos["F.h0"] < pos["F.outer"]
    # the open chain is cut (outside every part: no constraint), X never
    assert "C1" in pos and "X.outer" not in pos
    assert p.metrics["precedence_violations"] == 0


def test_lead_in_cut_first_from_its_free_end():
    parts, chains = nested_job()
    p = plan(parts, chains, PlanOptions(time_limit=3))
    by_id = {it.contour_id: it for it in p.items}
    po = by_id["P.outer"]
    assert po.lead_in_count >= 1
    assert _close(po.start, (380.0, -20.0))
    assert _close(po.segments[0].end, (400.0, 0.0))
    assert _close(po.entry, (400.0, 0.0))
    assert _close(po.end, (400.0, 0.0))
    qh = by_id["Q.h0"]
    assert _close(qh.start, (475.0, 300.0)) and _close(qh.entry, (450.0, 300.0))
    # a contour without lead-in is entered at the cut's first point
    assert by_id["F.outer"].lead_in_count == 0
    assert _close(by_id["F.outer"].start, by_id["F.outer"].entry)


def _unit_edges(p):
    """Every cut segment as an undirected key rounded to 1e-6 mm."""
    keys = []
    for it in p.items:
        for s in it.segments:
            a = tuple(round(v, 6) for v in s.start)
            b = tuple(round(v, 6) for v in s.end)
            keys.append(tuple(sorted([a, b])))
    return keys


@pytest.mark.parametrize("method", ["nn", "ga"])
def test_shared_edges_are_cut_once(method):
    parts = shared_edge_job()
    p = plan(parts, [], PlanOptions(method=method, time_limit=3))
    keys = _unit_edges(p)
    for x in (100.0, 200.0):
        shared = tuple(sorted([(x, 0.0), (x, 60.0)]))
        assert keys.count(shared) == 1, f"edge x={x} cut {keys.count(shared)} times"
    assert len(keys) == len(set(keys))
    assert p.metrics["cut_mm"] == pytest.approx(3 * 320.0 - 2 * 60.0)
    # the edge is kept by the item cut first: every item of the other contour
    # sharing it comes later
    for x, pair in ((100.0, ("A.outer", "B.outer")), (200.0, ("B.outer", "C.outer"))):
        shared = tuple(sorted([(x, 0.0), (x, 60.0)]))
        owner = next(i for i, it in enumerate(p.items)
                     if any(tuple(sorted([tuple(round(v, 6) for v in s.start),
                                          tuple(round(v, 6) for v in s.end)])) == shared
                            for s in it.segments))
        other = pair[1] if p.items[owner].contour_id == pair[0] else pair[0]
        assert all(i > owner for i, it in enumerate(p.items) if it.contour_id == other)
    for it in p.items:
        assert all(_close(a.end, b.start) for a, b in zip(it.segments, it.segments[1:]))


def test_lifts_exactly_where_heading_turns_more_than_angle():
    parts, chains = nested_job()
    for angle in (30.0, 100.0):
        p = plan(parts, chains, PlanOptions(time_limit=3, lift_angle=angle))
        total = 0
        for it in p.items:
            want = []
            segs = it.segments
            for i in range(1, len(segs)):
                if turn_angle(segs[i - 1].end_heading(), segs[i].start_heading()) > angle + 1e-9:
                    want.append(i)
            assert it.lifts == want, it.contour_id
            total += len(want)
        assert p.metrics["lifts"] == total
        if angle == 30.0:
            # squares: every corner cut through is a lift; the lead-in meets
            # P.outer at 45 degrees -> a lift there too
            po = next(it for it in p.items if it.contour_id == "P.outer")
            assert po.lead_in_count in po.lifts
            assert total >= 20
        else:
            assert total == 0
    p = plan(parts, chains, PlanOptions(time_limit=3, lift_angle=None))
    assert p.metrics["lifts"] == 0


def test_same_seed_same_plan():
    parts, chains = nested_job()
    a = plan(parts, chains, PlanOptions(seed=7, time_limit=30))
    b = plan(parts, chains, PlanOptions(seed=7, time_limit=30))
    assert a.metrics["converged"] and b.metrics["converged"]
    sig = lambda p: [(it.contour_id, tuple(round(v, 9) for v in it.entry)) for it in p.items]
    assert sig(a) == sig(b)
    assert a.metrics["idle_mm"] == b.metrics["idle_mm"]


@pytest.mark.parametrize("method", ["ga", "aco"])
def test_iteration_budget_gives_the_same_plan_at_any_speed(method):
    """With an iteration budget the plan does not depend on how fast the
    machine is: a run slowed down 200-fold in its progress hook (as a busy GUI
    or a loaded machine would) returns exactly the plan of an unhindered run."""
    import time as _time
    parts = leather_job(seed=3, n_parts=40, n_holes=4, size=800.0)
    budget = 6
    fast = plan(parts, [], PlanOptions(method=method, seed=5, max_iterations=budget, time_limit=120))
    calls = []

    def slow(frac, msg):
        calls.append(msg)
        _time.sleep(0.02)
    slow_plan = plan(parts, [], PlanOptions(method=method, seed=5, max_iterations=budget,
                                            time_limit=120), progress=slow)
    assert any("generation" in c or "iteration" in c for c in calls)
    for p in (fast, slow_plan):
        assert p.metrics["stopped_by"] in ("iterations", "converged")
        assert p.metrics["iterations"] <= budget
    sig = lambda p: [(it.contour_id, tuple(round(v, 9) for v in it.entry)) for it in p.items]
    assert sig(fast) == sig(slow_plan)
    assert fast.metrics["idle_mm"] == slow_plan.metrics["idle_mm"]


def test_time_cap_is_reported():
    """A budget too short to converge says so: stopped_by == "time"."""
    parts = leather_job(seed=4, n_parts=300, n_holes=0, size=2200.0)
    p = plan(parts, [], PlanOptions(method="ga", seed=1, time_limit=0.3))
    assert p.metrics["stopped_by"] == "time" and not p.metrics["converged"]
    assert p.metrics["idle_mm"] <= p.metrics["nn_idle_mm"] + 1e-6


def test_leather_job_ga_beats_nn_and_drawing_order():
    parts = leather_job(seed=1)
    nn = plan(parts, [], PlanOptions(method="nn"))
    ga = plan(parts, [], PlanOptions(method="ga", time_limit=3, seed=1))
    assert_real_job(ga, parts)
    m = ga.metrics
    assert m["idle_mm"] <= nn.metrics["idle_mm"] - 1.0
    assert m["nn_idle_mm"] == pytest.approx(nn.metrics["idle_mm"])
    assert m["idle_mm"] <= 0.67 * m["drawing_order_idle_mm"]
    assert 0 < m["lower_bound_mm"] <= m["idle_mm"]
    # holes (the first 9 parts have one) before outlines
    pos = {k: v[0] for k, v in index_of(ga).items()}
    for part in parts:
        for h in part.holes:
            assert pos[h.id] < pos[part.outer.id]


def test_aco_beats_nn_on_leather_job():
    parts = leather_job(seed=2)
    nn = plan(parts, [], PlanOptions(method="nn"))
    aco = plan(parts, [], PlanOptions(method="aco", time_limit=3, seed=1))
    assert_real_job(aco, parts)
    assert aco.metrics["idle_mm"] < nn.metrics["idle_mm"]


def test_metrics_are_consistent():
    parts, chains = nested_job()
    p = plan(parts, chains, PlanOptions(time_limit=3, lift_angle=30))
    m = p.metrics
    for key in ("idle_mm", "cut_mm", "lifts", "est_time_s", "drawing_order_idle_mm", "nn_idle_mm",
                "lower_bound_mm", "gap_to_lower_bound", "precedence_violations", "method", "seed",
                "time_s", "iterations"):
        assert key in m
    idle = sum(math.dist(a, b) for a, b in p.idle_moves())
    assert m["idle_mm"] == pytest.approx(idle, abs=1e-2)
    assert m["cut_mm"] == pytest.approx(sum(it.length for it in p.items), abs=1e-2)
    # time at least idle at rapid + cut at cut speed
    o = PlanOptions()
    assert m["est_time_s"] > idle / (o.rapid_speed / 60) + m["cut_mm"] / (o.cut_speed / 60)
    assert m["gap_to_lower_bound"] == pytest.approx(m["idle_mm"] / m["lower_bound_mm"] - 1, abs=1e-3)


def test_bad_options_raise_input_error():
    from LeatherCutWorkbench.core.errors import InputError
    parts, chains = nested_job()
    with pytest.raises(InputError):
        plan(parts, chains, PlanOptions(method="tabu"))
    with pytest.raises(InputError):
        plan(parts, chains, PlanOptions(entry_spacing=0))
    with pytest.raises(InputError):
        plan(parts, chains, PlanOptions(lift_angle=270))


def test_empty_job_is_an_empty_plan():
    p = plan([], [], PlanOptions())
    assert p.items == [] and p.metrics["idle_mm"] == 0
    assert any(f.code == "nothing-to-cut" for f in p.findings)


def test_open_chain_inside_part_cut_before_its_outline_and_lead_out_last():
    from LeatherCutWorkbench.core.geometry import LineSeg
    from LeatherCutWorkbench.core.model import LeadIn, OpenChain
    from plan_shapes import part, rect_pts
    lo = LeadIn("S.lo", "S.outer", [LineSeg((200.0, 50.0), (220.0, 30.0))], role="lead_out")
    s = part("S", rect_pts(0, 0, 200, 100), lead_ins=[lo])
    slit = OpenChain("slit", [LineSeg((50.0, 50.0), (150.0, 50.0))])
    outside = OpenChain("far", [LineSeg((500.0, 500.0), (520.0, 500.0))])
    for method in ("nn", "ga"):
        p = plan([s], [slit, outside], PlanOptions(method=method, time_limit=3))
        pos = {k: v[0] for k, v in index_of(p).items()}
        assert pos["slit"] < pos["S.outer"]
        it = p.items[pos["S.outer"]]
        # entered where the lead-out starts, closed there, then the lead-out
        assert _close(it.entry, (200.0, 50.0)) and _close(it.end, (220.0, 30.0))
        assert all(_close(a.end, b.start) for a, b in zip(it.segments, it.segments[1:]))
        assert it.length == pytest.approx(600.0 + math.hypot(20, 20))
