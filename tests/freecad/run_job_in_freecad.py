"""Run a whole LeatherCut job inside FreeCAD's own interpreter (freecadcmd).

Used by tests/test_freecadcmd_e2e.py:  freecadcmd tests/freecad/run_job_in_freecad.py
with LEATHERCUT_E2E_IN (DXF) and LEATHERCUT_E2E_OUT (folder) in the environment.
freecadcmd exits 0 even when a script raises, so every outcome ends in
os._exit(): 0 with result.json written, 1 with the traceback in error.txt.
"""

import json
import os
import sys
import traceback


def main() -> None:
    src = os.environ["LEATHERCUT_E2E_IN"]
    out = os.environ["LEATHERCUT_E2E_OUT"]
    os.makedirs(out, exist_ok=True)
    try:
        import FreeCAD
        import LeatherCutWorkbench
        from LeatherCutWorkbench.core.job import run_job
        from LeatherCutWorkbench.core.job_report import job_report
        from LeatherCutWorkbench.post import gcode
        from LeatherCutWorkbench.post.profiles import load_profile

        result = run_job(src)
        with open(os.path.join(out, "job.nc"), "w") as fh:
            fh.write(gcode.export(result.plan, load_profile("grblhal_tangential")))
        data = job_report(result)
        data["freecad_version"] = ".".join(FreeCAD.Version()[:3])
        data["package_file"] = LeatherCutWorkbench.__file__
        data["python"] = sys.executable
        with open(os.path.join(out, "result.json"), "w") as fh:
            json.dump(data, fh, indent=2)
    except BaseException:
        with open(os.path.join(out, "error.txt"), "w") as fh:
            fh.write(traceback.format_exc())
        sys.stderr.flush()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)


main()
