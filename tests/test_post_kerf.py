"""Kerf compensation, cut direction, generated lead-ins and tabs on real
drawings (examples/bag.dxf: lines, arcs, splines, holes, drawn lead-ins;
tests/data/samples/deepnest_ReadMeExampleSmall.dxf: 119 arcs, 18 holes).

The kerf check traces the written G-code back (our reader, and LinuxCNC's
rs274 in test_post_kerf_rs274) and buffers the traced centre line by half
the kerf: the band must touch every drawn outline within 0.02 mm without
entering any part (tests/kerf_helpers.py)."""

import json
import math
import os

import pytest
from shapely.geometry import LineString

from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.core.geometry import ArcSeg, LineSeg, path_points
from LeatherCutWorkbench.core.job import JobOptions, run_job
from LeatherCutWorkbench.core.pathplan import PlanOptions
from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.compensation import apply_to_job, material
from LeatherCutWorkbench.post.cut_direction import is_ccw
from LeatherCutWorkbench.post.kerf import OffsetError, offset_closed
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from kerf_helpers import kerf_deviation, swept_band, traced_moves

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BAG = os.path.join(ROOT, "examples", "bag.dxf")
ARCS = os.path.join(ROOT, "tests", "data", "samples", "deepnest_ReadMeExampleSmall.dxf")
TOL = 0.02


def torch(**over):
    d = load_profile("flame_plasma").to_json()
    d.update(over)
    return profile_from_dict(d, source="test")


def job(path, profile, **plan):
    opts = JobOptions(plan=PlanOptions(method="nn", **plan), move_to_origin=20.0)
    apply_to_job(opts, profile)
    return run_job(path, opts)


# ------------------------------------------------------------------ offsetting
def test_offset_keeps_arcs_exact_and_joins_corners():
    # a 40 x 20 slot with round ends (two lines, two half circles), cut CW
    segs = [LineSeg((0, 0), (40, 0)), ArcSeg((40, 10), 10, -90, 180),
            LineSeg((40, 20), (0, 20)), ArcSeg((0, 10), 10, 90, 180)]
    grown = offset_closed(segs, -1.0)            # CCW loop, right = outside
    arcs = [s for s in grown if isinstance(s, ArcSeg)]
    assert len(arcs) == 2 and all(abs(a.radius - 11.0) < 1e-12 for a in arcs)
    square = [LineSeg((0, 0), (10, 0)), LineSeg((10, 0), (10, 10)),
              LineSeg((10, 10), (0, 10)), LineSeg((0, 10), (0, 0))]
    rnd = offset_closed(square, -1.0, "round")
    ext = offset_closed(square, -1.0, "extended")
    assert sum(isinstance(s, ArcSeg) for s in rnd) == 4        # corner arcs r = 1
    assert all(isinstance(s, LineSeg) for s in ext)
    corners = {(round(x, 9), round(y, 9)) for s in ext for x, y in (s.start, s.end)}
    assert {(-1, -1), (11, -1), (11, 11), (-1, 11)} <= corners
    from shapely.geometry import Polygon
    assert Polygon(path_points(rnd, 0.001)).area == pytest.approx(144 - 4 + math.pi, abs=5e-3)
    assert Polygon(path_points(ext, 0.001)).area == pytest.approx(144, abs=1e-9)


def test_offset_reports_vanishing_and_narrow_features():
    circle = [ArcSeg((0, 0), 2.0, 0, 360)]
    with pytest.raises(OffsetError) as e:
        offset_closed(circle, 2.5)               # inwards of a CCW circle
    assert e.value.reason == "vanishes"
    # 30 x 10 with a 2 mm wide slot 8 mm deep: a 3 mm kerf cannot enter it
    pts = [(0, 0), (30, 0), (30, 10), (16, 10), (16, 2), (14, 2), (14, 10), (0, 10)]
    slot = [LineSeg(a, b) for a, b in zip(pts, pts[1:] + pts[:1])]
    with pytest.raises(OffsetError):
        offset_closed(slot, -1.5)
    assert len(offset_closed(slot, -0.5)) == 14  # 1 mm kerf fits: 8 lines, 6 corner arcs


