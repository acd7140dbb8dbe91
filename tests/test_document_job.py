"""The LeatherCut job in a FreeCAD document, headless (FreeCAD as a library).

A generated drawing (tests/gui/sample.py) with a pinwheel (over-recognised
gap), an outline open by 0.3 mm (under-recognised), a plate with a hole and a
lead-in and a stray line goes through every stage; the job is saved,
reopened and undone.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

FreeCAD = pytest.importorskip("FreeCAD") if os.environ.get("CI") != "true" else __import__("FreeCAD")

from LeatherCutWorkbench.core import model  # noqa: E402
from LeatherCutWorkbench.core.geometry import ArcSeg, CurveSeg, LineSeg  # noqa: E402
from LeatherCutWorkbench.document import codec, objects, pipeline  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui.sample import write_sample  # noqa: E402


@pytest.fixture
def sample(tmp_path):
    return write_sample(str(tmp_path / "sample.dxf"))


@pytest.fixture
def doc():
    d = FreeCAD.newDocument("LCTest")
    d.UndoMode = 1
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def _recognised(doc, sample):
    job = pipeline.make_job(doc, "Job", sample)
    pipeline.run_stage(job, "Import")
    pipeline.run_stage(job, "Recognise")
    return job


def _flag(job, kind):
    return [f for f in pipeline.flag_objects(job) if f.Kind == kind][0]


def test_import_groups_edges_by_layer(doc, sample):
    job = pipeline.make_job(doc, "Job", sample)
    drawing_obj = pipeline.run_stage(job, "Import")
    labels = sorted(o.Label for o in drawing_obj.Group)
    assert labels == ["Layer LEADIN", "Layer PARTS", "Layer STRAY"]
    drawing = objects.load_data(drawing_obj)
    assert isinstance(drawing, model.Drawing) and drawing.units == "mm"
    # every imported edge is shown on its layer's object, none lost or doubled
    for o in drawing_obj.Group:
        layer = o.Label.split(" ", 1)[1]
        assert len(o.Shape.Edges) == sum(1 for e in drawing.edges if e.src.layer == layer)
    parts_layer = [o for o in drawing_obj.Group if o.Label == "Layer PARTS"][0]
    # 5 rectangles of 4 sides, the plate (4 sides, one split by the lead-in) and the hole
    assert len(parts_layer.Shape.Edges) >= 5 * 4 + 4 + 1
    assert any(e.Curve.TypeId == "Part::GeomCircle" for e in parts_layer.Shape.Edges)


def test_recognition_objects_by_kind_and_flags(doc, sample):
    job = _recognised(doc, sample)
    rec_obj = objects.stage_object(job, "Recognition")
    kinds = {o.Kind: o for o in rec_obj.Group if objects.role(o) == "Geometry"}
    assert len(kinds["outer"].Shape.Wires) == 5          # pinwheel x4 + plate
    assert len(kinds["hole"].Shape.Wires) == 1
    assert len(kinds["lead_in"].Shape.Edges) == 1
    assert len(kinds["open"].Shape.Edges) >= 2           # open outline + stray line
    assert len(kinds["excluded"].Shape.Edges) == 4       # the scrap square, excluded by default
    flags = {f.Kind: f for f in pipeline.flag_objects(job)}
    assert flags["over"].Decision == "Undecided"
    rec = objects.load_data(rec_obj)
    scrap = [p for p in rec.parts if p.outer.id in flags["over"].Ids or p.id in flags["over"].Ids]
    assert len(scrap) == 1 and scrap[0].excluded
    assert abs(scrap[0].outer.area) == pytest.approx(20 * 20, rel=1e-6)
    assert flags["under"].Gap == pytest.approx(0.3, abs=1e-6)
    # the under flag shows the chain plus its bridge
    assert len(flags["under"].Shape.Edges) == 5


def test_decisions_change_the_parts_to_cut(doc, sample):
    job = _recognised(doc, sample)
    before = pipeline.effective_recognition(job)
    assert len(before.active_parts()) == 5
    pipeline.set_flag_decision(_flag(job, "under"), "Accept")
    pipeline.set_flag_decision(_flag(job, "over"), "Include")
    after = pipeline.effective_recognition(job)
    active = after.active_parts()
    assert len(active) == 7
    under = _flag(job, "under")
    fixed = [f for f in after.flags if f.id == under.FlagId][0]
    assert fixed.accepted is True                 # the core applied exactly this fix
    closed = [p for p in active if p.outer.id in fixed.ids][0]
    assert closed.outer.area == pytest.approx(40 * 30, rel=1e-6)   # CCW, closed by the bridge
    assert len(after.open_chains) == len(before.open_chains) - 1
    # the stored recognition keeps the proposal; rejecting restores it
    pipeline.set_flag_decision(under, "Reject")
    rejected = pipeline.effective_recognition(job)
    assert len(rejected.open_chains) == len(before.open_chains)
    assert [f for f in rejected.flags if f.id == under.FlagId][0].accepted is False
    scrap_ids = set(_flag(job, "over").Ids)
    assert [p for p in active if p.outer.id in scrap_ids or p.id in scrap_ids][0].excluded is False


def _write_fixes_sample(path):
    """A plate with a lead-in stopping 0.3 mm short (join), a square whose bottom
    line runs 0.3 mm past its corner (trim) and a square open by 0.2 mm (close)."""
    import ezdxf
    d = ezdxf.new("R2010")
    d.header["$INSUNITS"] = 4
    msp = d.modelspace()
    msp.add_lwpolyline([(0, 0), (20, 0), (20, 10), (0, 10)], close=True)
    msp.add_line((5, -4), (5, -0.3))
    msp.add_line((50, 0), (70.3, 0))
    msp.add_lwpolyline([(70, 0), (70, 20), (50, 20), (50, 0)], close=False)
    msp.add_lwpolyline([(100, 0.2), (100, 20), (120, 20), (120, 0), (100, 0)], close=False)
    d.saveas(path)
    return path


def test_accepting_join_and_trim_flags(doc, tmp_path):
    job = _recognised(doc, _write_fixes_sample(str(tmp_path / "fixes.dxf")))
    stored = objects.load_data(objects.stage_object(job, "Recognition"))
    action = {f.id: f.action for f in stored.flags}
    by_action = {action[f.FlagId]: f for f in pipeline.flag_objects(job) if f.Kind == "under"}
    assert sorted(by_action) == ["close", "join", "trim"]
    before = pipeline.effective_recognition(job)
    plate = [p for p in before.parts if p.outer.bbox[0] == pytest.approx(0.0)][0]
    assert not plate.lead_ins
    n_open = len(before.open_chains)
    doc.openTransaction("join")
    pipeline.set_flag_decision(by_action["join"], "Accept")
    doc.commitTransaction()
    joined = pipeline.effective_recognition(job)
    plate = [p for p in joined.parts if p.outer.bbox[0] == pytest.approx(0.0)][0]
    (li,) = plate.lead_ins
    assert li.start == pytest.approx((5.0, -4.0)) and li.end == pytest.approx((5.0, 0.0))
    assert len(joined.open_chains) == n_open - 1
    doc.openTransaction("trim")
    pipeline.set_flag_decision(by_action["trim"], "Accept")
    doc.commitTransaction()
    both = pipeline.effective_recognition(job)
    assert len(both.open_chains) == n_open - 2
    assert all(abs(c.length - 0.3) > 1e-6 for c in both.open_chains)
    state = {f.action: f.accepted for f in both.flags if f.kind == "under"}
    assert state == {"join": True, "trim": True, "close": None}
    assert len([p for p in both.parts if p.outer.bbox[0] == pytest.approx(0.0)][0].lead_ins) == 1
    # each decision is one undo step
    doc.undo()
    assert by_action["trim"].Decision == "Undecided"
    assert len(pipeline.effective_recognition(job).open_chains) == n_open - 1
    doc.undo()
    assert by_action["join"].Decision == "Undecided"
    assert len(pipeline.effective_recognition(job).open_chains) == n_open


def test_stage_options_are_properties(doc, sample):
    job = pipeline.make_job(doc, "Job", sample)
    assert job.RecogniseJoinTol == pytest.approx(0.01)
    job.RecogniseGapTol = 0.2
    job.NestRotationsOverride = "[0, 180]"
    opts = pipeline.stage_options(job, "Recognise")
    assert opts.gap_tol == pytest.approx(0.2)
    nest = pipeline.stage_options(job, "Nest")
    assert nest.rotations_override == [0, 180]
    assert nest.container is None                        # NestContainer "none"
    job.NestContainer = "sheet"
    job.NestSheetWidth, job.NestSheetHeight = 300.0, 200.0
    spec = pipeline.stage_options(job, "Nest").container
    assert (spec.kind, spec.width, spec.height) == ("sheet", 300.0, 200.0)
    job.NestRotationsOverride = "[0, 18"
    with pytest.raises(Exception, match="NestRotationsOverride"):
        pipeline.stage_options(job, "Nest")


def test_earlier_change_marks_later_stages_out_of_date(doc, sample):
    job = _recognised(doc, sample)
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    pipeline.run_stage(job, "Plan")
    assert objects.stage_states(job) == {"Drawing": "current", "Recognition": "current",
                                         "Layout": "missing", "CutPath": "current"}
    pipeline.set_flag_decision(_flag(job, "over"), "Include")
    assert objects.stage_states(job)["CutPath"] == "out of date"
    assert objects.stage_states(job)["Recognition"] == "current"
    pipeline.run_stage(job, "Plan")
    job.RecogniseJoinTol = 0.02
    assert objects.stage_states(job)["Recognition"] == "out of date"
    assert objects.stage_states(job)["CutPath"] == "out of date"
    assert objects.stage_states(job)["Drawing"] == "current"
    pipeline.run_stage(job, "Recognise")
    assert objects.stage_states(job)["Recognition"] == "current"
    # a decision survives re-recognition
    assert _flag(job, "over").Decision == "Include"
    pipeline.run_stage(job, "Plan")
    job.PostMachine = "linuxcnc_tangential"     # plan speeds come from the machine
    assert objects.stage_states(job)["CutPath"] == "out of date"
    assert objects.stage_states(job)["Recognition"] == "current"
    other = sample.replace("sample.dxf", "other.dxf")
    shutil.copy(sample, other)
    job.SourceFile = other
    assert set(objects.stage_states(job).values()) == {"out of date", "missing"}


def test_move_to_origin_without_nesting(doc, sample):
    """PlanMoveToOrigin moves the whole drawing (parts and open chains together)
    so its lower-left corner lies PlanOriginOffset from machine zero; the cut
    path is the same path, shifted, and changing the option marks it stale."""
    job = _recognised(doc, sample)
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    parts0, chains0 = pipeline.parts_to_cut(job)
    job.PlanMoveToOrigin, job.PlanOriginOffset = True, 5.0
    parts1, chains1 = pipeline.parts_to_cut(job)
    pts0 = [p for part in parts0 for p in part.outer.points(0.1)] + \
        [p for ch in chains0 for sg in ch.segments for p in sg.points(0.1)]
    pts1 = [p for part in parts1 for p in part.outer.points(0.1)] + \
        [p for ch in chains1 for sg in ch.segments for p in sg.points(0.1)]
    assert min(p[0] for p in pts0) != pytest.approx(5.0)
    assert min(p[0] for p in pts1) == pytest.approx(5.0)
    assert min(p[1] for p in pts1) == pytest.approx(5.0)
    dx = pts1[0][0] - pts0[0][0]
    dy = pts1[0][1] - pts0[0][1]
    for a, b in zip(pts0, pts1):
        assert b[0] - a[0] == pytest.approx(dx) and b[1] - a[1] == pytest.approx(dy)
    pipeline.run_stage(job, "Plan")
    plan = objects.load_data(objects.stage_object(job, "CutPath"))
    xs = [p[0] for it in plan.items for sg in it.segments for p in sg.points(0.1)]
    assert min(xs) >= 5.0 - 1e-6
    assert objects.stage_states(job)["CutPath"] == "current"
    job.PlanOriginOffset = 20.0
    assert objects.stage_states(job)["CutPath"] == "out of date"


def _full_job(doc, sample, out_dir):
    job = _recognised(doc, sample)
    pipeline.set_flag_decision(_flag(job, "under"), "Accept")
    job.NestContainer = "sheet"
    job.NestSheetWidth, job.NestSheetHeight = 400.0, 300.0
    job.NestMargin, job.NestSpacing = 2.0, 2.0
    job.NestTimeBudget, job.NestWorkers = 0.5, "1"
    pipeline.run_stage(job, "Nest")
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    pipeline.run_stage(job, "Plan")
    job.PostOutputFile = os.path.join(out_dir, "job.nc")
    pipeline.run_stage(job, "Post")
    return job


def test_whole_job_save_and_reopen(doc, sample, tmp_path):
    job = _full_job(doc, sample, str(tmp_path))
    placed = pipeline.placed_objects(job)
    assert len(placed) == 6 and not any(o.Collides for o in placed)
    text = open(job.PostLastOutput).read()
    assert "G21" in text and text.count("G1") > 20
    cut = objects.stage_object(job, "CutPath")
    items, idle = cut.Items, cut.IdleTravel
    assert items == 6 + 1 + 0        # 6 outers + 1 hole; no open chains after nesting
    assert idle > 0
    path = str(tmp_path / "job.FCStd")
    doc.saveAs(path)
    name = doc.Name
    FreeCAD.closeDocument(name)
    d2 = FreeCAD.openDocument(path)
    try:
        job2 = objects.jobs(d2)[0]
        assert type(job2.Proxy).__name__ == "JobProxy"
        assert job2.NestContainer == "sheet" and job2.NestMargin == 2.0
        assert job2.PlanMethod == "nn" and job2.SourceFile == sample
        assert objects.stage_states(job2) == {"Drawing": "current", "Recognition": "current",
                                              "Layout": "current", "CutPath": "current"}
        assert _flag(job2, "under").Decision == "Accept"
        plan = pipeline.stored_plan(job2)
        assert len(plan.items) == items
        assert objects.stage_object(job2, "CutPath").IdleTravel == pytest.approx(idle)
        assert len(pipeline.placed_objects(job2)) == 6
        # reopened objects keep working: re-plan and re-post
        pipeline.run_stage(job2, "Plan")
        assert pipeline.run_stage(job2, "Post") == job2.PostOutputFile
    finally:
        FreeCAD.closeDocument(d2.Name)


def test_manual_move_collision_and_layout(doc, sample, tmp_path):
    job = _full_job(doc, sample, str(tmp_path))
    a, b = pipeline.placed_objects(job)[:2]
    assert not pipeline.update_collisions(job)
    shift = b.Shape.BoundBox.Center - a.Shape.BoundBox.Center
    shift.z = 0
    a.Placement = FreeCAD.Placement(a.Placement.Base + shift, a.Placement.Rotation)
    problems = pipeline.update_collisions(job)
    assert problems and a.Collides and b.Collides
    assert objects.stage_states(job)["CutPath"] == "out of date"
    layout = pipeline.current_layout(job)
    pa = [p for p in layout.placements if (p.part_id, p.copy) == (a.PartId, a.Copy)][0]
    assert (pa.x, pa.y) == pytest.approx((a.Placement.Base.x, a.Placement.Base.y))
    a.Placement = FreeCAD.Placement(FreeCAD.Vector(1000, 1000, 0), FreeCAD.Rotation())
    problems = pipeline.update_collisions(job)
    assert a.Collides and not b.Collides      # now it is off the sheet
    assert any("outside" in p for p in problems)


def test_undo_redo_of_a_decision_and_a_stage(doc, sample):
    job = _recognised(doc, sample)
    flag = _flag(job, "over")
    doc.openTransaction("decide")
    pipeline.set_flag_decision(flag, "Include")
    doc.commitTransaction()
    doc.openTransaction("plan")
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    pipeline.run_stage(job, "Plan")
    doc.commitTransaction()
    assert objects.stage_object(job, "CutPath") is not None
    doc.undo()
    assert objects.stage_object(job, "CutPath") is None
    assert job.PlanMethod == "ga"
    doc.undo()
    assert flag.Decision == "Undecided"
    doc.redo()
    assert flag.Decision == "Include"


def test_both_pickling_protocols():
    for cls in (objects.JobProxy, objects.DrawingProxy, objects.FlagProxy, objects.CutPathProxy):
        p = cls.__new__(cls)
        p.__setstate__({"Role": cls.ROLE})
        assert p.__getstate__() == {"Role": cls.ROLE} == p.dumps()
        q = cls.__new__(cls)
        q.loads(p.dumps())
        assert q.Role == cls.ROLE


def test_codec_round_trip_keeps_types():
    part = model.Part("P1", model.Contour("C1", [LineSeg((0, 0), (1, 0)),
                                                 ArcSeg((1, 1), 1.0, -90.0, 180.0),
                                                 CurveSeg(((1, 2), (0.5, 2.5), (0, 0)), "spline")]),
                      rotations=[0.0, 180.0])
    plan = model.CutPlan(items=[model.CutItem("C1", "P1", "outer", (0.0, 0.0), part.outer.segments)],
                         metrics={"idle_mm": 1.5, "nested": {"a": [1, 2]}})
    for value in (part, plan, model.Recognition(parts=[part])):
        back = codec.loads(codec.dumps(value))
        assert back == value
    assert isinstance(codec.loads(codec.dumps(part)).outer.segments[2].pts, tuple)
    with pytest.raises(ValueError):
        codec._dec({"@": "os.system"})


def test_importer_hook_open_and_insert(sample):
    from LeatherCutWorkbench.document import importer
    d = importer.open(sample)
    try:
        job = objects.jobs(d)[0]
        assert objects.stage_states(job)["Drawing"] == "current"
        importer.insert(sample, d.Name)
        assert len(objects.jobs(d)) == 2
    finally:
        FreeCAD.closeDocument(d.Name)


@pytest.mark.freecadcmd
def test_freecadcmd_registers_importer_and_finds_venv_packages(tmp_path):
    """Init.py inside the real freecadcmd: importer registered, ezdxf 1.x and
    shapely 2.x from the venv, FreeCAD's numpy untouched."""
    if shutil.which("freecadcmd") is None:
        if os.environ.get("CI") == "true":
            pytest.fail("freecadcmd missing")
        pytest.skip("freecadcmd missing")
    from gui.freecad_gui import make_home
    home = make_home()
    code = ("import sys, FreeCAD, ezdxf, shapely, numpy; "
            "ok = 'LeatherCutWorkbench.document.importer' in FreeCAD.getImportType('dxf') "
            "and ezdxf.__version__.startswith('1.') and shapely.__version__.startswith('2.') "
            "and numpy.__file__.startswith('/usr/lib/python3/dist-packages'); "
            "print('LC', ezdxf.__version__, shapely.__version__, numpy.__file__); sys.exit(0 if ok else 1)")
    env = dict(os.environ, HOME=home)
    try:
        proc = subprocess.run(["freecadcmd", "-c", code], env=env, capture_output=True, text=True, timeout=60)
    finally:
        shutil.rmtree(home, ignore_errors=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "LC 1." in proc.stdout


@pytest.mark.timeout(120)
def test_nest_worker_processes_with_freecad_gui_stdin(doc, sample, monkeypatch, tmp_path):
    """FreeCAD's GUI replaces sys.stdin by an object without close(); forked
    nesting workers must still start (they close stdin first)."""

    class GuiStdin:
        def read(self, *args):
            return ""

    gui_stdin = GuiStdin()
    monkeypatch.setattr(sys, "stdin", gui_stdin)
    job = _recognised(doc, sample)
    job.NestContainer = "sheet"
    job.NestSheetWidth, job.NestSheetHeight = 400.0, 300.0
    job.NestMargin, job.NestSpacing = 2.0, 2.0
    job.NestTimeBudget, job.NestWorkers = 0.5, "2"
    pipeline.run_stage(job, "Nest")
    layout = objects.load_data(objects.stage_object(job, "Layout"))
    assert layout.metrics.get("workers") == 2
    assert len(pipeline.placed_objects(job)) == 5
    # Run job nests through core.job.run_job: the same protection applies
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    job.PostOutputFile = str(tmp_path / "run.nc")
    assert pipeline.run_all(job) == job.PostOutputFile
    layout = objects.load_data(objects.stage_object(job, "Layout"))
    assert layout.metrics.get("workers") == 2
    assert sys.stdin is gui_stdin


def test_post_formats_from_the_job(doc, sample, tmp_path):
    """The job writes every format its PostFormat offers: HPGL for the plotter
    profile, DXF of the cut job (readable by ezdxf), G-code for the knife."""
    import ezdxf
    job = _full_job(doc, sample, str(tmp_path))
    job.PostMachine, job.PostFormat = "hpgl_plotter", "hpgl"
    job.PostOutputFile = str(tmp_path / "job.plt")
    pipeline.run_stage(job, "Plan")
    text = open(pipeline.run_stage(job, "Post")).read()
    assert text.startswith("IN") and "PD" in text and "PU" in text
    job.PostFormat = "dxf"
    job.PostOutputFile = str(tmp_path / "job_cut.dxf")
    path = pipeline.run_stage(job, "Post")
    layers = {e.dxf.layer for e in ezdxf.readfile(path).modelspace()}
    assert len(layers) >= 2
    assert job.PostLastOutput == path


def test_hide_nesting_from_the_job_properties(doc, sample, tmp_path):
    """NestContainer "hide" reads NestHideFile (HIDE outline, DEFECT regions):
    every part lands on the hide and off the defect; the container and the
    defect are shown."""
    import ezdxf
    from shapely.geometry import Polygon
    hide = ezdxf.new("R2010")
    hide.header["$INSUNITS"] = 4
    msp = hide.modelspace()
    msp.add_lwpolyline([(0, 0), (260, -10), (300, 120), (200, 210), (20, 190), (-20, 90)], close=True,
                       dxfattribs={"layer": "HIDE"})
    msp.add_circle((140, 100), 25, dxfattribs={"layer": "DEFECT"})
    hide_path = str(tmp_path / "hide.dxf")
    hide.saveas(hide_path)
    job = _recognised(doc, sample)
    job.NestContainer, job.NestHideFile = "hide", hide_path
    job.NestMargin, job.NestSpacing, job.NestTimeBudget, job.NestWorkers = 2.0, 2.0, 0.5, "1"
    pipeline.run_stage(job, "Nest")
    layout = pipeline.current_layout(job)
    assert [c.kind for c in layout.containers] == ["hide"] and layout.containers[0].defects
    assert len(layout.placements) == 5 and not layout.unplaced
    assert not pipeline.update_collisions(job)
    kinds = sorted(o.Kind for o in objects.stage_object(job, "Layout").Group if objects.role(o) == "Geometry")
    assert kinds == ["container", "defect"]
    defect = Polygon(layout.containers[0].defects[0])
    for o in pipeline.placed_objects(job):
        bb = o.Shape.BoundBox
        assert not Polygon([(bb.XMin, bb.YMin), (bb.XMax, bb.YMin), (bb.XMax, bb.YMax),
                            (bb.XMin, bb.YMax)]).buffer(-0.5).contains(defect.centroid)
