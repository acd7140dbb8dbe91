"""*Manual nest*: move and rotate placed parts by hand with collision feedback.

Parts can be moved with the panel's arrows and rotate buttons, by editing
their Placement, or with FreeCAD's transform dragger; every 0.3 s the panel
checks the layout (overlaps, container edge, defects, spacing) and colours
colliding parts red.  OK keeps the changes as one undo step, Cancel restores
the layout.
"""

from __future__ import annotations

from typing import List

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from ..document import pipeline
from . import base, messages, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class ManualNestPanel(panel.JobPropertyPanel):
    UI = "ManualNest"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Manual nest")

    def __init__(self, job):
        super().__init__(job)
        self.step = self.form.findChild(QtGui.QDoubleSpinBox, "moveStep")
        self.angle = self.form.findChild(QtGui.QDoubleSpinBox, "angleStep")
        self.problems = self.form.findChild(QtGui.QListWidget, "problemList")
        self.target_label = self.form.findChild(QtGui.QLabel, "targetLabel")
        moves = {"leftButton": (-1, 0), "rightButton": (1, 0), "upButton": (0, 1), "downButton": (0, -1)}
        for name, (dx, dy) in moves.items():
            self.form.findChild(QtGui.QPushButton, name).clicked.connect(
                lambda _c=False, dx=dx, dy=dy: self.move(dx * self.step.value(), dy * self.step.value()))
        self.form.findChild(QtGui.QPushButton, "rotateCcwButton").clicked.connect(
            lambda: self.rotate(self.angle.value()))
        self.form.findChild(QtGui.QPushButton, "rotateCwButton").clicked.connect(
            lambda: self.rotate(-self.angle.value()))
        self.last_signature = None
        self.timer = QtCore.QTimer()
        self.timer.setInterval(300)
        self.timer.timeout.connect(self.check)
        self.timer.start()
        self.check()

    def targets(self) -> List:
        sel = base.selected("PlacedPart")
        if sel:
            return sel
        placed = pipeline.placed_objects(self.job)
        return placed[:1]

    def move(self, dx: float, dy: float) -> None:
        for o in self.targets():
            pl = o.Placement
            o.Placement = FreeCAD.Placement(pl.Base + FreeCAD.Vector(dx, dy, 0), pl.Rotation)
        self.check()

    def rotate(self, degrees: float) -> None:
        """Rotate each target about the centre of its bounding box."""
        for o in self.targets():
            centre = o.Shape.BoundBox.Center
            rot = FreeCAD.Placement(FreeCAD.Vector(), FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), degrees),
                                    FreeCAD.Vector(centre.x, centre.y, 0))
            o.Placement = rot.multiply(o.Placement)
        self.check()

    def _signature(self):
        return tuple((o.Name, tuple(o.Placement.toMatrix().A)) for o in pipeline.placed_objects(self.job))

    def check(self) -> List[str]:
        """Re-check the layout when a placement changed; colour colliding parts."""
        sig = self._signature()
        names = ", ".join(o.Label for o in self.targets())
        if self.target_label is not None:
            self.target_label.setText(translate("LeatherCut", "Moving: {0}").format(names or "–"))
        if sig == self.last_signature:
            return [self.problems.item(i).text() for i in range(self.problems.count())]
        self.last_signature = sig
        try:
            problems = pipeline.update_collisions(self.job)
        except Exception as exc:  # keep the panel alive; say what failed
            problems = [f"{type(exc).__name__}: {exc}"]
        self.problems.clear()
        self.problems.addItems([messages.for_gui(t) for t in problems])
        ok = not problems
        self.show_status(translate("LeatherCut", "No collisions.") if ok else
                         translate("LeatherCut", "{0} problems: colliding parts are red.").format(len(problems)),
                         error=False)
        return problems

    def run(self) -> None:
        self.check()

    def on_close(self) -> None:
        self.timer.stop()

    def reject(self):
        self.timer.stop()
        ok = super().reject()
        if ok:
            pipeline.update_collisions(self.job)
        return ok


class ManualNest(base.Command):
    NAME = "LeatherCut_ManualNest"
    ICON = "ManualNest"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_ManualNest", "Manual nest")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_ManualNest",
                            "Move and rotate placed parts by hand; colliding parts turn red")

    def active(self) -> bool:
        return base.has_stage("Layout") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(ManualNestPanel(base.active_job()))


COMMAND = ManualNest
