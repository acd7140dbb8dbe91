"""Recognition on real DXF samples (tests/data/samples, licences in its README)."""

import os

import pytest

from LeatherCutWorkbench.core.recognition import RecogniseOptions, recognise

dxfimport = pytest.importorskip("LeatherCutWorkbench.core.dxfimport")


def load(samples_dir, name):
    return dxfimport.read_drawing(os.path.join(samples_dir, name))


def loops(rec, active_only=True):
    parts = rec.active_parts() if active_only else rec.parts
    return sum(1 + len(p.holes) for p in parts)


def test_gmx_aama_every_piece_is_one_closed_part(samples_dir):
    d = load(samples_dir, "GMX1016S18_AAMA.DXF")
    rec = recognise(d)
    assert len(d.pieces) == 150
    assert len(rec.parts) == 150 and not rec.open_chains and not rec.flags
    names = [p.name for p in rec.parts]
    assert len(set(names)) == 150 and all(" size " in n for n in names)
    assert all(p.rotations == [0.0, 180.0] for p in rec.parts)     # every piece has a grain line
    assert all(p.outer.area > 0 and not p.holes for p in rec.parts)
    # notches and drill holes (not the grade-rule points) end up on their pieces
    wanted = sum(1 for m in d.marks if m.src.role == "mark")
    flat = recognise(d, RecogniseOptions(unfold=False))
    assert sum(len(p.marks) for p in flat.parts) == wanted > 0
    # 45 pieces are halves against a fold line: unfolded, their marks mirrored too
    assert sum(1 for f in rec.findings if f.code == "unfolded") == 45
    assert sum(len(p.marks) for p in rec.parts) > wanted


def test_stacked_sizes_are_not_merged_across_pieces(samples_dir):
    d = load(samples_dir, "WM_SLIM_TANK.DXF")
    rec = recognise(d)
    assert len(d.pieces) == 28 and len(rec.parts) == 28
    # graded sizes stacked at one origin: the parts overlap but none is a hole of another
    assert all(p.parent_id is None and not p.holes for p in rec.parts)


def test_doubled_lines_give_six_loops(samples_dir):
    rec = recognise(load(samples_dir, "dxf2gcode_1997_simplified_doppelte_linien.dxf"))
    assert loops(rec) == 6 and not rec.open_chains and not rec.flags


def test_deepnest_plate_is_flagged_over_and_parts_survive(samples_dir):
    d = load(samples_dir, "deepnest_ReadMeExampleSmall.dxf")
    rec = recognise(d)
    over = [f for f in rec.flags if f.kind == "over"]
    assert len(over) == 1 and "sheet border" in over[0].reason
    plate = next(p for p in rec.parts if p.excluded)
    assert over[0].ids == [plate.outer.id]
    assert plate.outer.bbox == pytest.approx((0, 0, 600, 200), abs=0.01)
    act = rec.active_parts()
    assert len(act) >= 12 and sum(len(p.holes) for p in act) >= 13
    assert all(p.outer.area > 0 and all(h.area < 0 for h in p.holes) for p in act)
    # nested parts touch the plate and each other but none crosses another
    assert not [f for f in rec.findings if f.code == "crossing-contours"]
    # the one outline left open by a 0.014 mm gap is flagged under with its bridge
    under = [f for f in rec.flags if f.kind == "under"]
    assert len(under) == 1 and under[0].gap == pytest.approx(0.0139, abs=1e-3)
    closed = recognise(d, RecogniseOptions(close_gaps=True))
    assert len(closed.active_parts()) > len(act)


def test_visicut_micro_gaps_are_under_flags_and_close(samples_dir):
    d = load(samples_dir, "visicut_6_HG2_Korpusinnen_2.dxf")
    rec = recognise(d)
    under = [f for f in rec.flags if f.kind == "under"]
    assert under and all(0 < f.gap <= 0.05 and f.fix for f in under)
    fixed = recognise(d, RecogniseOptions(close_gaps=True))
    assert loops(fixed) > loops(rec) and len(fixed.open_chains) < len(rec.open_chains) / 10
    assert all(f.accepted for f in fixed.flags if f.kind == "under")
    # a larger join tolerance closes the same gaps without any flag
    wide = recognise(d, RecogniseOptions(join_tol=0.1))
    assert not wide.open_chains and not [f for f in wide.flags if f.kind == "under"]


def test_mixed_lines_arcs_ellipses_sample(samples_dir):
    rec = recognise(load(samples_dir, "dxf2gcode_Bogen_Ellipsen_Polylinien_Block.dxf"))
    assert len(rec.parts) >= 50
    kinds = {type(s).__name__ for p in rec.parts for s in p.outer.segments}
    assert {"LineSeg", "ArcSeg"} <= kinds


def test_half_pieces_are_unfolded_about_the_fold_line(samples_dir):
    from LeatherCutWorkbench.core.geometry import dist
    from LeatherCutWorkbench.core.recognition.from_part import signed_path_area

    d = load(samples_dir, "WM_SLIM_TANK.DXF")
    whole = recognise(d)
    half = recognise(d, RecogniseOptions(unfold=False))
    assert sum(1 for f in whole.findings if f.code == "unfolded") == 28
    assert sum(1 for f in half.findings if f.code == "half-piece") == 28
    for p, q in zip(whole.parts, half.parts):
        a, b = signed_path_area(p.outer.segments), signed_path_area(q.outer.segments)
        assert a == pytest.approx(2 * b, rel=1e-6) and b > 0
        segs = p.outer.segments
        assert all(dist(s.end, t.start) < 1e-6 for s, t in zip(segs, segs[1:] + segs[:1]))
        # the fold line is the axis of symmetry: the piece grew on one side only
        assert p.outer.bbox[:3] == pytest.approx(q.outer.bbox[:3], abs=0.05)
        assert p.outer.bbox[3] > q.outer.bbox[3] + 100
