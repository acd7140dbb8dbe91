"""``leathercut run`` on the bundled example: the foundation's end-to-end job.

The example (examples/bag.dxf, made by tools/make_example.py) has 7 parts,
6 holes (an elliptical slot and 5 punched circles), 2 lead-ins (a line touching
the flap's corner and an arc touching the strap's edge) and a stitch line on
layer STITCH that is drawn but must not be cut.
"""

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from conftest import REPO_DIR

LEATHERCUT = os.path.join(os.path.dirname(sys.executable), "leathercut")
EXAMPLE = os.path.join(REPO_DIR, "examples", "bag.dxf")


@pytest.fixture(scope="module")
def job(tmp_path_factory):
    out = tmp_path_factory.mktemp("job")
    proc = subprocess.run([LEATHERCUT, "run", EXAMPLE, "-o", str(out)],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return out, proc


def test_run_writes_three_outputs(job):
    out, proc = job
    for name in ("job.nc", "preview.svg", "report.json"):
        assert (out / name).stat().st_size > 100, name
    assert "job.nc" in proc.stdout


def test_report_counts_match_the_drawing(job):
    out, _ = job
    rep = json.loads((out / "report.json").read_text())
    c = rep["counts"]
    assert c["parts"] == 7 and c["parts_excluded"] == 0
    assert c["holes"] == 6
    assert c["lead_ins"] == 2
    # The stitch guide line sits on layer STITCH: drawn, not cut, and said so.
    assert c["open_chains"] == 0
    assert any(w["code"] == "layer-not-cut" and "STITCH" in w["message"] for w in rep["warnings"])
    # Every hole and outline is cut exactly once.
    kinds = [o["kind"] for o in rep["order"]]
    assert kinds.count("outer") == 7 and kinds.count("hole") == 6
    # Cut length: perimeters are known from the drawing (within flattening error).
    back_panel = 2 * (240 + 180)
    assert rep["cut_length_mm"] > back_panel * 4
    assert rep["idle_travel_mm"] > 0


def test_holes_are_cut_before_their_outline(job):
    out, _ = job
    rep = json.loads((out / "report.json").read_text())
    pos = {}
    for o in rep["order"]:
        pos.setdefault(o["part"], []).append((o["n"], o["kind"]))
    for part, cuts in pos.items():
        outer = [n for n, k in cuts if k == "outer"]
        holes = [n for n, k in cuts if k == "hole"]
        assert all(h < outer[0] for h in holes), part


def test_gcode_knife_up_on_rapids_down_on_cuts(job):
    out, _ = job
    lines = [l.split(";")[0].split("(")[0].strip() for l in (out / "job.nc").read_text().splitlines()]
    lines = [l for l in lines if l]
    assert any(l.startswith("G21") or " G21" in l for l in lines)
    assert any("G90" in l for l in lines)
    z = None
    rapids_xy = cuts_xy = 0
    for l in lines:
        words = dict((w[0], w[1:]) for w in l.split() if w[0].isalpha())
        if "Z" in words:
            z = float(words["Z"])
        moves_xy = "X" in words or "Y" in words
        if l.startswith("G0") and moves_xy and not l.startswith("G0 Z"):
            rapids_xy += 1
            assert z is not None and z > 0, f"rapid with knife down: {l}"
        if (l.startswith("G1") or l.startswith("G2") or l.startswith("G3")) and moves_xy:
            cuts_xy += 1
            assert z is not None and z <= 0, f"cut with knife up: {l}"
    assert rapids_xy >= 14 and cuts_xy > 50


def test_preview_svg_shows_parts_order_and_dashed_idle(job):
    out, _ = job
    root = ET.parse(out / "preview.svg").getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    groups = {g.get("id"): g for g in root.findall("s:g", ns)}
    assert len(groups["parts"].findall("s:path", ns)) == 7
    assert groups["idle"].get("stroke-dasharray")
    numbers = [int(t.text) for t in groups["order"].findall("s:text", ns) if t.text.isdigit()]
    rep = json.loads((out / "report.json").read_text())
    assert numbers == list(range(1, len(rep["order"]) + 1))
