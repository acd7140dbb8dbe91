"""*Machine profiles*: browse the shipped and user machine profiles, pick one for
the job, copy one into the user folder and edit it there (every field,
checked like a profile file on *Save edits*)."""

from __future__ import annotations

import json
import os

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from . import base, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


class ProfilesPanel(panel.CloseOnlyPanel):
    """List of profiles with their settings; *Use for this job* sets the job's
    machine (one undo step); *Copy to user folder* makes an editable copy;
    *Save edits* checks the edited JSON of a user profile (the message names
    the field, e.g. ``blade_offset`` on a tangential knife) and saves it."""

    def __init__(self, job):
        from ..post import profiles
        self.profiles = profiles
        self.job = job
        self.form = panel.load_form("MachineProfiles")
        self.list = self.form.findChild(QtGui.QListWidget, "profileList")
        self.details = self.form.findChild(QtGui.QPlainTextEdit, "profileDetails")
        self.status = self.form.findChild(QtGui.QLabel, "statusLabel")
        self.form.findChild(QtGui.QPushButton, "useButton").clicked.connect(self.use)
        self.form.findChild(QtGui.QPushButton, "copyButton").clicked.connect(self.copy)
        self.form.findChild(QtGui.QPushButton, "folderButton").clicked.connect(self.open_folder)
        self.form.findChild(QtGui.QPushButton, "saveButton").clicked.connect(self.save)
        self.list.currentRowChanged.connect(self.show_profile)
        self.reload()

    def reload(self) -> None:
        self.entries = self.profiles.list_profiles()
        self.list.clear()
        for e in self.entries:
            origin = translate("LeatherCut", "user") if e["origin"] == "user" else translate("LeatherCut", "shipped")
            self.list.addItem(f"{e['name']} ({origin}) – {e['description']}")
        current = self.job.PostMachine if self.job is not None else ""
        names = [e["name"] for e in self.entries]
        self.list.setCurrentRow(names.index(current) if current in names else 0)

    def current(self):
        row = self.list.currentRow()
        return self.entries[row] if 0 <= row < len(self.entries) else None

    def show_profile(self, _row: int) -> None:
        e = self.current()
        if e is None:
            return
        self.details.setReadOnly(e["origin"] != "user")
        try:
            prof = self.profiles.load_profile(e["path"])
            self.details.setPlainText(json.dumps(prof.to_json(), indent=2))
        except Exception as exc:
            self.details.setPlainText(str(exc))

    def save(self) -> str:
        """Check the edited JSON of the current user profile and save it; the
        status line names what is wrong otherwise.  Returns the path saved."""
        from ..core.errors import InputError
        e = self.current()
        if e is None:
            return ""
        if e["origin"] != "user":
            self.status.setText(translate("LeatherCut", "Shipped profiles are read-only: copy "
                                                        "this one to the user folder to edit it."))
            return ""
        try:
            data = json.loads(self.details.toPlainText())
            if not isinstance(data, dict):
                raise InputError("a machine profile is a JSON object", source=e["path"])
            data["name"] = e["name"]
            prof = self.profiles.profile_from_dict(data, source=e["path"])
        except json.JSONDecodeError as exc:
            self.status.setText(translate("LeatherCut", "Not valid JSON: {0} at line {1}; not saved.")
                                .format(exc.msg, exc.lineno))
            return ""
        except InputError as exc:
            self.status.setText(translate("LeatherCut", "{0}; not saved.").format(exc))
            return ""
        path = self.profiles.save_user_profile(prof)
        self.status.setText(translate("LeatherCut", "Saved {0}.").format(path))
        return path

    def use(self) -> None:
        e = self.current()
        if e is None or self.job is None:
            return
        with base.transaction(self.job.Document, "LeatherCut: machine profile"):
            self.job.PostMachine = e["name"]
        self.status.setText(translate("LeatherCut", "{0} uses {1}.").format(self.job.Label, e["name"]))

    def copy(self) -> str:
        e = self.current()
        if e is None:
            return ""
        prof = self.profiles.load_profile(e["path"])
        name, ok = QtGui.QInputDialog.getText(self.form, translate("LeatherCut", "Copy profile"),
                                              translate("LeatherCut", "Name of the copy:"),
                                              text=prof.name + "_custom") if not base._quiet() \
            else (prof.name + "_custom", True)
        if not ok or not name:
            return ""
        from dataclasses import replace
        path = self.profiles.save_user_profile(replace(prof, name=name))
        self.reload()
        self.status.setText(translate("LeatherCut", "Copied to {0}; edit it here (Save edits) or with any text editor.").format(path))
        return path

    def open_folder(self) -> None:
        folder = self.profiles.user_profiles_dir()
        os.makedirs(folder, exist_ok=True)
        QtGui.QDesktopServices.openUrl(QtCore.QUrl.fromLocalFile(folder))


class MachineProfiles(base.Command):
    NAME = "LeatherCut_MachineProfiles"
    ICON = "MachineProfiles"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_MachineProfiles", "Machine profiles…")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_MachineProfiles",
                            "Browse machine profiles (table, speeds, knife, I/O), choose the job's "
                            "machine or copy a profile to edit it")

    def active(self) -> bool:
        return not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        panel.show(ProfilesPanel(base.active_job()))


COMMAND = MachineProfiles
