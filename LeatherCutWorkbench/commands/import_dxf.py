"""*Import DXF*: choose a drawing, set the import options, import it into a new
job (edges grouped by layer)."""

from __future__ import annotations

import os
from typing import List, Tuple

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..core.readable import readable_number
from ..document import objects, pipeline
from . import base, messages, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class ImportPanel(panel.StagePanel):
    UI = "ImportDXF"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Import DXF")
    STAGE = "Import"

    #: the panel made the document the job is in (closed again on Cancel)
    made_document = False

    def after_run(self) -> None:
        base.focus_job(self.job)
        base.fit_view()

    def reject(self):
        doc = self.doc
        closed = super().reject()
        if closed and self.made_document and not doc.Objects:
            # once the task dialog is gone: FreeCAD closes the dialog of a document
            # it closes, and would otherwise take the next panel with it
            name = doc.Name
            panel.later(self, lambda: FreeCAD.closeDocument(name)
                        if name in FreeCAD.listDocuments() else None)
        return closed

    def show_result(self) -> None:
        drawing = objects.load_data(objects.stage_object(self.job, "Drawing"))
        if drawing is None:
            return
        layers = {e.src.layer for e in drawing.edges}
        self.show_status(translate("LeatherCut", "{0} edges on {1} layers, {2} marks, units {3} ({4})").format(
            len(drawing.edges), len(layers), len(drawing.marks), drawing.units,
            translate("LeatherCut", UNIT_SOURCES.get(drawing.units_source, drawing.units_source))))
        box = self.form.findChild(QtGui.QListWidget, "findingsList")
        box.clear()
        for level, text in import_findings(drawing):
            item = QtGui.QListWidgetItem(text)
            if level == "warning":
                item.setForeground(QtGui.QBrush(QtGui.QColor("#b45309")))
            elif level == "error":
                item.setForeground(QtGui.QBrush(QtGui.QColor("#c62828")))
            box.addItem(item)


def import_findings(drawing) -> List[Tuple[str, str]]:
    """(level, text) lines for the panel: drawing size and units first, then
    every finding of the import (recovered file, missing units, clean-up,
    layers not cut, ...) worded for the GUI."""
    size = drawing.stats.get("size_mm") if drawing.stats else None
    out = []
    if size:
        out.append(("info", translate("LeatherCut", "Drawing size {0} × {1} mm, units {2} ({3})").format(
            readable_number(size[0]), readable_number(size[1]),
            drawing.units, translate("LeatherCut", UNIT_SOURCES.get(drawing.units_source, drawing.units_source)))))
    if drawing.pieces:
        out.append(("info", translate("LeatherCut", "{0} pattern pieces").format(len(drawing.pieces))))
    for f in drawing.findings:
        out.append((f.level, messages.for_gui(f.message)))
    return out


#: Drawing.units_source -> what the panel says
UNIT_SOURCES = {"header": QT_TRANSLATE_NOOP("LeatherCut", "stated in the file"),
                "aama-text": QT_TRANSLATE_NOOP("LeatherCut", "from the AAMA 'Units:' text"),
                "option": QT_TRANSLATE_NOOP("LeatherCut", "chosen in this panel"),
                "assumed": QT_TRANSLATE_NOOP("LeatherCut", "not stated: assumed")}


def open_import_panel(path: str) -> ImportPanel:
    """Create a job for ``path`` (in the panel's transaction) and open the import panel."""
    panel.ensure_no_dialog()
    made = FreeCAD.ActiveDocument is None
    stem = os.path.splitext(os.path.basename(path))[0]
    doc = FreeCAD.ActiveDocument or FreeCAD.newDocument(fresh_document_name(stem))
    doc.openTransaction("LeatherCut: Import DXF")
    job = pipeline.make_job(doc, os.path.splitext(os.path.basename(path))[0], path)
    p = ImportPanel(job, transaction_open=True)
    p.made_document = made
    panel.show(p)
    return p


_names_used = set()


def fresh_document_name(stem: str) -> str:
    """A document name not used before in this session (FreeCAD matches task
    dialogs to documents by name, so a closed document's name is not reused)."""
    clean = "".join(ch if ch.isalnum() else "_" for ch in stem) or "Job"
    clean = clean if not clean[0].isdigit() else "_" + clean
    name, n = clean, 1
    while name in _names_used or name in FreeCAD.listDocuments():
        n += 1
        name = f"{clean}{n}"
    _names_used.add(name)
    return name


class ImportDXF(base.Command):
    NAME = "LeatherCut_ImportDXF"
    ICON = "ImportDXF"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_ImportDXF", "Import DXF…")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_ImportDXF",
                            "Import a DXF drawing into a new LeatherCut job (edges grouped by layer)")

    def active(self) -> bool:
        return not Gui.Control.activeDialog()

    def run(self) -> None:
        from PySide import QtGui
        start = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/LeatherCut").GetString(
            "LastFolder", os.path.expanduser("~"))
        path, _f = QtGui.QFileDialog.getOpenFileName(
            Gui.getMainWindow(), translate("LeatherCut", "Import DXF"), start,
            translate("LeatherCut", "DXF drawings (*.dxf *.DXF);;All files (*)"))
        if not path:
            return
        FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/LeatherCut").SetString(
            "LastFolder", os.path.dirname(path))
        open_import_panel(path)


COMMAND = ImportDXF
