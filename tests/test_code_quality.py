"""Static check of the project's own Python: no unused imports or variables,
no undefined names (pyflakes).  InitGui.py is left out: FreeCAD injects
``Gui`` and ``Workbench`` into it before it runs."""

import subprocess
import sys

from conftest import REPO_DIR

CHECKED = ["LeatherCutWorkbench", "tests", "bench", "tools", "Init.py"]


def test_pyflakes_finds_nothing():
    proc = subprocess.run([sys.executable, "-m", "pyflakes", *CHECKED], cwd=REPO_DIR,
                          capture_output=True, text=True, timeout=300)
    assert not proc.stderr.strip(), proc.stderr
    assert proc.returncode == 0 and not proc.stdout.strip(), proc.stdout
