"""Machine profiles: everything that differs between cutters, held as data.

A :class:`MachineProfile` is loaded from a JSON file (``resources/machines/*.json``
ships with the workbench; a person's own profiles live in the user folder, see
:func:`user_profiles_dir`).  Writers, the safety check and the live link read
only the profile, never a machine name, so a new cutter is a new JSON file.

Units: lengths mm, feeds mm/min, acceleration mm/s^2, angles degrees, times s.
Every field is documented in docs/MACHINES.md.
"""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Tuple

from ..core.errors import InputError

#: Folder of the profiles shipped with the workbench.
BUILTIN_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))), "resources", "machines")

DIALECTS = ("grbl", "grblhal", "linuxcnc", "hpgl")
TOOLS = ("tangential_knife", "drag_knife", "torch", "pen")


@dataclass
class MachineProfile:
    """One cutter.  Coordinates written to the machine are plan coordinates plus
    ``origin``; the table spans ``[0, table_size[0]] x [0, table_size[1]]`` mm in
    plan coordinates and every move must stay inside it."""

    name: str
    description: str = ""
    dialect: str = "grblhal"              # grbl | grblhal | linuxcnc | hpgl
    tool: str = "tangential_knife"        # tangential_knife | drag_knife | torch | pen
    table_size: Tuple[float, float] = (2500.0, 1600.0)   # mm
    origin: Tuple[float, float] = (0.0, 0.0)             # mm, added to plan coordinates
    axes: str = "XYZC"                    # axis letters the controller has
    rapid_feed: float = 20000.0           # mm/min, travel with the tool up
    cut_feed: float = 6000.0              # mm/min
    plunge_feed: float = 1000.0           # mm/min, knife down / Z moves
    max_feed: float = 30000.0             # mm/min, any F above is refused
    acceleration: float = 1500.0          # mm/s^2 (informative, for time estimates)
    # knife heading axis
    rotary_axis: str = ""                 # "C", "A", "Z" ("" = no heading axis)
    rotary_wrap: bool = False             # LinuxCNC WRAPPED_ROTARY: sign selects direction
    units_per_turn: float = 360.0         # axis units for one knife turn (3.6 on GRBL Z)
    heading_offset: float = 0.0           # degrees added to the path heading
    rotary_in_feed: bool = True           # the controller counts rotary units in F (GRBL)
    lift_angle: float = 15.0              # degrees; larger turns lift, turn and plunge
    # knife / torch up and down
    lift_axis: str = "Z"                  # "" = lifted by an output (servo, torch on/off)
    z_up: float = 5.0                     # mm, lift_axis position with the knife up
    z_down: float = -1.2                  # mm, lift_axis position while cutting
    knife_up: List[str] = field(default_factory=list)     # template lines
    knife_down: List[str] = field(default_factory=list)   # template lines
    # I/O templates (lines, may be empty) and delays
    vacuum_on: List[str] = field(default_factory=list)
    vacuum_off: List[str] = field(default_factory=list)
    press_on: List[str] = field(default_factory=list)
    press_off: List[str] = field(default_factory=list)
    tool_on: List[str] = field(default_factory=list)      # oscillator / torch ignition
    tool_off: List[str] = field(default_factory=list)
    settle_dwell: float = 0.0             # s, after vacuum/press on
    pierce_delay: float = 0.0             # s, after the tool goes down (torch pierce)
    cooling_delay: float = 0.0            # s, after the tool goes up
    header: List[str] = field(default_factory=list)
    footer: List[str] = field(default_factory=list)
    # output form
    arcs: str = "g2g3"                    # g2g3 | split
    chord_tol: float = 0.01               # mm, max chord deviation when arcs are split
    decimals: int = 3
    line_numbers: bool = False
    max_line_length: int = 70             # characters sent per line (GRBL: 80 incl. EOL)
    sync_at_items: bool = True            # G4 P0 after each item: executed-progress points
    sync_every_segment: bool = False      # G4 P0 after each segment: exact resume after a
                                          # position-losing fault, but the planner empties
                                          # (the head stops) at every segment end
    homing: bool = False                  # machine homes with $H (resume re-homes)
    # live link (GRBL family)
    baud: int = 115200
    rx_buffer_size: int = 128             # bytes; the controller's [OPT] value wins
    # HP-GL
    hpgl_units_per_mm: float = 40.0
    hpgl_pen: int = 1
    hpgl_velocity: float = 20.0           # cm/s
    hpgl_force: float = 80.0              # g
    overcut: float = 0.0                  # mm cut past the start of a closed contour
    # drag knife (post/drag_knife.py): the blade tip trails the swivel axis
    blade_offset: float = 0.0             # mm, tip behind the axis (0 = no compensation)
    swivel_angle: float = 10.0            # degrees; sharper corners get a swivel arc
    # more tools (post/tools.py): pen, punch, crease, notch tool, scribe, ...
    tools: List[Dict[str, Any]] = field(default_factory=list)   # tool declarations
    tool_map: Dict[str, str] = field(default_factory=dict)      # role -> tool name
    tool_select: List[str] = field(default_factory=list)        # lines selecting the main tool
    notch_length: float = 3.0             # mm, a notch cut by the knife: slit length
    source: str = ""                      # file the profile came from
    # kerf compensation, cut direction, lead-ins/outs, tabs (post/compensation.py)
    kerf: float = 0.0                     # mm removed by the tool (torch kerf width)
    kerf_mode: str = "path"               # path (pre-offset) | controller (G41.1/G42.1 + G40)
    kerf_corners: str = "round"           # round | extended: outside corners of the offset
    outer_direction: str = ""             # cw | ccw | drawn ("" = torch cw, others drawn)
    hole_direction: str = ""              # cw | ccw | drawn ("" = torch ccw, others drawn)
    lead_in: str = ""                     # none | line | arc ("" = torch arc, others none)
    lead_in_length: float = 5.0           # mm along the lead-in
    lead_in_angle: float = 45.0           # degrees: line to the tangent, or arc sweep
    lead_out: str = ""                    # none | line | arc ("" = same as lead_in on a torch)
    lead_out_length: float = 2.0          # mm
    lead_out_angle: float = 45.0          # degrees
    tab_count: int = 0                    # tabs per outer contour (0 = none)
    tab_spacing: float = 0.0              # mm between tabs; > 0 overrides tab_count
    tab_width: float = 1.0                # mm left uncut per tab

    # ---------------------------------------------------------------- helpers
    @property
    def is_gcode(self) -> bool:
        return self.dialect in ("grbl", "grblhal", "linuxcnc")

    @property
    def tangential(self) -> bool:
        """True when the profile turns the knife with a rotary axis."""
        return bool(self.rotary_axis) and self.tool == "tangential_knife"

    def table_limits(self) -> Tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the table in plan coordinates, mm."""
        return (0.0, 0.0, float(self.table_size[0]), float(self.table_size[1]))

    def to_json(self) -> Dict[str, Any]:
        d = dataclasses.asdict(self)
        d.pop("source", None)
        d["table_size"] = list(self.table_size)
        d["origin"] = list(self.origin)
        return d


_FIELDS = {f.name: f for f in dataclasses.fields(MachineProfile)}


def user_profiles_dir() -> str:
    """Folder of the user's own profiles: ``<FreeCAD user data>/LeatherCut/machines``
    when FreeCAD is importable, else ``~/.config/leathercut/machines``.
    ``LEATHERCUT_MACHINES`` overrides both (used by tests and shared setups)."""
    env = os.environ.get("LEATHERCUT_MACHINES")
    if env:
        return env
    try:
        import FreeCAD  # noqa: F401  (optional: only for the folder name)
        return os.path.join(FreeCAD.getUserAppDataDir(), "LeatherCut", "machines")
    except Exception:
        return os.path.join(os.path.expanduser("~"), ".config", "leathercut", "machines")


def _search_dirs() -> List[str]:
    return [user_profiles_dir(), BUILTIN_DIR]


def list_profiles() -> List[Dict[str, str]]:
    """Every profile found, user folder first (a user profile with the same name
    hides the shipped one).  Each entry: ``name``, ``description``, ``path``,
    ``origin`` (``"user"`` or ``"builtin"``)."""
    seen: Dict[str, Dict[str, str]] = {}
    for origin, folder in (("user", user_profiles_dir()), ("builtin", BUILTIN_DIR)):
        if not os.path.isdir(folder):
            continue
        for fn in sorted(os.listdir(folder)):
            if not fn.endswith(".json"):
                continue
            name = fn[:-5]
            if name in seen:
                continue
            path = os.path.join(folder, fn)
            try:
                desc = load_profile(path).description
            except InputError as exc:
                desc = f"(unreadable: {exc.message})"
            seen[name] = {"name": name, "description": desc, "path": path, "origin": origin}
    return list(seen.values())


def load_profile(name_or_path: str) -> MachineProfile:
    """Load a profile by name (user folder, then shipped profiles) or by file path.

    Raises InputError naming the file and the field for unknown names, bad JSON,
    unknown fields or values of the wrong kind."""
    path = name_or_path
    if not (os.sep in name_or_path or name_or_path.endswith(".json")):
        path = ""
        for folder in _search_dirs():
            cand = os.path.join(folder, name_or_path + ".json")
            if os.path.isfile(cand):
                path = cand
                break
        if not path:
            names = ", ".join(p["name"] for p in list_profiles())
            raise InputError(f"no machine profile named {name_or_path!r} (known: {names})",
                             source=name_or_path)
    if not os.path.isfile(path):
        raise InputError("no such machine profile file", source=path)
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read machine profile: {exc}", source=path)
    except json.JSONDecodeError as exc:
        raise InputError(f"not valid JSON: {exc.msg} at line {exc.lineno}", source=path)
    if not isinstance(data, dict):
        raise InputError("a machine profile is a JSON object", source=path)
    data.setdefault("name", os.path.splitext(os.path.basename(path))[0])
    return profile_from_dict(data, source=path)


def profile_from_dict(data: Dict[str, Any], source: str = "") -> MachineProfile:
    """Build and validate a profile from a JSON-like dict."""
    kwargs: Dict[str, Any] = {}
    for key, value in data.items():
        if key.startswith("_") or key == "comment":
            continue                      # free-form notes inside the file
        if key not in _FIELDS:
            raise InputError(f"unknown field {key!r}", source=source)
        if key in ("tools", "tool_map"):      # checked by post/tools.py in _validate
            if not isinstance(value, list if key == "tools" else dict):
                raise InputError(f"field {key!r} has the wrong kind of value: {value!r}",
                                 source=source)
            kwargs[key] = value
            continue
        default = _FIELDS[key].default
        if default is dataclasses.MISSING:
            default = None
        if _FIELDS[key].default_factory is not dataclasses.MISSING:  # type: ignore[misc]
            default = []
        kwargs[key] = _coerce(key, value, default, source)
    prof = MachineProfile(**kwargs)
    prof.source = source
    _validate(prof, source)
    from .profile_check import check_profile   # hostile values: NaN, ranges, line form
    check_profile(prof, source)
    return prof


def _coerce(key: str, value: Any, default: Any, source: str) -> Any:
    bad = InputError(f"field {key!r} has the wrong kind of value: {value!r}", source=source)
    if isinstance(default, bool):
        if not isinstance(value, bool):
            raise bad
        return value
    if isinstance(default, int) and not isinstance(default, bool):
        if isinstance(value, bool) or not isinstance(value, int):
            raise bad
        return value
    if isinstance(default, float):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise bad
        return float(value)
    if isinstance(default, tuple):
        if (not isinstance(value, list) or len(value) != 2
                or not all(isinstance(v, (int, float)) for v in value)):
            raise bad
        return (float(value[0]), float(value[1]))
    if isinstance(default, list):
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise bad
        return list(value)
    if not isinstance(value, str):
        raise bad
    return value


def _validate(p: MachineProfile, source: str) -> None:
    def fail(msg: str) -> None:
        raise InputError(msg, source=source)

    if p.dialect not in DIALECTS:
        fail(f"dialect must be one of {', '.join(DIALECTS)}, not {p.dialect!r}")
    if p.tool not in TOOLS:
        fail(f"tool must be one of {', '.join(TOOLS)}, not {p.tool!r}")
    if p.table_size[0] <= 0 or p.table_size[1] <= 0:
        fail("table_size must be positive (mm)")
    for key in ("rapid_feed", "cut_feed", "plunge_feed", "max_feed"):
        v = getattr(p, key)
        if v <= 0:
            fail(f"{key} must be positive (mm/min)")
        if key != "max_feed" and v > p.max_feed:
            fail(f"{key} {v:g} mm/min exceeds max_feed {p.max_feed:g}")
    p.axes = p.axes.upper()
    p.rotary_axis = p.rotary_axis.upper()
    p.lift_axis = p.lift_axis.upper()
    if p.is_gcode:
        for letter in (p.rotary_axis, p.lift_axis):
            if letter and letter not in p.axes:
                fail(f"axis {letter} is not among the machine's axes {p.axes}")
        if p.rotary_axis and p.rotary_axis == p.lift_axis:
            fail("rotary_axis and lift_axis must differ")
        if not p.lift_axis and not p.knife_down and p.tool != "torch":
            fail("without a lift_axis the knife_down/knife_up templates are required")
    if not 0.0 <= p.lift_angle <= 180.0:
        fail("lift_angle must lie in [0, 180] degrees")
    if p.units_per_turn <= 0:
        fail("units_per_turn must be positive")
    if p.arcs not in ("g2g3", "split"):
        fail("arcs must be 'g2g3' or 'split'")
    if not 0 < p.chord_tol <= 1.0:
        fail("chord_tol must lie in (0, 1] mm")
    if not 1 <= p.decimals <= 6:
        fail("decimals must lie in 1..6")
    if p.rx_buffer_size < 16:
        fail("rx_buffer_size must be at least 16 bytes")
    for key in ("settle_dwell", "pierce_delay", "cooling_delay", "overcut"):
        if getattr(p, key) < 0:
            fail(f"{key} must not be negative")
    if p.blade_offset < 0:
        fail("blade_offset must not be negative (mm)")
    if p.blade_offset > 0 and p.tool != "drag_knife":
        why = {"tangential_knife": " (its blade is turned by the rotary axis, so there is no "
                                   "trailing offset)"}.get(p.tool, "")
        fail(f"blade_offset is for a drag knife: this profile's tool is {p.tool}{why}; "
             "set blade_offset to 0 or tool to drag_knife")
    if not 0.0 <= p.swivel_angle <= 180.0:
        fail("swivel_angle must lie in [0, 180] degrees")
    from .tools import validate_profile
    validate_profile(p, source)
    _validate_compensation(p, fail)
    if p.sync_every_segment and not p.is_gcode:
        fail(f"sync_every_segment needs a G-code dialect (G4 P0); {p.dialect} has no "
             "synchronising command")


def _validate_compensation(p: MachineProfile, fail) -> None:
    """The kerf / direction / lead / tab fields (docs/MACHINES.md, "Kerf, cut
    direction, lead-ins and tabs")."""
    choices = {"kerf_mode": ("path", "controller"), "kerf_corners": ("round", "extended"),
               "outer_direction": ("", "cw", "ccw", "drawn"),
               "hole_direction": ("", "cw", "ccw", "drawn"),
               "lead_in": ("", "none", "line", "arc"), "lead_out": ("", "none", "line", "arc")}
    for key, allowed in choices.items():
        if getattr(p, key) not in allowed:
            fail(f"{key} must be one of {', '.join(a for a in allowed if a)}, not {getattr(p, key)!r}")
    for key in ("kerf", "lead_in_length", "lead_out_length", "tab_spacing"):
        if not 0.0 <= getattr(p, key) < 1000.0:
            fail(f"{key} must lie in [0, 1000) mm, not {getattr(p, key):g}")
    for key in ("lead_in_angle", "lead_out_angle"):
        if not 0.0 < getattr(p, key) <= 180.0:
            fail(f"{key} must lie in (0, 180] degrees, not {getattr(p, key):g}")
    if p.tab_count < 0:
        fail("tab_count must not be negative")
    if (p.tab_count or p.tab_spacing) and not 0.0 < p.tab_width < 100.0:
        fail("tab_width must lie in (0, 100) mm when tabs are asked for")
    if p.kerf_mode == "controller" and p.kerf > 0 and p.dialect != "linuxcnc":
        fail(f"kerf_mode 'controller' (G41.1/G42.1 cutter compensation) needs the linuxcnc "
             f"dialect; {p.dialect} has none: use kerf_mode 'path'")


def save_user_profile(profile: MachineProfile) -> str:
    """Write ``profile`` into the user folder as ``<name>.json``; returns the path."""
    folder = user_profiles_dir()
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, profile.name + ".json")
    with open(path, "w", encoding="utf-8") as fh:
        json.dump(profile.to_json(), fh, indent=2)
        fh.write("\n")
    return path
