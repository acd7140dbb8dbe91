"""Start the real FreeCAD GUI under Xvfb on a script, isolated from the user's set-up.

Used by the GUI tests (tests/test_gui_*.py) and tools/screenshots.py.  The
script runs as a macro once the GUI is up; it must end with ``os._exit(code)``
(FreeCAD does not propagate exceptions from macros).  A temporary HOME holds a
``user.cfg`` that autoloads the LeatherCut workbench (so the Start page, which
crashes as root without a sandbox flag, never loads) and a Mod folder linking
this checkout as ``LeatherCut``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from typing import Dict, Optional

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

USER_CFG = """<?xml version="1.0" encoding="utf-8" standalone="no" ?>
<FCParameters>
  <FCParamGroup Name="Root">
    <FCParamGroup Name="BaseApp">
      <FCParamGroup Name="Preferences">
        <FCParamGroup Name="General">
          <FCText Name="AutoloadModule">LeatherCutWB</FCText>
        </FCParamGroup>
        <FCParamGroup Name="MainWindow">
          <FCBool Name="ShowSplasher" Value="0"/>
        </FCParamGroup>
        <FCParamGroup Name="Mod">
          <FCParamGroup Name="LeatherCut">
            <FCBool Name="NoDialogs" Value="{no_dialogs}"/>
          </FCParamGroup>
        </FCParamGroup>
      </FCParamGroup>
    </FCParamGroup>
  </FCParamGroup>
</FCParameters>
"""


@dataclass
class GuiRun:
    returncode: int
    log: str


def missing_tools() -> Optional[str]:
    """Name of the first missing program needed for GUI runs, or None."""
    for tool in ("xvfb-run", "freecad"):
        if shutil.which(tool) is None:
            return tool
    return None


def make_home(no_dialogs: bool = True) -> str:
    home = tempfile.mkdtemp(prefix="lc-gui-home-")
    cfg_dir = os.path.join(home, ".config", "FreeCAD")
    os.makedirs(cfg_dir)
    with open(os.path.join(cfg_dir, "user.cfg"), "w") as fh:
        fh.write(USER_CFG.format(no_dialogs=1 if no_dialogs else 0))
    mod = os.path.join(home, ".local", "share", "FreeCAD", "Mod")
    os.makedirs(mod)
    os.symlink(REPO, os.path.join(mod, "LeatherCut"))
    return home


def run_gui_script(script: str, env: Dict[str, str], timeout: float = 180.0,
                   no_dialogs: bool = True, size: str = "1280x1024x24") -> GuiRun:
    """Run ``script`` inside ``freecad`` under Xvfb; returns rc and the combined log."""
    home = make_home(no_dialogs)
    full_env = dict(os.environ)
    full_env.update(env)
    full_env.update({"HOME": home, "QTWEBENGINE_CHROMIUM_FLAGS": "--no-sandbox",
                     "LC_REPO": REPO, "PYTHONDONTWRITEBYTECODE": "1"})
    full_env.pop("QT_QPA_PLATFORM", None)
    cmd = ["xvfb-run", "-a", "-s", f"-screen 0 {size}", "freecad", script]
    try:
        proc = subprocess.run(cmd, env=full_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout, cwd=home)
        return GuiRun(proc.returncode, proc.stdout.decode("utf-8", "replace"))
    except subprocess.TimeoutExpired as exc:
        out = (exc.stdout or b"").decode("utf-8", "replace")
        return GuiRun(-9, out + f"\n[timed out after {timeout} s]")
    finally:
        shutil.rmtree(home, ignore_errors=True)
