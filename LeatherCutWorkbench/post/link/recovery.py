"""Which lines of a job the machine really executed, from its journal.

GRBL acknowledges a motion line when it enters the planner, so *acknowledged*
is not *executed*: after a stop with a soft reset the moves still queued are
dropped.  For every run of the job (the first stream and each resume) this
module decides what was executed, with the best evidence the journal holds:

1. ``done``: the run finished -- every acknowledged line was executed;
2. ``position``: the stop was clean (feed hold, then reset while not moving,
   or a soft-limit alarm) and the controller reported where the tool stopped.
   The job is traced with the G-code interpreter and the first acknowledged
   move (after the last synchronising line) whose path contains that position
   is where the machine stopped: lines before it were executed, that move and
   everything after it were not (a move the tool stopped at the very end of
   counts as executed);
3. ``status`` / ``sync``: otherwise (power loss, disconnect, reset while
   moving) what the status reports received while streaming proved executed
   (``exec`` records, :mod:`.progress`: the reported position, Idle with the
   receive buffer read) -- ``status`` when they reach past the last verified
   sync -- and what a *verified* sync proves: GRBL answers ``G4 P0`` only after the planner ran
   empty, and the link sends nothing after it until a status report received
   after that ``ok`` shows the controller ``Idle`` (a spurious or early ``ok``
   cannot fake it); every acknowledged line up to the last verified sync was
   executed.  The resume then starts at the first segment with a cutting line
   not proven executed: the interrupted segment or, when the power failed
   after the tool crossed segment ends and before a report showed it, an
   earlier one -- without a cut window (the default) the re-cut is what was
   executed since the last status report, with cut window 2 at most the
   segment before the interrupted one (why no report can tell these apart:
   :mod:`.progress`); with the profile's ``sync_every_segment`` (or cut
   window 1) only the interrupted segment.

Lines a controller refused (``error:N``) are never acknowledged and so never
executed: their segment is cut again even when later segments were executed.
"""

from __future__ import annotations

import math
import re
from typing import Dict, List, Optional, Sequence, Set, Tuple

from ..gcode_reader import GcodeError, Interpreter, TraceMove, strip_line

SYNC_LINE = re.compile(r"^(N\d+)?(G4P|M[345789](?!\d))")
STOP_EVENTS = ("error", "alarm", "reset", "stalled", "lost", "aborted", "check-failed",
               "garbled", "unanswered")


def trace_run(source: Sequence[str], acked: Set[int], axes: str, wrapped: str, turn: float
              ) -> Dict[int, List[TraceMove]]:
    """Motion moves of the acknowledged lines of one run (0-based index).

    Lines before the run's first acknowledged line are taken as executed (an
    earlier run or the resume preamble brought the machine there); after it
    only acknowledged lines are executed -- a line the controller refused
    changed nothing, so the axis values and modal state of later lines are
    traced as the machine really had them."""
    it = Interpreter(axes, wrapped, turn)
    first = min(acked) if acked else len(source)
    out: Dict[int, List[TraceMove]] = {}
    for i, line in enumerate(source):
        if i >= first and i not in acked:
            continue
        try:
            moves = it.execute(line, i + 1)
        except GcodeError:
            continue                    # the controller refused it too: never executed
        motion = [m for m in moves if m.kind in ("rapid", "line", "arc")]
        if motion and i >= first:
            out[i] = motion
    return out


def _tolerances(axes: str, rotary: str) -> Dict[str, float]:
    return {a: (0.05 if a == rotary or a in "ABC" else 0.02) for a in axes}


