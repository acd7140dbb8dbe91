"""G-code of every profile, read back by the interpreter: the traced knife path
must equal the planned one (0.001 mm), the knife must follow the tangent, lift
above the lift angle and never travel down."""

import math

import pytest

from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.model import CutItem, CutPlan
from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.gcode_reader import (GcodeError, interpreter_for, read_program,
                                                   traced_cuts)
from LeatherCutWorkbench.core.errors import InputError
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from post_helpers import arc_mid, dist_to_segment, sample_plan

GCODE_PROFILES = ["grblhal_tangential", "grbl11_knife_z_servo", "linuxcnc_tangential",
                  "flame_plasma"]
TOL = 0.001


def trace(text, profile):
    it = interpreter_for(profile)
    for n, line in enumerate(text.splitlines(), 1):
        it.execute(line, n)
    return it


def heading_of(value, profile):
    """Axis value -> knife heading in degrees."""
    return value * 360.0 / profile.units_per_turn - profile.heading_offset


def ang_diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("name", GCODE_PROFILES)
def test_traced_path_equals_plan(name):
    profile = load_profile(name)
    plan = sample_plan(dx=10, dy=20)
    assert_traced_path_equals_plan(gcode.export(plan, profile), plan, profile)


def assert_traced_path_equals_plan(text, plan, profile):
    lines = text.splitlines()
    segs, order = gcode.segment_map(lines)
    it = trace(text, profile)
    cuts, rapids_down = traced_cuts(it.moves, profile)
    assert rapids_down == [], "a rapid move with the knife down"
    planned = {f"{i}:{j}": s for i, item in enumerate(plan.items, 1)
               for j, s in enumerate(item.segments, 1)}
    assert order == list(planned), "segments out of order or missing"
    # (a) every traced cut lies on the planned segment it is labelled with
    chord = profile.chord_tol if profile.arcs == "split" else TOL
    by_seg = {}
    for m in cuts:
        sid = segs[m.line_no - 1]
        assert sid in planned, f"cut on line {m.line_no} belongs to no segment"
        by_seg.setdefault(sid, []).append(m)
        seg = planned[sid]
        for p in ((m.start["X"], m.start["Y"]), (m.end["X"], m.end["Y"])):
            assert dist_to_segment(p, seg) < TOL, (sid, p)
        if m.kind == "arc":
            mid = arc_mid(m.center, (m.start["X"], m.start["Y"]), (m.end["X"], m.end["Y"]), m.ccw)
            assert dist_to_segment(mid, seg) < TOL
        else:   # a chord of a split arc may leave the arc by the profile's chord tolerance
            mid = ((m.start["X"] + m.end["X"]) / 2, (m.start["Y"] + m.end["Y"]) / 2)
            assert dist_to_segment(mid, seg) < chord + TOL, (sid, mid)
    # (b) every planned segment is traced completely, once, start to end
    seen_order = []
    for m in cuts:
        sid = segs[m.line_no - 1]
        if not seen_order or seen_order[-1] != sid:
            assert sid not in seen_order, f"segment {sid} cut twice"
            seen_order.append(sid)
    assert seen_order == list(planned)
    for sid, seg in planned.items():
        ms = by_seg[sid]
        assert math.dist((ms[0].start["X"], ms[0].start["Y"]), seg.start) < TOL
        assert math.dist((ms[-1].end["X"], ms[-1].end["Y"]), seg.end) < TOL
        for a, b in zip(ms, ms[1:]):
            assert math.dist((a.end["X"], a.end["Y"]), (b.start["X"], b.start["Y"])) < 1e-9
        traced_len = 0.0
        for m in ms:
            if m.kind == "arc":
                r = math.dist(m.center, (m.start["X"], m.start["Y"]))
                a0 = math.atan2(m.start["Y"] - m.center[1], m.start["X"] - m.center[0])
                a1 = math.atan2(m.end["Y"] - m.center[1], m.end["X"] - m.center[0])
                sw = (a1 - a0) % (2 * math.pi) if m.ccw else (a0 - a1) % (2 * math.pi)
                traced_len += r * sw
            else:
                traced_len += math.dist((m.start["X"], m.start["Y"]), (m.end["X"], m.end["Y"]))
        rel = 1e-3 if profile.arcs == "split" else 1e-5
        assert traced_len == pytest.approx(seg.length, rel=rel, abs=TOL), sid
    # (c) tangential knife: heading follows the tangent, small turns while cutting
    if profile.tangential:
        ax = profile.rotary_axis
        # rotary words are rounded too: half a step of the last decimal
        rot_res = 0.5 * 10 ** -profile.decimals * 360.0 / profile.units_per_turn
        for m in cuts:
            h_end = heading_of(m.end[ax], profile)
            if m.kind == "line":
                want = math.degrees(math.atan2(m.end["Y"] - m.start["Y"], m.end["X"] - m.start["X"]))
                length = math.dist((m.start["X"], m.start["Y"]), (m.end["X"], m.end["Y"]))
                # coordinates are rounded to 0.001 mm: the heading of a short
                # piece is known to about 0.0015 / length radians
                assert ang_diff(h_end, want) < math.degrees(0.0015 / length) + rot_res + 0.002, \
                    (m.line_no, m.text)
                turned = abs(heading_of(m.end[ax], profile) - heading_of(m.start[ax], profile))
                assert turned <= profile.lift_angle + 0.01, (m.line_no, m.text)
            else:
                cx, cy = m.center
                rad = math.degrees(math.atan2(m.end["Y"] - cy, m.end["X"] - cx))
                want = rad + (90.0 if m.ccw else -90.0)
                assert ang_diff(h_end, want) < rot_res + 0.01, (m.line_no, m.text)


