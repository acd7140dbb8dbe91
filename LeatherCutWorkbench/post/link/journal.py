"""The job journal: an append-only record of what the controller acknowledged.

One JSON object per line.  The first record describes the job (file, SHA-256
of its lines, line count, segment ids in order); then one ``ack`` record per
acknowledged line (``{"e": "ack", "i": <line index>, "s": "<segment id>"}``),
and events: ``error``, ``alarm``, ``reset``, ``lost``, ``stopped``, ``done``,
``resume``, ``sync`` (the ``ok`` of a ``G4 P0``: everything before it was
*executed*, not only acknowledged).

Every record is written with one ``write`` call and flushed to the operating
system at once, so a crash of our process loses nothing; ``os.fsync`` runs for
every non-ack record and at least every ``fsync_interval`` seconds for acks
(a power cut loses at most that much, and an fsync per line would slow
streaming on slow disks).  The journal is never rewritten: a resumed run
appends to it.

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
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Set

from ...core.errors import InputError
from .recovery import STOP_EVENTS, executed_lines


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

    @classmethod
    def open(cls, path: str, job, mode: str, profile=None) -> "Journal":
        """Open ``path`` for appending the journal of ``job`` (a
        :class:`~.job.SendJob`); writes a ``job`` record unless the file already
        journals this very job (same digest), else refuses.  ``profile`` (the
        machine profile) tells the interpreter the axes and a wrapped axis; by
        default every axis letter is accepted and none wraps."""
        lines = job.source
        segs = [""] * len(lines)          # segment of every line that is sent
        for k, i in enumerate(job.index):
            if i is not None:
                segs[i] = job.segs[k]
        digest = job_digest(lines)
        if os.path.exists(path) and os.path.getsize(path) > 0:
            state = load_journal(path)
            if state.digest != digest:
                raise InputError("the journal belongs to another job (different G-code); "
                                 "choose a new --journal file", source=path)
            j = cls(path)
            return j
        j = cls(path)
        machine = {"axes": "XYZABC", "wrapped": "", "turn": 360.0, "rotary": ""}
        if profile is not None:
            machine = {"axes": profile.axes, "rotary": profile.rotary_axis,
                       "wrapped": profile.rotary_axis if profile.rotary_wrap else "",
                       "turn": profile.units_per_turn if profile.rotary_wrap else 360.0}
        j.write({"e": "job", "job": job.name, "sha256": digest, "lines": len(lines),
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

    def event(self, kind: str, **data) -> None:
        self.write({"e": kind, "time": time.time(), **data}, sync=True)

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

    @property
    def acked_set(self) -> set:
        return set(self.acked)

    def executed(self) -> Set[int]:
        """Line indices the machine executed (see :mod:`.recovery`); without the
        program in the journal (old journals) the acknowledged lines."""
        if self._executed is None:
            if self.source:
                m = self.machine
                self._executed, self.bases = executed_lines(
                    self.runs, self.source, m.get("axes", "XYZABC"), m.get("wrapped", ""),
                    float(m.get("turn", 360.0)), m.get("rotary", ""))
            else:
                self._executed, self.bases = self.acked_set, ["acks"] * len(self.runs)
        return self._executed

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
    """Read a journal; a truncated last record (crash mid-write) is ignored."""
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
            e = rec.get("e")
            if e == "job":
                if st.digest and rec.get("sha256") != st.digest:
                    raise InputError(f"journal holds two different jobs (line {n})", source=path)
                if not st.digest:
                    st.job = rec.get("job", "")
                    st.digest = rec.get("sha256", "")
                    st.lines = rec.get("lines", 0)
                    st.segs = rec.get("segs", [])
                    st.segments = rec.get("segments", [])
                    st.source = rec.get("source", [])
                    st.machine = rec.get("machine", {})
                    st.runs.append({"acked": [], "end": None})
            elif e == "ack":
                st.acked.append(rec["i"])
                if st.runs and st.runs[-1]["end"] is not None:
                    st.runs.append({"acked": [], "end": None})   # a resume without its event
                if st.runs:
                    st.runs[-1]["acked"].append(rec["i"])
            else:
                st.events.append(rec)
                if e == "sync":
                    st.last_sync = rec.get("i")
                elif e == "resume":
                    st.runs.append({"acked": [], "end": None})
                elif (e in STOP_EVENTS or e == "done") and st.runs:
                    st.runs[-1]["end"] = rec
    if not st.digest:
        raise InputError("not a LeatherCut job journal (no job record)", source=path)
    return st
