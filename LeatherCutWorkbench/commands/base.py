"""What every LeatherCut command shares: resources, the active job, errors,
undo transactions."""

from __future__ import annotations

import traceback
from contextlib import contextmanager
from typing import Optional

import FreeCAD
import FreeCADGui as Gui

from ..core.errors import CancelledError, LeatherCutError
from ..document import objects
from . import messages, paths

translate = FreeCAD.Qt.translate
QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP


class Command:
    """Base command: subclasses set NAME, ICON, MENU, TIP (untranslated; the
    class attributes are marked with QT_TRANSLATE_NOOP in each module) and
    implement ``run()`` and ``active()``."""

    NAME = ""
    ICON = "LeatherCut"
    MENU = ""
    TIP = ""
    ACCEL = ""

    def GetResources(self):
        res = {"Pixmap": paths.icon(self.ICON),
               "MenuText": translate(self.NAME, self.MENU),
               "ToolTip": translate(self.NAME, self.TIP)}
        if self.ACCEL:
            res["Accel"] = self.ACCEL
        return res

    def IsActive(self) -> bool:
        try:
            return bool(self.active())
        except Exception:  # IsActive is polled: never raise from it
            return False

    def active(self) -> bool:
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        try:
            self.run()
        except CancelledError:  # the user's choice, not an error
            FreeCAD.Console.PrintMessage(translate("LeatherCut", "LeatherCut: cancelled") + "\n")
        except LeatherCutError as exc:
            show_error(self.MENU, str(exc))
        except OSError as exc:  # a file the user named cannot be read or written
            show_error(self.MENU, file_error_text(exc))
        except Exception as exc:  # a bug: keep the traceback in the report view
            FreeCAD.Console.PrintError(traceback.format_exc())
            show_error(self.MENU, f"{type(exc).__name__}: {exc}")

    def run(self) -> None:
        raise NotImplementedError


def file_error_text(exc: OSError) -> str:
    """One line for a file that cannot be read or written."""
    what = exc.filename or ""
    return f"{what}: {exc.strerror or exc}" if what else str(exc)


def show_error(title: str, message: str) -> None:
    """Report a user-facing error in the report view and a message box
    (CLI option names rewritten for the GUI, see :mod:`.messages`)."""
    title = translate("LeatherCut", title)
    message = messages.for_gui(message)
    FreeCAD.Console.PrintError(f"LeatherCut {title}: {message}\n")
    if FreeCAD.GuiUp and not _quiet():
        from PySide import QtGui
        QtGui.QMessageBox.warning(Gui.getMainWindow(), f"LeatherCut – {title}", message)


def show_info(title: str, message: str) -> None:
    title = translate("LeatherCut", title)
    message = messages.for_gui(message)
    FreeCAD.Console.PrintMessage(f"LeatherCut {title}: {message}\n")
    if FreeCAD.GuiUp and not _quiet():
        from PySide import QtGui
        QtGui.QMessageBox.information(Gui.getMainWindow(), f"LeatherCut – {title}", message)


def _quiet() -> bool:
    """Scripted GUI runs (tests, screenshots) set this parameter to skip modal boxes."""
    return FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/LeatherCut").GetBool(
        "NoDialogs", False)


def active_job():
    """The job the user works on: the job of the selection, else the last job
    of the active document (None when there is none)."""
    doc = FreeCAD.ActiveDocument
    if doc is None:
        return None
    if FreeCAD.GuiUp:
        for sel in Gui.Selection.getSelection(doc.Name):
            job = objects.job_of(sel)
            if job is not None:
                return job
    jobs = objects.jobs(doc)
    return jobs[-1] if jobs else None


def has_stage(role: str) -> bool:
    return objects.stage_object(active_job(), role) is not None


@contextmanager
def transaction(doc, name: str):
    """One undo step: committed when the block succeeds, aborted otherwise."""
    doc.openTransaction(name)
    try:
        yield
    except BaseException:
        doc.abortTransaction()
        raise
    else:
        doc.commitTransaction()


def selected(role: str):
    """Selected objects with the given role."""
    if not FreeCAD.GuiUp:
        return []
    return [o for o in Gui.Selection.getSelection() if objects.role(o) == role]


def fit_view() -> None:
    if FreeCAD.GuiUp and Gui.ActiveDocument is not None:
        view = Gui.ActiveDocument.ActiveView
        if hasattr(view, "viewTop"):
            view.viewTop()
        if hasattr(view, "fitAll"):
            view.fitAll()


def focus_job(job: Optional[object]) -> None:
    """Select the job so the following commands act on it."""
    if FreeCAD.GuiUp and job is not None:
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(job)