def locate(move: TraceMove, pos: Dict[str, float], tol: Dict[str, float]) -> Optional[float]:
    """Fraction t in [0, 1] of ``move`` at which the tool is at ``pos``, or None
    when ``pos`` is not on the move's path (all axes within ``tol``)."""
    axes = [a for a in pos if a in move.start]
    if move.kind == "arc":
        cx, cy = move.center
        r = math.hypot(move.start["X"] - cx, move.start["Y"] - cy)
        if abs(math.hypot(pos["X"] - cx, pos["Y"] - cy) - r) > tol["X"]:
            return None
        a0 = math.atan2(move.start["Y"] - cy, move.start["X"] - cx)
        a1 = math.atan2(move.end["Y"] - cy, move.end["X"] - cx)
        ap = math.atan2(pos["Y"] - cy, pos["X"] - cx)
        if move.ccw:
            sweep, rel = (a1 - a0) % (2 * math.pi), (ap - a0) % (2 * math.pi)
        else:
            sweep, rel = (a0 - a1) % (2 * math.pi), (a0 - ap) % (2 * math.pi)
        if sweep < 1e-12:
            sweep = 2 * math.pi
        slack = tol["X"] / max(r, 1e-9)
        if rel > sweep + slack:
            if 2 * math.pi - rel <= slack:
                rel = 0.0
            else:
                return None
        t = min(rel / sweep, 1.0)
        others = [a for a in axes if a not in ("X", "Y")]
    else:
        deltas = {a: move.end[a] - move.start[a] for a in axes}
        lead = max(axes, key=lambda a: abs(deltas[a]) / tol[a])
        if abs(deltas[lead]) < 1e-12:
            t = 0.0
        else:
            t = min(max((pos[lead] - move.start[lead]) / deltas[lead], 0.0), 1.0)
        others = axes
    for a in others:
        want = move.start[a] + t * (move.end[a] - move.start[a])
        if abs(pos[a] - want) > tol[a]:
            return None
    return t


def executed_in_run(run: Dict, source: Sequence[str], axes: str, wrapped: str, turn: float,
                    tol: Dict[str, float]) -> Tuple[Set[int], str]:
    """(executed line indices, basis) of one run; see the module docstring."""
    acked: List[int] = run["acked"]
    acked_set = set(acked)
    end = run.get("end")
    if end is not None and end.get("e") == "done":
        return acked_set, "done"
    # verified syncs: the ok of a G4 P0 followed by a status report showing the
    # controller Idle (so the ok was not a spurious one); old journals without
    # "syncs" fall back to the acknowledged synchronising lines
    if "syncs" in run:
        syncs = [i for i in run["syncs"] if i in acked_set]
    else:
        syncs = [i for i in acked if SYNC_LINE.match(strip_line(source[i]))]
    last_sync = max(syncs) if syncs else -1
    pos = end.get("position") if end else None
    if pos and end.get("position_trusted"):
        motion = trace_run(source, acked_set, axes, wrapped, turn)
        # a position read on reconnect after a lost link counts only at the end
        # of the last acknowledged move (the controller ran on to the end of its
        # buffer; anywhere else it was moved since, e.g. jogged)
        last = max(motion) if motion else None
        # the lines a status report proved executed are behind the tool (or it
        # is at the end of the last one): the position is looked for from
        # there (a closed contour's start point is also where it ends)
        behind = -1 if end.get("reconnect") else max(run.get("proofs", ()), default=-1)
        for i in sorted(motion):
            if i <= last_sync or i < behind or (end.get("reconnect") and i != last):
                continue
            for k, mv in enumerate(motion[i]):
                t = locate(mv, pos, tol)
                if t is None:
                    continue
                at_end = t >= 1.0 - 1e-9 and k == len(motion[i]) - 1
                if end.get("reconnect") and not at_end:
                    continue
                stop = i + 1 if at_end else i
                run["tool"] = (i, "after" if at_end else "on")
                return {j for j in acked_set if j < stop} | set(run.get("proofs", ())), \
                    "position"
    synced = {j for j in acked_set if j <= last_sync}
    proofs = set(run.get("proofs", ()))
    return synced | proofs, ("status" if proofs - synced else "sync")


def executed_lines(runs: Sequence[Dict], source: Sequence[str], axes: str, wrapped: str,
                   turn: float, rotary: str) -> Tuple[Set[int], List[str], List[Set[int]]]:
    """Union of the executed lines of every run, the basis of each run and each
    run's own executed lines."""
    tol = _tolerances(axes, rotary)
    done: Set[int] = set()
    bases: List[str] = []
    per_run: List[Set[int]] = []
    for run in runs:
        lines, basis = executed_in_run(run, source, axes, wrapped, turn, tol)
        done |= lines
        bases.append(basis)
        per_run.append(lines)
    return done, bases, per_run


def tool_line(run: Dict, executed: Set[int], basis: str, source: Sequence[str]
              ) -> Optional[Tuple[int, str]]:
    """Where the tool is after the run's stop, as (0-based line, how known):
    with a reported position the move it stopped on ("on") or the move it
    stopped at the end of ("after"), as :func:`executed_in_run` located it;
    otherwise the last line known executed ("after")."""
    if basis == "position" and run.get("tool"):
        return run["tool"]
    acked = set(run["acked"])
    mine = sorted(i for i in executed if i in acked)
    return (mine[-1], "after") if mine else None
