"""Accepting and rejecting single under-recognition fixes (``accept_fixes`` /
``reject_fixes``) on generated drawings with known answers."""

import pytest

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.model import LineEdge, PieceInfo
from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise

import recognise_shapes as S


def run(edges, pieces=None, **kw):
    return recognise(S.drawing(edges, pieces=pieces), RecogniseOptions(**kw))


def two_gaps():
    """Two squares left open by 0.2 and 0.3 mm gaps, far apart."""
    return S.square_with_gap(0.2) + S.square_with_gap(0.3, x=100.0)


def mixed():
    """A gap (close), a lead-in stopping short (join), a stub (trim), and a
    pinwheel of four parts around an empty square (an over flag)."""
    return (S.square_with_gap(0.2) + S.shifted(S.square_overshoot(0.3), 50, 0)
            + S.shifted(S.rect(0, 0, 20, 10), 100, 0)
            + [LineEdge((105.0, -4.0), (105.0, -0.3), S.src())]
            + S.pinwheel_lines(200.0, 0.0))


def signature(rec):
    """Flag id -> what the flag is about (independent of the ids it names)."""
    return {f.id: (f.kind, f.action, round(f.gap or 0.0, 6)) for f in rec.flags}


def by_action(rec, action):
    (f,) = [f for f in rec.flags if f.action == action]
    return f


def test_accepting_one_of_two_gaps_closes_exactly_that_one():
    prop = run(two_gaps())
    assert not prop.parts and len(prop.open_chains) == 2
    small = next(f for f in prop.flags if f.gap == pytest.approx(0.2))
    large = next(f for f in prop.flags if f.gap == pytest.approx(0.3))
    rec = run(two_gaps(), accept_fixes=frozenset({large.id}))
    (p,) = rec.parts
    assert p.outer.bbox[0] == pytest.approx(100.0) and p.outer.area == pytest.approx(400.0)
    (chain,) = rec.open_chains
    assert max(x for s in chain.segments for x in (s.start[0], s.end[0])) <= 20.0 + 1e-9
    assert signature(rec) == signature(prop)
    flags = {f.id: f for f in rec.flags}
    assert flags[large.id].accepted is True and flags[large.id].ids == [p.outer.id]
    assert flags[small.id].accepted is None and flags[small.id].ids == [chain.id]
    # the other one alone
    rec2 = run(two_gaps(), accept_fixes=frozenset({small.id}))
    (p2,) = rec2.parts
    assert p2.outer.bbox[0] == pytest.approx(0.0)
    assert signature(rec2) == signature(prop)


def test_rejected_fix_stays_open_and_is_marked_rejected():
    prop = run(two_gaps())
    a, b = (f.id for f in prop.flags)
    rec = run(two_gaps(), accept_fixes=frozenset({a}), reject_fixes=frozenset({b}))
    assert len(rec.parts) == 1 and len(rec.open_chains) == 1
    flags = {f.id: f for f in rec.flags}
    assert flags[a].accepted is True and flags[b].accepted is False
    # a rejection wins over close_gaps ("accept all")
    rec2 = run(two_gaps(), close_gaps=True, reject_fixes=frozenset({b}))
    assert len(rec2.parts) == 1 and {f.id: f.accepted for f in rec2.flags} == {a: True, b: False}


def test_join_fix_makes_the_lead_in():
    prop = run(mixed())
    join = by_action(prop, "join")
    rec = run(mixed(), accept_fixes=frozenset({join.id}))
    assert signature(rec) == signature(prop)
    part = next(p for p in rec.parts if p.outer.bbox[0] == pytest.approx(100.0))
    (li,) = part.lead_ins
    assert li.start == pytest.approx((105.0, -4.0)) and li.end == pytest.approx((105.0, 0.0))
    got = by_action(rec, "join")
    assert got.accepted is True and got.ids == [li.id]
    # the gap and the stub stay proposals
    assert by_action(rec, "close").accepted is None and by_action(rec, "trim").accepted is None
    assert len(rec.open_chains) == len(prop.open_chains) - 1


def test_trim_fix_removes_only_the_stub():
    prop = run(mixed())
    trim = by_action(prop, "trim")
    (stub_id,) = trim.ids
    stub = next(c for c in prop.open_chains if c.id == stub_id)
    assert stub.length == pytest.approx(0.3)
    rec = run(mixed(), accept_fixes=frozenset({trim.id}))
    assert signature(rec) == signature(prop)
    assert len(rec.open_chains) == len(prop.open_chains) - 1
    assert all(c.length != pytest.approx(0.3) for c in rec.open_chains)
    got = by_action(rec, "trim")
    owner = next(p for p in rec.parts if p.outer.bbox[0] == pytest.approx(50.0))
    assert got.accepted is True and got.ids == [owner.outer.id]
    assert by_action(rec, "join").accepted is None and by_action(rec, "close").accepted is None
    # the square with the gap is still open, the lead-in still misses
    assert not any(p.outer.bbox[:2] == pytest.approx((0.0, 0.0)) for p in rec.parts)


