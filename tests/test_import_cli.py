"""``leathercut inspect``: JSON report, text report, exit codes, shared options."""

import argparse
import json
import os
import subprocess
import sys

import pytest

from LeatherCutWorkbench.cli import main
from LeatherCutWorkbench.cli.inspect_cmd import add_options, options_from_args

SAMPLES = os.path.join(os.path.dirname(__file__), "data", "samples")


def run_cli(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_inspect_json_report(capsys):
    code, out, err = run_cli(capsys, "inspect", os.path.join(SAMPLES, "GMX1016S18_AAMA.DXF"), "--json")
    assert code == 0, err
    r = json.loads(out)
    assert r["dxf_version"] == "AC1009" and r["release"] == "R12"
    assert r["units"] == {"unit": "mm", "source": "aama-text", "mm_per_unit": 1.0, "header_insunits": None}
    assert r["entities"]["found"] == {"INSERT": 150, "TEXT": 9}
    assert r["entities"]["after_explosion"]["POLYLINE"] == 1020
    assert r["pattern"] == "aama" and len(r["pieces"]) == 150
    assert {l["name"] for l in r["layers"]} >= {"1", "4", "7", "13"}
    assert len(r["blocks"]) == 150 and all(b["inserts"] == 1 for b in r["blocks"])
    x0, y0, x1, y1 = r["bbox_mm"]
    assert x1 - x0 == pytest.approx(r["size_mm"][0]) and 1500 < r["size_mm"][0] < 1800
    assert set(r["cleanup"]) >= {"zero_length_removed", "duplicates_removed", "overlaps_removed",
                                 "t_junction_splits"}
    assert isinstance(r["warnings"], list) and isinstance(r["findings"], list)


def test_inspect_text_and_skipped_entities(capsys):
    code, out, _ = run_cli(capsys, "inspect", os.path.join(SAMPLES, "acadsharp_sample_AC1015_binary.dxf"))
    assert code == 0
    assert "binary" in out and "units: inch (from header)" in out
    assert "skipped:" in out and "3DSOLID" in out
    code, out, _ = run_cli(capsys, "inspect", os.path.join(SAMPLES, "acadsharp_sample_AC1015_binary.dxf"),
                           "--json")
    r = json.loads(out)
    skipped = {s["type"]: s for s in r["skipped_entities"]}
    assert skipped["3DSOLID"]["handle"] and skipped["3DSOLID"]["reason"].startswith("3-D")


def test_inspect_units_option_and_no_cleanup(capsys):
    path = os.path.join(SAMPLES, "dxf2gcode_1997_simplified_doppelte_linien.dxf")
    code, out, _ = run_cli(capsys, "inspect", path, "--json", "--units", "mm", "--no-cleanup")
    r = json.loads(out)
    assert r["units"]["source"] == "option" and r["cleanup"] is None and r["edges"]["total"] == 908
    code, out, _ = run_cli(capsys, "inspect", path, "--json")
    assert json.loads(out)["edges"]["total"] == 454


def test_bad_input_exits_2_with_one_line(tmp_path, capsys):
    bad = tmp_path / "photo.dxf"
    bad.write_bytes(b"\x89PNG\r\n\x1a\nxxxx")
    code, out, err = run_cli(capsys, "inspect", str(bad))
    assert code == 2 and out == ""
    assert err.strip().count("\n") == 0 and "not a DXF file" in err and str(bad) in err
    code, _, err = run_cli(capsys, "inspect", str(tmp_path / "missing.dxf"))
    assert code == 2 and "file not found" in err
    code, _, err = run_cli(capsys, "inspect", os.path.join(SAMPLES, "WM_SLIM_TANK.DXF"),
                           "--units", "parsec")
    assert code == 2 and "unknown unit" in err


def test_console_script_entry_point():
    exe = os.path.join(os.path.dirname(sys.executable), "leathercut")
    assert os.path.exists(exe), "tools/setup.sh installs the console script into the venv"
    res = subprocess.run([exe, "inspect", os.path.join(SAMPLES, "ezdxf_recover01.dxf"), "--json"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0
    r = json.loads(res.stdout)
    assert r["recovered"] and r["recover_fixes"] == 68


def test_shared_options_for_later_verbs():
    for primary in (True, False):
        p = argparse.ArgumentParser()
        add_options(p, primary)
        args = p.parse_args(["--units", "cm", "--no-cleanup", "--cleanup-tol", "0.05",
                             "--pattern-mode", "off"])
        o = options_from_args(args)
        assert (o.units, o.cleanup, o.tolerance, o.pattern_mode) == ("cm", False, 0.05, "off")
    defaults = options_from_args(argparse.ArgumentParser().parse_args([]))
    assert defaults.units is None and defaults.cleanup and defaults.pattern_mode == "auto"
