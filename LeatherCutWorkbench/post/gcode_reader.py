"""A G-code interpreter: trace the tool path back from a program.

Used by the tests (the traced path must equal the planned one), by the
controller emulator (it executes what it receives) and by the live link (it
rebuilds the modal state and position at a segment to resume from).

It accepts the subset of RS274/NGC the GRBL family and LinuxCNC share and our
writers emit: G0 G1 G2 G3 (I/J centre offsets, helical extra axes), G4, G17,
G20/G21, G90/G91, G94, G40 G49 G54 G80 (accepted, no effect), M0 M1 M2 M30,
M3 M4 M5, M6 (tool change, the T word), M7 M8 M9, M62-M66 (recorded as I/O events), F S P L Q E N T words.
Errors are raised as :class:`GcodeError` carrying the GRBL error number the
firmware would answer (1 letter expected, 2 bad number, 20 unsupported command,
21 modal group violation, 22 feed not set, 25 repeated word, 26 no axis words,
33 arc target invalid, 35 no arc offset, 36 unused words).  Units: the trace is
in mm (G20 programs are converted), angles in axis units.

Written here by hand: the Python G-code parsers on PyPI read words but do not
answer with GRBL's error numbers, wrapped-rotary semantics or the modal state a
resume needs.  The LinuxCNC output is also checked against the real LinuxCNC
interpreter (tests/test_post_rs274.py).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Set, Tuple

from ..core.errors import LeatherCutError

GRBL_ERRORS = {
    1: "Expected command letter", 2: "Bad number format", 9: "G-code locked out during alarm or jog state",
    11: "Line overflow", 20: "Unsupported or invalid g-code command", 21: "Modal group violation",
    22: "Undefined feed rate", 25: "Repeated g-code word", 26: "No axis words",
    28: "Value word missing", 33: "Invalid target / arc radius mismatch",
    35: "No offsets in plane", 36: "Unused value words",
}

MOTION = {0.0: "G0", 1.0: "G1", 2.0: "G2", 3.0: "G3"}
_NUM = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)")
ALL_AXES = "XYZABCUVW"


class GcodeError(LeatherCutError):
    """A line the interpreter (and the firmware) would reject; ``code`` is the
    GRBL error number, ``line_no`` the 1-based line in the program."""

    def __init__(self, code: int, detail: str = "", line_no: Optional[int] = None):
        msg = f"error:{code} {GRBL_ERRORS.get(code, '')}" + (f" ({detail})" if detail else "")
        super().__init__(msg, source=f"line {line_no}" if line_no else None)
        self.code = code
        self.line_no = line_no


@dataclass
class TraceMove:
    """One executed block.  ``kind``: rapid | line | arc | dwell | io | stop.
    Positions are dicts axis -> value (mm, or axis units for rotary axes)."""

    kind: str
    line_no: int
    start: Dict[str, float]
    end: Dict[str, float]
    center: Optional[Tuple[float, float]] = None
    ccw: bool = True
    feed: float = 0.0
    spindle: str = "M5"
    coolant: Tuple[str, ...] = ()
    seconds: float = 0.0
    text: str = ""


@dataclass
class ModalState:
    motion: str = "G0"
    units: str = "G21"
    distance: str = "G90"
    plane: str = "G17"
    feed_mode: str = "G94"
    feed: Optional[float] = None
    spindle: str = "M5"
    speed: float = 0.0
    coolant: Set[str] = field(default_factory=set)
    outputs: Dict[int, bool] = field(default_factory=dict)
    ended: bool = False
    prepared: int = 0          # T word seen (tool prepared)
    tool: int = 0              # tool in the spindle after the last M6


def strip_line(line: str) -> str:
    """Upper-case block without comments or spaces: what GRBL's parser sees and
    what a host must send when character counting."""
    out = []
    depth = 0
    for ch in line:
        if depth:
            if ch == ")":
                depth = 0
            continue
        if ch == "(":
            depth = 1
            continue
        if ch == ";":
            break
        if ch in " \t\r\n":
            continue
        out.append(ch.upper())
    return "".join(out)


def parse_words(block: str, line_no: Optional[int] = None) -> List[Tuple[str, float]]:
    """``"G1X10.5Y-2"`` -> ``[("G", 1.0), ("X", 10.5), ("Y", -2.0)]``."""
    words = []
    i = 0
    while i < len(block):
        letter = block[i]
        if not ("A" <= letter <= "Z"):
            raise GcodeError(1, f"{letter!r} where a letter was expected", line_no)
        m = _NUM.match(block, i + 1)
        if not m:
            raise GcodeError(2, f"no number after {letter}", line_no)
        words.append((letter, float(m.group(0))))
        i = m.end()
    return words


class Interpreter:
    """Executes blocks one by one, keeping modal state and position.

    ``axes``: the machine's axis letters; ``wrapped``: rotary axes whose value
    is a target modulo ``turn`` with the sign selecting the direction
    (LinuxCNC WRAPPED_ROTARY); ``mcodes``: accepted M numbers (None = all this
    interpreter knows)."""

    KNOWN_M = {0, 1, 2, 30, 3, 4, 5, 6, 7, 8, 9, 62, 63, 64, 65, 66}

    def __init__(self, axes: str = "XYZC", wrapped: str = "", turn: float = 360.0,
                 mcodes: Optional[Set[int]] = None):
        self.axes = axes.upper()
        self.wrapped = wrapped.upper()
        self.turn = turn
        self.mcodes = self.KNOWN_M if mcodes is None else set(mcodes)
        self.state = ModalState()
        self.pos: Dict[str, float] = {a: 0.0 for a in self.axes}
        self.moves: List[TraceMove] = []

    # ------------------------------------------------------------------ public
    def execute(self, line: str, line_no: int = 0) -> List[TraceMove]:
        """Run one line; returns the moves it made (appended to ``moves`` too).
        State is unchanged when GcodeError is raised."""
        block = strip_line(line)
        if not block or block == "%":
            return []
        words = parse_words(block, line_no)
        return self._run(words, line, line_no)

    # ---------------------------------------------------------------- internal
    def _run(self, words: List[Tuple[str, float]], text: str, line_no: int) -> List[TraceMove]:
        s = self.state
        g_motion = None
        g_other: List[float] = []
        groups: Dict[str, float] = {}
        m_codes: List[int] = []
        vals: Dict[str, float] = {}
        for letter, v in words:
            if letter == "G":
                code = round(v, 1)
                group = self._g_group(code, line_no)
                if group in groups:
                    raise GcodeError(21, f"two G words of one group: G{groups[group]:g} G{code:g}",
                                     line_no)
                groups[group] = code
                if group == "motion":
                    g_motion = MOTION[code]
                else:
                    g_other.append(code)
            elif letter == "M":
                code = int(v)
                if v != code or code not in self.mcodes:
                    raise GcodeError(20, f"M{v:g}", line_no)
                m_codes.append(code)
            elif letter == "N":
                continue
            else:
                if letter in vals:
                    raise GcodeError(25, f"{letter} twice", line_no)
                if letter in ALL_AXES and letter not in self.axes:
                    raise GcodeError(20, f"no {letter} axis", line_no)
                if letter not in self.axes and letter not in "FSPLQEIJKRTD":
                    raise GcodeError(20, f"word {letter}", line_no)
                vals[letter] = v
        if "R" in vals:
            raise GcodeError(20, "R-form arcs are not supported; use I/J", line_no)
        if sum(1 for c in m_codes if c in (3, 4, 5)) > 1 or \
                sum(1 for c in m_codes if c in (0, 1, 2, 30)) > 1:
            raise GcodeError(21, "two M words of one group", line_no)

        new = ModalState(**{**s.__dict__, "coolant": set(s.coolant), "outputs": dict(s.outputs)})
        for code in g_other:
            if code in (20.0, 21.0):
                new.units = f"G{int(code)}"
            elif code in (90.0, 91.0):
                new.distance = f"G{int(code)}"
            elif code in (17.0, 18.0, 19.0):
                new.plane = f"G{int(code)}"
            elif code == 94.0:
                new.feed_mode = "G94"
        scale = 25.4 if new.units == "G20" else 1.0
        if "F" in vals:
            if vals["F"] <= 0:
                raise GcodeError(2, "F must be positive", line_no)
            new.feed = vals.pop("F") * scale
        if "S" in vals:
            new.speed = vals.pop("S")
        out: List[TraceMove] = []
        io_words = {"P", "L", "Q", "E"}
        for code in m_codes:
            if code in (3, 4, 5):
                new.spindle = f"M{code}"
            elif code in (7, 8):
                new.coolant.add(f"M{code}")
            elif code == 9:
                new.coolant.clear()
            elif code in (62, 63, 64, 65):
                if "P" not in vals:
                    raise GcodeError(28, f"M{code} needs P", line_no)
                new.outputs[int(vals["P"])] = code in (62, 64)
            elif code in (0, 1, 2, 30):
                new.ended = code in (2, 30)
            elif code == 6:                 # tool change to the prepared (T) tool
                new.tool = int(vals.get("T", new.prepared))
        if "T" in vals:
            new.prepared = int(vals.pop("T"))
        if any(c in (62, 63, 64, 65, 66) for c in m_codes):
            out.append(TraceMove("io", line_no, dict(self.pos), dict(self.pos),
                                 spindle=new.spindle, text=text))
            for w in io_words:
                vals.pop(w, None)
        dwell = 4.0 in g_other
        if dwell:
            if "P" not in vals:
                raise GcodeError(28, "G4 needs P (seconds)", line_no)
            secs = vals.pop("P")
            if secs < 0:
                raise GcodeError(2, "negative dwell", line_no)
            out.append(TraceMove("dwell", line_no, dict(self.pos), dict(self.pos),
                                 spindle=new.spindle, seconds=secs, text=text))
        if g_motion:
            new.motion = g_motion
        axis_vals = {a: vals.pop(a) for a in list(vals) if a in self.axes}
        ij = {k: vals.pop(k) for k in ("I", "J", "K") if k in vals}
        vals.pop("T", None)
        if vals:
            raise GcodeError(36, "unused " + " ".join(f"{k}{v:g}" for k, v in vals.items()), line_no)
        target = dict(self.pos)
        for a, v in axis_vals.items():
            if a in self.wrapped:
                if new.distance == "G90" and abs(v) >= self.turn:
                    raise GcodeError(33, f"invalid absolute position {v:g} for wrapped rotary "
                                         f"axis {a}", line_no)
                target[a] = self._wrapped_target(a, v, new.distance == "G91")
            elif new.distance == "G91":
                target[a] = self.pos[a] + v * (1.0 if a in "ABC" else scale)
            else:
                target[a] = v * (1.0 if a in "ABC" else scale)
        if axis_vals and not dwell:
            motion = new.motion
            if motion in ("G1", "G2", "G3") and new.feed is None:
                raise GcodeError(22, "no F yet", line_no)
            common = dict(spindle=new.spindle, coolant=tuple(sorted(new.coolant)),
                          feed=new.feed or 0.0, text=text)
            if motion in ("G0", "G1"):
                out.append(TraceMove("rapid" if motion == "G0" else "line", line_no,
                                     dict(self.pos), target, **common))
            else:
                if new.plane != "G17":
                    raise GcodeError(20, "arcs only in G17", line_no)
                if "I" not in ij and "J" not in ij:
                    raise GcodeError(35, "G2/G3 without I/J", line_no)
                cx = self.pos["X"] + ij.get("I", 0.0) * scale
                cy = self.pos["Y"] + ij.get("J", 0.0) * scale
                r0 = math.hypot(self.pos["X"] - cx, self.pos["Y"] - cy)
                r1 = math.hypot(target["X"] - cx, target["Y"] - cy)
                # GRBL 1.1 gcode.c: error 33 past 0.5 mm absolute, or past both
                # 0.005 mm and 0.1 % of the radius
                dr = abs(r0 - r1)
                if dr > 0.5 or (dr > 0.005 and dr > 0.001 * r0):
                    raise GcodeError(33, f"radius {r0:.4f} to start, {r1:.4f} to end", line_no)
                out.append(TraceMove("arc", line_no, dict(self.pos), target, center=(cx, cy),
                                     ccw=motion == "G3", **common))
        elif ij:
            raise GcodeError(36, "I/J without an arc", line_no)
        if new.ended:
            out.append(TraceMove("stop", line_no, dict(target), dict(target), text=text))
        # commit
        self.state = new
        self.pos = target
        self.moves.extend(out)
        return out

    def _g_group(self, code: float, line_no: int) -> str:
        if code in MOTION:
            return "motion"
        table = {4.0: "nonmodal", 17.0: "plane", 18.0: "plane", 19.0: "plane",
                 20.0: "units", 21.0: "units", 90.0: "distance", 91.0: "distance",
                 94.0: "feedmode", 40.0: "cutter", 41.1: "cutter", 42.1: "cutter", 49.0: "tlo", 54.0: "wcs", 80.0: "motion_cancel"}
        if code not in table:
            raise GcodeError(20, f"G{code:g}", line_no)
        return table[code]

    def _wrapped_target(self, axis: str, v: float, incremental: bool) -> float:
        cur = self.pos[axis]
        if incremental:
            return cur + v
        target = abs(v) % self.turn
        here = cur % self.turn
        eps = 1e-9 * self.turn          # float noise of ``cur % turn``: the same angle
        if v < 0 or (v == 0 and math.copysign(1.0, v) < 0):
            d = (here - target) % self.turn
            return cur - (0.0 if d > self.turn - eps or d < eps else d)
        d = (target - here) % self.turn
        return cur + (0.0 if d > self.turn - eps or d < eps else d)


def read_program(text: str, axes: str = "XYZC", wrapped: str = "", turn: float = 360.0
                 ) -> Interpreter:
    """Run a whole program; GcodeError names the first bad line."""
    it = Interpreter(axes, wrapped, turn)
    for n, line in enumerate(text.splitlines(), 1):
        it.execute(line, n)
    return it


def interpreter_for(profile) -> Interpreter:
    """An interpreter with the axes and wrap mode of a machine profile."""
    return Interpreter(profile.axes, profile.rotary_axis if profile.rotary_wrap else "",
                       profile.units_per_turn if profile.rotary_wrap else 360.0)


def tool_is_down(move: TraceMove, profile) -> bool:
    """Whether the knife/torch is down at the start of ``move`` for ``profile``:
    the lift axis below half-way between up and down, or (no lift axis) the
    spindle output on (servo lift, torch)."""
    if profile.lift_axis:
        mid = (profile.z_up + profile.z_down) / 2.0
        return move.start[profile.lift_axis] < mid and move.end[profile.lift_axis] < mid
    return move.spindle in ("M3", "M4")


def traced_cuts(moves: Sequence[TraceMove], profile) -> Tuple[List[TraceMove], List[TraceMove]]:
    """(moves cutting with the tool down, rapids made with the tool down).
    The second list must be empty for a safe program.  Plunge/lift moves (only
    the lift axis changes) are neither."""
    cuts, bad = [], []
    for m in moves:
        if m.kind not in ("rapid", "line", "arc"):
            continue
        moved_xy = abs(m.start["X"] - m.end["X"]) > 1e-9 or abs(m.start["Y"] - m.end["Y"]) > 1e-9
        if not moved_xy or not tool_is_down(m, profile):
            continue
        (bad if m.kind == "rapid" else cuts).append(m)
    return cuts, bad
