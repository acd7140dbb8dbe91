"""*Auto-nest*: place the parts on sheets, a strip or a hide (task panel with
container, spacing, rotations and time budget; live progress and cancel)."""

from __future__ import annotations

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..document import objects
from . import base, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class NestPanel(panel.StagePanel):
    UI = "AutoNest"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Auto-nest")
    STAGE = "Nest"

    #: container kind -> the fields that apply to it (the others are greyed out)
    FIELDS = {"sheet": ("NestSheetWidth", "NestSheetHeight", "NestSheetCount"),
              "strip": ("NestStripWidth",), "hide": ("NestHideFile", "browseNestHideFile")}

    def __init__(self, job):
        super().__init__(job)
        combo = self.form.findChild(QtGui.QComboBox, "NestContainer")
        combo.currentIndexChanged.connect(lambda _i: self._container_fields(combo.currentText()))
        if job.NestContainer == "none":
            self.set_widget("NestContainer", "sheet")
        self._container_fields(job.NestContainer)

    def _container_fields(self, kind: str) -> None:
        for k, names in self.FIELDS.items():
            for name in names:
                w = self.form.findChild(QtGui.QWidget, name)
                if w is not None:
                    w.setEnabled(k == kind)

    def after_run(self) -> None:
        rec = objects.stage_object(self.job, "Recognition")
        if rec is not None and FreeCAD.GuiUp:
            rec.ViewObject.Visibility = False
        base.fit_view()

    def show_result(self) -> None:
        layout = objects.load_data(objects.stage_object(self.job, "Layout"))
        if layout is None:
            return
        m = layout.metrics or {}
        parts = [translate("LeatherCut", "{0} placed, {1} unplaced").format(
            len(layout.placements), len(layout.unplaced))]
        if "utilisation" in m:
            parts.append(translate("LeatherCut", "utilisation {0:.1f} %").format(
                100.0 * float(m["utilisation"])))
        elif "density" in m:        # strips: item area / used length x width
            parts.append(translate("LeatherCut", "density {0:.1f} %").format(100.0 * float(m["density"])))
        if "strip_length_mm" in m:
            parts.append(translate("LeatherCut", "strip length {0:.1f} mm").format(float(m["strip_length_mm"])))
        parts.append(translate("LeatherCut", "{0} containers").format(len(layout.containers)))
        self.show_status(", ".join(parts))


class AutoNest(base.Command):
    NAME = "LeatherCut_AutoNest"
    ICON = "AutoNest"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_AutoNest", "Auto-nest")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_AutoNest",
                            "Nest the recognised parts on sheets, a strip or a leather hide with defects")

    def active(self) -> bool:
        return base.has_stage("Recognition") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(NestPanel(base.active_job()))


COMMAND = AutoNest
