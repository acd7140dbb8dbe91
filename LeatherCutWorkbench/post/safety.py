"""Safety before output: refuse a job that would drive the machine wrong.

Checks, in this order, and raises :class:`~..core.errors.SafetyError` naming the
move (item, segment, coordinates) or the output line at the first violation:

1. every move (travel, cut, and the full extent of arcs) lies inside the table
   ``[0, W] x [0, H]`` mm of the profile;
2. every feed is positive and at most ``max_feed`` mm/min;
3. every word of every output line is one the dialect understands: the
   dialect's G and M codes, its parameter letters and only the axes both the
   dialect and the profile have (stock GRBL 1.1 has X, Y and Z only, so a ``C``
   word is refused), and the line fits ``max_line_length``;
4. every output line is exactly one line of printable ASCII (no control
   character, no line break: a template or a name can never add a line), its
   comments well formed (``(`` closed, not nested);
5. the motion of the finished program, traced line by line from machine zero
   (:func:`check_motion`), stays inside the table: header, footer, templates
   and whatever a writer adds, not only the planned moves.

:func:`check_lines` (3 to 5) is the one check every G-code writer's finished
lines pass (``gcode.build_program`` and any writer assembling programs);
:func:`comment` turns user text (profile and part names) into a safe comment.  Writers call the checks before they
return text, so a refused job writes and sends nothing.
"""

from __future__ import annotations

import math
import re
from typing import Dict, FrozenSet, Iterable, Iterator, List, Sequence, Tuple

from ..core.errors import SafetyError
from .gcode_reader import GcodeError, parse_words, strip_line
from .profiles import MachineProfile
from .toolpath import Move, Toolpath

_GRBL_G = frozenset({0, 1, 2, 3, 4, 10, 17, 18, 19, 20, 21, 28, 28.1, 30, 30.1, 38.2, 38.3,
                     38.4, 38.5, 40, 43.1, 49, 53, 54, 55, 56, 57, 58, 59, 61, 80, 90, 91,
                     91.1, 92, 92.1, 93, 94})
_LINUXCNC_G = _GRBL_G | frozenset({5, 5.1, 5.2, 7, 8, 33, 33.1, 41, 41.1, 42, 42.1, 43, 43.2,
                                   52, 59.1, 59.2, 59.3, 61.1, 64, 73, 76, 81, 82, 83, 84, 85,
                                   86, 87, 88, 89, 90.1, 92.2, 92.3, 95, 96, 97, 98, 99})

#: What each dialect understands: G codes, M codes, non-axis letters, axes.
DIALECT_WORDS: Dict[str, Dict[str, FrozenSet]] = {
    "grbl": {"G": _GRBL_G, "M": frozenset({0, 1, 2, 3, 4, 5, 8, 9, 30, 56}),
             "letters": frozenset("FIJKLNPRST"), "axes": frozenset("XYZ")},
    "grblhal": {"G": _GRBL_G | frozenset({5, 33, 43, 51, 61.1, 64, 73, 76, 81, 82, 83, 85, 86,
                                          89, 95, 96, 97, 98, 99}),
                "M": frozenset({0, 1, 2, 3, 4, 5, 7, 8, 9, 30, 48, 49, 50, 51, 53, 56, 60,
                                61, 62, 63, 64, 65, 66, 67, 68}),
                "letters": frozenset("DEFHIJKLNPQRST"), "axes": frozenset("XYZABCUVW")},
    "linuxcnc": {"G": _LINUXCNC_G,
                 "M": frozenset(set(range(0, 10)) | {30, 48, 49, 50, 51, 52, 53, 60, 61, 62,
                                                     63, 64, 65, 66, 67, 68, 70, 71, 72, 73}
                                | set(range(100, 200))),
                 "letters": frozenset("DEFHIJKLNPQRST"), "axes": frozenset("XYZABCUVW")},
}