def test_lift_turn_plunge_above_lift_angle_only():
    profile = load_profile("grblhal_tangential")
    # a 10 degree kink (below 15) and a 90 degree corner (above)
    k = (100 + 50 * math.cos(math.radians(10)), 100 + 50 * math.sin(math.radians(10)))
    segs = [LineSeg((50, 100), (100, 100)), LineSeg((100, 100), k), LineSeg(k, (k[0], k[1] + 50))]
    plan = CutPlan([CutItem("C", "P", "open", (50, 100), segs)])
    lines = gcode.export(plan, profile).splitlines()
    ups = [n for n, l in enumerate(lines) if l == "G0 Z5"]
    # header, one lift at the corner, one after the item
    assert len(ups) == 3
    corner = lines.index("(seg 1:3)")
    assert lines[corner + 1] == "G0 Z5" and lines[corner + 2].startswith("G0 C")
    assert lines[corner + 3].startswith("G1 Z-1.2")
    kink = lines.index("(seg 1:2)")
    assert lines[kink + 1].startswith("G1 X") and " C10" in lines[kink + 1]


def test_shortest_rotation_continuous_axis():
    profile = load_profile("grblhal_tangential")
    # headings 170 then -170: the short way is +20, so C goes 170 -> 190
    a = (200 + 50 * math.cos(math.radians(170)), 100 + 50 * math.sin(math.radians(170)))
    b = (a[0] + 50 * math.cos(math.radians(-170)), a[1] + 50 * math.sin(math.radians(-170)))
    plan = CutPlan([CutItem("C", "P", "open", (200, 100),
                            [LineSeg((200, 100), a), LineSeg(a, b)])])
    text = gcode.export(plan, profile)
    it = trace(text, profile)
    cuts, _ = traced_cuts(it.moves, profile)
    assert [round(m.end["C"], 3) for m in cuts] == [170.0, 190.0]


def test_wrapped_axis_sign_selects_direction():
    profile = load_profile("linuxcnc_tangential")
    # heading 78.69 then a -90 degree turn: LinuxCNC wants C-348.69
    p0 = (100.0, 100.0)
    p1 = (102.0, 110.0)
    h = math.atan2(10, 2)
    p2 = (p1[0] + 10 * math.cos(h - math.pi / 2), p1[1] + 10 * math.sin(h - math.pi / 2))
    plan = CutPlan([CutItem("C", "P", "open", p0, [LineSeg(p0, p1), LineSeg(p1, p2)])])
    text = gcode.export(plan, profile)
    assert "G0 C-348.69" in text
    it = trace(text, profile)
    turns = [m for m in it.moves if m.kind == "rapid" and m.start["X"] == m.end["X"]
             and m.start["C"] != m.end["C"]]
    assert len(turns) == 1 and turns[0].end["C"] - turns[0].start["C"] == pytest.approx(-90, abs=0.01)


