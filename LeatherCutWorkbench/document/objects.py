"""FeaturePython objects of a LeatherCut job and their creation helpers.

A job in a FreeCAD document is one group::

    Job (App::DocumentObjectGroupPython)      stage options as properties
      Drawing (group)                          imported drawing (hidden Data)
        Layer <name> (Part::FeaturePython)     edges of one DXF layer
      Recognition (group)                      recognised parts (hidden Data)
        Outer contours / Holes / Lead-ins / Open chains / Excluded  (Part::FeaturePython)
        Flag <id> (Part::FeaturePython)        one per over-/under-recognition flag
      Layout (group)                           nesting result (hidden Data)
        Container <id> / Placed <part>#<copy>  (Part::FeaturePython, movable by hand)
      Cut path (Part::FeaturePython)           the planned job (hidden Data), metrics
      Tool paths (group)                       multi-tool jobs: Tool <name> per further tool

Stage values are stored with :mod:`.codec` in hidden string properties, so they
are saved with the document and undone like any other property.  Every object
of a stage has an ``OutOfDate`` property: changing an earlier stage (its
options, a flag decision, a part moved by hand) marks the later stages out of
date until they are run again.

Proxies are restored by module and class name: never rename these classes.
Both pickling protocols are defined (``__getstate__``/``__setstate__`` for
FreeCAD 0.20, ``dumps``/``loads`` for 0.21.2 and 1.x).
"""

from __future__ import annotations

from typing import Any, Dict, Optional

import FreeCAD

from . import codec, tree
from .job_properties import add_nest_container_properties
from .options import STAGE_OPTIONS, add_properties, preferences, stage_of_property

#: navigation helpers, defined in .tree so the view providers need not import this module
role, is_job, job_of, jobs = tree.role, tree.is_job, tree.job_of, tree.jobs
stage_object, walk, load_data = tree.stage_object, tree.walk, tree.load_data

#: Pipeline order of the stage objects; a change in one marks the later ones out of date.
STAGE_ORDER = ("Import", "Recognise", "Nest", "Plan", "Post")
#: The stage object role that belongs to each stage key.
ROLE_OF_STAGE = {"Import": "Drawing", "Recognise": "Recognition", "Nest": "Layout",
                 "Plan": "CutPath"}

POST_FORMATS = ["gcode", "hpgl", "dxf"]


def translate(context: str, text: str) -> str:
    """FreeCAD's translate when present (GUI), the text itself otherwise."""
    try:
        return FreeCAD.Qt.translate(context, text)
    except Exception:  # no Qt in a bare freecadcmd build
        return text


class Proxy:
    """Common behaviour of every LeatherCut FeaturePython proxy."""

    ROLE = ""

    def __init__(self, obj):
        obj.Proxy = self
        self.Role = self.ROLE
        self._add_common(obj)

    def _add_common(self, obj) -> None:
        if "Role" not in obj.PropertiesList:
            obj.addProperty("App::PropertyString", "Role", "LeatherCut", "what this object holds")
            obj.Role = self.ROLE
            obj.setEditorMode("Role", 1)

    # -- pickling: FreeCAD 0.20 and 0.21.2+/1.x ---------------------------------
    def __getstate__(self):
        return {"Role": self.ROLE}

    def __setstate__(self, state):
        self.Role = (state or {}).get("Role", self.ROLE)

    def dumps(self):
        return self.__getstate__()

    def loads(self, state):
        self.__setstate__(state)

    # -- document callbacks ---------------------------------------------------------
    def execute(self, obj):
        """Stage objects hold results; nothing to recompute from properties."""

    def onChanged(self, obj, prop):
        pass


def restoring(obj) -> bool:
    """True while the document is being loaded (no stage marking then)."""
    doc = getattr(obj, "Document", None)
    return bool(getattr(doc, "Restoring", False)) or "Restore" in getattr(obj, "State", [])


def add_stage_properties(obj) -> None:
    """Hidden ``Data`` (stored stage value) and read-only ``OutOfDate``."""
    if "Data" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "Data", "LeatherCut",
                        "stored stage result (encoded; do not edit)")
        obj.setEditorMode("Data", 2)
    if "OutOfDate" not in obj.PropertiesList:
        obj.addProperty("App::PropertyBool", "OutOfDate", "LeatherCut",
                        "an earlier stage changed since this result was made: run the stage again")
        obj.setEditorMode("OutOfDate", 1)