# ------------------------------------------------------------ the kerf check
@pytest.mark.parametrize("corners", ["round", "extended"])
def test_swept_kerf_touches_every_outline_bag(corners):
    prof = torch(kerf_corners=corners)
    res = job(BAG, prof)
    text = gcode.export(res.plan, prof)
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    dev = kerf_deviation(res.parts_to_cut, band, prof.kerf / 2, TOL)
    assert dev["penetration"] <= TOL, dev
    assert dev["gap"] <= TOL, dev
    assert dev["points"] > 10000
    # arcs of the drawing stay arcs: G2/G3 in the output
    assert sum(1 for ln in text.splitlines() if ln.startswith(("G2 ", "G3 "))) > 20


def spread(parts, gap=20.0):
    """The parts moved apart on a grid (the sample is a nest result whose parts
    touch each other: no kerf fits between them)."""
    from LeatherCutWorkbench.core.geometry import Transform2D
    out, x, y, row = [], 20.0, 20.0, 0.0
    for p in parts:
        x0, y0, x1, y1 = p.outer.bbox
        if x + (x1 - x0) > 1400:
            x, y, row = 20.0, y + row + gap, 0.0
        out.append(p.transformed(Transform2D(dx=x - x0, dy=y - y0)))
        x += x1 - x0 + gap
        row = max(row, y1 - y0)
    return out


def test_swept_kerf_arcs_sample():
    from LeatherCutWorkbench.core.job import load_and_recognise
    from LeatherCutWorkbench.core.pathplan import plan
    from LeatherCutWorkbench.post.compensation import compensate
    prof = torch(kerf=0.5)
    _, rec = load_and_recognise(ARCS, JobOptions())
    parts = spread(rec.active_parts())
    tool_parts, _ = compensate(parts, prof)
    cut = plan(tool_parts, [], PlanOptions(method="nn"))
    text = gcode.export(cut, prof)
    assert sum(1 for ln in text.splitlines() if ln.startswith(("G2 ", "G3 "))) > 100
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    dev = kerf_deviation(parts, band, prof.kerf / 2, TOL)
    assert dev["penetration"] <= TOL and dev["gap"] <= TOL, dev


def test_cut_direction_torch_and_knife():
    from LeatherCutWorkbench.core.geometry import turn_angle
    res = job(BAG, torch())
    by_lead = {f.source for f in res.findings if f.code == "direction-from-lead-in"}
    closed = [it for it in res.plan.items if it.kind in ("outer", "hole")]
    for it in closed:
        body = it.segments[it.lead_in_count:len(it.segments) - it.lead_out_count]
        lead = it.segments[:it.lead_in_count]
        # the lead-in flows into the contour, never against it
        assert turn_angle(lead[-1].end_heading(), body[0].start_heading()) <= 90.0 + 1e-6
        if it.contour_id not in by_lead:
            assert is_ccw(body) == (it.kind == "hole"), it.contour_id
    assert len(by_lead) < len(closed) // 2
    knife = load_profile("grblhal_tangential")
    res_k = job(BAG, profile_from_dict({**knife.to_json(), "outer_direction": "cw"}))
    by_lead = {f.source for f in res_k.findings if f.code == "direction-from-lead-in"}
    for it in res_k.plan.items:
        if it.contour_id in by_lead:
            continue
        if it.kind == "outer":
            assert not is_ccw(it.segments[it.lead_in_count:])
        if it.kind == "hole":          # holes as drawn (clockwise)
            assert not is_ccw(it.segments[it.lead_in_count:])


def test_knife_profiles_are_unchanged():
    """A profile without the new fields plans exactly as before (no hook)."""
    prof = load_profile("grblhal_tangential")
    opts = JobOptions(plan=PlanOptions(method="nn"), move_to_origin=20.0)
    apply_to_job(opts, prof)
    assert opts.prepare is None