def test_line_numbers_and_arcs_split_profile(tmp_path):
    profile = load_profile("grblhal_tangential")
    profile.arcs = "split"
    plan = sample_plan()
    text = gcode.export(plan, profile, gcode.ExportOptions(line_numbers=True))
    body = [l for l in text.splitlines() if not l.startswith("(")]
    assert all(l.startswith(f"N{n} ") for n, l in enumerate(body, 1))
    assert not any(w in ("G2", "G3") for l in body for w in l.split())
    it = read_program(text)
    cuts, _ = traced_cuts(it.moves, profile)
    hole = plan.items[0].segments[0]
    on_hole = [m for m in cuts if abs(math.dist((m.end["X"], m.end["Y"]), hole.center) - 20) < 1e-3]
    assert len(on_hole) > 20      # flattened within chord_tol 0.01 mm


def test_whole_table_is_reachable_for_run_profile():
    profile = load_profile("grblhal_tangential")
    corners = [(2, 2), (2498, 2), (2498, 1598), (2, 1598), (2, 2)]
    plan = CutPlan([CutItem("C", "P", "outer", (2, 2),
                            [LineSeg(a, b) for a, b in zip(corners, corners[1:])])])
    text = gcode.export(plan, profile)
    assert text.startswith("(") and "G21" in text and "G90" in text
    read_program(text)      # accepted by the interpreter


def test_interpreter_rejects_what_grbl_rejects():
    with pytest.raises(GcodeError) as e:
        read_program("G21\nG1 X10\n")
    assert e.value.code == 22
    with pytest.raises(GcodeError) as e:
        read_program("G0 X1 Q7\n")
    assert e.value.code == 36
    with pytest.raises(GcodeError) as e:
        read_program("G0 C90\n", axes="XYZ")
    assert e.value.code == 20
    with pytest.raises(GcodeError) as e:
        read_program("G1 F100\nG2 X10 Y0 I3 J0\n")
    assert e.value.code == 33
    with pytest.raises(GcodeError, match="wrapped"):      # as LinuxCNC 2.9 says
        read_program("G0 C-360\n", wrapped="C")
    it = read_program("G0 C90\nG0 C-0\n", wrapped="C")
    assert it.pos["C"] == 0.0                             # negative turn to 0


def test_planner_lifts_are_honoured_too():
    profile = load_profile("grblhal_tangential")
    k = (100 + 50 * math.cos(math.radians(5)), 100 + 50 * math.sin(math.radians(5)))
    segs = [LineSeg((50, 100), (100, 100)), LineSeg((100, 100), k)]
    plain = gcode.export(CutPlan([CutItem("C", "P", "open", (50, 100), segs)]), profile)
    lifted = gcode.export(CutPlan([CutItem("C", "P", "open", (50, 100), segs, lifts=[1])]),
                          profile)
    assert plain.count("G0 Z5") == 2 and lifted.count("G0 Z5") == 3
    lines = lifted.splitlines()
    at = lines.index("(seg 1:2)")
    assert lines[at + 1:at + 4] == ["G0 Z5", "G0 C5", "G1 Z-1.2 F1500"]


@pytest.mark.parametrize("name", ["grblhal_tangential", "grbl11_knife_z_servo",
                                  "linuxcnc_tangential"])
