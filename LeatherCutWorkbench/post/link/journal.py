"""The job journal: an append-only record of what the controller acknowledged.

One JSON object per line.  The first record describes the job (file, SHA-256
of its lines, line count, segment ids in order); then one ``ack`` record per
acknowledged line (``{"e": "ack", "i": <line index>, "s": "<segment id>"}``),
and events: ``error``, ``alarm``, ``reset``, ``lost``, ``stopped``, ``done``,
``resume``, ``sync`` (the ``ok`` of a ``G4 P0``: everything before it was
*executed*, not only acknowledged) and ``exec`` (``{"e": "exec", "i": [..]}``:
job lines a status report proved executed, :mod:`.progress`).

Every record is written with one ``write`` call and flushed to the operating
system at once, so a crash of our process loses nothing; ``os.fsync`` runs for
every non-ack record and at least every ``fsync_interval`` seconds for acks
(a power cut loses at most that much, and an fsync per line would slow
streaming on slow disks).  The journal is never rewritten: a resumed run
appends to it.

**Runs.**  Every fresh send of a job writes a new ``job`` record with a new
``run`` id: it starts a new *pass* over the job (e.g. the next hide), and a
pass never inherits the progress of an earlier one.  A resume writes a
``resume`` record naming the pass it continues (``of``) and its own run id.
:func:`load_journal` reasons only over the last pass: its first run and its
resumes.  A ``zero`` record says how the work zero was re-established before
a resume after a lost position (``homed`` or ``confirmed``).

The job record also holds the program itself and the machine's axes, so a
journal alone says what was executed (``load_journal``): acknowledged is not
executed -- GRBL acknowledges a line when it enters the planner -- so
:mod:`.recovery` decides per run from the stop position the controller
reported after a clean stop, or else from the last synchronising line.  A
segment is *complete* when every line of it was executed; the first
incomplete one is the suggested resume point.  The operator chooses where to
resume (``--resume-from``); it is never automatic.
"""

from __future__ import annotations

import hashlib
import json
import os
import time
import uuid
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Set

from ...core.errors import InputError
from .recovery import STOP_EVENTS, executed_lines, tool_line


def job_digest(lines: Sequence[str]) -> str:
    """SHA-256 of the job's lines (identifies the job a journal belongs to)."""
    h = hashlib.sha256()
    for line in lines:
        h.update(line.encode("utf-8", "replace"))
        h.update(b"\n")
    return h.hexdigest()


class Journal:
    """Append-only writer.  Use :meth:`open` to start or continue a journal."""

    def __init__(self, path: str, fsync_interval: float = 0.2):
        self.path = path
        self.fsync_interval = fsync_interval
        try:
            self._fh = open(path, "a", encoding="utf-8")
        except OSError as exc:
            raise InputError(f"cannot write the job journal: {exc.strerror}", source=path)
        self._last_sync = time.monotonic()
        self.run_id = ""
        self.pass_id = ""

    @classmethod
    def open(cls, path: str, job, mode: str, profile=None,
             resume_seg: Optional[str] = None) -> "Journal":
        """Open ``path`` for appending the journal of ``job`` (a
        :class:`~.job.SendJob`).  A fresh send (``resume_seg`` None) writes a new
        ``job`` record: a new pass that never inherits an earlier pass's
        progress.  A resume (``resume_seg`` = the segment it starts at) needs
        the journal of this very job and writes a ``resume`` record continuing
        its last pass.  A journal of another job (different digest) is refused.
        ``profile`` (the machine profile) tells the interpreter the axes and a
        wrapped axis; by default every axis letter is accepted and none wraps."""
        lines = job.source
        segs = [""] * len(lines)          # segment of every line that is sent
        for k, i in enumerate(job.index):
            if i is not None:
                segs[i] = job.segs[k]
        digest = job_digest(lines)
        state = None
        if os.path.exists(path) and os.path.getsize(path) > 0:
            state = load_journal(path)
            if state.digest != digest:
                raise InputError("the journal belongs to another job (different G-code); "
                                 "choose a new --journal file", source=path)
        j = cls(path)
        run = uuid.uuid4().hex[:12]
        j.run_id = run
        if resume_seg is not None:
            if state is None:
                j.close()
                raise InputError("no journal to resume from", source=path)
            j.pass_id = state.pass_id
            j.write({"e": "resume", "seg": resume_seg, "run": run, "of": state.pass_id,
                     "time": time.time()}, sync=True)
            return j
        machine = {"axes": "XYZABC", "wrapped": "", "turn": 360.0, "rotary": ""}
        if profile is not None:
            machine = {"axes": profile.axes, "rotary": profile.rotary_axis,
                       "wrapped": profile.rotary_axis if profile.rotary_wrap else "",
                       "turn": profile.units_per_turn if profile.rotary_wrap else 360.0}
        j.pass_id = run
        j.write({"e": "job", "run": run, "job": job.name, "sha256": digest, "lines": len(lines),
                 "segs": segs, "segments": list(job.segment_ids), "mode": mode,
                 "source": list(lines), "machine": machine, "time": time.time()}, sync=True)
        return j

    def write(self, record: Dict, sync: bool = False) -> None:
        self._fh.write(json.dumps(record, separators=(",", ":")) + "\n")
        self._fh.flush()
        now = time.monotonic()
        if sync or now - self._last_sync >= self.fsync_interval:
            os.fsync(self._fh.fileno())
            self._last_sync = now

    def ack(self, index: int, seg: str) -> None:
        self.write({"e": "ack", "i": index, "s": seg})

    def proof(self, lines: List[int]) -> None:
        """Job lines a status report proved executed (:mod:`.progress`)."""
        self.write({"e": "exec", "i": list(lines)})

    def event(self, kind: str, **data) -> None:
        self.write({"e": kind, "time": time.time(), **data}, sync=True)

    def __enter__(self) -> "Journal":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        if not self._fh.closed:
            self._fh.flush()
            os.fsync(self._fh.fileno())
            self._fh.close()