def _where(m: Move, tp: Toolpath) -> str:
    if m.item:
        label = tp.item_labels[m.item - 1] if m.item - 1 < len(tp.item_labels) else ""
        seg = f" segment {m.seg}" if m.seg else ""
        return f"item {m.item} ({label}){seg}"
    return "travel outside any item"


def check_moves(tp: Toolpath, profile: MachineProfile) -> None:
    """Table limits and feeds of every neutral move."""
    xmin, ymin, xmax, ymax = profile.table_limits()
    tol = 10.0 ** -profile.decimals      # below the output resolution: float noise
    for m in tp.moves:
        if m.kind not in ("rapid", "line", "arc"):
            continue
        if m.kind == "rapid" and not m.item:
            continue        # the return to machine zero (plan.home) is always reachable
        pts = [(m.x, m.y)]
        if m.kind == "arc":
            pts += _arc_extremes(m)
        for x, y in pts:
            if not (xmin - tol <= x <= xmax + tol and ymin - tol <= y <= ymax + tol):
                raise SafetyError(
                    f"{m.kind} to ({m.x:.3f}, {m.y:.3f}) mm reaches ({x:.3f}, {y:.3f}), outside "
                    f"the table {xmin:g}..{xmax:g} x {ymin:g}..{ymax:g} mm of {profile.name} "
                    f"(move the drawing onto the table with --move-to-origin MM, or nest it with "
                    f"--sheet/--hide)",
                    source=_where(m, tp))
        if not (0 < m.feed <= profile.max_feed):
            raise SafetyError(
                f"{m.kind} feed {m.feed:g} mm/min is outside 0..{profile.max_feed:g} mm/min "
                f"of {profile.name}", source=_where(m, tp))


def _arc_extremes(m: Move) -> List[tuple]:
    """Points of the arc at the compass directions it passes (its bbox)."""
    cx, cy = m.center
    r = math.hypot(m.start[0] - cx, m.start[1] - cy)
    a0 = math.degrees(math.atan2(m.start[1] - cy, m.start[0] - cx))
    a1 = math.degrees(math.atan2(m.y - cy, m.x - cx))
    sweep = (a1 - a0) % 360.0 if m.ccw else -((a0 - a1) % 360.0)
    out = []
    for k in range(4):
        ang = 90.0 * k
        rel = (ang - a0) % 360.0 if sweep > 0 else (a0 - ang) % 360.0
        if rel <= abs(sweep):
            out.append((cx + r * math.cos(math.radians(ang)), cy + r * math.sin(math.radians(ang))))
    return out


def check_lines(lines: Sequence[str], profile: MachineProfile) -> None:
    """The check every finished G-code program passes before it is returned,
    written or sent, whoever added its lines: every word known to the dialect
    and the machine; feeds within the profile; lines no longer than
    ``max_line_length``; each line exactly one line of printable ASCII with
    closed comments; and the motion, traced from machine zero
    (:func:`check_motion`), inside the table.  One parse per line for all."""
    _trace(_checked(lines, profile), profile)


