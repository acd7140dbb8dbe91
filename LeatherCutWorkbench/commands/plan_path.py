"""*Plan path*: order the cuts and choose entry points; metrics in the panel."""

from __future__ import annotations

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..document import objects
from . import base, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate

#: metric key -> (label, unit, format) shown in the panel's metrics table when present
METRICS = [
    ("idle_mm", QT_TRANSLATE_NOOP("LeatherCut", "Idle travel"), "mm", "{:.1f}"),
    ("cut_mm", QT_TRANSLATE_NOOP("LeatherCut", "Cut length"), "mm", "{:.1f}"),
    ("lifts", QT_TRANSLATE_NOOP("LeatherCut", "Knife lifts"), "", "{:d}"),
    ("est_time_s", QT_TRANSLATE_NOOP("LeatherCut", "Estimated time"), "s", "{:.1f}"),
    ("drawing_order_idle_mm", QT_TRANSLATE_NOOP("LeatherCut", "Idle travel, drawing order"), "mm", "{:.1f}"),
    ("nn_idle_mm", QT_TRANSLATE_NOOP("LeatherCut", "Idle travel, nearest neighbour"), "mm", "{:.1f}"),
    ("lower_bound_mm", QT_TRANSLATE_NOOP("LeatherCut", "Idle travel lower bound"), "mm", "{:.1f}"),
    ("idle_saving_vs_drawing_order", QT_TRANSLATE_NOOP("LeatherCut", "Saving vs drawing order"), "", "{:.1%}"),
    ("time_s", QT_TRANSLATE_NOOP("LeatherCut", "Planning time"), "s", "{:.2f}"),
]

#: why the search ended (metrics["stopped_by"]) -> panel text; "time" means a faster
#: machine or a longer budget could still find a shorter path
STOP_REASONS = {
    "converged": QT_TRANSLATE_NOOP("LeatherCut", "converged"),
    "iterations": QT_TRANSLATE_NOOP("LeatherCut", "iteration budget reached"),
    "time": QT_TRANSLATE_NOOP("LeatherCut", "time budget reached (not converged)"),
}


def metric_rows(metrics: dict):
    """(label, text) rows for every metric the plan reports, known ones first."""
    rows = []
    seen = set()
    for key, label, unit, fmt in METRICS:
        if key in metrics and isinstance(metrics[key], (int, float)):
            v = metrics[key]
            text = fmt.format(int(v)) if fmt == "{:d}" else fmt.format(float(v))
            unit = "" if fmt == "{:.1%}" else unit
            rows.append((translate("LeatherCut", label), f"{text} {unit}".strip()))
            seen.add(key)
    if metrics.get("stopped_by") in STOP_REASONS:
        rows.append((translate("LeatherCut", "Search ended"),
                     translate("LeatherCut", STOP_REASONS[metrics["stopped_by"]])))
    for key, v in sorted(metrics.items()):
        if key not in seen and isinstance(v, (int, float)) and not isinstance(v, bool):
            rows.append((key.replace("_", " "), f"{v:.4g}" if isinstance(v, float) else str(v)))
    return rows


class PlanPanel(panel.StagePanel):
    UI = "PlanPath"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Plan path")
    STAGE = "Plan"
    MACHINE_FIELDS = ("PlanLiftAngle", "PlanRapidSpeed", "PlanCutSpeed", "PlanAccel")

    def __init__(self, job):
        super().__init__(job)
        box = self.form.findChild(QtGui.QCheckBox, "PlanFromMachine")
        box.toggled.connect(self._machine_fields)
        self._machine_fields(box.isChecked())

    def _machine_fields(self, from_machine: bool) -> None:
        """Speeds and lift angle come from the machine profile when asked: grey them out."""
        for name in self.MACHINE_FIELDS:
            w = self.form.findChild(QtGui.QWidget, name)
            if w is not None:
                w.setEnabled(not from_machine)

    def show_result(self) -> None:
        obj = objects.stage_object(self.job, "CutPath")
        plan = objects.load_data(obj)
        if plan is None:
            return
        table = self.form.findChild(QtGui.QTableWidget, "metricsTable")
        rows = [(translate("LeatherCut", "Contours cut"), str(len(plan.items))),
                (translate("LeatherCut", "Method"), plan.method)] + metric_rows(plan.metrics or {})
        table.setRowCount(len(rows))
        table.setColumnCount(2)
        for r, (label, text) in enumerate(rows):
            table.setItem(r, 0, QtGui.QTableWidgetItem(label))
            table.setItem(r, 1, QtGui.QTableWidgetItem(text))
        table.resizeColumnsToContents()
        self.show_status(translate("LeatherCut", "Planned {0} contours.").format(len(plan.items)))


class PlanPath(base.Command):
    NAME = "LeatherCut_PlanPath"
    ICON = "PlanPath"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_PlanPath", "Plan path")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_PlanPath",
                            "Order the cuts and choose entry points (holes first, lead-ins respected); "
                            "shows cutting moves, idle moves dashed, order numbers and entry points")

    def active(self) -> bool:
        return base.has_stage("Recognition") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(PlanPanel(base.active_job()))


COMMAND = PlanPath
