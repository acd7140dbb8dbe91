"""One send, start to end: what ``leathercut send`` and the workbench's *Send to
cutter* command both run (the GUI runs it in a worker thread via
:meth:`SendSession.start`, never on the GUI thread).

Order: open the port (exclusive) -> greet and identify -> plan what to send
(the job, or the resume program) -> check the job's axes against the
controller -> refuse Door/Hold, home when locked in Alarm (profile ``homing``)
-> the safety check of the lines to send (:func:`..safety.check_program`:
the resume preamble and re-written feeds are the link's own lines) ->
optional check-mode pass (``$C``) -> open the journal -> stream -> close.
With ``resume_from`` the journal must exist and belong to the same job; the
stream is then :func:`~.job.resume_job` of the job at that segment, skipping
segments after the first incomplete one that the journal shows executed
(:mod:`.recovery` decides what was executed, not only acknowledged), over the
journal's last pass only.

A resume after a stop that lost the machine position (reset we did not ask
for, power loss, lost link, ALARM:1/3) needs the work zero re-established:
the link homes (``$H``, profile ``homing``) or the operator confirms the work
zero (``confirm_work_zero``, CLI ``--confirm-work-zero``); the journal records
which (``zero``).  Otherwise the resume is refused.  After a lost link, a
homing machine that is found Idle (so it kept its power: it would be locked in
Alarm otherwise) reports where it stopped, which the journal records
(``reconnect``) as evidence for the interrupted run.

grblHAL with ``$701=1`` applies F to the linear axes only: the knife-turning
cuts' raised F words are taken back (:func:`.feeds.linear_feed_only`).
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass
from typing import Callable, Dict, Optional

from ...core.errors import InputError
from ..profiles import MachineProfile
from ..safety import check_program
from .feeds import linear_feed_only
from .grbl import ControllerInfo, GrblLink, LinkError, StreamResult
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
    tool_at: Optional[Dict] = None           # where the tool is after a stop (journal)
    zero: str = ""                           # homed | confirmed (resume after a lost position)
    feeds_adjusted: int = 0                  # F words taken back for $701=1

    @property
    def ok(self) -> bool:
        return self.result is not None and self.result.ok

    def to_json(self) -> Dict:
        return {"controller": self.controller.to_json() if self.controller else None,
                "check": self.check.to_json() if self.check else None,
                "result": self.result.to_json() if self.result else None,
                "journal": self.journal, "resumed_from": self.resumed_from,
                "resume_from": self.resume_from, "resume_basis": self.basis,
                "lines": self.lines, "tool_at": self.tool_at, "zero": self.zero,
                "feeds_adjusted": self.feeds_adjusted}


class SendSession:
    """Configure once, then :meth:`run` (blocking) or :meth:`start` (thread)."""

    def __init__(self, job: SendJob, profile: MachineProfile, url: str, journal_path: str,
                 mode: str = "send-response", check: bool = False, home: bool = True,
                 resume_from: Optional[str] = None, baud: Optional[int] = None,
                 progress: Optional[Callable[[Dict], None]] = None,
                 confirm_work_zero: bool = False, **link_options):
        self.job = job
        self.profile = profile
        self.url = url
        self.journal_path = journal_path
        self.mode = mode
        self.check = check
        self.home = home
        self.resume_from = resume_from
        self.confirm_work_zero = confirm_work_zero
        self._state = None
        self.streamed: Optional[SendJob] = None      # what was (or is being) streamed
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
        """The lines to send: the job, or the resume program from the journal
        (its last pass).  Call after greeting: a lost link's reconnect evidence
        is taken from the controller's status."""
        if not self.resume_from:
            return self.job
        if not os.path.exists(self.journal_path):
            raise InputError("no journal to resume from", source=self.journal_path)
        state = load_journal(self.journal_path)
        self._reconnect_evidence(state)
        suggestion = state.first_incomplete()
        seg = suggestion if self.resume_from == "auto" else self.resume_from
        if seg is None:
            raise InputError("the journal shows every segment of its last run complete: "
                             "nothing to resume (send without --resume-from for a new run)",
                             source=self.journal_path)
        if seg not in self.job.segment_ids:
            raise InputError(f"no segment {seg!r} in the job", source=self.job.name)
        later_done = state.later_done(seg)
        self._state = state
        self.outcome.resumed_from = seg
        return resume_job(self.job, seg, self.profile, skip=later_done)

    def _reconnect_evidence(self, state) -> None:
        """After a lost link: a homing controller found Idle kept its power and
        position; its report says where the interrupted run stopped."""
        end = state.last_end
        st = self.link._status
        if (end is None or end.get("e") != "lost" or not self.profile.homing
                or st is None or st.state != "Idle"):
            return
        from .protocol import position
        pos = position(st, self.link._wco)
        if pos is None:
            return
        here = dict(zip(self.link.info.axes, pos))
        with Journal(self.journal_path) as j:
            j.event("reconnect", position=here, state=st.state)
        state.runs[-1]["end"] = {**end, "position": here, "position_trusted": True,
                                 "position_lost": False, "reconnect": True}
        state._executed = None

    def _zero(self) -> str:
        """Re-establish the work zero before a resume after a lost position:
        home (profile ``homing``) or the operator's confirmation; else refuse."""
        state = self._state
        if state is None or not state.position_lost():
            return ""
        if self.profile.homing and self.home:
            if not self.link.homed:
                self.link.ready_for_job(self.profile, home=True, force_home=True)
            return "homed"
        if self.confirm_work_zero:
            return "confirmed"
        end = state.last_end or {}
        raise LinkError(f"the machine position was lost at the stop ({end.get('e', 'no end record')}"
                        f"{': ' + end['message'] if end.get('message') else ''}): home the machine "
                        "or set the work zero at the machine again, then resume with "
                        "--confirm-work-zero", source=self.url)

    def run(self) -> SendOutcome:
        """Blocking.  Raises LinkError / InputError for a controller that cannot
        take the job; controller faults during the stream end in ``result``."""
        link = self.link
        journal = None
        try:
            link.open()
            self.outcome.controller = link.greet()
            to_send = self.plan_stream()
            self.outcome.lines = len(to_send.blocks)
            link.check_axes(to_send)
            link.ready_for_job(self.profile, home=self.home)
            zero = self._zero()
            if link.feed_linear_only and self.profile.rotary_in_feed:
                to_send, self.outcome.feeds_adjusted = linear_feed_only(to_send, self.profile)
            # the lines the link made (resume preamble, feeds taken back) pass
            # the same check as the job: nothing unchecked reaches the machine
            check_program(to_send.blocks, self.profile, f"{self.job.name} (lines to send)")
            self.streamed = to_send
            if self.check:
                self.outcome.check = link.run_check(to_send, self.mode)
                if not self.outcome.check.ok:
                    return self.outcome
                link.ready_for_job(self.profile, home=self.home)
            journal = Journal.open(self.journal_path, self.job, self.mode, self.profile,
                                   resume_seg=self.outcome.resumed_from)
            if zero:
                journal.event("zero", how=zero)
                self.outcome.zero = zero
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
            self.outcome.tool_at = state.tool_at()
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
