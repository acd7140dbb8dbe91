"""One send, start to end: what ``leathercut send`` and the workbench's *Send to
cutter* command both run (the GUI runs it in a worker thread via
:meth:`SendSession.start`, never on the GUI thread).

Order: open the port -> greet and identify -> check the job's axes against the
controller -> refuse Door/Hold, home when locked in Alarm (profile ``homing``)
-> optional check-mode pass (``$C``) -> open the journal -> stream -> close.
With ``resume_from`` the journal must exist and belong to the same job; the
stream is then :func:`~.job.resume_job` of the job at that segment, skipping
segments after the first incomplete one that the journal shows executed
(:mod:`.recovery` decides what was executed, not only acknowledged).
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass
from typing import Callable, Dict, Optional

from ...core.errors import InputError
from ..profiles import MachineProfile
from .grbl import ControllerInfo, GrblLink, StreamResult
from .job import SendJob, resume_job
from .journal import Journal, load_journal


@dataclass
class SendOutcome:
    controller: Optional[ControllerInfo] = None
    check: Optional[StreamResult] = None
    result: Optional[StreamResult] = None
    journal: str = ""
    resumed_from: Optional[str] = None
    resume_from: Optional[str] = None        # suggestion after a stop
    basis: str = ""                          # how the journal knows: position | sync
    lines: int = 0

    @property
    def ok(self) -> bool:
        return self.result is not None and self.result.ok

    def to_json(self) -> Dict:
        return {"controller": self.controller.to_json() if self.controller else None,
                "check": self.check.to_json() if self.check else None,
                "result": self.result.to_json() if self.result else None,
                "journal": self.journal, "resumed_from": self.resumed_from,
                "resume_from": self.resume_from, "resume_basis": self.basis,
                "lines": self.lines}


class SendSession:
    """Configure once, then :meth:`run` (blocking) or :meth:`start` (thread)."""

    def __init__(self, job: SendJob, profile: MachineProfile, url: str, journal_path: str,
                 mode: str = "send-response", check: bool = False, home: bool = True,
                 resume_from: Optional[str] = None, baud: Optional[int] = None,
                 progress: Optional[Callable[[Dict], None]] = None, **link_options):
        self.job = job
        self.profile = profile
        self.url = url
        self.journal_path = journal_path
        self.mode = mode
        self.check = check
        self.home = home
        self.resume_from = resume_from
        self.link = GrblLink(url, baud or profile.baud, progress=progress, **link_options)
        self.link.use_profile(profile)
        self.outcome = SendOutcome(journal=journal_path)
        self.error: Optional[BaseException] = None
        self._thread: Optional[threading.Thread] = None

    # ------------------------------------------------------------- control
    def pause(self) -> None:
        self.link.pause()

    def resume(self) -> None:
        self.link.resume()

    def abort(self) -> None:
        self.link.abort()

    @property
    def paused(self) -> bool:
        return self.link._paused.is_set()

    # ----------------------------------------------------------------- run
    def plan_stream(self) -> SendJob:
        """The lines to send: the job, or the resume program from the journal."""
        if not self.resume_from:
            return self.job
        if not os.path.exists(self.journal_path):
            raise InputError("no journal to resume from", source=self.journal_path)
        state = load_journal(self.journal_path)
        suggestion = state.first_incomplete()
        seg = suggestion if self.resume_from == "auto" else self.resume_from
        if seg is None:
            raise InputError("the journal shows every segment complete: nothing to resume",
                             source=self.journal_path)
        if seg not in self.job.segment_ids:
            raise InputError(f"no segment {seg!r} in the job", source=self.job.name)
        later_done = state.later_done(seg)
        self.outcome.resumed_from = seg
        return resume_job(self.job, seg, self.profile, skip=later_done)

    def run(self) -> SendOutcome:
        """Blocking.  Raises LinkError / InputError for a controller that cannot
        take the job; controller faults during the stream end in ``result``."""
        to_send = self.plan_stream()
        self.outcome.lines = len(to_send.blocks)
        link = self.link
        journal = None
        try:
            link.open()
            self.outcome.controller = link.greet()
            link.check_axes(to_send)
            link.ready_for_job(self.profile, home=self.home)
            if self.check:
                self.outcome.check = link.run_check(to_send, self.mode)
                if not self.outcome.check.ok:
                    return self.outcome
                link.ready_for_job(self.profile, home=self.home)
            journal = Journal.open(self.journal_path, self.job, self.mode, self.profile)
            if self.outcome.resumed_from:
                journal.event("resume", seg=self.outcome.resumed_from)
            self.outcome.result = link.stream(to_send, journal, self.mode)
        finally:
            if journal is not None:
                journal.close()
            link.close()
        if not self.outcome.result.ok:
            state = load_journal(self.journal_path)
            self.outcome.resume_from = state.first_incomplete()
            state.executed()
            self.outcome.basis = state.bases[-1] if state.bases else ""
        return self.outcome

    def start(self, on_done: Optional[Callable[["SendSession"], None]] = None
              ) -> threading.Thread:
        """Run in a worker thread; ``on_done(session)`` is called from that
        thread at the end (``session.outcome`` / ``session.error``)."""
        def work() -> None:
            try:
                self.run()
            except BaseException as exc:      # reported to the caller, not lost
                self.error = exc
            if on_done is not None:
                on_done(self)
        self._thread = threading.Thread(target=work, name="leathercut-send", daemon=True)
        self._thread.start()
        return self._thread
