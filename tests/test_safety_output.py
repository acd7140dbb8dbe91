"""Issue #16 item 3: every line the post emits passes one safety check, and a
hostile machine profile is refused when it is loaded, naming the field."""

import json
import math

import pytest

from LeatherCutWorkbench.core.errors import InputError, SafetyError
from LeatherCutWorkbench.core.geometry import LineSeg
from LeatherCutWorkbench.core.model import CutItem, CutPlan
from LeatherCutWorkbench.post import gcode, safety
from LeatherCutWorkbench.post.gcode_reader import read_program
from LeatherCutWorkbench.post.profiles import load_profile


def _profile_file(tmp_path, **fields):
    path = tmp_path / "hostile.json"
    path.write_text(json.dumps(dict({"name": "hostile"}, **fields)))   # NaN/Infinity literals
    return str(path)


def _square_plan(x0=100.0, y0=100.0, size=50.0):
    pts = [(x0, y0), (x0 + size, y0), (x0 + size, y0 + size), (x0, y0 + size), (x0, y0)]
    segs = [LineSeg(a, b) for a, b in zip(pts, pts[1:])]
    item = CutItem(contour_id="C1", part_id="P1", kind="outer", entry=(x0, y0), segments=segs)
    return CutPlan(items=[item])


# ------------------------------------------------------------------ profile at load
@pytest.mark.parametrize("field,value", [
    ("name", "x\nG0 X-9999 Y-9999\nM30"),
    ("name", "job\rM30"),
    ("knife_up", ["G0 Z5\nG0 X-9999 Y-9999"]),
    ("knife_down", ["G1 Z-1 F1000\rG0 X-9999"]),
    ("tool_on", ["M3 S1000\x1b"]),
    ("header", ["G21\x07"]),
    ("footer", ["M2\n"]),
    ("description", "two\nlines"),
    ("name", "a) G0 X-9999 (b"),
    ("name", "a; G0 X-9999"),
])
def test_line_breaks_and_control_characters_are_refused_naming_the_field(tmp_path, field, value):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, **{field: value}))
    assert f"field {field!r}" in err.value.message
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("field,value", [
    ("header", ["G0 X-5000 Y-5000"]),
    ("footer", ["G1 X99999 Y99999"]),
    ("footer", ["G1 X99999 Y99999 F1000"]),
    ("header", ["G91", "G0 X-5000", "G90"]),            # relative motion off the table
    ("footer", ["G2 X0 Y0 I-3000 J0 F1000"]),           # full circle through x = -6000
    ("header", ["G20", "G0 X200 Y10"]),                 # 200 inch = 5080 mm > 2500
    ("header", ["G92 X0 Y0"]),                          # shifts the coordinates
    ("footer", ["G28"]),                                # stored position: unknown
])
def test_header_and_footer_motion_outside_the_table_is_refused(tmp_path, field, value):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, **{field: value}))
    assert f"field {field!r}" in err.value.message


def test_item_templates_may_not_move_in_xy(tmp_path):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, knife_up=["G0 Z5 X10"]))
    assert "'knife_up'" in err.value.message and "X/Y motion" in err.value.message


def test_header_motion_inside_the_table_is_accepted(tmp_path):
    prof = load_profile(_profile_file(tmp_path, header=["G21 G90", "G0 X10 Y20"],
                                      footer=["G0 X0 Y0", "M2"]))
    assert prof.header == ["G21 G90", "G0 X10 Y20"]


@pytest.mark.parametrize("field,value", [
    ("origin", [math.nan, 0]),
    ("origin", [0, math.inf]),
    ("table_size", [math.inf, 1600]),
    ("table_size", [2500, math.nan]),
    ("acceleration", 0),
    ("units_per_turn", 1e-300),
    ("settle_dwell", 1e12),
    ("hpgl_units_per_mm", 0),
    ("chord_tol", 1e-12),
    ("cut_feed", math.nan),
    ("max_feed", 1e308),
    ("baud", 0),
    ("rx_buffer_size", 10 ** 9),
    ("max_line_length", 0),
])
def test_hostile_numbers_are_refused_naming_the_field(tmp_path, field, value):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, **{field: value}))
    assert f"{field!r}" in err.value.message, err.value.message


