"""G-code writer for GRBL 1.1, grblHAL and LinuxCNC, driven by the profile.

Everything machine-specific (axes, knife axis and wrap mode, units per turn,
knife up/down and I/O templates, header and footer, arc output, line length)
comes from the :class:`~.profiles.MachineProfile`; the dialect only selects
which words the safety check accepts and how a wrapped rotary axis is written.

Output shape (one block per line, ``\\n`` line ends, comments in parentheses)::

    (header comments)            G21 G90 G17 G94 ...     header template
    M8 / G4 P1                   vacuum and settle        I/O templates
    (item 1 outer P1/C1)
    (seg 1:1)
    G0 X.. Y.. C..               travel, knife up, pre-rotated
    G1 Z-1.2 F1000               knife down (template)
    G1 X.. Y.. C.. F6000         cut (C follows the tangent)
    G2 X.. Y.. I.. J.. C..       arc, C interpolated with the arc
    G0 Z5 / G0 C.. / G1 Z-1.2    lift, turn in the air, plunge (> lift angle)
    G4 P0                        per-segment sync (profile sync_every_segment)
    G0 Z5                        knife up after the item
    G4 P0                        sync: its ok means the item was executed
    ...                          footer template (M2)

``(seg I:S)`` comment lines mark where segment S of item I starts; the live
link reads them back from a ``.nc`` file to journal and resume by segment.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from ..core.model import CutPlan
from .profiles import MachineProfile
from .toolpath import Move, Toolpath, build_toolpath


@dataclass
class ExportOptions:
    """Options of every writer.  None = take the profile's value."""

    line_numbers: Optional[bool] = None   # N words on every block (G-code)
    overcut: Optional[float] = None       # mm past the entry of closed contours
    comments: bool = True                 # item / segment comments


@dataclass
class Program:
    """G-code as lines plus, for each line, the segment id it belongs to
    (``""`` between segments).  ``text()`` is what a file holds."""

    lines: List[str] = field(default_factory=list)
    segs: List[str] = field(default_factory=list)
    segment_ids: List[str] = field(default_factory=list)

    def add(self, line: str, seg: str = "") -> None:
        self.lines.append(line)
        self.segs.append(seg)

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"


def fmt(value: float, decimals: int = 3) -> str:
    """Number as G-code wants it: fixed decimals, no trailing zeros, no ``-0``."""
    s = f"{value:.{decimals}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    if s in ("-0", "", "-"):
        s = "0"
    return s


def template_values(profile: MachineProfile) -> Dict[str, str]:
    """Variables a template line may use, e.g. ``G1 {lift_axis}{z_down} F{plunge_feed}``."""
    d = profile.decimals
    return {
        "lift_axis": profile.lift_axis, "rotary_axis": profile.rotary_axis,
        "z_up": fmt(profile.z_up, d), "z_down": fmt(profile.z_down, d),
        "plunge_feed": fmt(profile.plunge_feed, 0), "cut_feed": fmt(profile.cut_feed, 0),
        "rapid_feed": fmt(profile.rapid_feed, 0), "pierce_delay": fmt(profile.pierce_delay, 3),
        "settle_dwell": fmt(profile.settle_dwell, 3), "cooling_delay": fmt(profile.cooling_delay, 3),
    }


def expand(templates: List[str], profile: MachineProfile) -> List[str]:
    """Fill the ``{name}`` variables of template lines (see :func:`template_values`)."""
    values = template_values(profile)
    out = []
    for t in templates:
        try:
            out.append(t.format_map(values))
        except (KeyError, ValueError) as exc:
            from ..core.errors import InputError
            raise InputError(f"template line {t!r} uses an unknown variable {exc}",
                             source=profile.source or profile.name)
    return out


def knife_up_lines(profile: MachineProfile) -> List[str]:
    if profile.knife_up:
        return expand(profile.knife_up, profile)
    if profile.lift_axis:
        return [f"G0 {profile.lift_axis}{fmt(profile.z_up, profile.decimals)}"]
    return []


def knife_down_lines(profile: MachineProfile) -> List[str]:
    if profile.knife_down:
        return expand(profile.knife_down, profile)
    if profile.lift_axis:
        return [f"G1 {profile.lift_axis}{fmt(profile.z_down, profile.decimals)} "
                f"F{fmt(profile.plunge_feed, 0)}"]
    return []


