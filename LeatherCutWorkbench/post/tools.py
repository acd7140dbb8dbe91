"""Tools of a machine and which tool does which role of the drawing.

A profile's main tool (its ``tool``: the knife, or the torch) cuts the
contours.  ``tools`` declares the other heads, each a JSON object::

    {"name": "punch4", "kind": "punch", "number": 2, "diameter": 4,
     "offset": [60, 0], "select": ["T2 M6"], "on": ["M64 P2", "G4 P0.3"],
     "off": ["M65 P2"], "feed": 3000}

``offset`` (mm) is where the tool sits relative to the main tool: to put the
tool on point P the machine drives the main tool to P - offset.  ``select``
lines make the tool active (``T2 M6`` by default on LinuxCNC; GRBL has no
``M6``, so there the lines must be given), ``on`` / ``off`` lower and raise it
(a punch strikes with ``on`` then ``off`` at each hole), ``feed`` (mm/min) is
its drawing speed, ``number`` its T word / HP-GL pen (``SPn``).  The main tool
is called ``knife`` (``torch`` / ``pen`` on such profiles), number
``hpgl_pen`` and selected again by the profile's ``tool_select`` lines.

``tool_map`` maps a *role* to a tool name: ``drill`` (AAMA drill holes),
``notch`` (notches), ``point`` (other point marks), ``internal`` (internal
lines), ``stitch`` (sew / stitch lines) or ``layer:NAME`` (marks and lines of
one DXF layer).  A notch mapped to the main knife is cut as a slit of
``notch_length`` mm into the part along the outline normal.  Roles that are
not mapped are not done (and reported).  Units mm, mm/min.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from ..core.errors import InputError

KINDS = ("knife", "pen", "marker", "punch", "crease", "notch", "torch", "scribe")
#: Kinds that act at a point (a strike), the others draw along lines.
POINT_KINDS = ("punch", "notch")
ROLES = ("drill", "notch", "point", "internal", "stitch")
_MAIN_NAMES = {"tangential_knife": "knife", "drag_knife": "knife", "torch": "torch", "pen": "pen"}
_KEYS = {"name", "kind", "number", "diameter", "offset", "select", "on", "off", "feed",
         "comment"}


@dataclass
class Tool:
    """One head of the machine (see the module docstring for the fields)."""

    name: str
    kind: str
    number: int
    offset: Tuple[float, float] = (0.0, 0.0)
    select: List[str] = field(default_factory=list)
    on: List[str] = field(default_factory=list)
    off: List[str] = field(default_factory=list)
    feed: float = 0.0
    diameter: float = 0.0
    main: bool = False


def main_tool(profile) -> Tool:
    """The profile's own cutting tool."""
    return Tool(_MAIN_NAMES.get(profile.tool, "knife"),
                "torch" if profile.tool == "torch" else ("pen" if profile.tool == "pen" else "knife"),
                profile.hpgl_pen, (0.0, 0.0), list(profile.tool_select), [], [],
                profile.cut_feed, 0.0, True)


def declared_tools(profile) -> Dict[str, Tool]:
    """Every tool of ``profile`` by name, the main tool first.  Raises
    InputError naming the field (``tools[2].diameter``) for a bad declaration."""
    src = profile.source or profile.name
    main = main_tool(profile)
    out: Dict[str, Tool] = {main.name: main}
    for i, d in enumerate(profile.tools):
        where = f"tools[{i}]"

        def fail(msg: str) -> None:
            raise InputError(f"{where}: {msg}", source=src)

        if not isinstance(d, dict):
            fail("a tool is a JSON object with name, kind, ...")
        unknown = sorted(set(d) - _KEYS)
        if unknown:
            fail(f"unknown field {unknown[0]!r}")
        name = d.get("name")
        if not isinstance(name, str) or not name or name in out:
            fail(f"needs a unique 'name' (not {name!r}; {main.name!r} is the main tool)")
        kind = d.get("kind")
        if kind not in KINDS:
            fail(f"'kind' must be one of {', '.join(KINDS)}, not {kind!r}")
        number = d.get("number", len(out) + 1)
        if isinstance(number, bool) or not isinstance(number, int) or number < 0:
            fail(f"'number' must be a whole number >= 0, not {number!r}")
        off = d.get("offset", [0.0, 0.0])
        if (not isinstance(off, list) or len(off) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in off)):
            fail(f"'offset' must be [dx, dy] in mm, not {off!r}")
        lines = {}
        for key in ("select", "on", "off"):
            v = d.get(key, [])
            v = [v] if isinstance(v, str) else v
            if not isinstance(v, list) or not all(isinstance(t, str) for t in v):
                fail(f"'{key}' must be a list of G-code template lines")
            lines[key] = v
        if "select" not in d:
            if profile.dialect == "linuxcnc":
                lines["select"] = [f"T{number} M6"]
            elif profile.is_gcode:
                fail(f"'select' is required: {profile.dialect} has no M6 tool change "
                     "(give the lines that make this tool active, e.g. an output and a dwell)")
        feed = d.get("feed", profile.cut_feed)
        if isinstance(feed, bool) or not isinstance(feed, (int, float)) or not 0 < feed <= profile.max_feed:
            fail(f"'feed' must lie in (0, max_feed {profile.max_feed:g}] mm/min, not {feed!r}")
        dia = d.get("diameter", 0.0)
        if isinstance(dia, bool) or not isinstance(dia, (int, float)) or dia < 0:
            fail(f"'diameter' must be a number >= 0 mm, not {dia!r}")
        if kind == "punch" and dia <= 0:
            fail("a punch needs its 'diameter' in mm")
        out[name] = Tool(name, kind, number, (float(off[0]), float(off[1])), lines["select"],
                         lines["on"], lines["off"], float(feed), float(dia))
    return out