class JobProxy(Proxy):
    """The job: owns the stage objects and holds every stage option."""

    ROLE = "Job"

    def __init__(self, obj):
        super().__init__(obj)
        add_job_properties(obj)

    def onChanged(self, obj, prop):
        stage = "Import" if prop == "SourceFile" else stage_of_property(prop)
        if stage is None or getattr(obj, "Proxy", None) is not self or restoring(obj):
            return
        if stage == "Import":
            mark_out_of_date(obj, "Import", include_self=True)
        elif stage != "Post":
            mark_out_of_date(obj, stage, include_self=True)
        elif prop == "PostMachine" and getattr(obj, "PlanFromMachine", False):
            # the plan's speeds and knife lift angle come from the machine
            mark_out_of_date(obj, "Plan", include_self=True)

    def onDocumentRestored(self, obj):
        # Options added by newer stage packages appear with their defaults.
        add_job_properties(obj)
        add_nest_container_properties(obj)


def add_job_properties(obj) -> None:
    if "SourceFile" not in obj.PropertiesList:
        obj.addProperty("App::PropertyFile", "SourceFile", "Import", "the DXF drawing of this job")
    for st in STAGE_OPTIONS:
        add_properties(obj, st)
    if "PostMachine" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "PostMachine", "Post",
                        "machine profile name (resources/machines) or path of a profile file")
        obj.PostMachine = "grblhal_tangential"
    if "PostFormat" not in obj.PropertiesList:
        obj.addProperty("App::PropertyEnumeration", "PostFormat", "Post", "machine file format")
        obj.PostFormat = POST_FORMATS
        obj.PostFormat = "gcode"
    if "PostOutputFile" not in obj.PropertiesList:
        obj.addProperty("App::PropertyFile", "PostOutputFile", "Post",
                        "where Post-process writes the machine file")
    if "PostToolMap" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "PostToolMap", "Post",
                        "which tool does which role, on top of the profile's tool_map "
                        "(e.g. stitch=pen,drill=punch4; docs/MACHINES.md)")
    if "PostPort" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "PostPort", "Post",
                        "serial port or pyserial URL for Send to cutter (e.g. /dev/ttyUSB0, socket://host:23)")
    if "PostLastOutput" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "PostLastOutput", "Post",
                        "file written by the last Post-process")
        obj.setEditorMode("PostLastOutput", 1)


def apply_preferences(obj) -> None:
    """Set job properties that have a default on the preferences page."""
    params = preferences()
    for kind, name, value in params.GetContents() or []:
        if name in obj.PropertiesList:
            try:
                setattr(obj, name, value)
            except Exception:  # wrong type stored by hand: keep the built-in default
                FreeCAD.Console.PrintWarning(f"LeatherCut: ignoring preference {name}={value!r}\n")


class StageProxy(Proxy):
    """A stage result group (Drawing, Recognition, Layout)."""

    def __init__(self, obj):
        super().__init__(obj)
        add_stage_properties(obj)


class DrawingProxy(StageProxy):
    ROLE = "Drawing"


class RecognitionProxy(StageProxy):
    ROLE = "Recognition"


class LayoutProxy(StageProxy):
    ROLE = "Layout"


class CutPathProxy(StageProxy):
    """The planned cut path; its shape holds cutting moves, idle moves are
    drawn dashed by its view provider."""

    ROLE = "CutPath"

    def __init__(self, obj):
        super().__init__(obj)
        for name, tip in (("IdleTravel", "idle travel (knife up), mm"),
                          ("CutLength", "cut length, mm"),
                          ("EstimatedTime", "estimated machine time, s")):
            obj.addProperty("App::PropertyFloat", name, "Metrics", tip)
            obj.setEditorMode(name, 1)
        obj.addProperty("App::PropertyInteger", "Lifts", "Metrics", "knife lifts at sharp corners")
        obj.setEditorMode("Lifts", 1)
        obj.addProperty("App::PropertyInteger", "Items", "Metrics", "contours cut, in order")
        obj.setEditorMode("Items", 1)
        obj.addProperty("App::PropertyString", "Method", "Metrics", "planning method used")
        obj.setEditorMode("Method", 1)


class ToolPathsProxy(StageProxy):
    """What the further tools of a multi-tool job do (one shape per tool, in the
    tool's colour), drawn next to the cut path; replaced with it."""

    ROLE = "ToolPaths"


class ShapeProxy(Proxy):
    """A Part::FeaturePython showing one kind of geometry (layer, contour kind,
    container).  The shape is stored in the file; nothing to recompute."""

    ROLE = "Geometry"

    def __init__(self, obj, kind: str):
        super().__init__(obj)
        obj.addProperty("App::PropertyString", "Kind", "LeatherCut", "what the geometry is")
        obj.Kind = kind
        obj.setEditorMode("Kind", 1)


