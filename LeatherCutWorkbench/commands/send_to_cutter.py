"""*Send to cutter*: stream the posted G-code to a GRBL-family controller.

The link runs in a worker thread (``post.link.GrblLink``); the panel polls its
progress with a timer, so the GUI never waits on the serial port.  Every
acknowledged line is journalled next to the G-code (``<file>.journal``);
after a fault the operator picks the segment to resume from (suggested: the
first incomplete one) -- never an automatic resend.  *Check first* runs the
whole job in the controller's check mode ($C) before anything moves.
"""

from __future__ import annotations

import os
import threading
from typing import Optional

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from ..core.errors import InputError, LeatherCutError
from ..document import pipeline
from . import base, messages, panel

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP
translate = FreeCAD.Qt.translate


def journal_path(gcode_path: str) -> str:
    return gcode_path + ".journal"


def journal_matches(gcode_path: str) -> bool:
    """True when the journal next to ``gcode_path`` records this very G-code."""
    from ..post.link import job_from_file, load_journal
    from ..post.link.journal import job_digest
    jpath = journal_path(gcode_path)
    if not os.path.exists(jpath):
        return False
    return load_journal(jpath).digest == job_digest(job_from_file(gcode_path).source)


def set_aside_stale_journal(gcode_path: str) -> str:
    """Move a journal of an earlier G-code (the file was posted again) to
    ``<journal>.<n>``; journals are never rewritten or deleted.  Returns the new
    name, or "" when nothing was moved."""
    jpath = journal_path(gcode_path)
    if not os.path.exists(jpath) or journal_matches(gcode_path):
        return ""
    n = 1
    while os.path.exists(f"{jpath}.{n}"):
        n += 1
    os.replace(jpath, f"{jpath}.{n}")
    return f"{jpath}.{n}"


class SendSession:
    """One run of :class:`post.link.SendSession` (greet, optional check mode,
    journalled stream, resume from the journal) in a worker thread, with the
    fields the panel polls: ``state``, ``progress``, ``log``, ``result``,
    ``error``.  The streaming logic itself lives in ``post.link`` so the GUI
    and ``leathercut send`` behave identically."""

    def __init__(self, gcode_path: str, machine: str, url: str, check_first: bool,
                 mode: str, resume_from: str = "", confirm_work_zero: bool = False,
                 cut_window: int = 0):
        """``confirm_work_zero``: the operator set the work zero again at the
        machine, so a resume after a lost position may go on without homing.
        ``cut_window``: segments whose cuts may be in flight before a status
        report proves them (0 = full look-ahead; as ``leathercut send
        --cut-window``)."""
        self.gcode_path = gcode_path
        self.cut_window = cut_window
        self.confirm_work_zero = confirm_work_zero
        self.machine = machine
        self.url = url
        self.check_first = check_first
        self.mode = mode
        self.resume_from = resume_from
        self.session = None
        self.progress = {}
        self.state = "starting"
        self.result = None
        self.error: Optional[str] = None
        self.log = []
        self.thread = threading.Thread(target=self._run, name="LeatherCut send", daemon=True)

    def start(self) -> None:
        self.thread.start()

    @property
    def running(self) -> bool:
        return self.thread.is_alive()

    def _on_progress(self, info) -> None:
        self.progress = dict(info)
        self.state = "checking" if info.get("state") == "Check" else "streaming"

    def _run(self) -> None:
        from ..post.link import SendSession as LinkSession, job_from_file
        from ..post.profiles import load_profile
        emulator = None
        try:
            if self.resume_from:
                self.log.append(f"resuming at segment {self.resume_from}")
            else:
                moved = set_aside_stale_journal(self.gcode_path)
                if moved:
                    self.log.append(f"journal of an earlier G-code kept as {moved}")
            profile = load_profile(self.machine)
            url, emulator = open_port(self.url, profile)
            if emulator is not None:
                self.log.append(f"dry run: {self.url} (the built-in controller emulator, "
                                "nothing moves)")
            self.session = LinkSession(job_from_file(self.gcode_path), profile,
                                       url, journal_path(self.gcode_path), mode=self.mode,
                                       check=self.check_first,
                                       resume_from=self.resume_from or None,
                                       progress=self._on_progress,
                                       confirm_work_zero=self.confirm_work_zero,
                                       cut_window=self.cut_window)
            self.state = "greeting"
            out = self.session.run()
            if out.controller is not None:
                c = out.controller
                self.log.append(f"controller: {c.flavour} {c.version} axes {c.axes} "
                                f"buffer {c.rx_size}")
            if out.check is not None:
                self.log.append(f"check: {out.check.status} {out.check.message}".strip())
            res = out.result if out.result is not None else out.check
            self.result = res
            self.state = res.status if res is not None else "failed"
            if out.result is not None:
                self.log.append(f"{res.status}: {res.acked}/{res.total} lines"
                                + (f", line {res.line} {res.block!r}: {res.message}"
                                   if res.line else ""))
            if out.resume_from:
                self.log.append(f"resume suggested at segment {out.resume_from} "
                                f"(journal knows it by {out.basis})")
        except LeatherCutError as exc:
            self.error = str(exc)
            self.state = "failed"
        except Exception as exc:  # a bug or an unexpected port error: say it, never hang
            import traceback
            FreeCAD.Console.PrintError(traceback.format_exc())
            self.error = f"{type(exc).__name__}: {exc}"
            self.state = "failed"
        finally:
            if emulator is not None:
                emulator.close()

    def pause(self) -> None:
        if self.session is not None:
            self.session.pause()

    def resume(self) -> None:
        if self.session is not None:   # waits for Hold:0: off the GUI thread
            threading.Thread(target=self.session.resume, daemon=True).start()

    def abort(self) -> None:
        if self.session is not None:
            self.session.abort()