def parse_tool_map(text: str, source: str = "--tool-map") -> Dict[str, str]:
    """``"stitch=pen,drill=punch4"`` -> {"stitch": "pen", "drill": "punch4"}."""
    out: Dict[str, str] = {}
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        role, sep, tool = (s.strip() for s in part.partition("="))
        if not sep or not role or not tool:
            raise InputError(f"expected ROLE=TOOL, got {part!r}", source=source)
        out[role] = tool
    return out


def check_role(role: str, source: str) -> None:
    if role not in ROLES and not (role.startswith("layer:") and len(role) > 6):
        raise InputError(f"unknown role {role!r}; roles are {', '.join(ROLES)} or layer:NAME",
                         source=source)


def tool_map(profile, overrides: Optional[Dict[str, str]] = None,
             overrides_from: str = "--tool-map") -> Dict[str, Tool]:
    """Role -> tool for ``profile``: its ``tool_map`` with ``overrides`` (from
    ``overrides_from``: ``--tool-map``, the job's ``PostToolMap``) on top; a
    value ``none`` unmaps a role.  Raises
    InputError naming the profile field or option when a role or a tool is
    unknown, or a tool cannot do the role (a punch cannot draw a line)."""
    tools = declared_tools(profile)
    src = profile.source or profile.name
    merged: Dict[str, Tuple[str, str]] = {r: (t, f"{src}: field tool_map")
                                          for r, t in profile.tool_map.items()}
    for r, t in (overrides or {}).items():
        merged[r] = (t, overrides_from)
    out: Dict[str, Tool] = {}
    for role, (name, where) in merged.items():
        check_role(role, where)
        if name == "none":
            continue
        if name not in tools:
            raise InputError(f"role {role!r} is mapped to tool {name!r}, which {profile.name} does "
                             f"not have (its tools: {', '.join(tools)}; declare it in the profile "
                             "field tools)", source=where)
        tool = tools[name]
        line_role = role in ("internal", "stitch")
        if line_role and tool.kind in POINT_KINDS:
            raise InputError(f"role {role!r} holds lines; tool {name!r} ({tool.kind}) only strikes "
                             "points", source=where)
        if role == "drill" and tool.main:
            raise InputError(f"role 'drill' cannot be done by the main tool {name!r}; map it to a "
                             "punch or a pen", source=where)
        out[role] = tool
    return out


def validate_profile(profile, source: str) -> None:
    """Profile-load check of ``tools``, ``tool_map`` and ``notch_length``."""
    if profile.notch_length <= 0:
        raise InputError("notch_length must be positive (mm)", source=source)
    tool_map(profile)


def role_of(kind_or_role: str) -> str:
    """Role of a mark kind (``drill``, ``notch``, else ``point``)."""
    return kind_or_role if kind_or_role in ("drill", "notch") else "point"


def describe(tools: Dict[str, Any]) -> str:
    """One line: ``role=tool`` pairs, for messages and the GUI."""
    return ", ".join(f"{r}={t.name}" for r, t in sorted(tools.items())) or "(no roles mapped)"
