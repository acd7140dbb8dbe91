"""*Recognise*: find parts, holes, lead-ins, open chains and doubtful contours."""

from __future__ import annotations

from typing import Optional

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from ..document import objects, part_objects
from . import base, messages, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class RecognisePanel(panel.StagePanel):
    """Recognition options, and the parts to cut: per size (graded pattern sets)
    and per part (include, quantity).  The part choices are part of the
    panel's undo step."""

    UI = "Recognise"
    TITLE = QT_TRANSLATE_NOOP("LeatherCut", "Recognise")
    STAGE = "Recognise"

    def __init__(self, job):
        super().__init__(job)
        self.sizes = self.form.findChild(QtGui.QListWidget, "sizeList")
        self.table = self.form.findChild(QtGui.QTableWidget, "partsTable")
        self.summary = self.form.findChild(QtGui.QLabel, "partsSummary")
        self.table.setColumnCount(3)
        self.table.setHorizontalHeaderLabels([translate("LeatherCut", "Part"), translate("LeatherCut", "Size"),
                                              translate("LeatherCut", "Qty")])
        self.table.horizontalHeader().setStretchLastSection(False)
        self.table.horizontalHeader().setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        self.table.verticalHeader().hide()
        for w in (self.table, self.sizes):   # never widen the panel: scroll inside
            w.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
            w.setMinimumWidth(120)
        self.table.itemChanged.connect(self._table_changed)
        self.sizes.itemChanged.connect(self._size_changed)
        self._filling = False
        rec = objects.stage_object(job, "Recognition")
        if rec is not None and not rec.OutOfDate:
            self.fresh = True   # nothing to run again: OK keeps the part choices only
        self.fill_parts()

    # -- parts to cut ---------------------------------------------------------------
    def fill_parts(self) -> None:
        """Sizes and parts of the current recognition, with the choices on them."""
        self._filling = True
        try:
            objs = part_objects.part_objects(self.job)
            groups = part_objects.by_size(self.job)
            self.sizes.clear()
            graded = [s for s in groups if s]
            for size in graded:
                members = groups[size]
                item = QtGui.QListWidgetItem(translate("LeatherCut", "size {0}").format(size))
                item.setData(QtCore.Qt.UserRole, size)
                item.setFlags(item.flags() | QtCore.Qt.ItemIsUserCheckable)
                n_in = sum(bool(o.Include) for o in members)
                item.setCheckState(QtCore.Qt.Checked if n_in == len(members) else
                                   QtCore.Qt.Unchecked if n_in == 0 else QtCore.Qt.PartiallyChecked)
                self.sizes.addItem(item)
            for w in (self.sizes, self.form.findChild(QtGui.QLabel, "sizesLabel")):
                w.setVisible(len(graded) > 1)
            self.table.setRowCount(len(objs))
            for r, o in enumerate(objs):
                name = QtGui.QTableWidgetItem(o.Label)
                name.setFlags((name.flags() | QtCore.Qt.ItemIsUserCheckable) & ~QtCore.Qt.ItemIsEditable)
                name.setCheckState(QtCore.Qt.Checked if o.Include else QtCore.Qt.Unchecked)
                name.setData(QtCore.Qt.UserRole, o.Name)
                name.setToolTip(translate("LeatherCut", "{0}, net area {1}").format(
                    o.Label, messages.readable_area(o.Area)))
                size = QtGui.QTableWidgetItem(o.Size)
                size.setFlags(size.flags() & ~QtCore.Qt.ItemIsEditable)
                qty = QtGui.QTableWidgetItem(str(o.Quantity))
                self.table.setItem(r, 0, name)
                self.table.setItem(r, 1, size)
                self.table.setItem(r, 2, qty)
            self.table.resizeColumnToContents(1)
            self.table.resizeColumnToContents(2)
        finally:
            self._filling = False
        self.show_summary()

    def show_summary(self) -> None:
        objs = part_objects.part_objects(self.job)
        chosen = [o for o in objs if o.Include]
        self.summary.setText(translate("LeatherCut", "{0} of {1} parts to cut, {2} copies in all.").format(
            len(chosen), len(objs), sum(o.Quantity for o in chosen)))

    def _part(self, row: int):
        item = self.table.item(row, 0)
        return self.doc.getObject(item.data(QtCore.Qt.UserRole)) if item is not None else None

    def _table_changed(self, item) -> None:
        if self._filling:
            return
        o = self._part(item.row())
        if o is None:
            return
        if item.column() == 0:
            part_objects.set_included([o], item.checkState() == QtCore.Qt.Checked)
        elif item.column() == 2:
            try:
                o.Quantity = max(1, int(item.text()))
            except ValueError:
                self.show_status(translate("LeatherCut", "Quantity must be a whole number."), error=True)
            self._filling = True
            item.setText(str(o.Quantity))
            self._filling = False
        self.fill_parts()

    def _size_changed(self, item) -> None:
        if self._filling:
            return
        self.set_size(item.data(QtCore.Qt.UserRole), item.checkState() == QtCore.Qt.Checked)

    def set_size(self, size: str, include: bool) -> None:
        """Include or exclude every part of one pattern size."""
        part_objects.set_included(part_objects.by_size(self.job).get(size, []), include)
        self.fill_parts()

    def set_part(self, part_id: str, include: Optional[bool] = None, quantity: Optional[int] = None) -> None:
        """Set one part's choice through its table row (macros, tests)."""
        for r in range(self.table.rowCount()):
            o = self._part(r)
            if o is not None and o.PartId == part_id:
                if include is not None:
                    self.table.item(r, 0).setCheckState(QtCore.Qt.Checked if include else QtCore.Qt.Unchecked)
                if quantity is not None:
                    self.table.item(r, 2).setText(str(quantity))
                return
        raise KeyError(part_id)

    # -- stage ----------------------------------------------------------------------
    def after_run(self) -> None:
        drawing = objects.stage_object(self.job, "Drawing")
        if drawing is not None and FreeCAD.GuiUp:
            drawing.ViewObject.Visibility = False
        base.fit_view()

    def show_result(self) -> None:
        rec = objects.load_data(objects.stage_object(self.job, "Recognition"))
        if rec is None:
            return
        self.fill_parts()
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