class FlagProxy(Proxy):
    """One recognition flag for a person to decide.

    Over-recognised (``Kind == "over"``): ``Decision`` "Exclude" (default:
    the region is not a part) or "Include".  Under-recognised (``"under"``):
    "Accept" closes the gap with the proposed bridge, "Reject" leaves the chain
    open; "Undecided" means the stage default (over: excluded; under: open
    unless the job closes gaps)."""

    ROLE = "Flag"

    DECISIONS = ["Undecided", "Include", "Exclude", "Accept", "Reject"]

    def __init__(self, obj):
        super().__init__(obj)
        obj.addProperty("App::PropertyString", "FlagId", "Flag", "flag id from recognition")
        obj.addProperty("App::PropertyString", "Kind", "Flag", "over or under")
        obj.addProperty("App::PropertyStringList", "Ids", "Flag", "contour / chain ids concerned")
        obj.addProperty("App::PropertyString", "Reason", "Flag", "why recognition flagged it")
        obj.addProperty("App::PropertyFloat", "Gap", "Flag", "gap to close, mm (under only)")
        obj.addProperty("App::PropertyEnumeration", "Decision", "Flag", "what a person decided")
        obj.Decision = self.DECISIONS
        for p in ("FlagId", "Kind", "Ids", "Reason", "Gap"):
            obj.setEditorMode(p, 1)

    def onChanged(self, obj, prop):
        if prop == "Decision" and getattr(obj, "Proxy", None) is self and not restoring(obj):
            job = job_of(obj)
            if job is not None:
                mark_out_of_date(job, "Recognise", include_self=False)
            from . import style
            style.style_flag(obj)


class PartProxy(Proxy):
    """One recognised part, named from the drawing (AAMA piece and size, block
    name or layer).  ``Include`` and ``Quantity`` are a person's choice: a part
    not included is neither nested nor cut; nesting places ``Quantity`` copies.
    Changing either marks nesting and planning out of date."""

    ROLE = "Part"

    def __init__(self, obj):
        super().__init__(obj)
        obj.addProperty("App::PropertyString", "PartId", "Part", "recognised part id")
        obj.addProperty("App::PropertyString", "PartName", "Part",
                        "name from the drawing (AAMA piece name, block name) or empty")
        obj.addProperty("App::PropertyString", "Size", "Part", "pattern size (graded sets) or empty")
        obj.addProperty("App::PropertyFloat", "Area", "Part", "net area (outline minus holes), mm²")
        obj.addProperty("App::PropertyBool", "Include", "Part", "cut this part")
        obj.addProperty("App::PropertyInteger", "Quantity", "Part",
                        "copies to nest (a drawing cut where it lies cuts each part once)")
        for p in ("PartId", "PartName", "Size", "Area"):
            obj.setEditorMode(p, 1)

    def onChanged(self, obj, prop):
        if prop in ("Include", "Quantity") and getattr(obj, "Proxy", None) is self \
                and not restoring(obj):
            if prop == "Quantity" and obj.Quantity < 1:
                obj.Quantity = 1
                return
            job = job_of(obj)
            if job is not None:
                mark_out_of_date(job, "Recognise", include_self=False)
            if prop == "Include" and FreeCAD.GuiUp and obj.ViewObject is not None:
                obj.ViewObject.Visibility = bool(obj.Include)


class PlacedPartProxy(Proxy):
    """One placed copy of a part.  Its shape is the part in part coordinates
    (mirrored when ``Mirrored``); its ``Placement`` is the nesting placement
    (rotation about Z, translation in mm), so moving or rotating it by hand
    changes the layout.  ``Collides`` is set when it overlaps another part, a
    defect or leaves its container."""

    ROLE = "PlacedPart"

    def __init__(self, obj):
        super().__init__(obj)
        obj.addProperty("App::PropertyString", "PartId", "Placement", "recognised part id")
        obj.addProperty("App::PropertyInteger", "Copy", "Placement", "copy number")
        obj.addProperty("App::PropertyString", "ContainerId", "Placement", "container it lies on")
        obj.addProperty("App::PropertyBool", "Mirrored", "Placement", "mirrored about its Y axis")
        obj.addProperty("App::PropertyBool", "Collides", "Placement",
                        "overlaps another part or a defect, or leaves its container")
        for p in ("PartId", "Copy", "ContainerId", "Mirrored", "Collides"):
            obj.setEditorMode(p, 1)

    def onChanged(self, obj, prop):
        if prop == "Placement" and getattr(obj, "Proxy", None) is self and not restoring(obj):
            job = job_of(obj)
            if job is not None:
                mark_out_of_date(job, "Nest", include_self=False)


# ---------------------------------------------------------------------------
# Stage marking and stored values (navigation helpers live in .tree)
# ---------------------------------------------------------------------------

