"""Result recording for the scripts run inside the real FreeCAD GUI.

Each check prints ``CHECK <name> ok`` or ``CHECK <name> FAILED: ...`` (the
pytest side greps the log) and is kept for ``$LC_OUT/result.json``.
:func:`finish` runs the steps, records an exception as a failed check, writes
the file and leaves FreeCAD with ``os._exit`` (0 only when every check passed):
FreeCAD's own exit code does not reflect a failing macro.
"""

import json
import os
import sys
import time
import traceback

T0 = time.monotonic()
results = []


def check(name, cond, detail=""):
    """Record one check; returns ``cond`` so steps can branch on it."""
    results.append({"check": name, "ok": bool(cond), "detail": str(detail)})
    print(f"CHECK {name} {'ok' if cond else 'FAILED: ' + str(detail)} "
          f"[{time.monotonic() - T0:.1f} s]", flush=True)
    return cond


def pump(seconds=0.2):
    """Let the GUI process events for ``seconds``."""
    from PySide import QtGui
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.01)


def finish(steps, out_dir):
    """Run ``steps()``, write ``out_dir/result.json`` and exit FreeCAD."""
    code = 1
    try:
        os.makedirs(out_dir, exist_ok=True)
        steps()
        code = 0 if results and all(r["ok"] for r in results) else 1
    except Exception:
        traceback.print_exc()
        results.append({"check": "no exception", "ok": False, "detail": traceback.format_exc()})
    with open(os.path.join(out_dir, "result.json"), "w") as fh:
        json.dump(results, fh, indent=1)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
