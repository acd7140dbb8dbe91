"""*Run job*: the whole pipeline (import, recognise, nest when a container is
set, plan, post-process) on the active job, or on a DXF chosen now."""

from __future__ import annotations

import os

import FreeCAD
import FreeCADGui as Gui

from ..document import pipeline
from . import base, runner

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


def run_job(job) -> str:
    """Run every stage on ``job`` as one undo step; returns the machine file written."""
    with base.transaction(job.Document, "LeatherCut: Run job"):
        out = runner.run_stage(job, "RunJob")
    job.Document.recompute()
    base.fit_view()
    return out


def run_file(path: str):
    """Make a job for ``path`` in the active (or a new) document and run it; returns the job."""
    doc = FreeCAD.ActiveDocument or FreeCAD.newDocument()
    with base.transaction(doc, "LeatherCut: Run job"):
        job = pipeline.make_job(doc, os.path.splitext(os.path.basename(path))[0], path)
        runner.run_stage(job, "RunJob")
    doc.recompute()
    base.focus_job(job)
    base.fit_view()
    return job


class RunJob(base.Command):
    NAME = "LeatherCut_RunJob"
    ICON = "RunJob"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_RunJob", "Run job")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_RunJob",
                            "Run the whole job from the DXF to the machine file with the job's options "
                            "(asks for a DXF when there is no job)")

    def active(self) -> bool:
        return not Gui.Control.activeDialog()

    def run(self) -> None:
        job = base.active_job()
        if job is None or not job.SourceFile:
            from PySide import QtGui
            path, _f = QtGui.QFileDialog.getOpenFileName(
                Gui.getMainWindow(), translate("LeatherCut", "Run job"), "",
                translate("LeatherCut", "DXF drawings (*.dxf *.DXF)"))
            if not path:
                return
            job = run_file(path)
        else:
            run_job(job)
        base.show_info(translate("LeatherCut", "Run job"),
                       translate("LeatherCut", "Machine file written: {0}").format(job.PostLastOutput))


COMMAND = RunJob
