"""The flag review panel shared by *Flag over-recognised* and *Flag under-recognised*.

Steps through the candidates of one kind: the current one is selected and
zoomed to; *Include* / *Exclude* (over) or *Accept fix* / *Reject fix* (under)
record the decision on the flag object as one undo step each, then move to the
next undecided candidate.  Decisions are saved with the document; nesting and
planning use them (they mark later stages out of date).
"""

from __future__ import annotations

from typing import List

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from ..document import objects, pipeline
from . import base, messages, panel

translate = FreeCAD.Qt.translate

#: kind -> (button 1 text, decision 1, button 2 text, decision 2)
ACTIONS = {
    "over": (FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Include (it is a part)"), "Include",
             FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Exclude (not a part)"), "Exclude"),
    "under": (FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Accept fix (close the gap)"), "Accept",
              FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Reject fix (leave open)"), "Reject"),
}


#: decision -> how the list says it
DECISION_TEXT = {
    "Undecided": FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "undecided"),
    "Include": FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "included (a part)"),
    "Exclude": FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "excluded (not a part)"),
    "Accept": FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "fix accepted"),
    "Reject": FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "fix rejected"),
}


def flags_of_kind(job, kind: str) -> List:
    return [o for o in pipeline.flag_objects(job) if o.Kind == kind]


def flag_label(f) -> str:
    """One list line a person can read: id, what it is about, the decision."""
    what = ", ".join(f.Ids[:4]) + (" …" if len(f.Ids) > 4 else "")
    decision = translate("LeatherCut", DECISION_TEXT.get(f.Decision, f.Decision))
    if f.Kind == "under":
        return translate("LeatherCut", "{0}: gap {1} mm at {2} – {3}").format(
            f.FlagId, f"{f.Gap:.2f}", what, decision)
    return translate("LeatherCut", "{0}: region {1} – {2}").format(f.FlagId, what, decision)


def bulk_candidates(flags: List, kind: str, limit_mm: float) -> List:
    """Flags the bulk button decides: under -- gaps up to ``limit_mm``;
    over -- every one."""
    if kind == "under":
        return [f for f in flags if f.Gap <= limit_mm + 1e-9]
    return list(flags)


