"""HP-GL/1 writer for cutting plotters (and a reader for tests).

Plotter units: ``profile.hpgl_units_per_mm`` (40 per mm = 0.025 mm, the HP-GL
default of 1016 per inch).  Output uses only the HP-GL/1 (7475A) subset
cutters accept -- ``IN`` ``SP`` ``PU`` ``PD`` ``VS`` (speed, cm/s) ``FS``
(force, g) -- and never the HP-GL/2 encoded polyline ``PE``::

    IN;VS20;FS80;SP1;
    PU400,400;PD1200,400,1200,800,400,800,400,400,440,400;
    ...
    PU0,0;SP0;

Arcs and curves are cut as polylines within ``profile.chord_tol``; closed
contours get ``overcut`` mm cut again past their start (the knife overlaps the
start so the part falls out).  No trailing ``IN``: on some cutters a second
``IN`` cancels work still in the plotter's buffer.
"""

from __future__ import annotations

import re
from typing import List, Optional, Tuple

from ..core.errors import InputError, SafetyError
from ..core.geometry import Point
from ..core.model import CutPlan
from .gcode import ExportOptions
from .profiles import MachineProfile
from .toolpath import build_toolpath

#: Coordinate pairs per PD instruction (keeps instructions short for small buffers).
MAX_PAIRS = 64
ALLOWED = {"IN", "SP", "PU", "PD", "VS", "FS"}


def export(plan: CutPlan, profile: MachineProfile, options: Optional[ExportOptions] = None) -> str:
    """The HP-GL text of ``plan``.  Raises SafetyError (nothing returned) when a
    point leaves the plotter's table or the speed exceeds the profile."""
    from . import safety

    opts = options or ExportOptions()
    if profile.dialect != "hpgl":
        raise InputError(f"profile {profile.name} is for {profile.dialect}, not HP-GL",
                         source=profile.source or profile.name)
    tp = build_toolpath(plan, profile, opts.overcut)
    safety.check_moves(tp, profile)
    if not 0 < profile.hpgl_velocity * 600.0 <= profile.max_feed:
        raise SafetyError(f"VS{profile.hpgl_velocity:g} cm/s is outside 0..{profile.max_feed:g} "
                          f"mm/min of {profile.name}", source="VS")
    k = profile.hpgl_units_per_mm
    ox, oy = profile.origin

    def u(p: Point) -> str:
        return f"{int(round((p[0] + ox) * k))},{int(round((p[1] + oy) * k))}"

    out: List[str] = ["IN;", f"VS{_num(profile.hpgl_velocity)};", f"FS{_num(profile.hpgl_force)};",
                      f"SP{profile.hpgl_pen};"]
    down = False
    stroke: List[str] = []

    def flush() -> None:
        for i in range(0, len(stroke), MAX_PAIRS):
            out.append("PD" + ",".join(stroke[i:i + MAX_PAIRS]) + ";")
        stroke.clear()

    for m in tp.moves:
        if m.kind == "rapid":
            flush()
            out.append(f"PU{u((m.x, m.y))};")
        elif m.kind == "down":
            down = True
        elif m.kind == "up":
            flush()
            down = False
        elif m.kind in ("line", "arc") and down:
            stroke.append(u((m.x, m.y)))
    flush()
    out.append("SP0;")
    text = "\n".join(out) + "\n"
    check_instructions(text)
    return text


def check_instructions(text: str) -> None:
    """Raise SafetyError for an instruction outside the HP-GL/1 cutter subset."""
    for n, instr in enumerate(_instructions(text), 1):
        if instr[:2] not in ALLOWED:
            raise SafetyError(f"instruction {instr[:2]} is not in the HP-GL/1 cutter subset",
                              source=f"instruction {n}")


def _num(v: float) -> str:
    return f"{v:g}"


def _instructions(text: str) -> List[str]:
    return [s.strip() for s in text.replace("\n", "").split(";") if s.strip()]


def read_hpgl(text: str, units_per_mm: float = 40.0) -> List[List[Point]]:
    """Knife-down strokes of an HP-GL program in mm (absolute PU/PD only).
    Raises InputError for instructions outside the subset written here."""
    strokes: List[List[Point]] = []
    pos: Tuple[float, float] = (0.0, 0.0)
    for n, instr in enumerate(_instructions(text), 1):
        op, args = instr[:2].upper(), instr[2:]
        if op not in ALLOWED:
            raise InputError(f"unsupported HP-GL instruction {op!r}", source=f"instruction {n}")
        if op not in ("PU", "PD"):
            continue
        nums = [float(v) for v in re.split(r"[,\s]+", args) if v] if args else []
        if len(nums) % 2:
            raise InputError("odd number of coordinates", source=f"instruction {n}")
        pts = [(nums[i] / units_per_mm, nums[i + 1] / units_per_mm) for i in range(0, len(nums), 2)]
        if op == "PU":
            if pts:
                pos = pts[-1]
            strokes.append([])
        else:
            if not strokes or not strokes[-1]:
                if not strokes:
                    strokes.append([])
                strokes[-1].append(pos)
            strokes[-1].extend(pts)
            if pts:
                pos = pts[-1]
    return [s for s in strokes if len(s) > 1]