@dataclass
class JournalState:
    """What a journal says about its job."""

    path: str
    job: str = ""
    digest: str = ""
    lines: int = 0
    segs: List[str] = field(default_factory=list)          # segment id per line
    segments: List[str] = field(default_factory=list)      # ordered ids
    acked: List[int] = field(default_factory=list)         # line indices, in ack order
    events: List[Dict] = field(default_factory=list)
    last_sync: Optional[int] = None                        # line index of last synced G4 P0
    source: List[str] = field(default_factory=list)        # the job's lines
    machine: Dict = field(default_factory=dict)            # axes, wrapped, turn, rotary
    runs: List[Dict] = field(default_factory=list)         # {"acked": [...], "end": event}
    _executed: Optional[Set[int]] = None
    bases: List[str] = field(default_factory=list)
    pass_id: str = ""                                      # run id of the pass's first run
    passes: int = 0                                        # fresh sends in the journal
    run_executed: List[Set[int]] = field(default_factory=list)

    @property
    def last_end(self) -> Optional[Dict]:
        """How the last run of the pass ended (its stop or done record)."""
        return self.runs[-1]["end"] if self.runs else None

    def position_lost(self) -> bool:
        """True when the last run ended with the machine position lost (reset we
        did not ask for, power cycle, disconnect, ALARM:1/3, or no end record
        at all): a resume must then home or have the work zero confirmed."""
        end = self.last_end
        if not self.runs or end is None:       # LeatherCut or the PC died mid-run
            return bool(self.runs and self.runs[-1]["acked"])
        return bool(end.get("position_lost"))

    @property
    def acked_set(self) -> set:
        return set(self.acked)

    def executed(self) -> Set[int]:
        """Line indices the machine executed (see :mod:`.recovery`); without the
        program in the journal (old journals) the acknowledged lines."""
        if self._executed is None:
            if self.source:
                m = self.machine
                self._executed, self.bases, self.run_executed = executed_lines(
                    self.runs, self.source, m.get("axes", "XYZABC"), m.get("wrapped", ""),
                    float(m.get("turn", 360.0)), m.get("rotary", ""))
            else:
                self._executed, self.bases = self.acked_set, ["acks"] * len(self.runs)
                self.run_executed = [set(r["acked"]) for r in self.runs]
        return self._executed

    def tool_at(self) -> Optional[Dict]:
        """Where the tool is after the last run's stop: ``{"line": 1-based line,
        "block", "segment", "how": on | after}`` (on = the move it stopped on,
        from the reported position; after = the last line known executed)."""
        self.executed()
        if not self.runs or not self.source:
            return None
        got = tool_line(self.runs[-1], self.run_executed[-1], self.bases[-1], self.source)
        if got is None:
            return None
        i, how = got
        return {"line": i + 1, "block": self.source[i].strip(),
                "segment": self.segs[i] if i < len(self.segs) else "", "how": how}

    def _segments_with(self, have: Set[int]) -> List[str]:
        lines_of: Dict[str, List[int]] = {}
        for i, s in enumerate(self.segs):
            if s:
                lines_of.setdefault(s, []).append(i)
        return [s for s in self.segments if s in lines_of and all(i in have for i in lines_of[s])]

    def done_segments(self) -> List[str]:
        """Segments whose every line the machine executed (in job order)."""
        return self._segments_with(self.executed())

    def first_incomplete(self) -> Optional[str]:
        """The suggested resume point: the first segment not completely executed
        (None when every segment is)."""
        done = set(self.done_segments())
        for s in self.segments:
            if s not in done:
                return s
        return None

    def later_done(self, seg: Optional[str] = None) -> List[str]:
        """Complete segments after the suggested resume point: a resume skips them."""
        first = self.first_incomplete()
        if first is None:
            return []
        k = self.segments.index(first)
        return [s for s in self.done_segments() if self.segments.index(s) > k and s != seg]