def _checked(lines: Sequence[str], profile: MachineProfile
             ) -> Iterator[Tuple[int, str, List[Tuple[str, float]]]]:
    """(line number, line, words) of every line after the word and line-form
    checks of :func:`check_lines`; SafetyError at the first bad line."""
    words = DIALECT_WORDS[profile.dialect]
    axes = set(profile.axes) & set(words["axes"])
    g_codes, m_codes, letters = words["G"], words["M"], words["letters"]

    def where(n: int, line: str) -> str:
        return f"output line {n} {line.strip()!r}"

    for n, line in enumerate(lines, 1):
        if _BAD_LINE.search(line):
            raise SafetyError(_bad_line_reason(line), source=where(n, line))
        block = strip_line(line)
        if not block:
            yield n, line, []
            continue
        if len(block) > profile.max_line_length:
            raise SafetyError(f"{len(block)} characters, more than {profile.max_line_length} "
                              f"{profile.dialect} accepts", source=where(n, line))
        try:
            parsed = parse_words(block, n)
        except GcodeError as exc:
            raise SafetyError(f"not G-code: {exc.message}", source=where(n, line))
        for letter, v in parsed:
            if letter == "G" or letter == "M":
                code = round(v, 1) if letter == "G" else v
                if code not in (g_codes if letter == "G" else m_codes):
                    raise SafetyError(f"{letter}{v:g} is not understood by {profile.dialect}",
                                      source=where(n, line))
            elif letter in "XYZABCUVW":
                if letter not in axes:
                    have = "".join(sorted(axes, key="XYZABCUVW".index))
                    raise SafetyError(f"word {letter} names an axis {profile.dialect} / "
                                      f"{profile.name} does not have (axes {have})",
                                      source=where(n, line))
            elif letter not in letters:
                raise SafetyError(f"word {letter} is not understood by {profile.dialect}",
                                  source=where(n, line))
            if letter == "F" and not (0 < v <= profile.max_feed):
                raise SafetyError(f"feed F{v:g} is outside 0..{profile.max_feed:g} mm/min",
                                  source=where(n, line))
        yield n, line, parsed


def check_program(lines: Sequence[str], profile: MachineProfile, name: str = "") -> None:
    """A ready G-code program (e.g. a ``.nc`` file to send): every word known to
    the dialect (:func:`check_lines`), and every move, traced by the
    interpreter, inside the table (plan coordinates = machine minus origin)."""
    from .gcode_reader import interpreter_for

    check_lines(lines, profile)
    it = interpreter_for(profile)
    xmin, ymin, xmax, ymax = profile.table_limits()
    ox, oy = profile.origin
    for n, line in enumerate(lines, 1):
        try:
            moves = it.execute(line, n)
        except GcodeError as exc:
            raise SafetyError(f"not accepted: {exc.message}", source=f"{name} line {n}")
        for m in moves:
            if m.kind not in ("rapid", "line", "arc"):
                continue
            pts = [(m.end["X"], m.end["Y"])]
            if m.kind == "arc":
                pts += _arc_extremes(Move("arc", x=m.end["X"], y=m.end["Y"], center=m.center,
                                          ccw=m.ccw, start=(m.start["X"], m.start["Y"])))
            for x, y in pts:
                if not (xmin - 1e-6 <= x - ox <= xmax + 1e-6 and ymin - 1e-6 <= y - oy <= ymax + 1e-6):
                    raise SafetyError(
                        f"move to ({m.end['X']:.3f}, {m.end['Y']:.3f}) reaches ({x:.3f}, {y:.3f}), "
                        f"outside the table of {profile.name}", source=f"{name} line {n}")


#: A character no output line may hold: control characters (line breaks
#: included), non-ASCII, or a comment that is nested or never closed.
_BAD_LINE = re.compile(r"[^\x20-\x7e]|\([^)]*\(|\([^)]*$")
_COMMENT_DROP = re.compile(r"[^\x20-\x7e]|[();]")


def _bad_line_reason(line: str) -> str:
    m = re.search(r"[^\x20-\x7e]", line)
    if m:
        return (f"character {m.group(0)!r} in an output line: every line must be exactly one "
                f"line of printable ASCII")
    return "comment not closed or nested: '(' must be closed by ')' on the same line"


def comment(text: str, limit: int = 200) -> str:
    """``(text)`` with everything that could end the comment or the line
    removed (parentheses, semicolons, control and non-ASCII characters) and
    spaces collapsed: user text (profile, part and layer names) can never
    become G-code."""
    clean = " ".join(_COMMENT_DROP.sub(" ", text).split())
    return f"({clean[:limit]})"


def words(line: str) -> List[Tuple[str, float]]:
    """The (letter, value) words of one line (comments removed)."""
    block = strip_line(line)
    return parse_words(block) if block else []


