"""What the link streams: the job's lines, their segments, and resume programs.

A :class:`SendJob` holds the program as written (``source`` lines, with
comments, for the journal digest and for rebuilding state) and, per line, the
cleaned block actually sent (upper case, no spaces or comments: GRBL strips
them anyway, and with character counting they would waste receive buffer),
the segment id the line belongs to and its index in the original job.

:func:`resume_job` builds the program that continues a job from a chosen
segment on a controller that was stopped, reset or power-cycled: it runs the
interpreter over the job up to the segment's first line to learn the modal
state, outputs, spindle and position there, then emits

1. the modal state (``G21 G90 G17 G94``) and coolant (vacuum) as they were,
2. the profile's knife-up lines,
3. a rapid to where the segment starts, knife axis pre-turned (``G0 X Y C``),
4. the aux outputs (``M64/M65 Pn``) and spindle (oscillator, servo, torch) as
   they were, with the pierce delay for a torch,
5. the knife down to its depth at the plunge feed when it was down, the feed,
6. the job's lines from the segment's first line to the end, leaving out the
   segments the caller names as already complete (each later run of segments
   gets its own preamble, so the knife never drags across a skipped segment).

Homing or unlocking happens before, in the link (:meth:`GrblLink.prepare_resume`).
"""

from __future__ import annotations

import copy
import os
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from ...core.errors import InputError
from ..gcode import Program, fmt, knife_down_lines, knife_up_lines, segment_map
from ..gcode_reader import GcodeError, ModalState, interpreter_for, strip_line
from ..profiles import MachineProfile


@dataclass
class SendJob:
    """Lines to stream.  ``blocks[k]`` is sent; ``index[k]`` is the line's index
    in the original job (None for lines a resume added); ``segs[k]`` its segment."""

    name: str
    source: List[str]
    blocks: List[str] = field(default_factory=list)
    segs: List[str] = field(default_factory=list)
    index: List[Optional[int]] = field(default_factory=list)
    segment_ids: List[str] = field(default_factory=list)
    job_segs: List[str] = field(default_factory=list)     # segment per source line
    fence: bool = True        # limit cutting lines in flight by segment (progress.py);
                              # off for foreign G-code (a segment per line)

    def axes_used(self) -> str:
        """Axis letters the job's blocks use (for the controller axes check)."""
        used = set()
        for b in self.blocks:
            for ch in "XYZABCUVW":
                if ch in b:
                    used.add(ch)
        return "".join(a for a in "XYZABCUVW" if a in used)


def job_from_lines(name: str, lines: List[str], segs: Optional[List[str]] = None,
                   segment_ids: Optional[List[str]] = None) -> SendJob:
    """A SendJob from program lines; segments from ``segs`` or the ``(seg ..)``
    comments.  Blank and comment-only lines are not sent."""
    if segs is None:
        segs, order = segment_map(lines)
        segment_ids = segment_ids or order
    job = SendJob(name, list(lines), segment_ids=list(segment_ids or []), job_segs=list(segs))
    for i, line in enumerate(lines):
        block = strip_line(line)
        if not block or block == "%":
            continue
        job.blocks.append(block)
        job.segs.append(segs[i])
        job.index.append(i)
    return job


def job_from_program(name: str, prog: Program) -> SendJob:
    return job_from_lines(name, prog.lines, prog.segs, prog.segment_ids)


def job_from_file(path: str, allow_unsealed: bool = False) -> SendJob:
    """Read a ``.nc``/``.ngc``/``.gcode`` file written by ``leathercut post``
    (or any G-code: without ``(seg ..)`` comments it is one unnamed segment per line).

    The file's end marker and checksum are verified first
    (:func:`..jobfile.check_sealed`): a truncated or edited job is refused.
    ``allow_unsealed`` accepts a hand-written file without a marker (never one
    that looks like a LeatherCut job)."""
    from ..jobfile import check_sealed

    try:
        if not os.path.isfile(path):
            raise InputError("not a regular file (a G-code job must be a file)", source=path)
        with open(path, "rb") as fh:
            data = fh.read()
        check_sealed(data, path, allow_unsealed)
        lines = data.decode("ascii", errors="strict").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read G-code file: {exc}", source=path)
    segs, order = segment_map(lines)
    if not order:
        # foreign G-code: every line is its own segment "L<line number>"
        segs = [f"L{i + 1}" if strip_line(l) else "" for i, l in enumerate(lines)]
        order = [s for s in segs if s]
        job = job_from_lines(os.path.basename(path), lines, segs, order)
        job.fence = False
        return job
    return job_from_lines(os.path.basename(path), lines, segs, order)