#: the cut window choices (text, segments; see ``leathercut send --cut-window``)
CUT_WINDOWS = (
    (QT_TRANSLATE_NOOP("LeatherCut", "full look-ahead (fastest)"), 0),
    (QT_TRANSLATE_NOOP("LeatherCut", "2 segments"), 2),
    (QT_TRANSLATE_NOOP("LeatherCut", "1 segment: exact resume, stops at segment ends"), 1),
)

#: port choices offered besides the serial ports found: the controller emulator
EMULATOR_PORTS = ("emulator:grblhal", "emulator:grbl")


def open_port(url: str, profile):
    """(URL to open, emulator or None): ``emulator:grbl`` / ``emulator:grblhal``
    start the built-in fake controller, as ``leathercut send`` does."""
    from ..cli.send_cmd import _open_port
    return _open_port(url, profile)


def serial_ports():
    """Device names of the serial ports pyserial finds (empty without pyserial)."""
    try:
        from serial.tools import list_ports
        return [p.device for p in list_ports.comports()]
    except Exception:  # no pyserial or no permission to list: the user types the port
        return []


class SendPanel:
    """Port, check mode, start / pause / resume / stop, progress and log."""

    def __init__(self, job):
        self.job = job
        self.form = panel.load_form("SendToCutter")
        self.port = self.form.findChild(QtGui.QLineEdit, "PostPort")
        self.port.setText(job.PostPort)
        self.choices = self.form.findChild(QtGui.QComboBox, "portChoices")
        self.choices.addItem(translate("LeatherCut", "Choose a port…"), "")
        for dev in serial_ports():
            self.choices.addItem(dev, dev)
        for url in EMULATOR_PORTS:
            self.choices.addItem(translate("LeatherCut", "{0} – dry run, no machine").format(url), url)
        self.choices.activated.connect(self._choose_port)
        self.check = self.form.findChild(QtGui.QCheckBox, "checkFirst")
        self.confirm_zero = self.form.findChild(QtGui.QCheckBox, "confirmWorkZero")
        self.mode = self.form.findChild(QtGui.QComboBox, "streamMode")
        self.cut_window = self.form.findChild(QtGui.QComboBox, "cutWindow")
        for text, window in CUT_WINDOWS:
            self.cut_window.addItem(translate("LeatherCut", text), window)
        self.resume = self.form.findChild(QtGui.QComboBox, "resumeFrom")
        self.bar = self.form.findChild(QtGui.QProgressBar, "progressBar")
        self.status = self.form.findChild(QtGui.QLabel, "statusLabel")
        self.log = self.form.findChild(QtGui.QPlainTextEdit, "logView")
        self.file_label = self.form.findChild(QtGui.QLabel, "fileLabel")
        for name, fn in (("startButton", self.start), ("pauseButton", self.pause),
                         ("resumeButton", self.resume_motion), ("stopButton", self.stop)):
            self.form.findChild(QtGui.QPushButton, name).clicked.connect(fn)
        self.session: Optional[SendSession] = None
        self.logged = 0
        self.timer = QtCore.QTimer()
        self.timer.setInterval(100)
        self.timer.timeout.connect(self.poll)
        self.gcode = job.PostLastOutput
        self.file_label.setText(self.gcode or translate("LeatherCut", "(post-process the job first)"))
        self.fill_resume_points()

    def _choose_port(self, index: int) -> None:
        url = self.choices.itemData(index)
        if url:
            self.port.setText(url)

    def choose_port(self, url: str) -> bool:
        """Pick ``url`` from the offered ports (macros, tests); False when not offered."""
        i = self.choices.findData(url)
        if i < 0:
            return False
        self.choices.setCurrentIndex(i)
        self._choose_port(i)
        return True

    def fill_resume_points(self) -> None:
        """Segments of the journal's job; the first incomplete one is suggested."""
        self.resume.clear()
        self.resume.addItem(translate("LeatherCut", "start of the job"), "")
        if not self.gcode or not os.path.isfile(self.gcode):
            return
        from ..post.link import load_journal
        try:
            if not journal_matches(self.gcode):
                return
            st = load_journal(journal_path(self.gcode))
        except LeatherCutError:
            return
        done = set(st.done_segments())
        suggest = 0
        for seg in st.segments:
            self.resume.addItem(seg + (" ✓" if seg in done else ""), seg)
            if not suggest and seg not in done and done:
                suggest = self.resume.count() - 1
        self.resume.setCurrentIndex(suggest)

    def start(self) -> Optional[SendSession]:
        if self.session is not None and self.session.running:
            return None
        if not self.gcode or not os.path.isfile(self.gcode):
            self.show(translate("LeatherCut", "Post-process the job as G-code first."), True)
            return None
        url = self.port.text().strip()
        if not url:
            self.show(translate("LeatherCut", "Enter the port (e.g. /dev/ttyUSB0 or socket://host:23), "
                                              "or choose emulator:grblhal for a dry run."), True)
            return None
        try:  # the layout gate: parts may have been moved since the file was written
            pipeline.check_gate(self.job)
        except LeatherCutError as exc:
            self.show(str(exc), True)
            return None
        if url != self.job.PostPort:
            with base.transaction(self.job.Document, "LeatherCut: port"):
                self.job.PostPort = url
        self.session = SendSession(self.gcode, self.job.PostMachine, url, self.check.isChecked(),
                                   self.mode.currentText(), self.resume.currentData() or "",
                                   confirm_work_zero=self.confirm_zero.isChecked(),
                                   cut_window=int(self.cut_window.currentData()))
        self.logged = 0
        self.log.clear()
        self.session.start()
        self.timer.start()
        return self.session

    def pause(self) -> None:
        if self.session is not None:
            self.session.pause()

    def resume_motion(self) -> None:
        if self.session is not None:
            self.session.resume()

    def stop(self) -> None:
        if self.session is not None:
            self.session.abort()

    def poll(self) -> None:
        s = self.session
        if s is None:
            return
        p = s.progress
        if p:
            self.bar.setValue(int(p.get("percent", 0)))
        for line in s.log[self.logged:]:
            self.log.appendPlainText(line)
        self.logged = len(s.log)
        if s.error:
            self.show(s.error, True)
        else:
            self.show(translate("LeatherCut", "{0}: {1}/{2} lines, segment {3}, controller {4}").format(
                s.state, p.get("acked", 0), p.get("total", 0), p.get("segment", ""), p.get("state", "")))
        if not s.running:
            self.timer.stop()
            if s.result is not None and not s.result.ok:
                # a stop the operator asked for is not an error
                asked = s.result.status == "aborted"
                self.show(translate("LeatherCut", "Stopped ({0}) at line {1}: {2}. Choose where to resume.").format(
                    s.result.status, s.result.line, s.result.message), not asked)
            self.fill_resume_points()

    def show(self, text: str, error: bool = False) -> None:
        self.status.setText(messages.for_gui(text))
        self.status.setStyleSheet("color: #c62828;" if error else "")

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        if self.session is not None and self.session.running:
            self.show(translate("LeatherCut", "Stop the job before closing."), True)
            return False
        self.timer.stop()
        Gui.Control.closeDialog()
        return True

    def accept(self):
        return self.reject()


class SendToCutter(base.Command):
    NAME = "LeatherCut_SendToCutter"
    ICON = "SendToCutter"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_SendToCutter", "Send to cutter…")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_SendToCutter",
                            "Stream the posted G-code to a GRBL / grblHAL controller over a serial port, "
                            "with check mode, pause, stop and resume from the journal")

    def active(self) -> bool:
        job = base.active_job()
        return job is not None and bool(job.PostLastOutput) and not Gui.Control.activeDialog()

    def run(self) -> None:
        panel.ensure_no_dialog()
        job = base.active_job()
        if job.PostFormat != "gcode":
            raise InputError(translate("LeatherCut", "Send to cutter streams G-code: post-process as gcode"))
        panel.show(SendPanel(job))


COMMAND = SendToCutter
