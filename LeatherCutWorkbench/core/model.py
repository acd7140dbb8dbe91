"""The job model: the value each pipeline stage returns and the next one takes.

    DXF --import--> Drawing --recognise--> Recognition --nest--> Layout
        --plan--> CutPlan --post--> machine file / live stream

Units: every length is millimetres, every angle degrees, every area mm^2.
All classes are plain dataclasses (no FreeCAD, no GUI) so a headless run, a
test and the workbench share them.  ``to_json()`` methods return the structures
documented in docs/CLI.md; they are the machine-readable contract of the CLI.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace
from typing import Any, Dict, List, Optional, Sequence, Tuple

from .geometry import (Point, Segment, Transform2D, bbox, path_length, path_points,
                       signed_area)


def _prefixed(prefix: str, ident: str) -> str:
    """Id of a transformed copy: ``"<prefix>/<id>"`` (unchanged when no prefix)."""
    return f"{prefix}/{ident}" if prefix else ident


class _Path:
    """Start, end and length (mm) of anything cut along its ``segments``
    (lead-ins, open chains, cut items): a connected, directed path."""

    segments: List[Segment]

    @property
    def start(self) -> Point:
        return self.segments[0].start

    @property
    def end(self) -> Point:
        return self.segments[-1].end

    @property
    def length(self) -> float:
        return path_length(self.segments)


# --------------------------------------------------------------------------
# Findings: what a stage wants a person to know (never printed by the core).
# --------------------------------------------------------------------------

@dataclass
class Finding:
    """A warning or note produced by a stage.

    ``level`` is ``"info"``, ``"warning"`` or ``"error"``; ``code`` is a stable
    machine-readable key (e.g. ``"skipped-entity"``); ``source`` names where it
    came from (file, entity handle, layer, line) so a person can find it."""

    level: str
    code: str
    message: str
    source: Optional[str] = None

    def to_json(self) -> Dict[str, Any]:
        return {"level": self.level, "code": self.code, "message": self.message,
                "source": self.source}


# --------------------------------------------------------------------------
# Import stage: Drawing
# --------------------------------------------------------------------------

@dataclass
class EdgeSource:
    """Where an imported edge came from in the DXF."""

    layer: str = "0"
    color: int = 256          # ACI colour, 256 = BYLAYER
    handle: str = ""          # handle of the model-space entity (or INSERT)
    dxftype: str = ""         # original entity type, e.g. "LWPOLYLINE"
    block: str = ""           # "/"-joined block path when exploded from INSERTs
    role: str = "cut"         # "cut", "mark", "grain", "mirror", "internal", "annotation", "ignore"
    piece: str = ""           # key into Drawing.pieces (AAMA/ASTM pattern files), "" otherwise


@dataclass
class LineEdge:
    start: Point
    end: Point
    src: EdgeSource = field(default_factory=EdgeSource)


@dataclass
class ArcEdge:
    """Circular arc; ``sweep`` is signed (positive = CCW) in degrees.  A full
    circle has |sweep| == 360."""

    center: Point
    radius: float
    start_angle: float
    sweep: float
    src: EdgeSource = field(default_factory=EdgeSource)


@dataclass
class EllipseEdge:
    """Elliptical arc in world XY: ``major_axis`` is the vector from the centre
    to the major apex (mm), ``ratio`` minor/major, params in radians running
    counter-clockwise from ``start_param`` to ``end_param``."""

    center: Point
    major_axis: Point
    ratio: float
    start_param: float
    end_param: float
    src: EdgeSource = field(default_factory=EdgeSource)


@dataclass
class SplineEdge:
    """Non-uniform rational B-spline: ``poles`` (mm), ``knots`` (full knot
    vector with repeats), ``weights`` (empty = non-rational), ``degree``.
    ``from_fit_points`` is True when the DXF only held fit points and the poles
    were re-interpolated."""

    poles: List[Point]
    knots: List[float]
    weights: List[float]
    degree: int
    closed: bool = False
    from_fit_points: bool = False
    src: EdgeSource = field(default_factory=EdgeSource)


@dataclass
class Mark:
    """A point mark (drill hole, notch, punch) in mm."""

    position: Point
    kind: str = "point"       # "drill", "notch", "point"
    src: EdgeSource = field(default_factory=EdgeSource)

    def transformed(self, xf: Transform2D) -> "Mark":
        return Mark(xf.apply(self.position), self.kind, copy.deepcopy(self.src))


@dataclass
class TextNote:
    """TEXT / MTEXT kept as annotation."""

    text: str
    position: Point
    height: float = 0.0
    src: EdgeSource = field(default_factory=EdgeSource)


@dataclass
class PieceInfo:
    """One pattern piece of an AAMA / ASTM D6673 file (one block INSERT).

    ``edges``, ``marks`` and ``texts`` are indices into the Drawing's lists.
    ``grain_angle`` is the direction of the grain line (layer 7) in degrees in
    [0, 180), None without one; ``mirror_line`` the two end points (mm) of the
    fold line (layer 6) when the drawn piece is half of the cut piece.
    ``bbox`` is (xmin, ymin, xmax, ymax) in mm of the piece's cut edges."""

    key: str
    name: str
    size: str = ""
    quantity: int = 1
    block: str = ""
    insert_handle: str = ""
    category: str = ""
    annotation: str = ""
    edges: List[int] = field(default_factory=list)
    marks: List[int] = field(default_factory=list)
    texts: List[int] = field(default_factory=list)
    grain_angle: Optional[float] = None
    mirror_line: Optional[Tuple[Point, Point]] = None
    bbox: Optional[Tuple[float, float, float, float]] = None

    def to_json(self) -> Dict[str, Any]:
        return {"key": self.key, "name": self.name, "size": self.size,
                "quantity": self.quantity, "block": self.block,
                "insert_handle": self.insert_handle, "category": self.category,
                "annotation": self.annotation, "edges": len(self.edges),
                "marks": len(self.marks), "texts": len(self.texts),
                "grain_angle": self.grain_angle,
                "mirror_line": [list(p) for p in self.mirror_line] if self.mirror_line else None,
                "bbox": list(self.bbox) if self.bbox else None}


