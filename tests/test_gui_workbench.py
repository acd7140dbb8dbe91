"""The real FreeCAD GUI under Xvfb: the workbench from DXF to a streamed job.

Starts ``freecad`` (isolated HOME, workbench autoloaded) on
tests/gui/workflow.py, which drives every command through its task panel on
a generated sample job, undoes, saves and reopens (see that script).  The
test fails on a non-zero exit, on any ``Traceback`` in FreeCAD's log (FreeCAD
swallows exceptions inside GUI commands) and when the outputs lack content.
Under CI=true a missing ``xvfb-run`` or ``freecad`` fails instead of skipping.
"""

from __future__ import annotations

import json
import os
import sys

import pytest

TESTS = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, TESTS)
from gui.freecad_gui import missing_tools, run_gui_script  # noqa: E402
from gui.sample import write_sample  # noqa: E402

pytestmark = [pytest.mark.gui, pytest.mark.slow]


def _require_gui_tools():
    tool = missing_tools()
    if tool is not None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{tool} is missing: GUI tests need it (tools/setup.sh installs it)")
        pytest.skip(f"{tool} is missing")


def _run(script: str, tmp_path, sample: str, timeout: float = 240.0):
    out = tmp_path / "out"
    out.mkdir()
    run = run_gui_script(os.path.join(TESTS, "gui", script),
                         {"LC_OUT": str(out), "LC_SAMPLE": sample}, timeout=timeout)
    log = run.log
    (tmp_path / "freecad.log").write_text(log)
    return run, log, out


def test_gui_workflow_from_dxf_to_streamed_job(tmp_path):
    _require_gui_tools()
    sample = write_sample(str(tmp_path / "sample.dxf"))
    run, log, out = _run("workflow.py", tmp_path, sample)
    failed = [line for line in log.splitlines() if line.startswith("CHECK ") and " FAILED: " in line]
    assert run.returncode == 0, "\n".join(failed) or log[-4000:]
    assert "Traceback" not in log, log[log.index("Traceback"):][:3000]
    results = json.loads((out / "result.json").read_text())
    assert len(results) >= 60 and all(r["ok"] for r in results)
    nc = (out / "job.nc").read_text()
    assert "G21" in nc and nc.count("G1") > 20
    assert (out / "job.nc.journal").stat().st_size > 1000
    assert (out / "job.FCStd").stat().st_size > 10000


def test_gui_import_real_sample_via_file_import(tmp_path, samples_dir):
    """File > Import path: the importer registered for .dxf on a real drawing
    (VisiCut sample, 63 parts cut where they lie), then Recognise and Run job."""
    _require_gui_tools()
    sample = os.path.join(samples_dir, "visicut_6_HG2_Korpusinnen_2.dxf")
    run, log, out = _run("import_sample.py", tmp_path, sample, timeout=120.0)
    assert run.returncode == 0, log[-4000:]
    assert "Traceback" not in log, log[log.index("Traceback"):][:3000]
    results = json.loads((out / "result.json").read_text())
    assert all(r["ok"] for r in results), results
