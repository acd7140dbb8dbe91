"""Fit a task panel form into FreeCAD's combo view at any screen size.

FreeCAD's default combo view is narrow (about 300-400 px at 1280x800) and a
screen may be only 1000 px high.  :func:`scrolling` puts the form's options
in a scroll area and keeps the progress bar and the status text below it,
outside the scroll area, so they are always visible; the status text wraps
instead of widening the panel (so the task box's OK / Cancel stay in view).
"""

from __future__ import annotations

from PySide import QtCore, QtGui

#: widgets kept below the scroll area (always visible), in this order
PINNED = ("progressBar", "statusLabel")
#: the options part never asks for more than this height (px); it scrolls beyond
MAX_OPTIONS_HEIGHT = 560


def scrolling(form: QtGui.QWidget, max_height: int = MAX_OPTIONS_HEIGHT) -> QtGui.QWidget:
    """A new widget: ``form`` in a vertical scroll area, the pinned widgets under it.

    Widgets keep their object names, so ``findChild`` on the returned widget
    still finds every control of ``form``."""
    outer = QtGui.QWidget()
    outer.setWindowTitle(form.windowTitle())
    outer.setObjectName(form.objectName() + "Panel")
    layout = QtGui.QVBoxLayout(outer)
    layout.setContentsMargins(0, 0, 0, 0)
    area = QtGui.QScrollArea(outer)
    area.setObjectName("optionsScrollArea")
    area.setWidgetResizable(True)
    area.setFrameShape(QtGui.QFrame.NoFrame)
    area.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAsNeeded)
    pinned = []
    for name in PINNED:
        w = form.findChild(QtGui.QWidget, name)
        if w is not None:
            _take_out(form, w)
            pinned.append(w)
    for label in form.findChildren(QtGui.QLabel):
        label.setWordWrap(True)
    for combo in form.findChildren(QtGui.QComboBox):
        combo.setSizeAdjustPolicy(QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(8)
    area.setWidget(form)
    hint = form.sizeHint().height() + 4
    area.setMinimumHeight(min(hint, 160))
    area.setMaximumHeight(max(min(hint, max_height), 160))
    layout.addWidget(area)
    for w in pinned:
        w.setParent(outer)
        if isinstance(w, QtGui.QLabel):
            w.setWordWrap(True)
            w.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Preferred)
            w.setMinimumWidth(50)
        layout.addWidget(w)
    layout.addStretch(1)
    return outer


def _take_out(form: QtGui.QWidget, widget: QtGui.QWidget) -> None:
    """Remove ``widget`` from whichever layout of ``form`` holds it."""
    for lay in [form.layout()] + form.findChildren(QtGui.QLayout):
        if lay is None:
            continue
        if isinstance(lay, QtGui.QFormLayout):
            row, _role = lay.getWidgetPosition(widget)
            if row >= 0:
                lay.removeWidget(widget)
                return
        elif lay.indexOf(widget) >= 0:
            lay.removeWidget(widget)
            return