@dataclass
class Drawing:
    """What import returns: edges in mm with their source, marks, texts.

    ``pieces`` maps a piece key (the block name, ``"#2"``... appended when a
    block is inserted more than once) to a :class:`PieceInfo` for pattern files
    where each block is a piece (AAMA/ASTM); empty for ordinary drawings.
    Every edge/mark/text of a piece has ``src.piece`` set to that key.
    ``units`` is the unit the file was read in (``units_source``: "header",
    "aama-text", "option" or "assumed"); coordinates are always mm.
    ``offset`` is the translation (mm) that was removed to bring huge
    coordinates to a local origin (add it back on export).  ``stats`` holds
    what ``leathercut inspect`` reports (entity counts, layers, blocks, bbox,
    clean-up counts; see docs/CLI.md)."""

    path: str
    edges: List[Any] = field(default_factory=list)      # LineEdge | ArcEdge | EllipseEdge | SplineEdge
    marks: List[Mark] = field(default_factory=list)
    texts: List[TextNote] = field(default_factory=list)
    units: str = "mm"
    units_source: str = "default"
    dxf_version: str = ""
    offset: Point = (0.0, 0.0)
    pieces: Dict[str, PieceInfo] = field(default_factory=dict)
    findings: List[Finding] = field(default_factory=list)
    stats: Dict[str, Any] = field(default_factory=dict)


# --------------------------------------------------------------------------
# Recognition stage: parts with contours, lead-ins, open chains and flags
# --------------------------------------------------------------------------

@dataclass
class Contour:
    """A closed loop of segments (start of the first == end of the last).

    Outer contours are stored counter-clockwise, holes clockwise.  ``shared``
    holds the indices of segments shared with another contour (common-edge
    layouts): the planner cuts each shared edge once."""

    id: str
    segments: List[Segment]
    layer: str = ""
    shared: List[int] = field(default_factory=list)

    def points(self, chord_tol: float = 0.01) -> List[Point]:
        """Closed polyline without the repeated first point."""
        pts = path_points(self.segments, chord_tol)
        return pts[:-1] if len(pts) > 1 else pts

    @property
    def length(self) -> float:
        return path_length(self.segments)

    @property
    def area(self) -> float:
        """Signed area in mm^2 (positive = counter-clockwise)."""
        return signed_area(self.points())

    @property
    def bbox(self) -> Tuple[float, float, float, float]:
        return bbox(self.points())

    def transformed(self, xf: Transform2D, prefix: str = "") -> "Contour":
        """Copy moved by ``xf``.  A mirroring transform would flip the
        orientation, so the loop is then reversed (outer stays CCW, holes CW)
        and the shared-segment indices follow the reversal."""
        segs = [s.transformed(xf) for s in self.segments]
        shared = list(self.shared)
        if xf.mirrored:
            segs = [s.reversed() for s in reversed(segs)]
            shared = sorted(len(segs) - 1 - i for i in shared)
        return Contour(_prefixed(prefix, self.id), segs, self.layer, shared)