class RotaryWriter:
    """Writes the knife heading as a rotary word: continuous headings become axis
    units (``units_per_turn`` per 360 degrees); a wrapped axis gets the target
    modulo one turn with the sign choosing the direction (LinuxCNC
    WRAPPED_ROTARY; a negative turn to 0 is written ``-0``)."""

    def __init__(self, profile: MachineProfile):
        self.p = profile
        self.last: Optional[float] = None

    def word(self, heading: Optional[float]) -> str:
        p = self.p
        if not p.tangential or heading is None:
            return ""
        if self.last is not None and abs(heading - self.last) < 1e-9:
            return ""
        scale = p.units_per_turn / 360.0
        if p.rotary_wrap:
            target = heading % 360.0
            negative = self.last is not None and heading < self.last
            if round(target, p.decimals) >= 360.0:
                target = 0.0
            value = target * scale
            if negative:
                # "-0" is a negative turn to 0 (LinuxCNC reads the sign of the
                # text; an absolute value of a full turn is refused)
                text = "-" + fmt(value, p.decimals)
            else:
                text = fmt(value, p.decimals)
        else:
            text = fmt(heading * scale, p.decimals)
        self.last = heading
        return f" {p.rotary_axis}{text}"


def rotary_feed(m: Move, heading_before: Optional[float], profile: MachineProfile) -> float:
    """F for a cutting move that also turns the knife.

    GRBL and grblHAL take F along the move's length in *all* axes, rotary units
    counted like mm: a 90 degree turn on a 3 mm arc would crawl at 3 % of the
    cutting speed.  With ``rotary_in_feed`` the F word is scaled so the knife
    still cuts at ``cut_feed`` in XY (capped at ``max_feed``).  LinuxCNC
    applies F to the linear axes only (``rotary_in_feed`` false)."""
    if (not profile.tangential or not profile.rotary_in_feed or heading_before is None
            or m.heading is None):
        return m.feed
    turn_units = abs(m.heading - heading_before) * profile.units_per_turn / 360.0
    if turn_units < 1e-9:
        return m.feed
    if m.kind == "arc":
        r = math.dist(m.center, m.start)
        a0 = math.atan2(m.start[1] - m.center[1], m.start[0] - m.center[0])
        a1 = math.atan2(m.y - m.center[1], m.x - m.center[0])
        sweep = (a1 - a0) % (2 * math.pi) if m.ccw else (a0 - a1) % (2 * math.pi)
        xy = r * sweep
    else:
        xy = math.dist(m.start, (m.x, m.y))
    if xy < 1e-9:
        return m.feed
    factor = math.hypot(xy, turn_units) / xy
    if factor < 1.001:                     # under 0.1 %: keep the F word unchanged
        return m.feed
    return min(m.feed * factor, profile.max_feed)


