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
STATUS_LINES = 5


def scrolling(form: QtGui.QWidget) -> QtGui.QWidget:
    """``form`` (loaded from a panel .ui) with wrapping labels and narrow combo
    boxes; returns ``form``."""
    for label in form.findChildren(QtGui.QLabel):
        label.setWordWrap(True)
    status = form.findChild(QtGui.QLabel, "statusLabel")
    if status is not None:
        status.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
        status.setMinimumWidth(50)
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
    """Cap the options' height of a shown panel so the whole panel -- progress
    bar and status included -- fits the task view's visible height.

    What is hidden is read from the form's own visible region: asking Qt for
    FreeCAD's task view widgets (``parentWidget()``) from Python gets them
    deleted when the Python wrappers go (FreeCAD 0.20, PySide2 5.15)."""
    area = form.findChild(QtGui.QScrollArea, "optionsScrollArea")
    if area is None or not form.isVisible():
        return
    visible = form.visibleRegion().boundingRect()
    if visible.isEmpty():
        return
    hidden = form.height() - (visible.y() + visible.height())
    status = form.findChild(QtGui.QLabel, "statusLabel")
    if status is not None:  # room for a status of up to STATUS_LINES lines
        hidden += max(0, STATUS_LINES * status.fontMetrics().lineSpacing() - status.height())
    if hidden > 0:
        area.setMaximumHeight(max(MIN_OPTIONS_HEIGHT, area.height() - hidden - 8))
        area.setMinimumHeight(min(area.maximumHeight(), MIN_OPTIONS_HEIGHT))