@dataclass
class LeadIn(_Path):
    """Open chain that enters a contour: the cut starts at ``segments[0].start``
    (the free end) and reaches the contour at ``segments[-1].end``.
    ``role`` is ``"lead_in"`` or ``"lead_out"`` (then it starts on the contour)."""

    id: str
    contour_id: str
    segments: List[Segment]
    role: str = "lead_in"

    def transformed(self, xf: Transform2D, prefix: str = "") -> "LeadIn":
        return LeadIn(_prefixed(prefix, self.id), _prefixed(prefix, self.contour_id),
                      [s.transformed(xf) for s in self.segments], self.role)



@dataclass
class Part:
    """One part: an outer contour, its holes, its lead-ins and marks.

    ``excluded`` parts are not nested or cut (a person or a flag decided so).
    ``quantity`` and ``rotations`` feed nesting; ``rotations`` is None for any
    angle, or a list of allowed angles in degrees."""

    id: str
    outer: Contour
    holes: List[Contour] = field(default_factory=list)
    lead_ins: List[LeadIn] = field(default_factory=list)
    marks: List[Mark] = field(default_factory=list)
    name: str = ""
    excluded: bool = False
    quantity: int = 1
    rotations: Optional[List[float]] = None
    mirror_allowed: bool = False
    grade: int = 0
    parent_id: Optional[str] = None    # part whose hole this part lies in
    lines: List["OpenChain"] = field(default_factory=list)   # internal / stitch lines (drawn, not cut)
    size: str = ""                     # pattern size (AAMA / ASTM graded sets), "" otherwise
    #: part regions with their own grade: (grade, closed contour inside the outer),
    #: drawn, not cut; see core/nesting/part_regions.py
    grade_regions: List[Tuple[int, Contour]] = field(default_factory=list)

    @property
    def net_area(self) -> float:
        return abs(self.outer.area) - sum(abs(h.area) for h in self.holes)

    def contours(self) -> List[Contour]:
        return list(self.holes) + [self.outer]

    def transformed(self, xf: Transform2D, new_id: Optional[str] = None) -> "Part":
        """Copy moved by ``xf`` (mirror, rotate about the origin, translate).
        With ``new_id`` the copy gets that id and its contours / lead-ins ids
        ``"<new_id>/<old id>"``; without, every id is kept."""
        prefix = new_id or ""
        return replace(self, id=new_id or self.id,
                       outer=self.outer.transformed(xf, prefix),
                       holes=[h.transformed(xf, prefix) for h in self.holes],
                       lead_ins=[li.transformed(xf, prefix) for li in self.lead_ins],
                       marks=[m.transformed(xf) for m in self.marks],
                       lines=[ln.transformed(xf) for ln in self.lines],
                       grade_regions=[(g, c.transformed(xf, prefix)) for g, c in self.grade_regions],
                       rotations=copy.copy(self.rotations))


@dataclass
class OpenChain(_Path):
    """A connected run of edges that does not close and is not a lead-in."""

    id: str
    segments: List[Segment]
    layer: str = ""


    def transformed(self, xf: Transform2D) -> "OpenChain":
        return OpenChain(self.id, [s.transformed(xf) for s in self.segments], self.layer)


