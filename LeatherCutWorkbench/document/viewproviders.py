"""View providers of LeatherCut objects (GUI only: imported when FreeCAD.GuiUp).

The cut path view draws, on top of its shape (the cutting moves, solid blue),
the idle moves dashed green, the entry points as black dots, the cut order
numbers next to each entry and the knife marker used by *Simulate*.
Proxies restore by module and class name: never rename these classes.
"""

from __future__ import annotations

import os
from typing import List, Optional, Sequence, Tuple

import FreeCADGui as Gui

from . import style, tree

ICON_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                        "resources", "icons")


def icon(name: str) -> str:
    return os.path.join(ICON_DIR, name + ".svg")


class ViewProvider:
    """Common view provider: icon per role, both pickling protocols."""

    ICON = "LeatherCut"

    def __init__(self, vobj):
        vobj.Proxy = self
        self.Object = vobj.Object

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        obj = getattr(self, "Object", None)
        if obj is not None and getattr(obj, "OutOfDate", False):
            return icon("OutOfDate")
        return icon(self.ICON)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None

    def updateData(self, obj, prop):
        if prop == "OutOfDate":
            vo = obj.ViewObject
            if vo is not None and hasattr(vo, "signalChangeIcon"):
                vo.signalChangeIcon()  # re-reads getIcon (out-of-date icon)

    def onChanged(self, vobj, prop):
        pass


class JobViewProvider(ViewProvider):
    ICON = "Job"


def _open_stage_panel(vobj, command: str) -> bool:
    """Double-click on a stage object: select its job and open the stage's panel."""
    job = tree.job_of(vobj.Object)
    if job is None or Gui.Control.activeDialog():
        return False
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(job)
    Gui.runCommand(command)
    return True


class StageViewProvider(ViewProvider):
    ICONS = {"Drawing": "ImportDXF", "Recognition": "Recognise", "Layout": "AutoNest"}
    #: double-click re-opens the panel of the stage that made the object
    COMMANDS = {"Recognition": "LeatherCut_Recognise", "Layout": "LeatherCut_AutoNest"}

    def doubleClicked(self, vobj):
        command = self.COMMANDS.get(tree.role(vobj.Object))
        return _open_stage_panel(vobj, command) if command else False

    def getIcon(self):
        obj = getattr(self, "Object", None)
        if obj is not None and getattr(obj, "OutOfDate", False):
            return icon("OutOfDate")
        return icon(self.ICONS.get(tree.role(obj), "LeatherCut"))


class ShapeViewProvider(ViewProvider):
    ICON = "Contour"


class FlagViewProvider(ViewProvider):
    def getIcon(self):
        obj = getattr(self, "Object", None)
        return icon("FlagOver" if getattr(obj, "Kind", "") == "over" else "FlagUnder")

    def doubleClicked(self, vobj):
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(vobj.Object)
        Gui.runCommand("LeatherCut_FlagOver" if vobj.Object.Kind == "over" else "LeatherCut_FlagUnder")
        return True


class PartViewProvider(ViewProvider):
    """A recognised part: double-click opens the Recognise panel's parts list."""

    ICON = "Contour"

    def doubleClicked(self, vobj):
        return _open_stage_panel(vobj, "LeatherCut_Recognise")


class PlacedViewProvider(ViewProvider):
    ICON = "ManualNest"

    def updateData(self, obj, prop):
        if prop == "Collides":
            style.style_placed(obj)

    def doubleClicked(self, vobj):
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(vobj.Object)
        Gui.runCommand("LeatherCut_ManualNest")
        return True


