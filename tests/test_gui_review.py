"""The real FreeCAD GUI under Xvfb at 1280x800: what an operator reviews
(issue #12 items 4, 5 and "parts a person can read"; see tests/gui/review.py).

Runs with message boxes enabled (the script answers them and checks their
text).  Fails on a non-zero exit, a failed check or any ``Traceback`` in
FreeCAD's log; under CI=true a missing ``xvfb-run`` or ``freecad`` fails.
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


def test_gui_review_at_1280x800(tmp_path, samples_dir):
    tool = missing_tools()
    if tool is not None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{tool} is missing: GUI tests need it (tools/setup.sh installs it)")
        pytest.skip(f"{tool} is missing")
    out = tmp_path / "out"
    out.mkdir()
    sample = write_sample(str(tmp_path / "sample.dxf"))
    run = run_gui_script(os.path.join(TESTS, "gui", "review.py"),
                         {"LC_OUT": str(out), "LC_SAMPLE": sample, "LC_DATA": samples_dir},
                         timeout=300.0, no_dialogs=False, size="1280x800x24")
    log = run.log
    (tmp_path / "freecad.log").write_text(log)
    failed = [line for line in log.splitlines() if line.startswith("CHECK ") and " FAILED: " in line]
    assert run.returncode == 0, "\n".join(failed) or log[-4000:]
    assert "Traceback" not in log, log[log.index("Traceback"):][:3000]
    results = json.loads((out / "result.json").read_text())
    assert len(results) >= 60 and all(r["ok"] for r in results), [r for r in results if not r["ok"]]
