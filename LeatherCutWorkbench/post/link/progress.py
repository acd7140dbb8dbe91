"""What the controller's status reports prove was *executed* while a job
streams, and the cut look-ahead limit that bounds a re-cut after a power loss.

GRBL acknowledges a line when it enters the planner, so acknowledgements say
nothing about execution.  A status report does: it is produced when the
``?`` arrives and tells where the tool is (``MPos``/``WPos``) and, with
``Bf:`` (GRBL ``$10`` bit 1, grblHAL), how many receive-buffer bytes are
still unread.  :class:`ExecutionProof` turns each report into the set of
blocks that were certainly executed by then:

* **position**: the tool is on the path of the first block, from the first
  block not yet proven on, whose path contains the reported position (the
  machine executes blocks in order, so the true block is that one or a later
  one): every block before it was executed, and the block itself when the
  tool is at its very end;
* **Idle with Bf**: Idle means the planner is empty; every line read out of
  the receive buffer (sent bytes minus unread bytes) was executed, except
  possibly the last one (a dwell or sync may still be running);
* **Idle, all answered** (only without ``Bf``): with no spurious ``ok``
  seen, Idle after every sent line was answered means they were all
  executed (a dwell still running has no answer yet).

Proofs are journaled (``exec`` records) and :mod:`.recovery` counts them as
executed after a stop that lost the position (power loss, disconnect), so a
resume starts at the segment the tool was in, not at the item's last
verified sync.

**Why not always exactly one segment.**  Inside a contour the knife crosses
from one segment to the next without stopping; for that the next segment's
first line must already be in the planner.  If the power fails after the
crossing and before the next status report, the host has seen exactly what
it would have seen had the power failed just before the crossing: no report,
acknowledgement or journal record tells the two apart.  A lossless resume
must then cut the tail of the earlier segment again.  By default (``window``
0, no limit) the re-cut after a power loss is the interrupted segment plus
what was executed since the last status report (about ``status_interval`` of
motion), rounded out to whole segments, and the planner keeps its full
look-ahead.  The *cut window* bounds it structurally instead: with
``window`` N the link never has cutting lines of more than N segments in
flight that no report has proven executed -- with 2 a re-cut is the
interrupted segment plus, at most, the segment before it, and that only when
the boundary was crossed after the last status report; 1 (or the profile's
``sync_every_segment``) bounds it to the interrupted segment, at the price of
the head stopping at every segment end.  A window also limits the planner's
look-ahead to that many segments, which starves chains of very short
segments (a curve imported as many short lines): window 2 made a job of 5 ms
lines up to 2.3 times slower (docs/BENCHMARKS.md), hence the default 0.
Faults that keep the position (error, soft-limit alarm, stall,
garbled reply) resume exactly from the stop position (:mod:`.recovery`).
"""

from __future__ import annotations

import re
from typing import Dict, List, Optional

from ..gcode_reader import GcodeError, TraceMove, interpreter_for
from .recovery import _tolerances, locate

#: a cutting block: G1/G2/G3 (not G17, G20, G21 ...) inside a segment
CUT_BLOCK = re.compile(r"^(N\d+)?G0*[123](?![0-9.])")


def is_cut(block: str, seg: str) -> bool:
    """Whether a cleaned block of segment ``seg`` cuts (feed motion in a segment)."""
    return bool(seg) and bool(CUT_BLOCK.match(block))


class ExecutionProof:
    """Per stream: the blocks proven executed (``proven``: every block with a
    lower position in the stream) and the cut window.  Positions are work
    coordinates (mm / axis units) keyed by axis letter."""

    def __init__(self, job, profile, window: int = 0):
        self.job = job
        self.window = max(0, int(window))     # 0: no limit
        self.proven = 0
        self.stopped = False              # an error was answered: prove nothing more
        self.tol = _tolerances(profile.axes, profile.rotary_axis)
        self.moves: List[List[TraceMove]] = []
        it = interpreter_for(profile)
        for k, block in enumerate(job.blocks):
            try:
                got = it.execute(block, k + 1)
            except GcodeError:
                got = []                  # the controller refuses it too
            self.moves.append([m for m in got if m.kind in ("rapid", "line", "arc")])
        self.cut = [is_cut(b, s) and bool(self.moves[k])
                    for k, (b, s) in enumerate(zip(job.blocks, job.segs))]
        self.ends: List[int] = []         # bytes sent through block k (len + newline)
        total = 0
        for b in job.blocks:
            total += len(b) + 1
            self.ends.append(total)

    # ---------------------------------------------------------- proofs
    def located(self, pos: Dict[str, float], sent: int) -> int:
        """Blocks proven executed by a reported position (see the module
        docstring); ``proven`` when the position is on no block from there."""
        for k in range(self.proven, sent):
            mv = self.moves[k]
            for n, m in enumerate(mv):
                t = locate(m, pos, self.tol)
                if t is None:
                    continue
                return k + 1 if t >= 1.0 - 1e-9 and n == len(mv) - 1 else k
        return self.proven

    def consumed(self, read_bytes: int) -> int:
        """How many blocks were read out of the receive buffer when ``read_bytes``
        of the stream had been read."""
        lo, hi = 0, len(self.ends)
        while lo < hi:
            mid = (lo + hi) // 2
            if self.ends[mid] <= read_bytes:
                lo = mid + 1
            else:
                hi = mid
        return lo

    def update(self, pos: Optional[Dict[str, float]], sent: int, idle: bool = False,
               read_bytes: Optional[int] = None, answered: Optional[int] = None) -> List[int]:
        """Take one status report; returns the job line indices newly proven
        executed (to journal).  ``read_bytes``: bytes of this stream the
        controller had read when it answered (from ``Bf``), or None;
        ``answered``: blocks answered ``ok`` before the report when no answer
        was spurious (None otherwise) -- Idle then proves them executed."""
        if self.stopped:
            return []
        new = self.proven
        if pos is not None:
            new = max(new, self.located(pos, sent))
        if idle and read_bytes is not None:
            new = max(new, min(sent, self.consumed(read_bytes) - 1))
        if idle and answered is not None:
            new = max(new, min(sent, answered))
        if new <= self.proven:
            return []
        lines = [self.job.index[k] for k in range(self.proven, new)
                 if self.job.index[k] is not None]
        self.proven = new
        return lines

    # ------------------------------------------------------------ fence
    def allows(self, k: int, sent: int) -> bool:
        """Whether block ``k`` may be sent: a cutting block of a new segment only
        while fewer than ``window`` segments have cutting lines in flight that
        no report has proven executed."""
        if not self.cut[k] or not self.job.fence or not self.window:
            return True
        segs = self.job.segs
        open_segs = {segs[j] for j in range(self.proven, sent) if self.cut[j]}
        return segs[k] in open_segs or len(open_segs) < self.window


def proof_for(job, profile, window: int) -> Optional[ExecutionProof]:
    """The tracker of a stream, or None without a profile (nothing to trace)."""
    if profile is None:
        return None
    return ExecutionProof(job, profile, window)
