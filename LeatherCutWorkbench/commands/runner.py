"""Run a pipeline stage from the GUI without freezing it.

``prepare`` and ``apply`` touch the document and run on the GUI thread; the
slow ``compute`` (the core stage function) runs in a worker thread.  While it
runs the GUI thread keeps processing events, drives FreeCAD's progress
indicator (status bar; Esc cancels) and, when given, a panel's progress bar and
status label (its Cancel button cancels).  Cancelling makes the stage's
``progress`` callback return False; the stage then raises CancelledError.
"""

from __future__ import annotations

import threading
from typing import Any, Optional

import FreeCAD

from ..core.errors import CancelledError
from ..document import pipeline

translate = FreeCAD.Qt.translate


class StageRun:
    """Shared state between the worker thread and the GUI thread."""

    def __init__(self):
        self.fraction = 0.0
        self.message = ""
        self.cancel_requested = False
        self.result: Any = None
        self.error: Optional[BaseException] = None

    def progress(self, fraction: float, message: str) -> bool:
        """The stage's progress callback (called from the worker thread)."""
        self.fraction = fraction
        self.message = message
        return not self.cancel_requested

    def cancel(self) -> None:
        self.cancel_requested = True


def run_stage(job, key: str, panel=None, state: Optional[StageRun] = None):
    """Run stage ``key`` on ``job``; returns what the stage's ``apply`` made.

    ``panel`` may have ``show_progress(fraction, message)``.  Raises the
    stage's error (CancelledError when cancelled)."""
    stage = pipeline.STAGES[key]
    state = state or StageRun()
    if panel is not None:
        panel.run_state = state
    inputs = stage.prepare(job)
    result = compute_in_thread(stage.compute, inputs, state, stage.title, panel)
    return stage.apply(job, result)


def compute_in_thread(compute, inputs, state: StageRun, title: str, panel=None):
    from PySide import QtCore, QtGui

    def work():
        try:
            state.result = compute(inputs, state.progress)
        except BaseException as exc:  # handed to the GUI thread
            state.error = exc

    worker = threading.Thread(target=work, name=f"LeatherCut {title}", daemon=True)
    bar = FreeCAD.Base.ProgressIndicator()
    bar.start(translate("LeatherCut", title) + "…", 100)
    steps = 0
    app = QtGui.QApplication.instance()
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.03)
            target = int(state.fraction * 100)
            try:
                while steps < min(target, 99):
                    steps += 1
                    bar.next(True)
            except Exception:  # Esc in the status bar
                state.cancel()
            if panel is not None:
                panel.show_progress(state.fraction, state.message)
            if app is not None:
                app.processEvents(QtCore.QEventLoop.AllEvents, 30)
    finally:
        bar.stop()
        worker.join()
    if state.error is not None:
        raise state.error
    if state.cancel_requested:
        raise CancelledError(f"{title} cancelled")
    if panel is not None:
        panel.show_progress(1.0, "")
    return state.result