def test_close_fix_alone_in_a_mixed_drawing():
    prop = run(mixed())
    close = by_action(prop, "close")
    rec = run(mixed(), accept_fixes=frozenset({close.id}))
    assert signature(rec) == signature(prop)
    assert any(p.outer.bbox[:2] == pytest.approx((0.0, 0.0)) and
               p.outer.area == pytest.approx(400.0) for p in rec.parts)
    assert by_action(rec, "close").accepted is True
    assert by_action(rec, "trim").accepted is None and by_action(rec, "join").accepted is None


def test_flag_ids_are_the_same_for_every_subset_of_accepted_fixes():
    prop = run(mixed())
    under = [f.id for f in prop.flags if f.kind == "under"]
    assert len(under) == 3 and any(f.kind == "over" for f in prop.flags)
    for k in range(1 << len(under)):
        chosen = frozenset(u for i, u in enumerate(under) if k >> i & 1)
        rec = run(mixed(), accept_fixes=chosen)
        assert signature(rec) == signature(prop), chosen
        assert {f.id for f in rec.flags if f.accepted} == chosen
    all_fixed = run(mixed(), close_gaps=True)
    assert signature(all_fixed) == signature(prop)
    assert signature(all_fixed) == signature(run(mixed(), accept_fixes=frozenset(under)))


def test_flag_ids_stable_across_pattern_pieces():
    # two pieces, each with a gap; pieces are recognised separately
    a = S.square_with_gap(0.2)
    b = S.square_with_gap(0.3, x=100.0)
    pieces = {"A": PieceInfo(key="A", name="A", edges=list(range(len(a)))),
              "B": PieceInfo(key="B", name="B", edges=list(range(len(a), len(a) + len(b))))}
    prop = run(a + b, pieces=pieces)
    first = next(f for f in prop.flags if f.gap == pytest.approx(0.2))
    rec = run(a + b, pieces=pieces, accept_fixes=frozenset({first.id}))
    assert signature(rec) == signature(prop)
    (p,) = rec.parts
    assert p.outer.bbox[0] == pytest.approx(0.0)


def test_close_gaps_accepts_everything_as_before():
    rec = run(mixed(), close_gaps=True)
    under = [f for f in rec.flags if f.kind == "under"]
    assert len(under) == 3 and all(f.accepted is True for f in under)
    assert not any(c.length == pytest.approx(0.3) for c in rec.open_chains)
    closed = run(mixed(), accept_fixes=frozenset(f.id for f in under))
    assert sorted(round(p.outer.area, 6) for p in closed.parts) == \
        sorted(round(p.outer.area, 6) for p in rec.parts)
    assert [c.id for c in closed.open_chains] == [c.id for c in rec.open_chains]


def test_unknown_and_contradictory_fix_ids():
    rec = run(two_gaps(), accept_fixes=frozenset({"F99"}))
    assert any(f.code == "unknown-id" and "F99" in f.message for f in rec.findings)
    assert all(f.accepted is None for f in rec.flags)
    with pytest.raises(InputError):
        run(two_gaps(), accept_fixes=frozenset({"F1"}), reject_fixes=frozenset({"F1"}))


def test_cli_accept_fix(tmp_path):
    import argparse

    ezdxf = pytest.importorskip("ezdxf")
    from LeatherCutWorkbench.cli import recognise_cmd

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0.2), (0, 20), (20, 20), (20, 0), (0, 0)])          # 0.2 mm gap
    msp.add_lwpolyline([(100, 0.3), (100, 20), (120, 20), (120, 0), (100, 0)])  # 0.3 mm gap
    path = str(tmp_path / "gaps.dxf")
    doc.saveas(path)

    def call(argv):
        parser = argparse.ArgumentParser()
        recognise_cmd.register(parser.add_subparsers(dest="verb"))
        args = parser.parse_args(["recognise", path, "--json"] + argv)
        return args.func(args).data

    first = call([])
    assert first["counts"]["parts"] == 0 and len(first["flags"]) == 2
    large = next(f["id"] for f in first["flags"] if f["gap"] == pytest.approx(0.3))
    small = next(f["id"] for f in first["flags"] if f["gap"] == pytest.approx(0.2))
    data = call(["--accept-fix", large.lower(), "--reject-fix", small])
    assert data["counts"]["parts"] == 1 and data["counts"]["open_chains"] == 1
    assert data["parts"][0]["bbox"][0] == pytest.approx(100.0)
    assert {f["id"]: f["accepted"] for f in data["flags"]} == {large: True, small: False}
    with pytest.raises(SystemExit):
        call(["--accept-fix", "C3"])
