"""*Simulate*: animate the knife along the planned path (cutting and idle moves)
in the planner's estimated machine time (speeds, acceleration, knife lifts)
times a speed-up factor."""

from __future__ import annotations

import time

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from ..document import objects, pipeline
from . import base, panel
from .timeline import timeline_of

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class SimulatePanel:
    """Play / pause / stop, speed-up factor and a position slider."""

    def __init__(self, job):
        self.job = job
        self.obj = objects.stage_object(job, "CutPath")
        plan = pipeline.stored_plan(job)
        self.timeline = timeline_of(job)
        self.items = len(plan.items)
        self.form = panel.load_form("Simulate")
        self.slider = self.form.findChild(QtGui.QSlider, "positionSlider")
        self.slider.setRange(0, 1000)
        self.speed = self.form.findChild(QtGui.QDoubleSpinBox, "speedFactor")
        self.label = self.form.findChild(QtGui.QLabel, "statusLabel")
        self.form.findChild(QtGui.QPushButton, "playButton").clicked.connect(self.play)
        self.form.findChild(QtGui.QPushButton, "pauseButton").clicked.connect(self.pause)
        self.form.findChild(QtGui.QPushButton, "stopButton").clicked.connect(self.stop)
        self.slider.sliderMoved.connect(lambda v: self.seek(v / 1000.0 * self.timeline.duration))
        self.t = 0.0
        self.wall = None
        self.timer = QtCore.QTimer()
        self.timer.setInterval(40)
        self.timer.timeout.connect(self.tick)
        size = max(self._extent() / 25.0, 2.0)
        self.knife_size = size
        self.seek(0.0)

    def _extent(self) -> float:
        xs = [p[0] for p in self.timeline.points]
        ys = [p[1] for p in self.timeline.points]
        return max(max(xs) - min(xs), max(ys) - min(ys), 1.0)

    def vp(self):
        return self.obj.ViewObject.Proxy if self.obj is not None and self.obj.ViewObject else None

    def seek(self, t: float) -> None:
        self.t = min(max(t, 0.0), self.timeline.duration)
        pos, item = self.timeline.at(self.t)
        vp = self.vp()
        if vp is not None and hasattr(vp, "show_knife"):
            vp.show_knife(pos, self.knife_size)
        self.slider.blockSignals(True)
        self.slider.setValue(int(1000 * self.t / max(self.timeline.duration, 1e-9)))
        self.slider.blockSignals(False)
        if item >= 0 and self.timeline.what[item][0]:
            tool, k, n = self.timeline.what[item]
            what = translate("LeatherCut", "{0}: {1} of {2}").format(tool, k, n)
        elif item >= 0:
            what = translate("LeatherCut", "cutting {0} of {1}").format(item + 1, self.items)
        else:
            what = translate("LeatherCut", "idle move (knife up)")
        self.label.setText(translate("LeatherCut", "t = {0:.1f} s of {1:.1f} s – {2}").format(
            self.t, self.timeline.duration, what))

    def play(self) -> None:
        if self.t >= self.timeline.duration:
            self.t = 0.0
        self.wall = time.monotonic()
        self.timer.start()

    def pause(self) -> None:
        self.timer.stop()

    def stop(self) -> None:
        self.timer.stop()
        self.seek(0.0)

    def tick(self) -> None:
        now = time.monotonic()
        dt = (now - (self.wall or now)) * self.speed.value()
        self.wall = now
        self.seek(self.t + dt)
        if self.t >= self.timeline.duration:
            self.timer.stop()

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        self.timer.stop()
        vp = self.vp()
        if vp is not None and hasattr(vp, "show_knife"):
            vp.show_knife(None)
        Gui.Control.closeDialog()
        return True

    def accept(self):
        return self.reject()


class Simulate(base.Command):
    NAME = "LeatherCut_Simulate"
    ICON = "Simulate"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_Simulate", "Simulate")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_Simulate",
                            "Animate the knife along the planned cut path at the machine's speeds")

    def active(self) -> bool:
        return base.has_stage("CutPath") and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(SimulatePanel(base.active_job()))


COMMAND = Simulate