class FlagPanel(panel.CloseOnlyPanel):
    """Review the flags of one kind; every decision is its own undo step.

    The list follows the document: undo / redo of a decision (or of the whole
    recognition) shows up within 0.3 s."""

    def __init__(self, job, kind: str):
        self.job = job
        self.kind = kind
        self.doc = job.Document
        self.form = panel.load_form("Flags")
        self.form.setWindowTitle(translate("LeatherCut", "Over-recognised contours" if kind == "over"
                                           else "Under-recognised contours"))
        self.flags = flags_of_kind(job, kind)
        self.list = self.form.findChild(QtGui.QListWidget, "flagList")
        self.reason = self.form.findChild(QtGui.QLabel, "reasonLabel")
        b1, self.d1, b2, self.d2 = ACTIONS[kind]
        self.button1 = self.form.findChild(QtGui.QPushButton, "decideButton1")
        self.button2 = self.form.findChild(QtGui.QPushButton, "decideButton2")
        self.button1.setText(translate("LeatherCut", b1))
        self.button2.setText(translate("LeatherCut", b2))
        self.button1.clicked.connect(lambda: self.decide(self.d1))
        self.button2.clicked.connect(lambda: self.decide(self.d2))
        self.form.findChild(QtGui.QPushButton, "previousButton").clicked.connect(lambda: self.step(-1))
        self.form.findChild(QtGui.QPushButton, "nextButton").clicked.connect(lambda: self.step(1))
        self.form.findChild(QtGui.QPushButton, "zoomButton").clicked.connect(lambda: self.zoom())
        self.form.findChild(QtGui.QPushButton, "undecideButton").clicked.connect(
            lambda: self.decide("Undecided"))
        self.bulk_limit = self.form.findChild(QtGui.QDoubleSpinBox, "bulkLimit")
        bulk = self.form.findChild(QtGui.QPushButton, "bulkButton")
        bulk.clicked.connect(lambda: self.decide_all())
        if kind == "over":
            bulk.setText(translate("LeatherCut", "Exclude all over-recognised regions"))
            self.bulk_limit.hide()
        else:
            bulk.setText(translate("LeatherCut", "Accept all fixes up to"))
            self.bulk_limit.setValue(max((f.Gap for f in self.flags), default=0.5))
        self.list.currentRowChanged.connect(self.show_flag)
        self.shown = None
        self.refresh_list()
        if self.flags:
            self.list.setCurrentRow(self._first_undecided())
        self.timer = QtCore.QTimer()
        self.timer.setInterval(300)
        self.timer.timeout.connect(self.follow_document)
        self.timer.start()

    def _first_undecided(self) -> int:
        for i, f in enumerate(self.flags):
            if f.Decision == "Undecided":
                return i
        return 0

    def _state(self):
        try:
            return tuple((f.Name, f.Decision) for f in flags_of_kind(self.job, self.kind))
        except Exception:  # the job itself was undone / deleted
            return None

    def follow_document(self) -> None:
        """Re-read the flags when the document changed under the panel (undo, redo)."""
        if panel.CURRENT is not self or not Gui.Control.activeDialog():
            self.timer.stop()        # closed some other way (document closed, ...)
            return
        state = self._state()
        if state is None:
            self.reject()
            return
        if state != self.shown:
            self.flags = flags_of_kind(self.job, self.kind)
            self.refresh_list()

    def refresh_list(self) -> None:
        row = self.list.currentRow()
        self.list.blockSignals(True)
        self.list.clear()
        for f in self.flags:
            self.list.addItem(flag_label(f))
        self.list.blockSignals(False)
        self.shown = self._state()
        if self.flags:
            self.list.setCurrentRow(min(max(row, 0), len(self.flags) - 1))

    def current(self):
        row = self.list.currentRow()
        return self.flags[row] if 0 <= row < len(self.flags) else None

    def show_flag(self, row: int) -> None:
        if not 0 <= row < len(self.flags):
            return
        f = self.flags[row]
        text = f.Reason
        if f.Kind == "under":
            text = translate("LeatherCut", "Gap: {0} mm. {1}").format(f"{f.Gap:.3f}", f.Reason)
        self.reason.setText(messages.for_gui(text))
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(f)
        self.zoom(f)

    def zoom(self, f=None) -> bool:
        """Fit the 3D view to the flag's gap (its proposed fix), or to the whole
        flag when there is no fix; returns True when the view moved."""
        f = f or self.current()
        if f is None or Gui.ActiveDocument is None:
            return False
        box = gap_box(self.job, f)
        if box is None:
            Gui.SendMsgToActiveView("ViewSelection")
            return True
        return zoom_view_to(box)

    def step(self, delta: int) -> None:
        if self.flags:
            self.list.setCurrentRow((self.list.currentRow() + delta) % len(self.flags))

    def decide(self, decision: str) -> None:
        f = self.current()
        if f is None:
            return
        with base.transaction(self.doc, f"LeatherCut: {decision} {f.FlagId}"):
            pipeline.set_flag_decision(f, decision)
        self.doc.recompute()
        self.refresh_list()
        if decision != "Undecided" and any(x.Decision == "Undecided" for x in self.flags):
            self.list.setCurrentRow(self._first_undecided())

    def decide_all(self) -> int:
        """Over: exclude every region; under: accept every fix up to the limit.
        One undo step; returns how many flags it decided."""
        chosen = bulk_candidates(self.flags, self.kind, self.bulk_limit.value())
        if not chosen:
            return 0
        decision = self.d2 if self.kind == "over" else self.d1
        with base.transaction(self.doc, f"LeatherCut: {decision} {len(chosen)} flags"):
            for f in chosen:
                pipeline.set_flag_decision(f, decision)
        self.doc.recompute()
        self.refresh_list()
        return len(chosen)

    def reject(self):
        self.timer.stop()
        return super().reject()


def gap_box(job, flag_obj):
    """(xmin, ymin, xmax, ymax) mm of the flag's proposed fix, None without one."""
    from ..core.geometry import bbox, path_points
    rec = objects.load_data(objects.stage_object(job, "Recognition"))
    for f in (rec.flags if rec is not None else []):
        if f.id == flag_obj.FlagId and f.fix:
            return bbox(path_points(f.fix, 0.05))
    return None


def zoom_view_to(box, min_size: float = 15.0) -> bool:
    """Top view centred on ``box`` (mm), showing about ten times its size."""
    view = Gui.ActiveDocument.ActiveView
    if not hasattr(view, "getCameraNode"):
        return False
    view.viewTop()
    cam = view.getCameraNode()
    if not hasattr(cam, "height"):  # perspective camera: fall back to the selection
        Gui.SendMsgToActiveView("ViewSelection")
        return True
    xmin, ymin, xmax, ymax = box
    size = max(10.0 * max(xmax - xmin, ymax - ymin), min_size)
    z = cam.position.getValue()[2]
    cam.position.setValue((xmin + xmax) / 2.0, (ymin + ymax) / 2.0, z)
    cam.height.setValue(size)
    return True


def open_flag_panel(kind: str) -> FlagPanel:
    panel.ensure_no_dialog()
    job = base.active_job()
    p = FlagPanel(job, kind)
    sel = [o for o in Gui.Selection.getSelection() if getattr(o, "Role", "") == "Flag" and o.Kind == kind]
    if sel and sel[0] in p.flags:
        p.list.setCurrentRow(p.flags.index(sel[0]))
    panel.show(p)
    return p