def build_program(plan: CutPlan, profile: MachineProfile,
                  options: Optional[ExportOptions] = None,
                  toolpath: Optional[Toolpath] = None) -> Program:
    """Moves -> G-code lines with their segment ids (after the safety check)."""
    from . import safety

    if not profile.is_gcode:
        from ..core.errors import InputError
        raise InputError(f"profile {profile.name} is for {profile.dialect}, not G-code",
                         source=profile.source or profile.name)
    opts = options or ExportOptions()
    tp = toolpath or build_toolpath(plan, profile, opts.overcut)
    safety.check_moves(tp, profile)
    prog = Program(segment_ids=list(tp.segment_ids))
    d = profile.decimals
    ox, oy = profile.origin
    rot = RotaryWriter(profile)
    feed: Optional[float] = None
    last_seg = None
    up_lines, down_lines = knife_up_lines(profile), knife_down_lines(profile)
    io = {name: expand(getattr(profile, name), profile)
          for name in ("vacuum_on", "vacuum_off", "press_on", "press_off",
                       "tool_on", "tool_off")}

    if opts.comments:
        prog.add(safety.comment(f"LeatherCut job for {profile.name}: {len(plan.items)} items, "
                                f"{len(tp.segment_ids)} segments"))
    for line in expand(profile.header, profile):
        prog.add(line)
    for line in up_lines:
        prog.add(line)

    def feed_word(f: float) -> str:
        nonlocal feed
        if feed is not None and abs(f - feed) < 1e-9:
            return ""
        feed = f
        return f" F{fmt(f, 0)}"

    heading: Optional[float] = None        # knife heading before the move
    for m in tp.moves:
        if opts.comments and m.seg and m.seg != last_seg:
            if m.seg.endswith(":1"):
                prog.add(safety.comment(f"item {m.item} {tp.item_labels[m.item - 1]}"), m.seg)
            prog.add(f"(seg {m.seg})", m.seg)
        elif opts.comments and not m.seg and last_seg:
            prog.add(f"(end item {last_seg.split(':')[0]})")
        last_seg = m.seg
        xy = f"X{fmt(m.x + ox, d)} Y{fmt(m.y + oy, d)}"
        if m.kind == "rapid":
            prog.add(f"G0 {xy}{rot.word(m.heading)}", m.seg)
        elif m.kind == "line":
            f = rotary_feed(m, heading, profile)
            prog.add(f"G1 {xy}{rot.word(m.heading)}{feed_word(f)}", m.seg)
        elif m.kind == "arc":
            i = m.center[0] - m.start[0]
            j = m.center[1] - m.start[1]
            g = "G3" if m.ccw else "G2"
            f = rotary_feed(m, heading, profile)
            prog.add(f"{g} {xy} I{fmt(i, d)} J{fmt(j, d)}{rot.word(m.heading)}"
                     f"{feed_word(f)}", m.seg)
        elif m.kind == "turn":
            w = rot.word(m.heading)
            if w:
                prog.add(f"G0{w}", m.seg)
        elif m.kind in ("up", "down"):
            for line in (up_lines if m.kind == "up" else down_lines):
                prog.add(line, m.seg)
            feed = None          # a template may have set its own F
        elif m.kind == "io":
            for line in io[m.name]:
                prog.add(line, m.seg)
            feed = None
        elif m.kind == "dwell":
            prog.add(f"G4 P{fmt(m.seconds, 3)}", m.seg)
        elif m.kind == "sync":
            prog.add("G4 P0", m.seg)
        elif m.kind == "comp":            # controller kerf compensation (LinuxCNC)
            prog.add({"left": f"G41.1 D{fmt(profile.kerf, d)}",
                      "right": f"G42.1 D{fmt(profile.kerf, d)}"}.get(m.name, "G40"), m.seg)
        if m.heading is not None:
            heading = m.heading
    for line in expand(profile.footer, profile):
        prog.add(line)

    numbered = profile.line_numbers if opts.line_numbers is None else opts.line_numbers
    if numbered:
        number_lines(prog.lines)
    safety.check_lines(prog.lines, profile)
    return prog


def number_lines(lines: List[str]) -> None:
    """Put ``N1``, ``N2``, ... before every block (not before comment lines), in place."""
    n = 0
    for k, line in enumerate(lines):
        if not line.startswith("("):
            n += 1
            lines[k] = f"N{n} {line}"


def export(plan: CutPlan, profile: MachineProfile, options: Optional[ExportOptions] = None) -> str:
    """The G-code text of ``plan`` for ``profile``.

    Raises :class:`~..core.errors.SafetyError` naming the move or line when a
    move leaves the table, a feed is outside the profile or a word is unknown
    to the dialect; nothing is returned (and so nothing written) then."""
    return build_program(plan, profile, options).text()


def segment_map(lines: List[str]) -> Tuple[List[str], List[str]]:
    """Segment ids of the lines of a G-code file written by :func:`export`, read
    back from its ``(seg I:S)`` and ``(end item I)`` comments: returns (per-line
    ids, ordered ids).  Lines outside every segment carry ``""``."""
    segs: List[str] = []
    order: List[str] = []
    cur = ""
    for raw in lines:
        s = raw.strip()
        up = s.upper()
        if up.startswith("(SEG ") and s.endswith(")"):
            cur = s[5:-1].strip()
            if cur not in order:
                order.append(cur)
        elif up.startswith("(END ITEM"):
            cur = ""
        segs.append(cur)
    return segs, order
