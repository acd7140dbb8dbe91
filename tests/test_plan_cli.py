"""``leathercut plan`` on a real DXF (tests/data/samples, see its README)."""

import argparse
import json
import os

import pytest

from LeatherCutWorkbench.cli import plan_cmd
from LeatherCutWorkbench.core.errors import InputError

SAMPLE = "deepnest_ReadMeExampleSmall.dxf"


def _parser():
    p = argparse.ArgumentParser(prog="leathercut")
    sub = p.add_subparsers(dest="verb")
    plan_cmd.register(sub)
    return p


def _run(argv):
    args = _parser().parse_args(argv)
    return args.func(args)


@pytest.fixture
def sample(samples_dir):
    path = os.path.join(samples_dir, SAMPLE)
    if not os.path.isfile(path):
        pytest.skip(f"{SAMPLE} not in tests/data/samples")
    return path


@pytest.mark.slow
def test_plan_json_reports_order_entries_and_metrics(sample):
    rep = _run(["plan", sample, "--json", "--time", "3", "--lift-angle", "20", "--seed", "4"])
    d = json.loads(json.dumps(rep.data))
    assert rep.exit_code == 0
    assert d["method"] == "ga" and d["order"]
    contours = [o["contour"] for o in d["order"]]
    assert len(contours) == len(set(contours))
    for o in d["order"]:
        assert len(o["entry"]) == 2 and o["part"] is not None
    m = d["metrics"]
    for key in ("idle_mm", "cut_mm", "lifts", "est_time_s", "drawing_order_idle_mm", "nn_idle_mm",
                "lower_bound_mm", "gap_to_lower_bound", "precedence_violations", "method", "seed",
                "time_s", "iterations"):
        assert key in m, key
    assert m["seed"] == 4 and m["precedence_violations"] == 0
    assert m["lower_bound_mm"] <= m["idle_mm"] <= m["nn_idle_mm"] + 1e-6
    assert m["lifts"] == sum(o["lifts"] for o in d["order"]) > 0
    assert "idle travel" in rep.text


def test_plan_objective_time_minimises_idle_seconds(sample):
    args = ["plan", sample, "--json", "--iterations", "15", "--time", "600", "--lift-angle", "20"]
    by_time = _run(args + ["--objective", "time"]).data["metrics"]
    by_dist = _run(args).data["metrics"]
    assert by_time["objective"] == "time" and by_dist["objective"] == "distance"
    assert by_time["precedence_violations"] == 0
    # both plans are real: never above nearest neighbour in mm for the distance objective,
    # and the time objective's idle distance stays a plausible tour
    assert by_dist["idle_mm"] <= by_dist["nn_idle_mm"] + 1e-6
    assert by_time["lower_bound_mm"] <= by_time["idle_mm"] <= 2 * by_time["nn_idle_mm"]
    with pytest.raises(SystemExit):
        _parser().parse_args(["plan", sample, "--objective", "money"])


def test_plan_nn_without_knife(sample):
    rep = _run(["plan", sample, "--method", "nn", "--lift-angle", "none"])
    m = rep.data["metrics"]
    assert m["method"] == "nn" and m["lifts"] == 0
    assert m["idle_mm"] == pytest.approx(m["nn_idle_mm"])


def test_missing_file_is_input_error(tmp_path):
    with pytest.raises(InputError):
        _run(["plan", str(tmp_path / "nope.dxf")])


def test_options_get_plan_prefix_when_not_primary():
    p = argparse.ArgumentParser()
    plan_cmd.add_options(p, primary=False)
    a = p.parse_args(["--plan-time", "4", "--plan-method", "aco", "--entry-spacing", "7",
                      "--lift-angle", "25", "--home", "10,-5"])
    a.seed = 9
    o = plan_cmd.options_from_args(a)
    assert (o.time_limit, o.method, o.entry_spacing, o.lift_angle, o.home, o.seed) == \
        (4.0, "aco", 7.0, 25.0, (10.0, -5.0), 9)
    with pytest.raises(SystemExit):
        p.parse_args(["--time", "4"])
    with pytest.raises(SystemExit):
        p.parse_args(["--lift-angle", "200"])


def test_machine_profile_supplies_speeds_and_knife():
    class Machine:
        rapid_feed, cut_feed, acceleration = 30000.0, 4000.0, 800.0
        tool, lift_angle, origin = "tangential_knife", 12.0, (5.0, 7.0)
    p = argparse.ArgumentParser()
    plan_cmd.add_options(p, primary=False)
    a = p.parse_args([])
    o = plan_cmd.options_from_args(a, Machine())
    assert (o.rapid_speed, o.cut_speed, o.accel, o.lift_angle, o.home) == \
        (30000.0, 4000.0, 800.0, 12.0, (-5.0, -7.0))
    a = p.parse_args(["--lift-angle", "none", "--cut-speed", "100"])
    o = plan_cmd.options_from_args(a, Machine())
    assert o.lift_angle is None and o.cut_speed == 100.0


def test_console_entry_exit_codes(sample, tmp_path, capsys):
    from LeatherCutWorkbench.cli import main
    assert main(["plan", str(tmp_path / "missing.dxf")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "missing.dxf" in err
    assert main(["plan", sample, "--method", "nn", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["metrics"]["method"] == "nn" and d["order"]