class CutPathViewProvider(ViewProvider):
    """Cutting moves (the shape) plus idle moves, entry points, order numbers
    and the simulation knife, drawn with Coin nodes."""

    ICON = "PlanPath"

    def doubleClicked(self, vobj):
        return _open_stage_panel(vobj, "LeatherCut_PlanPath")

    def __init__(self, vobj):
        super().__init__(vobj)
        self._add_properties(vobj)

    def _add_properties(self, vobj):
        for name, tip in (("ShowIdleMoves", "draw idle moves (knife up) dashed"),
                          ("ShowEntryPoints", "draw entry points"),
                          ("ShowOrderNumbers", "draw the cut order number at each entry")):
            if name not in vobj.PropertiesList:
                vobj.addProperty("App::PropertyBool", name, "LeatherCut", tip)
                setattr(vobj, name, True)

    def attach(self, vobj):
        from pivy import coin
        self.Object = vobj.Object
        self.overlay = coin.SoSeparator()
        self.knife = coin.SoSwitch()
        self.knife.whichChild = coin.SO_SWITCH_NONE
        knife_sep = coin.SoSeparator()
        self.knife_pos = coin.SoTranslation()
        mat = coin.SoBaseColor()
        mat.rgb = (0.9, 0.1, 0.1)
        self.knife_rot = coin.SoRotationXYZ()
        self.knife_rot.axis = coin.SoRotationXYZ.Z
        cone = coin.SoCone()
        self.knife_cone = cone
        upright = coin.SoRotationXYZ()
        upright.axis = coin.SoRotationXYZ.X
        upright.angle = -1.5707963
        knife_sep.addChild(self.knife_pos)
        knife_sep.addChild(mat)
        knife_sep.addChild(upright)
        knife_sep.addChild(cone)
        self.knife.addChild(knife_sep)
        vobj.RootNode.addChild(self.overlay)
        vobj.RootNode.addChild(self.knife)
        self._rebuild()

    def updateData(self, obj, prop):
        if prop in ("Data", "Shape"):
            self._rebuild()
        super().updateData(obj, prop)

    def onChanged(self, vobj, prop):
        if prop in ("ShowIdleMoves", "ShowEntryPoints", "ShowOrderNumbers", "Visibility"):
            self._rebuild()

    # -- simulation ---------------------------------------------------------------
    def show_knife(self, pos: Optional[Tuple[float, float]], size: float = 5.0) -> None:
        """Put the knife marker at ``pos`` (mm) or hide it (None)."""
        from pivy import coin
        if not hasattr(self, "knife"):
            return
        if pos is None:
            self.knife.whichChild = coin.SO_SWITCH_NONE
            return
        self.knife_cone.bottomRadius = size * 0.4
        self.knife_cone.height = size
        self.knife_pos.translation.setValue(pos[0], pos[1], size * 0.5)
        self.knife.whichChild = coin.SO_SWITCH_ALL

    # -- drawing ------------------------------------------------------------------
    def _rebuild(self) -> None:
        if not hasattr(self, "overlay"):
            return
        self.overlay.removeAllChildren()
        obj = self.Object
        vobj = obj.ViewObject
        if vobj is None or not vobj.Visibility:
            return
        plan = tree.load_data(obj)
        if plan is None:
            return
        size = _label_size(plan)
        # holes red, open chains grey, lead-ins orange over the blue cutting moves
        for kind, style_kind in (("hole", "hole"), ("open", "open")):
            moves = _polyline_moves([it.segments for it in plan.items if it.kind == kind])
            if moves:
                self.overlay.addChild(_lines(moves, style.colour(style_kind), 0xFFFF, 2.0))
        leads = _polyline_moves([it.segments[:it.lead_in_count] for it in plan.items if it.lead_in_count]
                                + [it.segments[len(it.segments) - it.lead_out_count:]
                                   for it in plan.items if it.lead_out_count])
        if leads:
            self.overlay.addChild(_lines(leads, style.colour("lead_in"), 0xFFFF, 3.0))
        tabs = _tab_moves(obj, plan)
        if tabs:
            self.overlay.addChild(_lines(tabs, (0.0, 0.0, 0.0), 0xFFFF, 6.0))
        if getattr(vobj, "ShowIdleMoves", True):
            self.overlay.addChild(_lines(plan.idle_moves(), style.colour("idle"), 0x0F0F, 1.5))
        if getattr(vobj, "ShowEntryPoints", True):
            entries = [it.start for it in plan.items]
            self.overlay.addChild(_points(entries, style.colour("entry"), 7.0))
        if getattr(vobj, "ShowOrderNumbers", True):
            labels = [(str(i + 1), it.start) for i, it in enumerate(plan.items)]
            self.overlay.addChild(_labels(labels, (0.0, 0.0, 0.0), size))


def _tab_moves(obj, plan) -> List[Tuple[Tuple[float, float], Tuple[float, float]]]:
    """Tabs of the job's machine profile (post/tabs.py) as short thick bars
    over the path; none when the profile has no tabs or cannot be read."""
    job = tree.job_of(obj)
    try:
        from ..post.profiles import load_profile
        from ..post.tabs import plan_tabs, point_along
        prof = load_profile(job.PostMachine) if job is not None and job.PostMachine else None
    except Exception:  # no post package or an unreadable profile: nothing to show
        return []
    if prof is None:
        return []
    return [(point_along(plan.items[i].segments, a), point_along(plan.items[i].segments, b))
            for i, spans in plan_tabs(plan, prof).items() for a, b in spans]


def _polyline_moves(paths) -> List[Tuple[Tuple[float, float], Tuple[float, float]]]:
    """Chord pairs of flattened paths (for Coin line sets)."""
    from ..core.geometry import path_points
    out = []
    for segs in paths:
        pts = path_points(segs, 0.05)
        out.extend(zip(pts, pts[1:]))
    return out


def _label_size(plan) -> float:
    xs = [it.start[0] for it in plan.items] or [0.0]
    ys = [it.start[1] for it in plan.items] or [0.0]
    return max(max(xs) - min(xs), max(ys) - min(ys), 10.0) / 150.0


def _lines(moves: Sequence[Tuple[Tuple[float, float], Tuple[float, float]]], rgb, pattern: int,
           width: float):
    from pivy import coin
    sep = coin.SoSeparator()
    ds = coin.SoDrawStyle()
    ds.linePattern = pattern
    ds.lineWidth = width
    col = coin.SoBaseColor()
    col.rgb = rgb
    coords = coin.SoCoordinate3()
    pts: List[Tuple[float, float, float]] = []
    for a, b in moves:
        pts.append((a[0], a[1], 0.05))
        pts.append((b[0], b[1], 0.05))
    coords.point.setValues(0, len(pts), pts)
    ls = coin.SoLineSet()
    ls.numVertices.setValues(0, len(moves), [2] * len(moves))
    for n in (ds, col, coords, ls):
        sep.addChild(n)
    return sep


def _points(points, rgb, size: float):
    from pivy import coin
    sep = coin.SoSeparator()
    ds = coin.SoDrawStyle()
    ds.pointSize = size
    col = coin.SoBaseColor()
    col.rgb = rgb
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(points), [(p[0], p[1], 0.1) for p in points])
    ps = coin.SoPointSet()
    for n in (ds, col, coords, ps):
        sep.addChild(n)
    return sep


def _labels(labels, rgb, offset: float):
    from pivy import coin
    sep = coin.SoSeparator()
    col = coin.SoBaseColor()
    col.rgb = rgb
    font = coin.SoFont()
    font.size = 12
    sep.addChild(col)
    sep.addChild(font)
    for text, p in labels:
        s = coin.SoSeparator()
        t = coin.SoTranslation()
        t.translation.setValue(p[0] + offset, p[1] + offset, 0.2)
        txt = coin.SoText2()
        txt.string = text
        s.addChild(t)
        s.addChild(txt)
        sep.addChild(s)
    return sep
