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
from PySide import QtGui

from ..document import pipeline
from . import base, panel

translate = FreeCAD.Qt.translate

#: kind -> (button 1 text, decision 1, button 2 text, decision 2)
ACTIONS = {
    "over": (FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Include (it is a part)"), "Include",
             FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Exclude (not a part)"), "Exclude"),
    "under": (FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Accept fix (close the gap)"), "Accept",
              FreeCAD.Qt.QT_TRANSLATE_NOOP("LeatherCut", "Reject fix (leave open)"), "Reject"),
}


def flags_of_kind(job, kind: str) -> List:
    return [o for o in pipeline.flag_objects(job) if o.Kind == kind]


class FlagPanel(panel.CloseOnlyPanel):
    """Review the flags of one kind; every decision is its own undo step."""

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
        self.form.findChild(QtGui.QPushButton, "undecideButton").clicked.connect(
            lambda: self.decide("Undecided"))
        self.list.currentRowChanged.connect(self.show_flag)
        self.refresh_list()
        if self.flags:
            self.list.setCurrentRow(self._first_undecided())

    def _first_undecided(self) -> int:
        for i, f in enumerate(self.flags):
            if f.Decision == "Undecided":
                return i
        return 0

    def refresh_list(self) -> None:
        row = self.list.currentRow()
        self.list.blockSignals(True)
        self.list.clear()
        for f in self.flags:
            gap = f" – {f.Gap:.3f} mm" if f.Kind == "under" else ""
            self.list.addItem(f"{f.FlagId}: {', '.join(f.Ids)}{gap} [{translate('LeatherCut', f.Decision)}]")
        self.list.blockSignals(False)
        if 0 <= row < len(self.flags):
            self.list.setCurrentRow(row)

    def current(self):
        row = self.list.currentRow()
        return self.flags[row] if 0 <= row < len(self.flags) else None

    def show_flag(self, row: int) -> None:
        if not 0 <= row < len(self.flags):
            return
        f = self.flags[row]
        self.reason.setText(f.Reason)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(f)
        if Gui.ActiveDocument is not None:
            Gui.SendMsgToActiveView("ViewSelection")

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


def open_flag_panel(kind: str) -> FlagPanel:
    panel.ensure_no_dialog()
    job = base.active_job()
    p = FlagPanel(job, kind)
    sel = [o for o in Gui.Selection.getSelection() if getattr(o, "Role", "") == "Flag" and o.Kind == kind]
    if sel and sel[0] in p.flags:
        p.list.setCurrentRow(p.flags.index(sel[0]))
    panel.show(p)
    return p