# ------------------------------------------------------------------ lead-ins
def test_generated_leadins_clear_parts_and_defects_and_win_when_drawn():
    prof = torch()
    res = job(BAG, prof)
    mats = [material(p) for p in res.parts_to_cut]
    drawn = {li.contour_id for p in res.parts_to_cut for li in p.lead_ins}
    n_generated = 0
    for it in res.plan.items:
        if it.kind not in ("outer", "hole"):
            continue
        assert it.lead_in_count > 0, it.contour_id      # torch: always a lead-in
        lead = it.segments[:it.lead_in_count]
        if it.contour_id in drawn:
            continue
        n_generated += 1
        band = LineString(path_points(lead, 0.01)).buffer(prof.kerf / 2 - 0.005)
        for m in mats:
            assert band.intersection(m).area < 1e-6, it.contour_id
        # on the scrap side: the pierce point is outside every part
        pierce = LineString([lead[0].start, lead[0].start]).buffer(0.01)
        assert all(not m.intersects(pierce) for m in mats)
    assert n_generated >= 8


def test_leadins_avoid_hide_defects_and_report_when_blocked():
    from shapely.geometry import Polygon
    from LeatherCutWorkbench.core.job import arrange, load_and_recognise
    from LeatherCutWorkbench.core.model import Container, Layout
    from LeatherCutWorkbench.post.compensation import job_hook
    prof = torch(lead_in="line", lead_in_angle=90.0, lead_out="none")
    opts = JobOptions(move_to_origin=20.0)
    _, rec = load_and_recognise(BAG, opts)
    _, parts, _ = arrange(rec, opts)
    part = max(parts, key=lambda p: abs(p.outer.area))
    x0, y0, x1, y1 = part.outer.bbox
    xm = (x0 + x1) / 2
    half = [(x0 - 50, y0 - 50), (xm, y0 - 50), (xm, y1 + 50), (x0 - 50, y1 + 50)]
    hook = job_hook(prof)
    out, findings = hook([part], Layout(containers=[Container("h", "hide", half, [half])]))
    gen = [li for li in out[0].lead_ins if li.contour_id == part.outer.id]
    assert gen, "the right half is free: some entries must remain"
    blocked = Polygon(half)
    for li in gen:
        assert not LineString(path_points(li.segments, 0.01)).buffer(prof.kerf / 2).intersects(
            blocked.buffer(-0.01))
    # a defect all round the outer: no lead-in fits, and that is reported
    allround = list(material(part).buffer(30.0).exterior.coords)
    out, findings = hook([part], Layout(containers=[Container("h", "hide", half, [allround])]))
    assert any(f.code == "no-lead-in" and f.source == part.outer.id for f in findings)
    assert not [li for li in out[0].lead_ins if li.contour_id == part.outer.id]


# ------------------------------------------------------------------ tabs
def test_tabs_leave_uncut_gaps_on_outers_only():
    prof = torch(tab_count=3, tab_width=2.0)
    res = job(BAG, prof)
    text = gcode.export(res.plan, prof)
    lines = text.splitlines()
    outers = [it for it in res.plan.items if it.kind == "outer"]
    # 3 tabs per outer contour: M5 ... M3 pairs inside each outer item
    ons = sum(1 for ln in lines if ln.startswith("M3"))
    assert ons == len(res.plan.items) + 3 * len(outers)
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    uncut = 0.0
    for p in res.parts_to_cut:
        ring = LineString(p.outer.points(0.001) + [p.outer.points(0.001)[0]])
        uncut += ring.difference(band.buffer(0.005)).length
    # each tab leaves 2 mm of outline uncut, less the chord the 0.005 mm
    # tolerance band of the cut's round ends covers
    d = prof.kerf / 2
    per_tab = 2.0 - 2 * math.sqrt((d + 0.005) ** 2 - d ** 2)
    assert uncut == pytest.approx(3 * per_tab * len(outers), rel=0.05)