def mark_out_of_date(job, stage: str, include_self: bool) -> None:
    """Mark the result of ``stage`` (if ``include_self``) and every later stage
    out of date."""
    if stage not in STAGE_ORDER:
        return
    i = STAGE_ORDER.index(stage)
    later = STAGE_ORDER[i if include_self else i + 1:]
    for st in later:
        r = ROLE_OF_STAGE.get(st)
        obj = stage_object(job, r) if r else None
        if obj is not None and "OutOfDate" in obj.PropertiesList and not obj.OutOfDate:
            obj.OutOfDate = True


def store_data(obj, value: Any) -> None:
    obj.Data = codec.dumps(value)


def remove_tree(obj) -> None:
    """Delete ``obj`` and everything in its groups."""
    doc = obj.Document
    names = [o.Name for o in walk(obj)]
    for name in reversed(names):
        if doc.getObject(name) is not None:
            doc.removeObject(name)


# ---------------------------------------------------------------------------
# Creation
# ---------------------------------------------------------------------------

def _view(obj, vp_class: Optional[str]) -> None:
    if FreeCAD.GuiUp and vp_class:
        from . import viewproviders
        getattr(viewproviders, vp_class)(obj.ViewObject)


def make_job(doc, label: str = "Job"):
    """A new, empty job in ``doc`` with options from the preferences."""
    obj = doc.addObject("App::DocumentObjectGroupPython", "Job")
    JobProxy(obj)
    obj.Label = label
    apply_preferences(obj)
    _view(obj, "JobViewProvider")
    return obj


def make_stage_group(job, proxy_cls, name: str, label: str):
    """Replace the job's stage group of this role with a new empty one."""
    old = stage_object(job, proxy_cls.ROLE)
    if old is not None:
        remove_tree(old)
    obj = job.Document.addObject("App::DocumentObjectGroupPython", name)
    proxy_cls(obj)
    obj.Label = label
    job.addObject(obj)
    _view(obj, "StageViewProvider")
    return obj


def make_shape(group, name: str, label: str, kind: str, shape):
    """A Part::FeaturePython holding ``shape`` inside ``group``."""
    obj = group.Document.addObject("Part::FeaturePython", name)
    ShapeProxy(obj, kind)
    obj.Label = label
    obj.Shape = shape
    group.addObject(obj)
    _view(obj, "ShapeViewProvider")
    from . import style
    style.style_kind(obj, kind)
    return obj


def make_flag(group, flag, shape):
    obj = group.Document.addObject("Part::FeaturePython", "Flag")
    FlagProxy(obj)
    obj.FlagId = flag.id
    obj.Kind = flag.kind
    obj.Ids = list(flag.ids)
    obj.Reason = flag.reason
    obj.Gap = float(flag.gap or 0.0)
    if flag.accepted is not None:
        obj.Decision = ("Accept" if flag.accepted else "Reject") if flag.kind == "under" \
            else ("Exclude" if flag.accepted else "Include")
    kind_text = translate("LeatherCut", "over-recognised") if flag.kind == "over" \
        else translate("LeatherCut", "under-recognised")
    obj.Label = f"Flag {flag.id} ({kind_text})"
    obj.Shape = shape
    group.addObject(obj)
    _view(obj, "FlagViewProvider")
    from . import style
    style.style_flag(obj)
    return obj


def make_placed(group, name: str, shape, placement, part_id: str, copy: int,
                container: str, mirrored: bool):
    obj = group.Document.addObject("Part::FeaturePython", name)
    PlacedPartProxy(obj)
    obj.PartId = part_id
    obj.Copy = copy
    obj.ContainerId = container
    obj.Mirrored = mirrored
    obj.Shape = shape
    obj.Placement = placement
    obj.Label = f"{part_id}#{copy}"
    group.addObject(obj)
    _view(obj, "PlacedViewProvider")
    from . import style
    style.style_placed(obj)
    return obj


def make_cut_path(job, name: str = "CutPath"):
    old = stage_object(job, CutPathProxy.ROLE)
    if old is not None:
        remove_tree(old)
    obj = job.Document.addObject("Part::FeaturePython", name)
    CutPathProxy(obj)
    obj.Label = translate("LeatherCut", "Cut path")
    job.addObject(obj)
    _view(obj, "CutPathViewProvider")
    from . import style
    style.style_kind(obj, "cut")
    return obj


def stage_states(job) -> Dict[str, str]:
    """``{"Drawing": "current" | "out of date" | "missing", ...}`` for panels and tests."""
    out = {}
    for st in ("Import", "Recognise", "Nest", "Plan"):
        r = ROLE_OF_STAGE[st]
        o = stage_object(job, r)
        out[r] = "missing" if o is None else ("out of date" if o.OutOfDate else "current")
    return out
