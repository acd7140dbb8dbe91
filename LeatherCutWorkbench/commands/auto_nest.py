"""*Auto-nest*: place the parts on sheets, a strip or a hide (task panel with
container, spacing, rotations and time budget).

Anytime: while the search runs the status line shows the best layout so far
(placed copies, utilisation / strip length) and the 3D view redraws it every
couple of seconds; *Stop* (a button added next to *Nest now*) ends the
search and keeps that best layout; *Cancel* alone discards the run."""

from __future__ import annotations

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..document import objects, pipeline
from . import base, panel, runner

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class NestPanel(panel.StagePanel):
    UI = "AutoNest"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Auto-nest")
    STAGE = "Nest"

    #: container kind -> the fields that apply to it (the others are greyed out)
    FIELDS = {"sheet": ("NestSheetWidth", "NestSheetHeight", "NestSheetCount"),
              "strip": ("NestStripWidth",), "hide": ("NestHideFile", "browseNestHideFile")}

    #: seconds between two redraws of the best layout so far in the 3D view
    LIVE_EVERY_S = 2.0

    def __init__(self, job):
        super().__init__(job)
        self.live = _LiveNest()
        self._inputs = None
        self.stop_button = self._add_stop_button()
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

    def _add_stop_button(self):
        """A *Stop* button right after *Nest now* (created here, not in the .ui)."""
        run = self.form.findChild(QtGui.QPushButton, "runButton")
        button = QtGui.QPushButton(translate("LeatherCut", "Stop (keep the best layout)"))
        button.setObjectName("stopButton")
        button.setEnabled(False)
        button.clicked.connect(self.live.request_stop)
        grid = run.parentWidget().layout() if run is not None else None
        if isinstance(grid, QtGui.QGridLayout):
            idx = grid.indexOf(run)
            row, _col, _rs, _cs = grid.getItemPosition(idx)
            grid.removeWidget(run)
            grid.addWidget(run, row, 0, 1, 1)
            grid.addWidget(button, row, 1, 1, 1)
        elif grid is not None:
            grid.addWidget(button)
        return button

    def run(self) -> None:
        """Nest in a worker thread with live best-so-far and Stop (see module doc)."""
        stage = pipeline.STAGES[self.STAGE]
        inputs = self._inputs = stage.prepare(self.job)
        state = runner.StageRun()
        self.run_state = state
        self.live.reset()
        live = self.live

        def compute(inp, progress):
            from ..core.nesting import nest
            parts, opts = inp
            return parts, nest(parts, opts, progress, on_best=live.offer, stop=live.stopped), opts

        self.stop_button.setEnabled(True)
        try:
            result = runner.compute_in_thread(compute, inputs, state, stage.title, self)
        finally:
            self.stop_button.setEnabled(False)
        stage.apply(self.job, result)
        self.after_run()

    def show_progress(self, fraction: float, message: str) -> None:
        super().show_progress(fraction, message)
        layout = self.live.take(self.LIVE_EVERY_S)
        if layout is not None and self._inputs is not None:
            parts, opts = self._inputs
            pipeline.STAGES[self.STAGE].apply(self.job, (parts, layout, opts))
            self.after_run()

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


class _LiveNest:
    """Best layout handed over from the nesting thread, and the Stop request."""

    def __init__(self):
        import threading
        self.lock = threading.Lock()
        self.reset()

    def reset(self) -> None:
        self.layout = None
        self.stop = False
        self.shown = 0.0

    def offer(self, layout) -> None:          # nesting thread
        with self.lock:
            self.layout = layout

    def take(self, every_s: float):
        """The newest layout if one arrived and ``every_s`` passed (GUI thread)."""
        import time
        now = time.monotonic()
        with self.lock:
            if self.layout is None or now - self.shown < every_s:
                return None
            layout, self.layout, self.shown = self.layout, None, now
        return layout

    def request_stop(self) -> None:
        self.stop = True

    def stopped(self) -> bool:
        return self.stop


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
