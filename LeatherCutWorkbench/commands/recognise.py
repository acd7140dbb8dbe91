"""*Recognise*: find parts, holes, lead-ins, open chains and doubtful contours."""

from __future__ import annotations

import FreeCAD
import FreeCADGui as Gui

from ..document import objects
from . import base, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class RecognisePanel(panel.StagePanel):
    UI = "Recognise"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Recognise")
    STAGE = "Recognise"

    def after_run(self) -> None:
        drawing = objects.stage_object(self.job, "Drawing")
        if drawing is not None and FreeCAD.GuiUp:
            drawing.ViewObject.Visibility = False
        base.fit_view()

    def show_result(self) -> None:
        rec = objects.load_data(objects.stage_object(self.job, "Recognition"))
        if rec is None:
            return
        over = sum(1 for f in rec.flags if f.kind == "over")
        under = len(rec.flags) - over
        self.show_status(translate(
            "LeatherCut", "{0} parts ({1} excluded), {2} holes, {3} lead-ins, {4} open chains; "
            "flags: {5} over-recognised, {6} under-recognised").format(
            len(rec.parts), sum(p.excluded for p in rec.parts), sum(len(p.holes) for p in rec.parts),
            sum(len(p.lead_ins) for p in rec.parts), len(rec.open_chains), over, under))


class Recognise(base.Command):
    NAME = "LeatherCut_Recognise"
    ICON = "Recognise"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_Recognise", "Recognise")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_Recognise",
                            "Recognise closed part contours, holes, lead-ins and open chains "
                            "and flag doubtful contours")

    def active(self) -> bool:
        return base.has_stage("Drawing") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(RecognisePanel(base.active_job()))


COMMAND = Recognise