def test_feed_keeps_xy_speed_while_the_knife_turns(name):
    """GRBL counts rotary units in F: the F word is raised so XY still runs at
    cut_feed (capped at max_feed); LinuxCNC applies F to XY only."""
    profile = load_profile(name)
    it = trace(gcode.export(sample_plan(), profile), profile)
    cuts, _ = traced_cuts(it.moves, profile)
    ax = profile.rotary_axis
    raised = capped = 0
    for m in cuts:
        if m.kind == "arc":
            r = math.dist(m.center, (m.start["X"], m.start["Y"]))
            a0 = math.atan2(m.start["Y"] - m.center[1], m.start["X"] - m.center[0])
            a1 = math.atan2(m.end["Y"] - m.center[1], m.end["X"] - m.center[0])
            xy = r * ((a1 - a0) % (2 * math.pi) if m.ccw else (a0 - a1) % (2 * math.pi))
        else:
            xy = math.dist((m.start["X"], m.start["Y"]), (m.end["X"], m.end["Y"]))
        turn = abs(m.end[ax] - m.start[ax])
        if not profile.rotary_in_feed:
            assert m.feed == profile.cut_feed
            continue
        xy_speed = m.feed * xy / math.hypot(xy, turn)
        if m.feed >= profile.max_feed:
            capped += 1
            assert xy_speed <= profile.cut_feed
        else:
            assert xy_speed == pytest.approx(profile.cut_feed, rel=2e-3), m.text
            raised += m.feed > profile.cut_feed
    if profile.rotary_in_feed and profile.units_per_turn == 360:
        assert raised > 10 and capped > 0


@pytest.mark.parametrize("name", GCODE_PROFILES)
def test_sync_every_segment_profile(name):
    """``sync_every_segment``: a ``G4 P0`` closes every segment, after its last
    cutting move and inside the segment (so its ok proves the segment was
    executed); the traced path still equals the plan.  Shipped profiles keep
    the item syncs only."""
    base = load_profile(name)
    assert base.sync_every_segment is False
    profile = profile_from_dict({**base.to_json(), "sync_every_segment": True})
    plan = sample_plan(dx=10, dy=20)
    plan.items[2].lifts = [3]                      # a planned lift at a segment start too
    text = gcode.export(plan, profile)
    assert_traced_path_equals_plan(text, plan, profile)
    lines = text.splitlines()
    segs, order = gcode.segment_map(lines)
    n_items, n_segs = len(plan.items), len(order)
    plain = gcode.export(plan, base).splitlines()
    assert plain.count("G4 P0") == n_items          # item syncs only
    assert lines.count("G4 P0") == n_items + n_segs
    it = trace(text, profile)
    moving = {m.line_no for m in it.moves if m.kind in ("rapid", "line", "arc")}
    for sid in order:
        body = [n for n, s in enumerate(segs) if s == sid and not lines[n].startswith("(")]
        assert lines[body[-1]] == "G4 P0", sid       # the segment ends with its sync
        assert [lines[n] for n in body].count("G4 P0") == 1, sid
        cuts = [n for n in body if n + 1 in moving]
        assert cuts and cuts[-1] < body[-1], sid     # after the last move of the segment
    # the next segment starts right after the sync (its lift, if any, follows)
    for a, b in zip(order, order[1:]):
        if a.split(":")[0] == b.split(":")[0]:
            last_a = max(n for n, s in enumerate(segs) if s == a)
            assert lines[last_a] == "G4 P0" and lines[last_a + 1] == f"(seg {b})"


def test_sync_every_segment_is_validated(tmp_path):
    data = load_profile("grblhal_tangential").to_json()
    with pytest.raises(InputError, match="sync_every_segment"):
        profile_from_dict({**data, "sync_every_segment": "yes"}, source="bad.json")
    hpgl = load_profile("hpgl_plotter").to_json()
    with pytest.raises(InputError, match="sync_every_segment"):
        profile_from_dict({**hpgl, "sync_every_segment": True}, source="plotter.json")
    assert profile_from_dict({**hpgl, "sync_every_segment": False}).sync_every_segment is False


def test_wrapped_axis_same_angle_is_no_turn():
    """A C word naming the angle the axis is already at (up to float noise of
    the wrapped position, e.g. 870.658 mod 360) does not turn the knife, as in
    LinuxCNC 2.9 (found in a multi-tool job, tests/test_post_rs274.py)."""
    it = read_program("G0 C150.658\nG0 C330.658\nG0 C150.658\nG0 C330.658\nG0 C150.658\n"
                      "G1 X1 C150.658 F100\nG1 X2 C-150.658\n", wrapped="C")
    ends = [round(m.end["C"], 6) for m in it.moves if m.kind in ("rapid", "line")]
    assert ends == [150.658, 330.658, 510.658, 690.658, 870.658, 870.658, 870.658]