def first_line_of(job: SendJob, seg: str) -> int:
    """Index (into ``job.source``) of the first line belonging to ``seg``."""
    for i, s in enumerate(job.job_segs):
        if s == seg:
            return i
    raise InputError(f"no segment {seg!r} in the job (segments {job.segment_ids[0]} .. "
                     f"{job.segment_ids[-1]})" if job.segment_ids else f"no segment {seg!r}",
                     source=job.name)


def resume_job(job: SendJob, seg: str, profile: MachineProfile,
               skip: Sequence[str] = ()) -> SendJob:
    """The program that continues ``job`` at the start of segment ``seg``.

    Segments in ``skip`` (already complete according to the journal, e.g. lines
    a controller executed from its buffer after an error) are left out; each
    run of segments after a gap gets its own re-positioning preamble.  Lines
    outside segments (lifts, I/O off, sync, footer) are always kept."""
    start = first_line_of(job, seg)
    skip_set = set(skip) - {seg}
    it = interpreter_for(profile)
    snaps: Dict[str, Tuple[ModalState, Dict[str, float]]] = {}
    for n, line in enumerate(job.source):
        s = job.job_segs[n]
        if n >= start and s and s not in snaps:
            snaps[s] = (copy.deepcopy(it.state), dict(it.pos))
        try:
            it.execute(line, n + 1)
        except GcodeError as exc:
            raise InputError(f"cannot rebuild the machine state: {exc}", source=job.name)
    out = SendJob(job.name, job.source, segment_ids=job.segment_ids, job_segs=job.job_segs,
                  fence=job.fence)
    gap = True
    for k, i in enumerate(job.index):
        if i is None or i < start:
            continue
        s = job.segs[k]
        if s and s in skip_set:
            gap = True
            continue
        if gap and s:
            state, pos = snaps[s]
            for line in _preamble(state, pos, profile):
                out.blocks.append(strip_line(line))
                out.segs.append(s)
                out.index.append(None)
            gap = False
        out.blocks.append(job.blocks[k])
        out.segs.append(s)
        out.index.append(i)
    return out


def _preamble(st: ModalState, pos: Dict[str, float], profile: MachineProfile) -> List[str]:
    """Lines that bring a reset controller to modal state ``st`` at ``pos``
    with the knife as it was there (see the module docstring)."""
    d = profile.decimals
    pre: List[str] = [f"{st.units} {st.distance} {st.plane} {st.feed_mode}"]
    pre += sorted(st.coolant)
    pre += knife_up_lines(profile)
    xy = f"G0 X{fmt(pos['X'], d)} Y{fmt(pos['Y'], d)}"
    ax = profile.rotary_axis
    if ax and ax in pos and ax != profile.lift_axis:
        val = pos[ax]
        if profile.rotary_wrap:
            val = val % profile.units_per_turn
        xy += f" {ax}{fmt(val, d)}"
    pre.append(xy)
    for port, on in sorted(st.outputs.items()):
        pre.append(f"M{64 if on else 65} P{port}")
    lift = profile.lift_axis
    knife_was_down = (pos.get(lift, profile.z_up) < (profile.z_up + profile.z_down) / 2
                      if lift else st.spindle in ("M3", "M4"))
    if st.spindle in ("M3", "M4"):
        if not lift and profile.knife_down:
            pre += knife_down_lines(profile)            # servo / torch down = spindle on
        else:
            pre.append(f"{st.spindle} S{fmt(st.speed, 0)}")
        if profile.pierce_delay > 0 and profile.tool == "torch":
            pre.append(f"G4 P{fmt(profile.pierce_delay, 3)}")
    if lift and knife_was_down:
        pre.append(f"G1 {lift}{fmt(pos[lift], d)} F{fmt(profile.plunge_feed, 0)}")
    if st.feed:
        pre.append(f"F{fmt(st.feed, 0)}")
    return pre
