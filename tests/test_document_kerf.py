"""The flame job from the workbench: the document pipeline (FreeCAD objects,
stage by stage and *Run job*) with the ``flame_plasma`` profile on
examples/bag.dxf writes a kerf-compensated program that passes the kerf check
(tests/kerf_helpers.py), exactly like the CLI."""

from __future__ import annotations

import os

import pytest

FreeCAD = pytest.importorskip("FreeCAD") if os.environ.get("CI") != "true" else __import__("FreeCAD")

from LeatherCutWorkbench.document import objects, pipeline  # noqa: E402
from LeatherCutWorkbench.post.profiles import load_profile  # noqa: E402

from kerf_helpers import kerf_deviation, swept_band, traced_moves  # noqa: E402

BAG = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                   "examples", "bag.dxf")


def _flame_job(doc, out):
    job = pipeline.make_job(doc, "Job", BAG)
    job.PostMachine = "flame_plasma"
    job.NestContainer = "none"
    job.PlanMoveToOrigin, job.PlanOriginOffset = True, 20.0
    job.PlanMethod, job.PlanTimeLimit = "nn", 0.5
    job.PostOutputFile = out
    return job


def _check(job):
    prof = load_profile("flame_plasma")
    text = open(job.PostLastOutput).read()
    parts, _ = pipeline.parts_to_cut(job)
    band = swept_band(traced_moves(text, prof), prof.kerf / 2, prof.origin)
    dev = kerf_deviation(parts, band, prof.kerf / 2, 0.02)
    assert dev["penetration"] <= 0.02 and dev["gap"] <= 0.02, dev
    plan = pipeline.stored_plan(job)
    assert all(it.lead_in_count > 0 for it in plan.items)
    return plan


def test_flame_job_stage_by_stage(doc, tmp_path):
    job = _flame_job(doc, str(tmp_path / "flame.nc"))
    for stage in ("Import", "Recognise", "Plan", "Post"):
        pipeline.run_stage(job, stage)
    plan = _check(job)
    # the plan's time estimate includes the lead-ins the torch really cuts
    cut = objects.stage_object(job, "CutPath")
    assert cut.CutLength == pytest.approx(sum(it.length for it in plan.items), rel=1e-3)


def test_flame_job_run_job(doc, tmp_path):
    job = _flame_job(doc, str(tmp_path / "flame_run.nc"))
    pipeline.run_stage(job, "RunJob")
    _check(job)


def test_cut_path_view_shows_the_tabs(doc, tmp_path, monkeypatch):
    """The cut path view draws the tabs of the job's machine profile."""
    import json
    from LeatherCutWorkbench.document import viewproviders
    d = load_profile("flame_plasma").to_json()
    d.update(name="flame_tabs", tab_count=2, tab_width=1.5)
    monkeypatch.setenv("LEATHERCUT_MACHINES", str(tmp_path))
    (tmp_path / "flame_tabs.json").write_text(json.dumps(d))
    job = _flame_job(doc, str(tmp_path / "flame.nc"))
    job.PostMachine = "flame_tabs"
    for stage in ("Import", "Recognise", "Plan"):
        pipeline.run_stage(job, stage)
    plan = pipeline.stored_plan(job)
    bars = viewproviders._tab_moves(objects.stage_object(job, "CutPath"), plan)
    outers = sum(1 for it in plan.items if it.kind == "outer")
    assert len(bars) == 2 * outers
    assert all(abs(((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5 - 1.5) < 0.2 for a, b in bars)