@dataclass
class Flag:
    """A recognition doubt for a person to resolve.

    ``kind`` is ``"over"`` (a closed region that is probably not a part) or
    ``"under"`` (an open chain that is probably a contour with a gap).
    ``ids`` are the contour / chain ids concerned; ``gap`` the gap in mm for
    under-recognition; ``fix`` the proposed bridge segments; ``accepted`` is None
    until a person (or ``--close-gaps``) decides."""

    id: str
    kind: str
    ids: List[str]
    reason: str
    gap: Optional[float] = None
    fix: List[Segment] = field(default_factory=list)
    accepted: Optional[bool] = None
    # what accepting the flag does: "exclude" (over: the contour is not cut),
    # "close" (under: chains + fix form a closed outline), "join" (under: fix joins
    # the chain to a contour, it becomes a lead-in), "trim" (under: drop the
    # chain, a stub past a corner; fix is empty)
    action: str = "close"


@dataclass
class Recognition:
    """What recognition returns."""

    parts: List[Part] = field(default_factory=list)
    open_chains: List[OpenChain] = field(default_factory=list)
    flags: List[Flag] = field(default_factory=list)
    findings: List[Finding] = field(default_factory=list)
    units: str = "mm"

    def active_parts(self) -> List[Part]:
        return [p for p in self.parts if not p.excluded]


# --------------------------------------------------------------------------
# Nesting stage: containers and placements
# --------------------------------------------------------------------------

@dataclass
class Container:
    """Material to nest on.  ``kind`` is ``"sheet"``, ``"strip"`` or ``"hide"``.

    ``outline`` is a closed polygon (mm, CCW).  For a strip the outline's length
    is the used length after nesting.  ``defects`` are polygons no part may
    overlap; ``zones`` are (grade, polygon) pairs: a part of grade g may only lie
    where the zone grade is >= g (outside every zone the hide has ``base_grade``)."""

    id: str
    kind: str
    outline: List[Point]
    defects: List[List[Point]] = field(default_factory=list)
    zones: List[Tuple[int, List[Point]]] = field(default_factory=list)
    base_grade: int = 0


@dataclass
class Placement:
    """Where one copy of a part goes: mirror (about the part's Y axis) first,
    then rotate by ``angle`` degrees about the part's origin, then translate by
    (``x``, ``y``) mm into container coordinates."""

    part_id: str
    copy: int
    container: str
    x: float
    y: float
    angle: float = 0.0
    mirrored: bool = False


@dataclass
class Layout:
    """What nesting returns."""

    containers: List[Container] = field(default_factory=list)
    placements: List[Placement] = field(default_factory=list)
    unplaced: List[Tuple[str, int]] = field(default_factory=list)
    metrics: Dict[str, Any] = field(default_factory=dict)
    findings: List[Finding] = field(default_factory=list)


# --------------------------------------------------------------------------
# Planning stage: the ordered cut job
# --------------------------------------------------------------------------

@dataclass
class CutItem(_Path):
    """One contour (or lead-in + contour, or open chain) cut in one go.

    ``segments`` are in cutting order: the lead-in (if any) first, then the
    contour starting and ending at ``entry``.  ``kind`` is ``"hole"``,
    ``"outer"`` or ``"open"``; ``lead_in_count`` says how many leading segments
    are the lead-in; ``lifts`` are indices into ``segments`` before which the
    knife lifts, turns and plunges again."""

    contour_id: str
    part_id: str
    kind: str
    entry: Point
    segments: List[Segment]
    lead_in_count: int = 0
    lifts: List[int] = field(default_factory=list)
    lead_out_count: int = 0        # trailing segments that are the lead-out



@dataclass
class CutPlan:
    """What planning returns: cut items in order, starting from and returning to
    ``home`` (machine zero).  Idle moves are implied between consecutive items."""

    items: List[CutItem] = field(default_factory=list)
    home: Point = (0.0, 0.0)
    method: str = "nn"
    metrics: Dict[str, Any] = field(default_factory=dict)
    findings: List[Finding] = field(default_factory=list)

    def idle_moves(self) -> List[Tuple[Point, Point]]:
        """Knife-up moves: home -> first start, end -> next start, last end -> home."""
        moves: List[Tuple[Point, Point]] = []
        here = self.home
        for it in self.items:
            moves.append((here, it.start))
            here = it.end
        moves.append((here, self.home))
        return moves


def polygons_of(contours: Sequence[Contour], chord_tol: float = 0.01) -> List[List[Point]]:
    """Closed polylines of several contours (helper for nesting and previews)."""
    return [c.points(chord_tol) for c in contours]