def load_journal(path: str) -> JournalState:
    """Read a journal; a truncated last record (crash mid-write) is ignored.
    The state describes the journal's last pass (its last fresh send and the
    resumes of it): earlier passes are history, never progress."""
    st = JournalState(path)
    try:
        fh = open(path, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot read journal: {exc.strerror}", source=path)
    with fh:
        for n, line in enumerate(fh, 1):
            try:
                rec = json.loads(line)
            except json.JSONDecodeError:
                continue              # torn final write
            if not isinstance(rec, dict):
                continue
            e = rec.get("e")
            if e == "job":
                if st.digest and rec.get("sha256") != st.digest:
                    raise InputError(f"journal holds two different jobs (line {n})", source=path)
                # a fresh send: a new pass, nothing of the earlier one carries over
                st.job = rec.get("job", "")
                st.digest = rec.get("sha256", "")
                st.lines = rec.get("lines", 0)
                st.segs = rec.get("segs", [])
                st.segments = rec.get("segments", [])
                st.source = rec.get("source", [])
                st.machine = rec.get("machine", {})
                st.pass_id = rec.get("run", f"line{n}")
                st.passes += 1
                st.acked, st.events, st.last_sync = [], [], None
                st.runs = [{"acked": [], "end": None, "syncs": [], "run": st.pass_id}]
            elif e == "exec":
                if st.runs:
                    st.runs[-1].setdefault("proofs", set()).update(rec.get("i", []))
            elif e == "ack":
                st.acked.append(rec["i"])
                if st.runs and st.runs[-1]["end"] is not None:
                    # acks after a stop without a resume record (old journals)
                    st.runs.append({"acked": [], "end": None, "syncs": []})
                if st.runs:
                    st.runs[-1]["acked"].append(rec["i"])
            else:
                if e == "resume" and rec.get("of") not in (None, st.pass_id):
                    continue          # resumes an earlier pass: not this pass's progress
                st.events.append(rec)
                if e == "sync":
                    st.last_sync = rec.get("i")
                    if st.runs:
                        st.runs[-1]["syncs"].append(rec.get("i"))
                elif e == "resume":
                    st.runs.append({"acked": [], "end": None, "syncs": [],
                                    "run": rec.get("run", "")})
                elif e == "zero" and st.runs:
                    st.runs[-1]["zeroed"] = rec.get("how", "")
                elif e == "reconnect" and st.runs and st.runs[-1]["end"] is not None:
                    # the controller kept power and position over a lost link and
                    # reported where it stopped: evidence for the interrupted run
                    st.runs[-1]["end"] = {**st.runs[-1]["end"], "position": rec.get("position"),
                                          "position_trusted": True, "position_lost": False,
                                          "reconnect": True}
                elif (e in STOP_EVENTS or e == "done") and st.runs:
                    st.runs[-1]["end"] = rec
    if not st.digest:
        raise InputError("not a LeatherCut job journal (no job record)", source=path)
    return st
