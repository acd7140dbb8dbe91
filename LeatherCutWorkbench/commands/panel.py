"""Task panel base: a Qt Designer form bound to the Job's option properties.

Every widget whose ``objectName`` is a property of the Job edits that
property (spin boxes, check boxes, line edits, combo boxes).  Opening the
panel opens one undo transaction; *OK* runs the stage (off the GUI thread,
with the panel's progress bar and FreeCAD's) and commits the transaction,
*Cancel* aborts it (or, while the stage runs, cancels the run).  So a stage
run together with the option changes that led to it is one undo step.
"""

from __future__ import annotations

import traceback
from typing import Optional

import FreeCAD
import FreeCADGui as Gui
from PySide import QtGui

from ..core.errors import CancelledError, LeatherCutError
from . import messages, panel_layout, paths, runner

translate = FreeCAD.Qt.translate


def load_form(name: str):
    """``resources/ui/<name>.ui`` in a scroll area, progress and status pinned
    below it (see :mod:`.panel_layout`)."""
    return panel_layout.scrolling(Gui.PySideUic.loadUi(paths.ui(name)))


class JobPropertyPanel:
    """Loads ``resources/ui/<UI>.ui`` and binds its widgets to job properties."""

    UI = ""
    TITLE = ""

    def __init__(self, job, transaction_open: bool = False):
        """``transaction_open``: the caller already opened this panel's transaction
        (e.g. to create the job inside it)."""
        self.job = job
        self.doc = job.Document
        self.form = load_form(self.UI)
        self.form.setWindowTitle(translate("LeatherCut", self.TITLE))
        self.run_state: Optional[runner.StageRun] = None
        self.running = False
        self.closed = False
        if not transaction_open:
            self.doc.openTransaction(f"LeatherCut: {self.TITLE}")
        self._bind()
        self._browse_buttons()
        self.progress_bar = self.form.findChild(QtGui.QProgressBar, "progressBar")
        self.status = self.form.findChild(QtGui.QLabel, "statusLabel")
        if self.progress_bar is not None:
            self.progress_bar.setRange(0, 100)
            self.progress_bar.setValue(0)

    # -- property binding ---------------------------------------------------------
    def _bind(self) -> None:
        props = set(self.job.PropertiesList)
        for w in self.form.findChildren(QtGui.QWidget):
            name = w.objectName()
            if name not in props:
                continue
            value = getattr(self.job, name)
            tip = self.job.getDocumentationOfProperty(name)
            if tip and not w.toolTip():
                w.setToolTip(tip)
            if isinstance(w, QtGui.QCheckBox):
                w.setChecked(bool(value))
                w.toggled.connect(lambda v, n=name: self._set(n, bool(v)))
            elif isinstance(w, QtGui.QDoubleSpinBox):
                w.setValue(float(value))
                w.valueChanged.connect(lambda v, n=name: self._set(n, float(v)))
            elif isinstance(w, QtGui.QSpinBox):
                w.setValue(int(value))
                w.valueChanged.connect(lambda v, n=name: self._set(n, int(v)))
            elif isinstance(w, QtGui.QComboBox):
                if self.job.getTypeIdOfProperty(name) == "App::PropertyEnumeration":
                    w.clear()
                    w.addItems(self.job.getEnumerationsOfProperty(name))
                i = w.findText(str(value))
                if i < 0 and w.isEditable():
                    w.setEditText(str(value))
                else:
                    w.setCurrentIndex(max(i, 0))
                w.currentIndexChanged.connect(lambda _i, n=name, cw=w: self._set(n, cw.currentText()))
                if w.isEditable():
                    w.editTextChanged.connect(lambda t, n=name: self._set(n, t))
            elif isinstance(w, QtGui.QLineEdit):
                w.setText(str(value))
                w.textChanged.connect(lambda t, n=name: self._set(n, t))

    def _browse_buttons(self) -> None:
        """A tool button ``browse<Prop>`` next to a file property opens a file dialog."""
        for b in self.form.findChildren(QtGui.QToolButton):
            name = b.objectName()
            if name.startswith("browse") and name[6:] in self.job.PropertiesList:
                b.clicked.connect(lambda _c=False, n=name[6:]: self._browse(n))

    def _browse(self, name: str) -> None:
        edit = self.form.findChild(QtGui.QLineEdit, name)
        start = edit.text() if edit is not None else ""
        if name.endswith("OutputFile"):
            path, _f = QtGui.QFileDialog.getSaveFileName(self.form, self.TITLE, start)
        else:
            path, _f = QtGui.QFileDialog.getOpenFileName(
                self.form, self.TITLE, start, translate("LeatherCut", "DXF drawings (*.dxf *.DXF)"))
        if path and edit is not None:
            edit.setText(path)

    def _set(self, name: str, value) -> None:
        try:
            if getattr(self.job, name) != value:
                setattr(self.job, name, value)
        except Exception as exc:  # bad value typed: say so, keep the old one
            self.show_status(translate("LeatherCut", "Cannot set {0}: {1}").format(name, exc), error=True)

    def set_widget(self, name: str, value) -> None:
        """Set a bound widget (and so the property) from code (macros, tests)."""
        w = self.form.findChild(QtGui.QWidget, name)
        if isinstance(w, QtGui.QCheckBox):
            w.setChecked(bool(value))
        elif isinstance(w, (QtGui.QDoubleSpinBox, QtGui.QSpinBox)):
            w.setValue(value)
        elif isinstance(w, QtGui.QComboBox):
            i = w.findText(str(value))
            if i >= 0:
                w.setCurrentIndex(i)
            else:
                w.setEditText(str(value))
        elif isinstance(w, QtGui.QLineEdit):
            w.setText(str(value))
        else:
            self._set(name, value)

    # -- feedback -------------------------------------------------------------------
    def show_progress(self, fraction: float, message: str) -> None:
        if self.progress_bar is not None:
            self.progress_bar.setValue(int(round(fraction * 100)))
        if message:
            self.show_status(message)

    def show_status(self, text: str, error: bool = False) -> None:
        text = messages.for_gui(text)
        if self.status is not None:
            self.status.setText(text)
            self.status.setStyleSheet("color: #c62828;" if error else "")
        if error:
            FreeCAD.Console.PrintError(f"LeatherCut {self.TITLE}: {text}\n")

    def report_failure(self, exc: BaseException, cancelled_text: str) -> None:
        """Say in the panel why a run failed: a cancel is the user's choice (not
        logged as an error), a LeatherCutError or file error the user can act on
        (no traceback), anything else a bug (traceback in the report view)."""
        if isinstance(exc, CancelledError):
            self.show_status(cancelled_text)
            FreeCAD.Console.PrintMessage(f"LeatherCut {self.TITLE}: {cancelled_text}\n")
        elif isinstance(exc, LeatherCutError):
            self.show_status(str(exc), error=True)
        elif isinstance(exc, OSError):
            from .base import file_error_text
            self.show_status(file_error_text(exc), error=True)
        else:
            FreeCAD.Console.PrintError(traceback.format_exc())
            self.show_status(f"{type(exc).__name__}: {exc}", error=True)

    # -- task dialog protocol -------------------------------------------------------
    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def run(self) -> None:
        """Do the panel's work (subclasses); raise LeatherCutError on failure."""

    def accept(self):
        if self.running:
            return False
        self.running = True
        try:
            self.run()
        except Exception as exc:
            self.report_failure(exc, translate(
                "LeatherCut", "Cancelled. Change the options and press OK, or Cancel."))
            return False
        finally:
            self.running = False
        self.doc.commitTransaction()
        self.doc.recompute()
        self._close()
        return True

    def reject(self):
        if self.running and self.run_state is not None:
            self.run_state.cancel()
            return False
        self.doc.abortTransaction()
        self.doc.recompute()
        self._close()
        return True

    def _close(self) -> None:
        if not self.closed:
            self.closed = True
            self.on_close()
            Gui.Control.closeDialog()

    def on_close(self) -> None:
        """Subclasses release what they hold (timers, observers)."""


