"""The workbench side of issue 13's knife jobs, headless (FreeCAD as a library):
a multi-tool leather job (knife + punch + pen, AAMA pattern nested on a hide,
tool map changed in the job's PostToolMap) and a drag-knife HP-GL job, both
through the document pipeline that *Run job* / *Post-process* use."""

from __future__ import annotations

import os

import pytest

FreeCAD = pytest.importorskip("FreeCAD") if os.environ.get("CI") != "true" else __import__("FreeCAD")

from LeatherCutWorkbench.core.errors import InputError  # noqa: E402
from LeatherCutWorkbench.document import pipeline  # noqa: E402
from LeatherCutWorkbench.post import hpgl  # noqa: E402
from LeatherCutWorkbench.post.profiles import load_profile  # noqa: E402

from conftest import SAMPLES_DIR  # noqa: E402
from drag_sim import drawn_lines, simulate, split_deviation, swivel_corners  # noqa: E402
from test_post_multitool import MACHINE, hide_dxf, one_size, trace  # noqa: E402


def test_multitool_leather_job_from_the_workbench(doc, tmp_path):
    job = pipeline.make_job(doc, "Job", one_size(tmp_path))
    job.NestContainer, job.NestHideFile = "hide", hide_dxf(tmp_path)
    job.NestTimeBudget, job.NestWorkers = 0.0, "1"
    job.PlanMethod = "nn"
    job.PostMachine, job.PostFormat = MACHINE, "gcode"
    job.PostToolMap = "stitch=crease"
    job.PostOutputFile = str(tmp_path / "job.nc")
    assert pipeline.run_all(job) == job.PostOutputFile
    text = open(job.PostOutputFile).read()
    parts = pipeline.parts_to_cut(job)[0]
    drills = [m.position for p in parts for m in p.marks if m.kind == "drill"]
    events = trace(text, load_profile(MACHINE))
    strikes = [(x + 60.0, y) for t, e, x, y, _ in events if e == "strike"]
    assert len(strikes) == len(drills) == 2
    assert all(min(abs(s[0] - d[0]) + abs(s[1] - d[1]) for s in strikes) < 1e-3 for d in drills)
    assert [ln for ln in text.splitlines() if ln.endswith("M6")] == ["T3 M6", "T2 M6", "T1 M6"]
    # Plan path shows each further tool as its own shape (colour in the GUI)
    from LeatherCutWorkbench.document import objects
    group = objects.stage_object(job, "ToolPaths")
    shown = {o.Label: o.Shape for o in group.Group}
    assert set(shown) == {"Tool pen", "Tool punch4"}
    assert len(shown["Tool punch4"].Vertexes) == 2
    assert len(shown["Tool pen"].Edges) >= sum(len(p.lines) for p in parts)
    # a role mapped to a tool the machine lacks: refused, nothing new written
    os.remove(job.PostOutputFile)
    job.PostToolMap = "drill=laser"
    with pytest.raises(InputError, match="PostToolMap.*laser"):
        pipeline.run_stage(job, "Post")
    assert not os.path.exists(job.PostOutputFile)


def test_drag_knife_hpgl_job_from_the_workbench(doc, tmp_path):
    job = pipeline.make_job(doc, "Job", os.path.join(SAMPLES_DIR, "deepnest_ReadMeExampleSmall.dxf"))
    job.PlanMethod = "nn"
    job.PlanMoveToOrigin, job.PlanOriginOffset = True, 10.0
    job.PostMachine, job.PostFormat = "hpgl_drag_knife", "hpgl"
    job.PostOutputFile = str(tmp_path / "job.plt")
    # Run job honours PlanMoveToOrigin like Plan path (it did not: the drawing
    # was cut where it lies, off the table, and marks and plan disagreed)
    assert pipeline.run_all(job) == job.PostOutputFile
    plan = pipeline.stored_plan(job)
    strokes = hpgl.read_hpgl(open(job.PostOutputFile).read(), 40)
    away, at_swivel = split_deviation(simulate(strokes, 0.25), drawn_lines(plan),
                                      swivel_corners(plan, 10.0), 0.375)
    assert away <= 0.05 and at_swivel <= 0.05
