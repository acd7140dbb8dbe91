"""End to end inside the real ``freecadcmd`` binary.

The workbench is installed the way tools/setup.sh installs it (a symlink in
FreeCAD's user Mod folder, here under an isolated HOME), FreeCAD's own
interpreter imports the package through that Mod folder and runs the whole job
on the bundled example.  freecadcmd exits 0 even when a script raises, so the
script reports through its exit code and files (see tests/freecad/).
"""

import json
import os
import shutil
import subprocess

import pytest

from conftest import REPO_DIR

pytestmark = [pytest.mark.freecadcmd, pytest.mark.slow]


def test_whole_job_runs_inside_freecadcmd(tmp_path):
    freecadcmd = shutil.which("freecadcmd")
    assert freecadcmd, "freecadcmd not installed (tools/setup.sh installs freecad-python3)"
    home = tmp_path / "home"
    mod = home / ".local" / "share" / "FreeCAD" / "Mod"
    mod.mkdir(parents=True)
    os.symlink(REPO_DIR, mod / "LeatherCut")
    out = tmp_path / "out"
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env.update(HOME=str(home), LEATHERCUT_E2E_IN=os.path.join(REPO_DIR, "examples", "bag.dxf"),
               LEATHERCUT_E2E_OUT=str(out))
    proc = subprocess.run([freecadcmd, os.path.join(REPO_DIR, "tests", "freecad",
                                                    "run_job_in_freecad.py")],
                          env=env, cwd=str(tmp_path), capture_output=True, text=True, timeout=300)
    error = out / "error.txt"
    assert proc.returncode == 0, (error.read_text() if error.exists() else "") + proc.stderr[-3000:]
    data = json.loads((out / "result.json").read_text())
    # It really ran inside FreeCAD, from the installed workbench folder.
    assert data["freecad_version"].startswith("0.") or data["freecad_version"].startswith("1.")
    assert data["package_file"].startswith(str(mod / "LeatherCut"))
    assert data["counts"]["parts"] == 7
    assert data["counts"]["holes"] == 6
    assert data["counts"]["lead_ins"] == 2
    assert data["cut_length_mm"] > 3000
    nc = (out / "job.nc").read_text()
    assert "G21" in nc and "G90" in nc
    assert nc.count("G1") > 50
