"""One source of truth and the layout gate (issue 12, items 2 and 3).

The same FreeCAD document is driven stage by stage (Import, Recognise, decisions,
[Auto-nest, a hand move], Plan path, Post-process), by *Run job*, and the
drawing by ``leathercut run`` with the equivalent options; the three G-code
files must be byte for byte the same (the G-code carries no time stamp).  Then
a part moved onto another and a 2.4 mm gap where 3 mm spacing is set are
refused by the document stages and the CLI verbs, naming the parts, and pass
with the explicit override, which is logged.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

FreeCAD = pytest.importorskip("FreeCAD") if os.environ.get("CI") != "true" else __import__("FreeCAD")

from LeatherCutWorkbench.core.errors import InputError  # noqa: E402
from LeatherCutWorkbench.core.nesting.outputs import layout_json  # noqa: E402
from LeatherCutWorkbench.document import pipeline  # noqa: E402

from conftest import SAMPLES_DIR  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui.sample import write_sample  # noqa: E402

LEATHERCUT = os.path.join(os.path.dirname(sys.executable), "leathercut")
VISICUT = os.path.join(SAMPLES_DIR, "visicut_6_HG2_Korpusinnen_2.dxf")
DEEPNEST = os.path.join(SAMPLES_DIR, "deepnest_ReadMeExampleSmall.dxf")
#: an AAMA file lying at negative X (like GMX1016S18_AAMA.DXF of the issue, a quarter of its size)
AAMA = os.path.join(SAMPLES_DIR, "WM_SLIM_TANK.DXF")
#: plan options both ways: nearest neighbour is deterministic and quick
PLAN_CLI = ["--plan-method", "nn", "--plan-time", "1"]


def _job(doc, path, out_dir):
    job = pipeline.make_job(doc, "Job", path)
    job.PlanMethod, job.PlanTimeLimit = "nn", 1.0
    job.PostMachine = "grblhal_tangential"
    job.PostOutputFile = os.path.join(out_dir, "stages.nc")
    pipeline.run_stage(job, "Import")
    pipeline.run_stage(job, "Recognise")
    return job


def _decide(job, decisions):
    for f in pipeline.flag_objects(job):
        if f.FlagId in decisions:
            pipeline.set_flag_decision(f, decisions[f.FlagId])


def _stages_then_run_job(job, out_dir):
    """G-code of Plan path + Post-process, then of Run job on the same document."""
    pipeline.run_stage(job, "Plan")
    staged = open(pipeline.run_stage(job, "Post"), "rb").read()
    job.PostOutputFile = os.path.join(out_dir, "runjob.nc")
    whole = open(pipeline.run_all(job), "rb").read()
    return staged, whole


def _cli(*args, ok=True):
    proc = subprocess.run([LEATHERCUT, *args], capture_output=True, text=True, timeout=600)
    if ok:
        assert proc.returncode == 0, proc.stderr
    return proc


def _cli_run(path, out_dir, *options):
    out = os.path.join(out_dir, "cli")
    _cli("run", path, "-o", out, "--machine", "grblhal_tangential", *PLAN_CLI, *options)
    return open(os.path.join(out, "job.nc"), "rb").read()


# -- item 2: the same plan every way -----------------------------------------------------

def test_accepted_fixes_are_the_job_everywhere(doc, tmp_path):
    """VisiCut file with F2 and F3 accepted: Plan path cut 202 contours, Run job
    200 (it ignored the decisions)."""
    job = _job(doc, VISICUT, str(tmp_path))
    _decide(job, {"F2": "Accept", "F3": "Accept"})
    staged, whole = _stages_then_run_job(job, str(tmp_path))
    assert pipeline.stored_plan(job).items and len(pipeline.stored_plan(job).items) == 202
    assert whole == staged
    assert _cli_run(VISICUT, str(tmp_path), "--accept-fix", "F2,F3") == staged
    # Run job kept the decisions on the flag objects
    assert {f.FlagId: f.Decision for f in pipeline.flag_objects(job)}["F2"] == "Accept"


def test_move_to_origin_is_the_job_everywhere(doc, tmp_path):
    """AAMA file lying at negative coordinates with PlanMoveToOrigin: Plan and
    Post succeeded, Run job refused 'outside the table' (it ignored the option)."""
    job = _job(doc, AAMA, str(tmp_path))
    job.PlanMoveToOrigin, job.PlanOriginOffset = True, 10.0
    staged, whole = _stages_then_run_job(job, str(tmp_path))
    assert whole == staged
    assert _cli_run(AAMA, str(tmp_path), "--move-to-origin", "10") == staged


def test_over_and_under_decisions_are_the_job_everywhere(doc, tmp_path):
    """DeepNest example: F1 (gap) accepted, F2 (the plate border, over-recognised)
    included.  The CLI equivalent of Include on an over flag is the part id
    (``--recognise-include P1``: the part is cut as recognised), not the contour
    id (which recomputes containment)."""
    job = _job(doc, DEEPNEST, str(tmp_path))
    job.PlanMoveToOrigin, job.PlanOriginOffset = True, 10.0
    _decide(job, {"F1": "Accept", "F2": "Include"})
    staged, whole = _stages_then_run_job(job, str(tmp_path))
    assert len(pipeline.stored_plan(job).items) == 14 + 18       # 14 parts, 18 holes
    assert whole == staged
    assert _cli_run(DEEPNEST, str(tmp_path), "--accept-fix", "F1", "--recognise-include", "P1",
                    "--move-to-origin", "10") == staged


def _nested_job(doc, tmp_path, spacing=2.0):
    sample = write_sample(str(tmp_path / "sample.dxf"))
    job = _job(doc, sample, str(tmp_path))
    under = [f for f in pipeline.flag_objects(job) if f.Kind == "under"][0]
    pipeline.set_flag_decision(under, "Accept")
    job.NestContainer = "sheet"
    job.NestSheetWidth, job.NestSheetHeight = 400.0, 300.0
    job.NestMargin, job.NestSpacing = 2.0, spacing
    job.NestTimeBudget, job.NestWorkers = 0.5, "1"
    pipeline.run_stage(job, "Nest")
    return job, sample, under.FlagId


def _move_to(obj, x, y):
    """Move a placed part so the lower-left corner of its box is at (x, y) mm."""
    bb = obj.Shape.BoundBox
    obj.Placement = FreeCAD.Placement(obj.Placement.Base + FreeCAD.Vector(x - bb.XMin, y - bb.YMin, 0),
                                      obj.Placement.Rotation)


def _write_layout(job, path):
    rec = pipeline.effective_recognition(job)
    with open(path, "w") as fh:
        json.dump(layout_json(rec.active_parts(), pipeline.current_layout(job)), fh)
    return path


def test_run_job_keeps_a_hand_placed_layout(doc, tmp_path):
    """Run job re-nested over a hand-placed layout; now it cuts the layout as it
    stands (RunNestAgain asks for a new nest), as does ``run --layout-in``."""
    job, sample, fix = _nested_job(doc, tmp_path)
    a = pipeline.placed_objects(job)[0]
    key = (a.PartId, a.Copy)
    _move_to(a, 250.0, 200.0)                       # by hand, to a free spot
    assert not pipeline.update_collisions(job)
    staged, whole = _stages_then_run_job(job, str(tmp_path))
    assert whole == staged
    kept = [o for o in pipeline.placed_objects(job) if (o.PartId, o.Copy) == key][0]
    assert kept.Shape.BoundBox.XMin == pytest.approx(250.0, abs=1e-6)
    layout = _write_layout(job, str(tmp_path / "layout.json"))
    assert _cli_run(sample, str(tmp_path), "--accept-fix", fix, "--sheet", "400x300",
                    "--spacing", "2", "--margin", "2", "--layout-in", layout) == staged
    # asked to, Run job nests again and the hand move is gone
    job.RunNestAgain = True
    job.PostOutputFile = str(tmp_path / "renest.nc")
    pipeline.run_all(job)
    moved = [o for o in pipeline.placed_objects(job) if (o.PartId, o.Copy) == key][0]
    assert moved.Shape.BoundBox.XMin != pytest.approx(250.0, abs=1e-3)


# -- item 3: the gate ----------------------------------------------------------------------

def _bad_layouts(doc, tmp_path):
    """Yields (name, job, labels of the two parts concerned, expected text)."""
    job, sample, fix = _nested_job(doc, tmp_path, spacing=3.0)
    a, b = pipeline.placed_objects(job)[:2]
    _move_to(a, 250.0, 200.0)
    bb = a.Shape.BoundBox
    _move_to(b, bb.XMax + 2.4, bb.YMin)            # 2.4 mm apart, 3 mm spacing set
    return job, sample, fix, (f"{a.PartId}#{a.Copy}", f"{b.PartId}#{b.Copy}"), a, b


def test_gate_refuses_spacing_and_overlap_in_the_document(doc, tmp_path, capfd):
    job, _sample, _fix, (la, lb), a, b = _bad_layouts(doc, tmp_path)
    for stage in ("Plan", "RunJob"):
        with pytest.raises(InputError) as err:
            pipeline.run_stage(job, stage)
        text = str(err.value)
        assert "not safe to cut" in text and la in text and lb in text and "2.4 mm apart" in text
    # one part onto the other: an overlap, its area written readably
    _move_to(b, a.Shape.BoundBox.XMin, a.Shape.BoundBox.YMin)
    with pytest.raises(InputError) as err:
        pipeline.run_stage(job, "Plan")
    text = str(err.value)
    assert "overlaps" in text and la in text and lb in text and "mm²" in text and "e+" not in text
    # the expert override: planned and posted, every problem in the report view
    job.AllowInvalidLayout = True
    FreeCAD.Console.SetStatus("Console", "Wrn", True)    # the report view of freecadcmd
    capfd.readouterr()
    pipeline.run_stage(job, "Plan")
    pipeline.run_stage(job, "Post")
    logged = capfd.readouterr()
    assert "cut despite the layout gate" in logged.out + logged.err and la in logged.out + logged.err
    kept = [f.message for f in pipeline.stored_plan(job).findings if f.code == "layout-override"]
    assert kept and all(la in m and lb in m for m in kept)   # saved with the document
    assert os.path.getsize(job.PostLastOutput) > 100
    # a later hand move is caught by Post-process too (the plan was made before it)
    job.AllowInvalidLayout = False
    with pytest.raises(InputError):
        pipeline.run_stage(job, "Post")
    with pytest.raises(InputError):
        pipeline.check_gate(job)                     # what Send to cutter calls


def test_gate_refuses_spacing_and_overlap_on_the_command_line(doc, tmp_path):
    job, sample, fix, (la, lb), a, b = _bad_layouts(doc, tmp_path)
    gap = _write_layout(job, str(tmp_path / "gap.json"))
    _move_to(b, a.Shape.BoundBox.XMin, a.Shape.BoundBox.YMin)
    overlap = _write_layout(job, str(tmp_path / "overlap.json"))
    common = ["--accept-fix", fix, "--sheet", "400x300", "--spacing", "3", "--margin", "2"]
    out = str(tmp_path / "out")
    verbs = [("run", ["-o", out, *PLAN_CLI]), ("plan", ["--method", "nn", "--time", "1"]),
             ("post", ["-o", str(tmp_path / "x.nc"), *PLAN_CLI]),
             ("send", ["--port", "emulator:grblhal", "--journal", str(tmp_path / "x.journal"),
                       *PLAN_CLI])]
    cases = [(gap, "2.4 mm apart (spacing 3 mm)", verb, extra) for verb, extra in verbs]
    cases.append((overlap, "overlaps", *verbs[0]))
    for layout, what, verb, extra in cases:
        proc = _cli(verb, sample, *extra, *common, "--layout-in", layout, ok=False)
        assert proc.returncode == 2, (verb, proc.stderr)
        assert what in proc.stderr and la in proc.stderr and lb in proc.stderr, proc.stderr
        assert "Traceback" not in proc.stderr
    assert not os.path.exists(str(tmp_path / "x.nc"))
    proc = _cli("run", sample, "-o", out, *common, *PLAN_CLI, "--layout-in", overlap,
                "--allow-invalid-layout")
    assert "warning: cut despite the layout gate" in proc.stderr and la in proc.stderr
    report = json.load(open(os.path.join(out, "report.json")))
    assert report["layout_override"] and all(la in m or lb in m for m in report["layout_override"])
    assert any(w["code"] == "layout-override" for w in report["warnings"])
