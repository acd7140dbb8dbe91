"""*Post-process*: write the planned job as G-code, HPGL or DXF for a machine profile."""

from __future__ import annotations

import os

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..document import objects, pipeline
from . import base, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


def profile_names():
    from ..post.profiles import list_profiles
    return [p["name"] for p in list_profiles()]


class PostPanel(panel.StagePanel):
    UI = "PostProcess"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Post-process")
    STAGE = "Post"

    def __init__(self, job):
        combo = None
        super().__init__(job)
        combo = self.form.findChild(QtGui.QComboBox, "PostMachine")
        current = job.PostMachine
        combo.blockSignals(True)
        combo.clear()
        combo.addItems(profile_names())
        combo.setEditText(current)
        combo.blockSignals(False)
        if not job.PostOutputFile:
            self.set_widget("PostOutputFile", pipeline.default_output(job))
        combo.currentIndexChanged.connect(lambda _i: self._match_format())
        edit = self.form.findChild(QtGui.QLineEdit, "PostToolMap")
        if edit is not None:
            edit.editingFinished.connect(self.show_tools)
        self.show_tools()

    def show_tools(self) -> None:
        """The effective role -> tool map (profile tool_map + PostToolMap) and
        the machine's tools, or why the map is refused."""
        label = self.form.findChild(QtGui.QLabel, "toolMapLabel")
        if label is None:
            return
        try:
            from ..post.profiles import load_profile
            from ..post.tools import declared_tools, describe, parse_tool_map, tool_map
            prof = load_profile(self.job.PostMachine)
            mapping = tool_map(prof, parse_tool_map(getattr(self.job, "PostToolMap", "") or "", "PostToolMap"),
                               "PostToolMap")
            label.setText(translate("LeatherCut", "Tools: {0}. Roles: {1}.").format(
                ", ".join(f"{t.name} ({t.kind})" for t in declared_tools(prof).values()),
                describe(mapping)))
        except Exception as exc:
            label.setText(str(exc))

    def _match_format(self) -> None:
        """Plotter profiles write HPGL, the others G-code (the user may still choose DXF)."""
        try:
            from ..post.profiles import load_profile
            dialect = load_profile(self.job.PostMachine).dialect
        except Exception:
            return
        self.show_tools()
        if dialect == "hpgl" and self.job.PostFormat == "gcode":
            self.set_widget("PostFormat", "hpgl")
        elif dialect != "hpgl" and self.job.PostFormat == "hpgl":
            self.set_widget("PostFormat", "gcode")
        out = self.job.PostOutputFile
        if out:
            self.set_widget("PostOutputFile", os.path.splitext(out)[0]
                            + pipeline.POST_EXTENSIONS.get(self.job.PostFormat, ".nc"))

    def show_result(self) -> None:
        path = self.job.PostLastOutput
        if path and os.path.isfile(path):
            with open(path, "r", encoding="utf-8", errors="replace") as fh:
                lines = fh.read().count("\n")
            self.show_status(translate("LeatherCut", "Wrote {0} ({1} lines).").format(path, lines))


class PostProcess(base.Command):
    NAME = "LeatherCut_PostProcess"
    ICON = "PostProcess"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_PostProcess", "Post-process…")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_PostProcess",
                            "Write the planned job as a machine file (G-code, HPGL or DXF) for a machine profile; "
                            "moves outside the table or unsafe feeds are refused")

    def active(self) -> bool:
        return base.has_stage("CutPath") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        job = base.active_job()
        if objects.stage_object(job, "CutPath").OutOfDate:
            FreeCAD.Console.PrintWarning(translate(
                "LeatherCut", "LeatherCut: the cut path is out of date; plan the path again first.") + "\n")
        panel.show(PostPanel(job))


COMMAND = PostProcess
