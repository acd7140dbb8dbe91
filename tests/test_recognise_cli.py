"""``leathercut recognise FILE --json`` on a DXF written by ezdxf."""

import argparse
import json
import os
import subprocess
import sys

import pytest

ezdxf = pytest.importorskip("ezdxf")
pytest.importorskip("LeatherCutWorkbench.core.dxfimport")

from LeatherCutWorkbench.cli import recognise_cmd  # noqa: E402


@pytest.fixture
def dxf(tmp_path):
    """Pinwheel of four parts around a scrap square, a 40x30 part with a round
    hole and a lead-in, and a square left open by a 0.2 mm gap."""
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    for x, y, w, h in [(0, 0, 20, 10), (20, 0, 10, 20), (10, 20, 20, 10), (0, 10, 10, 20)]:
        msp.add_lwpolyline([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], close=True)
    msp.add_lwpolyline([(100, 0), (140, 0), (140, 30), (100, 30)], close=True)
    msp.add_circle((120, 15), 5)
    msp.add_line((105, -3), (105, 0))
    msp.add_lwpolyline([(200, 0.2), (200, 0), (220, 0), (220, 20), (200, 20), (200, 0.4)])
    path = tmp_path / "job.dxf"
    doc.saveas(path)
    return str(path)


def call(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="verb")
    recognise_cmd.register(sub)
    args = parser.parse_args(["recognise"] + argv)
    return args.func(args)


def test_json_report(dxf):
    rep = call([dxf, "--json"])
    data = json.loads(json.dumps(rep.data))
    c = data["counts"]
    assert c["parts"] == 6 and c["parts_excluded"] == 1 and c["holes"] == 1
    assert c["lead_ins"] == 1 and c["open_chains"] == 1
    assert c["flags_over"] == 1 and c["flags_under"] == 1
    holed = next(p for p in data["parts"] if p["holes"])
    assert holed["net_area"] == pytest.approx(1200 - 3.14159265 * 25, abs=1e-3)
    assert holed["outer_length"] == pytest.approx(140.0)
    assert holed["bbox"] == [100.0, 0.0, 140.0, 30.0]
    assert holed["holes"][0]["area"] == pytest.approx(78.5398, abs=1e-3)
    assert holed["holes"][0]["length"] == pytest.approx(31.4159, abs=1e-3)
    li = holed["lead_ins"][0]
    assert li["start"] == [105.0, -3.0] and li["end"] == [105.0, 0.0] and li["length"] == 3.0
    scrap = next(p for p in data["parts"] if p["excluded"])
    over = next(f for f in data["flags"] if f["kind"] == "over")
    assert over["ids"] == [scrap["outer"]["id"]] and over["reason"]
    under = next(f for f in data["flags"] if f["kind"] == "under")
    assert under["gap"] == pytest.approx(0.2) and len(under["fix"]) == 1
    (chain,) = data["open_chains"]
    assert under["ids"] == [chain["id"]] and chain["length"] == pytest.approx(79.8)
    assert "findings" in data and "F1" in rep.text


def test_close_gaps_and_include(dxf):
    first = call([dxf, "--json"]).data
    scrap_id = next(p["outer"]["id"] for p in first["parts"] if p["excluded"])
    data = call([dxf, "--close-gaps", "--include", scrap_id.lower()]).data
    assert data["counts"]["open_chains"] == 0 and data["counts"]["parts_excluded"] == 0
    assert data["counts"]["parts"] == 7
    assert all(f["accepted"] is not None for f in data["flags"])


def test_bad_options_and_files(dxf, tmp_path):
    with pytest.raises(SystemExit):
        call([dxf, "--exclude", "X7"])
    with pytest.raises(SystemExit):
        call([dxf, "--join-tol", "-1"])
    from LeatherCutWorkbench.core.errors import InputError
    with pytest.raises(InputError):
        call([dxf, "--join-tol", "0"])
    with pytest.raises(InputError):
        call([str(tmp_path / "missing.dxf")])


def test_console_script(dxf):
    exe = os.path.join(os.path.dirname(sys.executable), "leathercut")
    try:
        from LeatherCutWorkbench.cli import build_parser
        build_parser()
    except Exception as exc:  # another verb of the CLI is not there yet
        pytest.skip(f"full CLI not assembled: {exc}")
    out = subprocess.run([exe, "recognise", dxf, "--json"], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["counts"]["parts"] == 6
    bad = subprocess.run([exe, "recognise", dxf + ".nope"], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1


def test_no_unfold_option_reaches_the_stage(samples_dir):
    path = os.path.join(samples_dir, "WM_SLIM_TANK.DXF")
    whole = call([path, "--json"]).data
    half = call([path, "--no-unfold", "--json"]).data
    assert whole["counts"]["parts"] == half["counts"]["parts"] == 28
    a = sum(p["net_area"] for p in whole["parts"])
    b = sum(p["net_area"] for p in half["parts"])
    assert a == pytest.approx(2 * b, rel=1e-6)
    assert any(f["code"] == "half-piece" for f in half["findings"])