# ------------------------------------------------------------------ bad input
def test_kerf_larger_than_a_feature_is_refused_from_cli(tmp_path, capsys):
    from LeatherCutWorkbench.cli import main
    prof = load_profile("flame_plasma").to_json()
    prof.update(name="fat_torch", kerf=12.0)
    path = tmp_path / "fat_torch.json"
    path.write_text(json.dumps(prof))
    out = tmp_path / "out"
    rc = main(["run", BAG, "-o", str(out), "--machine", str(path), "--move-to-origin", "20",
               "--plan-method", "nn"])
    err = capsys.readouterr().err
    assert rc == 2
    assert "profile field kerf" in err and "contour" in err
    assert "Traceback" not in err
    assert not (out / "job.nc").exists()


@pytest.mark.parametrize("field,value", [("kerf_mode", "controller"), ("kerf_corners", "sharp"),
                                         ("lead_in", "spiral"), ("lead_in_angle", 0.0),
                                         ("kerf", -1.0), ("tab_width", 0.0)])
def test_bad_compensation_fields_name_the_field(field, value):
    d = load_profile("flame_plasma").to_json()
    d[field] = value
    if field == "tab_width":
        d["tab_count"] = 2
    with pytest.raises(InputError) as e:
        profile_from_dict(d, source="t.json")
    assert field in e.value.message


def test_nesting_reserves_kerf_and_leadin_room():
    from LeatherCutWorkbench.core.nesting.options import ContainerSpec, NestOptions
    prof = torch()
    opts = JobOptions(nest=NestOptions(container=ContainerSpec.sheet(1000, 1000), spacing=1.0))
    apply_to_job(opts, prof)
    # kerf 1.5 + an arc lead-in of 5 mm over 90 degrees reaching r = 3.18 mm out
    assert opts.nest.spacing == pytest.approx(1.0 + 1.5 + 5.0 / (math.pi / 2), abs=1e-6)


def test_flame_job_end_to_end_from_cli(tmp_path, capsys):
    """``leathercut run`` with a torch profile: job.nc passes the kerf check,
    the preview shows the compensated path, lead-ins, lead-outs and tabs."""
    from LeatherCutWorkbench.cli import main
    d = load_profile("flame_plasma").to_json()
    d.update(name="flame_tabs", tab_count=2, tab_width=1.5)
    path = tmp_path / "flame_tabs.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "out"
    rc = main(["run", BAG, "-o", str(out), "--machine", str(path), "--move-to-origin", "20",
               "--plan-method", "nn", "--json"])
    assert rc == 0, capsys.readouterr().err
    svg = (out / "preview.svg").read_text()
    assert svg.count('class="tab"') == 2 * 7           # 7 outer contours
    assert svg.count('class="lead-in"') == 13 and svg.count('class="lead-out"') >= 11
    prof = load_profile(str(path))
    text = (out / "job.nc").read_text()
    assert "G41" not in text                          # pre-offset path
    report = json.loads((out / "report.json").read_text())
    assert report["machine"] == "flame_tabs"
    tp = report["tool_path"]
    assert tp["kerf_mm"] == 1.5 and tp["outer_direction"] == "cw" and tp["tabs"] == 14
    assert tp["items_with_lead_in"] == 13 and tp["closed_items_without_lead_in"] == []
    # without tabs the same job's band touches every outline (checked above);
    # with tabs the band still never enters a part
    res = job(BAG, prof)
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    assert kerf_deviation(res.parts_to_cut, band, prof.kerf / 2, TOL)["penetration"] <= TOL


def test_nested_flame_job_keeps_room_for_kerf_and_leads():
    """Nested on a sheet with the spacing the profile reserves: every contour
    gets a collision-free lead-in, drawn lead-ins that nesting moved into a
    neighbour are replaced (and reported), and the kerf check holds."""
    from LeatherCutWorkbench.core.nesting.options import ContainerSpec, NestOptions
    prof = torch()
    nest = NestOptions(container=ContainerSpec.sheet(1200, 800), spacing=1.0, margin=2.0,
                       time_budget=0, rotation_step=90, workers=1)
    opts = JobOptions(plan=PlanOptions(method="nn"), nest=nest)
    apply_to_job(opts, prof)
    res = run_job(BAG, opts)
    assert not res.layout.unplaced
    codes = [f.code for f in res.findings]
    assert "no-lead-in" not in codes
    assert all(it.lead_in_count > 0 for it in res.plan.items)
    text = gcode.export(res.plan, prof)
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    dev = kerf_deviation(res.parts_to_cut, band, prof.kerf / 2, TOL)
    assert dev["penetration"] <= TOL and dev["gap"] <= TOL, (dev, codes)


