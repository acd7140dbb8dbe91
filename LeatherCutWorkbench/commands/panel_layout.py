"""Fit a task panel form into FreeCAD's combo view at any screen size.

FreeCAD's default combo view at 1280x800 shows a task panel only about
240 x 370 px.  Every panel .ui therefore holds its options in a scroll area
(``optionsScrollArea``) with the progress bar and the status text below it,
outside the scroll area.  :func:`scrolling` makes the labels wrap instead of
widening the panel (so the task box's OK / Cancel stay in view) and
:func:`fit_to_task_view` caps the options' height, once the panel is shown,
so the progress bar and the status are visible without scrolling the task view.
"""

from __future__ import annotations

from PySide import QtCore, QtGui

#: the options part never asks for more than this height (px); it scrolls beyond
MAX_OPTIONS_HEIGHT = 560
#: the options part keeps at least this height (px)
MIN_OPTIONS_HEIGHT = 80
#: lines of status text kept visible below the options
STATUS_LINES = 3
#: px between the panel's last widget and the combo view's bottom (task box frame)
BOTTOM_MARGIN = 24


def scrolling(form: QtGui.QWidget) -> QtGui.QWidget:
    """``form`` (loaded from a panel .ui) with wrapping labels and narrow combo
    boxes; returns ``form``."""
    for label in form.findChildren(QtGui.QLabel):
        label.setWordWrap(True)
    status = form.findChild(QtGui.QLabel, "statusLabel")
    if status is not None:
        status.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        status.setMinimumWidth(50)
    for lay in form.findChildren(QtGui.QFormLayout):  # labels above fields when narrow
        lay.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)
    for combo in form.findChildren(QtGui.QComboBox):
        combo.setSizeAdjustPolicy(QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(8)
    area = form.findChild(QtGui.QScrollArea, "optionsScrollArea")
    if area is not None:
        area.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAsNeeded)
        inner = area.widget()
        hint = inner.sizeHint().height() + 4 if inner is not None else MAX_OPTIONS_HEIGHT
        area.setMaximumHeight(min(hint, MAX_OPTIONS_HEIGHT))
        area.setMinimumHeight(min(hint, MIN_OPTIONS_HEIGHT))
    return form


def fit_to_task_view(form: QtGui.QWidget) -> None:
    """Set the options' height of a shown panel so the whole panel -- progress
    bar and status (up to :data:`STATUS_LINES` lines) included -- ends above
    the bottom of the combo view (or, with the combo view undocked or renamed,
    is not clipped by the task view).

    The task view's own widgets are not asked for: getting them from Python
    (``parentWidget()``) gets them deleted when the wrappers go (FreeCAD 0.20,
    PySide2 5.15)."""
    area = form.findChild(QtGui.QScrollArea, "optionsScrollArea")
    if area is None or area.widget() is None or not form.isVisible():
        return
    hint = area.widget().sizeHint().height() + 4
    if area.horizontalScrollBar().isVisible():
        hint += area.horizontalScrollBar().height()
    below = 0
    for name in ("progressBar", "statusLabel"):
        w = form.findChild(QtGui.QWidget, name)
        if w is None:
            continue
        if isinstance(w, QtGui.QLabel):   # wrapped text: its height at its width
            needed = max(w.heightForWidth(max(w.width(), 100)), w.fontMetrics().lineSpacing())
            below += max(needed, STATUS_LINES * w.fontMetrics().lineSpacing()) + 6
        else:
            below += w.sizeHint().height() + 6
    import FreeCADGui as Gui
    dock = Gui.getMainWindow().findChild(QtGui.QDockWidget, "Combo View")
    if dock is not None and dock.isVisible() and not dock.isFloating():
        bottom = dock.mapToGlobal(QtCore.QPoint(0, dock.height())).y()
        room = bottom - area.mapToGlobal(QtCore.QPoint(0, 0)).y() - below - BOTTOM_MARGIN
    else:
        visible = form.visibleRegion().boundingRect()
        hidden = form.height() - (visible.y() + visible.height()) if not visible.isEmpty() else 0
        room = area.height() - max(hidden, 0)
    height = max(MIN_OPTIONS_HEIGHT, min(hint, MAX_OPTIONS_HEIGHT, room))
    area.setMaximumHeight(height)
    area.setMinimumHeight(height)
