#!/usr/bin/env python3
"""Regenerate the workbench screenshots in docs/img/ from a sample job.

    .venv/bin/python tools/screenshots.py            # writes docs/img/*.png

Starts the real FreeCAD GUI under Xvfb (1280x800 with FreeCAD's default
docks, isolated HOME, see tests/gui/freecad_gui.py) with this file as its macro.  Inside FreeCAD it
builds a job from the generated sample drawing (tests/gui/sample.py: every
contour kind and both flag kinds), runs each stage through its command and
task panel and grabs the whole screen (X root window: the 3D view included)
after each stage.  Needs xvfb-run and freecad (tools/setup.sh installs them).
"""

from __future__ import annotations

import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
IMG_DIR = os.path.join(REPO, "docs", "img")

#: file name -> what the picture shows (docs/WORKBENCH.md uses the same names)
SHOTS = [
    ("01-import.png", "Import DXF: the drawing grouped by layer, import options panel"),
    ("02-recognise.png", "Recognise: parts, holes, lead-ins, open chains and flags in their colours"),
    ("03-flag-over.png", "Flag over-recognised: the scrap square between four parts, include / exclude"),
    ("04-flag-under.png", "Flag under-recognised: a 0.3 mm gap with the proposed bridge, accept / reject"),
    ("05-auto-nest.png", "Auto-nest: parts on a sheet, container and search options"),
    ("06-manual-nest.png", "Manual nest: a part moved onto another turns red, problems listed"),
    ("07-plan-path.png", "Plan path: cuts solid, idle moves dashed, order numbers, entry points, metrics"),
    ("08-simulate.png", "Simulate: the knife (red cone) on its way along the path"),
    ("09-post-process.png", "Post-process: machine profile, format and output file"),
    ("10-send-to-cutter.png", "Send to cutter: streaming to a GRBL controller with journal and resume"),
    ("11-aama-sizes.png", "Recognise on a graded AAMA set: parts named by piece and size, one size to cut"),
]


def launch() -> int:
    """Outside FreeCAD: run FreeCAD under Xvfb with this file as the macro."""
    sys.path.insert(0, os.path.join(REPO, "tests"))
    from gui.freecad_gui import missing_tools, run_gui_script
    tool = missing_tools()
    if tool:
        print(f"screenshots: {tool} is missing (run tools/setup.sh)", file=sys.stderr)
        return 2
    os.makedirs(IMG_DIR, exist_ok=True)
    run = run_gui_script(os.path.abspath(__file__), {"LC_IMG_DIR": IMG_DIR}, timeout=300,
                         size="1280x800x24")
    for line in run.log.splitlines():
        if line.startswith("SHOT") or "Traceback" in line or "Error" in line:
            print(line)
    if run.returncode != 0:
        print(run.log[-3000:], file=sys.stderr)
        print(f"screenshots: FreeCAD exited with {run.returncode}", file=sys.stderr)
        return 1
    print(f"screenshots: wrote {len(SHOTS)} pictures to {IMG_DIR}")
    return 0