#: G codes the motion trace refuses: they change the coordinate system or move
#: to a position stored in the controller, which no check here can see.
_UNTRACEABLE_G = {10.0: "sets coordinate offsets", 28.0: "moves to a stored position",
                  30.0: "moves to a stored position", 92.0: "shifts the coordinate system",
                  92.2: "shifts the coordinate system", 92.3: "shifts the coordinate system",
                  52.0: "shifts the coordinate system"}


def check_motion(lines: Sequence[str], profile: MachineProfile, start=None) -> None:
    """Trace X/Y of ``lines`` (absolute and incremental distance, mm and inch,
    G0-G3 with arcs by their full extent) from ``start`` (machine coordinates;
    default machine zero) and refuse any target outside the table in plan
    coordinates (machine minus ``origin``).  Machine zero itself is always
    allowed (the return home).  Lines must be G-code (see :func:`check_lines`,
    which runs this trace itself)."""
    _trace(((n, line, words(line)) for n, line in enumerate(lines, 1)), profile, start)


def _trace(parsed: Iterable[Tuple[int, str, List[Tuple[str, float]]]],
           profile: MachineProfile, start=None) -> None:
    """The motion check of :func:`check_motion` over already parsed lines."""
    xmin, ymin, xmax, ymax = profile.table_limits()
    ox, oy = profile.origin
    tol = 10.0 ** -profile.decimals
    x, y = start if start is not None else (0.0, 0.0)
    absolute, scale, motion = True, 1.0, 0.0

    def inside(px: float, py: float) -> bool:
        if px == 0.0 and py == 0.0:
            return True
        return (xmin - tol <= px - ox <= xmax + tol) and (ymin - tol <= py - oy <= ymax + tol)

    for n, line, ws in parsed:
        if not ws:
            continue
        gs = [round(v, 1) for letter, v in ws if letter == "G"]
        vals = {letter: v for letter, v in ws if letter in "XYIJ"}
        for g in gs:
            if g in _UNTRACEABLE_G:
                raise SafetyError(f"G{g:g} {_UNTRACEABLE_G[g]}: the safety check cannot follow "
                                  f"it, so it is never written or sent",
                                  source=f"output line {n} {line.strip()!r}")
            if g in (90.0, 91.0):
                absolute = g == 90.0
            elif g in (20.0, 21.0):
                scale = 25.4 if g == 20.0 else 1.0
            elif g in (0.0, 1.0, 2.0, 3.0):
                motion = g
        arc = motion in (2.0, 3.0) and ("I" in vals or "J" in vals)
        if ("X" not in vals and "Y" not in vals and not arc) or 4.0 in gs:
            continue
        nx = vals.get("X", 0.0 if not absolute else x / scale) * scale
        ny = vals.get("Y", 0.0 if not absolute else y / scale) * scale
        if not absolute:
            nx, ny = x + nx, y + ny
        pts = [(nx, ny)]
        if arc:
            cx, cy = x + vals.get("I", 0.0) * scale, y + vals.get("J", 0.0) * scale
            if abs(nx - x) < 1e-9 and abs(ny - y) < 1e-9:     # full circle
                r = math.hypot(x - cx, y - cy)
                pts += [(cx + r, cy), (cx - r, cy), (cx, cy + r), (cx, cy - r)]
            else:
                pts += [(px + ox, py + oy) for px, py in _arc_extremes(Move(
                    "arc", x=nx - ox, y=ny - oy, center=(cx - ox, cy - oy), ccw=motion == 3.0,
                    start=(x - ox, y - oy)))]
        for px, py in pts:
            if not (math.isfinite(px) and math.isfinite(py)) or not inside(px, py):
                raise SafetyError(
                    f"motion reaches ({px - ox:.3f}, {py - oy:.3f}) mm, outside the table "
                    f"{xmin:g}..{xmax:g} x {ymin:g}..{ymax:g} mm of {profile.name}",
                    source=f"output line {n} {line.strip()!r}")
        x, y = nx, ny