class StagePanel(JobPropertyPanel):
    """A panel whose OK runs one pipeline stage.

    A ``runButton`` in the form runs the stage as a preview (the result shows
    in the 3D view and the panel) without closing; OK then commits it, or runs
    it first when the options changed since; Cancel removes it again."""

    STAGE = ""

    def __init__(self, job, transaction_open: bool = False):
        super().__init__(job, transaction_open)
        self.fresh = False
        button = self.form.findChild(QtGui.QPushButton, "runButton")
        if button is not None:
            button.clicked.connect(self.preview)
        self.job_signature = self._signature()

    def _signature(self):
        return tuple((p, str(getattr(self.job, p))) for p in self.job.PropertiesList
                     if p not in ("Label", "Label2", "Group", "ExpressionEngine", "Visibility"))

    def preview(self) -> bool:
        """Run the stage now and keep the panel open (returns success)."""
        if self.running:
            return False
        self.running = True
        try:
            self.run()
            self.fresh = True
            self.job_signature = self._signature()
            self.show_result()
            return True
        except Exception as exc:
            self.report_failure(exc, translate("LeatherCut", "Cancelled."))
        finally:
            self.running = False
        return False

    def accept(self):
        if self.fresh and self._signature() == self.job_signature:
            if self.running:
                return False
            self.doc.commitTransaction()
            self.doc.recompute()
            self._close()
            return True
        return super().accept()

    def run(self) -> None:
        runner.run_stage(self.job, self.STAGE, panel=self)
        self.after_run()

    def show_result(self) -> None:
        """Subclasses show metrics of the fresh result in the panel."""

    def after_run(self) -> None:
        from .base import fit_view
        fit_view()


#: the panel opened last (macros and the GUI tests drive it)
CURRENT = None


class CloseOnlyPanel:
    """Mixin for panels whose work is done as the user clicks (each click its
    own undo step): only a *Close* button, which just closes the panel."""

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        Gui.Control.closeDialog()
        return True

    def accept(self):
        return self.reject()


def show(panel) -> None:
    """Open ``panel`` in the task view."""
    global CURRENT
    Gui.Control.showDialog(panel)
    CURRENT = panel
    if getattr(panel, "form", None) is not None:
        # the task box unfolds over a few hundred ms: fit again while it does
        later(panel, lambda: fit_panel(panel), times=12, interval_ms=150)


def fit_panel(panel) -> None:
    """Fit an open panel's form to the task view (nothing once it is closed)."""
    if Gui.Control.activeDialog() and CURRENT is panel:
        panel_layout.fit_to_task_view(panel.form)


def later(owner, fn, times: int = 1, interval_ms: int = 0) -> None:
    """Call ``fn`` ``times`` times, every ``interval_ms``, from the event loop.
    The timer is kept on ``owner``."""
    from PySide import QtCore
    timer = QtCore.QTimer()
    timer.setInterval(interval_ms)
    left = [times]

    def tick():
        left[0] -= 1
        if left[0] <= 0:
            timer.stop()
            owner._later_timer = None   # let go of fn (and what it holds)
        fn()

    timer.timeout.connect(tick)
    owner._later_timer = timer
    timer.start()


def ensure_no_dialog() -> None:
    """Refuse to open a panel while another task panel is open."""
    if Gui.Control.activeDialog():
        raise LeatherCutError(translate("LeatherCut", "finish or cancel the open task panel first"))