def test_chord_tol_refusal_gives_the_allowed_range(tmp_path):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, chord_tol=1e-12))
    assert "0.001 .. 1" in err.value.message


def test_z_up_must_lie_above_z_down(tmp_path):
    with pytest.raises(InputError) as err:
        load_profile(_profile_file(tmp_path, z_up=-5.0, z_down=1.0))
    assert "'z_up'" in err.value.message and "above z_down" in err.value.message


@pytest.mark.parametrize("name", ["grblhal_tangential", "grbl11_knife_z_servo",
                                  "linuxcnc_tangential", "flame_plasma", "hpgl_plotter"])
def test_shipped_profiles_pass(name):
    assert load_profile(name).name == name


# ------------------------------------------------------------------ the output check
def test_the_writer_checks_every_line_whoever_added_it():
    """A profile changed after loading (as another writer or a GUI edit could)
    still cannot get a line past the check: the check runs on the finished
    program, not on the profile."""
    prof = load_profile("grblhal_tangential")
    plan = _square_plan()
    assert "G0 X" in gcode.export(plan, prof)
    for field, lines in (("footer", ["G1 X99999 Y99999"]), ("header", ["G0 X-5000 Y-5000"]),
                         ("knife_up", ["G0 Z5", "G0 X-9999 Y-9999"]),
                         ("footer", ["M2\nG0 X-9999"]), ("header", ["G92 X0"])):
        hostile = load_profile("grblhal_tangential")
        setattr(hostile, field, lines)
        with pytest.raises(SafetyError):
            gcode.export(plan, hostile)


def test_profile_name_in_comments_is_sanitised():
    prof = load_profile("grblhal_tangential")
    prof.name = "evil) G0 X-9999 Y-9999 (; M30"
    text = gcode.export(_square_plan(), prof)
    first = text.splitlines()[0]
    assert first.startswith("(") and first.endswith(")") and first.count("(") == 1
    assert ";" not in first
    it = read_program(text, axes=prof.axes)
    xs = [m.end["X"] for m in it.moves if m.kind in ("rapid", "line", "arc")]
    assert min(xs) >= 0.0       # nothing of the name became motion


def test_comment_strips_everything_that_could_end_it():
    assert safety.comment("a(b)c;d\ne\x00f\u00e9g") == "(a b c d e f g)"


@pytest.mark.parametrize("line", ["G0 X10\nG0 X-999", "G0 X10\r", "(open comment G0 X1",
                                  "(nested (comment)) G0 X1", "M3 S1000\x1b", "G0 X1 (caf\u00e9)"])
def test_output_line_form_is_checked(line):
    prof = load_profile("grblhal_tangential")
    with pytest.raises(SafetyError):
        safety.check_lines(["G21 G90", line], prof)


def test_motion_trace_follows_relative_moves_and_arcs():
    prof = load_profile("grblhal_tangential")     # table 2500 x 1600
    safety.check_lines(["G90 G0 X100 Y100", "G91 G1 X100 F1000", "G90"], prof)
    with pytest.raises(SafetyError):
        safety.check_lines(["G90 G0 X2400 Y100", "G91 G1 X200 F1000"], prof)
    with pytest.raises(SafetyError):     # half circle bulging below y = 0
        safety.check_lines(["G0 X100 Y10", "G3 X140 Y10 I20 J0 F1000"], prof)
    safety.check_lines(["G0 X100 Y10", "G2 X140 Y10 I20 J0 F1000"], prof)   # bulges up
    safety.check_lines(["G0 X100 Y30", "G0 X0 Y0"], prof)    # machine zero: the return home


def test_a_ready_program_to_send_gets_the_same_line_form_check():
    """``send FILE.nc`` checks foreign programs with check_program: a control
    character or a second line hidden in one line is refused there too."""
    prof = load_profile("grblhal_tangential")
    safety.check_program(["G21 G90", "G0 X10 Y10"], prof, "ok.nc")
    for bad in ("G0 X10 Y10\x07", "G0 X10\rG0 X-99"):
        with pytest.raises(SafetyError):
            safety.check_program(["G21 G90", bad], prof, "bad.nc")
