"""File > Import of a real drawing with the LeatherCut importer, inside the GUI,
then Recognise (panel) and Run job (toolbar command).  Writes
``$LC_OUT/result.json`` and exits 0 only when every check passed."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore

OUT = os.environ["LC_OUT"]
SAMPLE = os.environ["LC_SAMPLE"]


def check_preferences_page():
    """Edit ▸ Preferences ▸ LeatherCut: change the join tolerance, press OK; new jobs use it."""
    from PySide import QtGui
    seen = {}

    def edit_and_accept():
        dialog = QtGui.QApplication.activeModalWidget()
        box = dialog.findChild(QtGui.QDoubleSpinBox, "RecogniseJoinTol") if dialog else None
        seen["found"] = box is not None
        if box is not None:
            box.setValue(0.02)
        if dialog is not None:
            dialog.accept()

    QtCore.QTimer.singleShot(1500, edit_and_accept)
    Gui.showPreferences("LeatherCut", 0)
    check("preferences page has the LeatherCut fields", seen.get("found"), seen)
    value = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/LeatherCut").GetFloat("RecogniseJoinTol")
    check("preference saved", abs(value - 0.02) < 1e-9, value)


def steps():
    from LeatherCutWorkbench.commands import panel
    from LeatherCutWorkbench.document import objects

    Gui.activateWorkbench("LeatherCutWB")
    check_preferences_page()
    doc = FreeCAD.newDocument("Imported")
    # what File > Import does with the "LeatherCut DXF drawing" filter selected
    import importlib
    modules = FreeCAD.getImportType("dxf")
    module = "LeatherCutWorkbench.document.importer"
    check("File > Import offers LeatherCut for .dxf", module in modules, modules)
    importlib.import_module(module).insert(SAMPLE, doc.Name)
    jobs = objects.jobs(doc)
    check("importer made a job", len(jobs) == 1, [o.Name for o in doc.Objects][:10])
    job = jobs[0]
    check("new job takes the preference", abs(job.RecogniseJoinTol - 0.02) < 1e-9, job.RecogniseJoinTol)
    drawing = objects.stage_object(job, "Drawing")
    check("layers imported", drawing is not None and len(drawing.Group) >= 1
          and len(drawing.Group[0].Shape.Edges) > 100,
          [o.Label for o in drawing.Group] if drawing else None)
    Gui.Selection.addSelection(job)
    Gui.runCommand("LeatherCut_Recognise")
    check("recognised", panel.CURRENT.accept())
    rec = objects.load_data(objects.stage_object(job, "Recognition"))
    check("pattern pieces recognised", rec is not None and len(rec.active_parts()) >= 50,
          len(rec.active_parts()) if rec else None)
    job.PlanMethod, job.PlanTimeLimit = "nn", 1.0
    job.PostOutputFile = os.path.join(OUT, "pattern.nc")
    Gui.runCommand("LeatherCut_RunJob")
    check("run job wrote G-code", os.path.isfile(job.PostOutputFile)
          and open(job.PostOutputFile).read().count("G1") > 50)


def main():
    finish(steps, OUT)


QtCore.QTimer.singleShot(500, main)