def test_offset_of_joins_meeting_to_a_micron_is_accepted():
    """Regression: the first part of dxf2gcode_Bogen_Ellipsen_Polylinien_Block.dxf
    as nested (a 90 degree arc and two lines); the corner arcs overshoot by
    2e-11 degrees and the ring then backtracked 1e-13 mm, which was refused
    as 'the offset path crosses itself'."""
    segs = [ArcSeg((645.6801000000005, 459.6136999999999), 635.0000000000005, 225.0, -90.0),
            LineSeg((196.66729394654294, 908.6265060534579), (645.6801, 459.6136999999999)),
            LineSeg((645.6801, 459.6136999999999), (196.6672939465425, 10.600893946541873))]
    out = offset_closed(segs, 0.75)
    assert sum(isinstance(s, ArcSeg) for s in out) == 4
    assert [s.radius for s in out if isinstance(s, ArcSeg)][0] == pytest.approx(635.75)


def test_knife_with_optional_lead_ins():
    """A tangential knife asks for line lead-ins: they are generated on the
    scrap side, clear of every part, and the contours keep the drawn direction."""
    knife = load_profile("grblhal_tangential").to_json()
    knife.update(lead_in="line", lead_in_length=4.0, lead_in_angle=30.0)
    prof = profile_from_dict(knife, source="test")
    res = job(BAG, prof)
    mats = [material(p) for p in res.parts_to_cut]
    drawn = {li.contour_id for p in res.parts_to_cut for li in p.lead_ins}
    unled = {f.source for f in res.findings if f.code == "no-lead-in"}
    assert len(unled) <= 2
    for it in res.plan.items:
        assert (it.lead_in_count > 0) != (it.contour_id in unled)
        assert it.lead_out_count == 0
        body = it.segments[it.lead_in_count:]
        if it.contour_id not in drawn:
            assert is_ccw(body) == (it.kind == "outer")        # as drawn
            if it.contour_id in unled:
                continue
            # the lead ends on the contour: it touches its own part only there
            band = LineString(path_points(it.segments[:1], 0.01)).buffer(0.005)
            assert not any(band.intersects(m.buffer(-0.01)) for m in mats)


def test_offset_every_contour_of_an_arc_sample():
    """All 30 contours of the deepnest sample (lines and 119 arcs, micro-gaps)
    offset to the scrap side: with a 1.5 mm kerf every one succeeds (a corner
    arc next to a short consumed piece used to be extended past its corner and
    the path refused as self-crossing, contour C17); with 3 mm the contours too
    small or too narrow are reported, none dropped silently."""
    from LeatherCutWorkbench.core.job import load_and_recognise
    from LeatherCutWorkbench.post.cut_direction import oriented, scrap_on_left
    _, rec = load_and_recognise(ARCS, JobOptions())
    prof = torch()
    results = {}
    for kerf in (1.5, 3.0):
        res = results.setdefault(kerf, {})
        for p in rec.active_parts():
            for kind, c in [("hole", h) for h in p.holes] + [("outer", p.outer)]:
                segs = oriented(c.segments, kind, prof)
                d = kerf / 2 if scrap_on_left(segs, kind) else -kerf / 2
                try:
                    out = offset_closed(segs, d)
                    res[c.id] = "ok"
                    n_arcs = sum(isinstance(s, ArcSeg) for s in segs)
                    assert sum(isinstance(s, ArcSeg) for s in out) >= n_arcs - 2
                except OffsetError as exc:
                    res[c.id] = exc.reason
    assert list(results[1.5].values()).count("ok") == len(results[1.5]) == 30
    assert results[1.5]["C17"] == "ok"
    bad = {k: v for k, v in results[3.0].items() if v != "ok"}
    assert sorted(bad.values()) == ["splits", "vanishes", "vanishes"]