def in_freecad() -> None:
    """Inside the FreeCAD GUI: build the sample job stage by stage and grab the screen."""
    import tempfile
    import time
    import traceback

    import FreeCAD
    import FreeCADGui as Gui
    from PySide import QtCore, QtGui

    out = os.environ["LC_IMG_DIR"]

    def pump(seconds: float = 0.3) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            QtGui.QApplication.processEvents()
            time.sleep(0.01)

    def shot(name: str) -> None:
        Gui.updateGui()
        pump(1.0)
        screen = QtGui.QGuiApplication.primaryScreen()
        pix = screen.grabWindow(0)
        path = os.path.join(out, name)
        pix.save(path, "PNG")
        print(f"SHOT {path} {pix.width()}x{pix.height()}", flush=True)

    def fit() -> None:
        view = Gui.ActiveDocument.ActiveView
        view.viewTop()
        view.fitAll()
        pump(0.2)

    def main() -> None:
        code = 1
        try:
            sys.path.insert(0, os.path.join(REPO, "tests"))
            from gui.sample import write_sample
            from LeatherCutWorkbench.commands import import_dxf, panel
            from LeatherCutWorkbench.document import objects, pipeline
            from LeatherCutWorkbench.post.emulator import FakeController

            mw = Gui.getMainWindow()
            mw.setGeometry(0, 0, 1280, 800)      # FreeCAD's default docks, as a user sees them
            Gui.activateWorkbench("LeatherCutWB")
            work = tempfile.mkdtemp(prefix="lc-shots-")
            sample = write_sample(os.path.join(work, "sample.dxf"))
            p = import_dxf.open_import_panel(sample)
            p.preview()
            doc = FreeCAD.ActiveDocument
            job = objects.jobs(doc)[-1]
            fit()
            area = p.form.findChild(QtGui.QScrollArea, "optionsScrollArea")
            area.ensureWidgetVisible(p.form.findChild(QtGui.QWidget, "findingsList"))
            area.horizontalScrollBar().setValue(0)
            shot("01-import.png")
            p.accept()

            Gui.Selection.addSelection(job)
            Gui.runCommand("LeatherCut_Recognise")
            p = panel.CURRENT
            p.preview()
            fit()
            shot("02-recognise.png")
            p.accept()

            Gui.runCommand("LeatherCut_FlagOver")
            pump(0.8)
            shot("03-flag-over.png")
            panel.CURRENT.decide("Exclude")
            panel.CURRENT.reject()
            Gui.runCommand("LeatherCut_FlagUnder")
            pump(0.8)
            panel.CURRENT.zoom()
            pump(0.3)
            shot("04-flag-under.png")
            panel.CURRENT.decide("Accept")
            panel.CURRENT.reject()
            Gui.Selection.clearSelection()

            Gui.runCommand("LeatherCut_AutoNest")
            p = panel.CURRENT
            for prop, value in (("NestContainer", "sheet"), ("NestSheetWidth", 250.0),
                                ("NestSheetHeight", 160.0), ("NestMargin", 3.0), ("NestSpacing", 3.0),
                                ("NestTimeBudget", 3.0)):
                p.set_widget(prop, value)
            p.preview()
            fit()
            shot("05-auto-nest.png")
            p.accept()

            placed = pipeline.placed_objects(job)
            Gui.Selection.addSelection(placed[0])
            Gui.runCommand("LeatherCut_ManualNest")
            p = panel.CURRENT
            shift = placed[1].Shape.BoundBox.Center - placed[0].Shape.BoundBox.Center
            p.move(shift.x * 0.7, shift.y * 0.7)
            p.check()
            Gui.Selection.clearSelection()
            shot("06-manual-nest.png")
            p.reject()

            Gui.runCommand("LeatherCut_PlanPath")
            p = panel.CURRENT
            p.set_widget("PlanTimeLimit", 2.0)
            p.preview()
            layout = objects.stage_object(job, "Layout")
            for o in pipeline.placed_objects(job):
                o.ViewObject.Transparency = 70
            fit()
            shot("07-plan-path.png")
            p.accept()

            Gui.runCommand("LeatherCut_Simulate")
            p = panel.CURRENT
            p.seek(p.timeline.duration * 0.37)
            shot("08-simulate.png")
            p.reject()

            Gui.runCommand("LeatherCut_PostProcess")
            p = panel.CURRENT
            p.set_widget("PostOutputFile", os.path.join(work, "job.nc"))
            p.preview()
            shot("09-post-process.png")
            p.accept()

            from LeatherCutWorkbench.post.profiles import load_profile
            prof = load_profile(job.PostMachine)
            ctrl = FakeController(flavour="grblhal", axes=prof.axes,
                                  wrapped=prof.rotary_axis if prof.rotary_wrap else "", line_time=0.05)
            ctrl.start()
            try:
                Gui.runCommand("LeatherCut_SendToCutter")
                p = panel.CURRENT
                p.port.setText(ctrl.port)
                session = p.start()
                t0 = time.monotonic()
                while session.running and time.monotonic() - t0 < 60:
                    pump(0.1)
                    if session.progress.get("percent", 0) > 40:
                        break
                shot("10-send-to-cutter.png")
                session.abort()
                while session.running and time.monotonic() - t0 < 90:
                    pump(0.1)
                p.poll()
                p.reject()
            finally:
                ctrl.close()
            del layout
            aama = os.path.join(REPO, "tests", "data", "samples", "GMX1016S18_AAMA.DXF")
            FreeCAD.newDocument("Pattern")
            p = import_dxf.open_import_panel(aama)
            p.accept()
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(objects.jobs(FreeCAD.ActiveDocument)[-1])
            Gui.runCommand("LeatherCut_Recognise")
            p = panel.CURRENT
            p.preview()
            fit()
            pump(0.8)
            area = p.form.findChild(QtGui.QScrollArea, "optionsScrollArea")
            area.ensureWidgetVisible(p.form.findChild(QtGui.QWidget, "partsSummary"))
            area.horizontalScrollBar().setValue(0)
            shot("11-aama-sizes.png")
            p.accept()
            code = 0
        except Exception:
            traceback.print_exc()
        sys.stdout.flush()
        os._exit(code)

    QtCore.QTimer.singleShot(500, main)


if __name__ == "__main__":
    sys.exit(launch())
elif "FreeCADGui" in sys.modules and os.environ.get("LC_IMG_DIR"):
    in_freecad()
