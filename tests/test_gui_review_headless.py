"""What the GUI shows an operator, checked headless (FreeCAD as a library):
messages without CLI option names, readable areas, bad files leaving nothing
behind, the default output folder, filled parts, Simulate's time, part
objects with their choices (issue #12).  The same behaviour inside the real
GUI: tests/test_gui_review.py."""

from __future__ import annotations

import os
import re
import sys

import pytest

FreeCAD = pytest.importorskip("FreeCAD") if os.environ.get("CI") != "true" else __import__("FreeCAD")

from LeatherCutWorkbench.commands.messages import for_gui, readable_area  # noqa: E402
from LeatherCutWorkbench.core.errors import InputError, SafetyError  # noqa: E402
from LeatherCutWorkbench.document import importer, objects, part_objects, pipeline  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui.sample import write_sample  # noqa: E402
import test_document_job  # noqa: E402

doc = test_document_job.doc     # the same document fixture (undo on, closed after)

CLI_OPTION = re.compile(r"(?<![\w-])--[a-z]")


def _job(doc, path, *stages):
    job = pipeline.make_job(doc, os.path.splitext(os.path.basename(path))[0], path)
    for st in stages:
        pipeline.run_stage(job, st)
    return job


def test_table_refusal_and_overlap_area_read_for_the_gui(doc, tmp_path):
    """The post refusal of a drawing off the table names GUI settings, not
    ``--move-to-origin MM`` / ``--sheet/--hide``; an overlap area reads 41 410 mm²."""
    import ezdxf
    far = str(tmp_path / "far.dxf")
    d = ezdxf.new("R2010")
    d.header["$INSUNITS"] = 4
    d.modelspace().add_lwpolyline([(5000, 5000), (5100, 5000), (5100, 5080), (5000, 5080)], close=True)
    d.saveas(far)
    job = _job(doc, far, "Import", "Recognise", "Plan")
    job.PostOutputFile = str(tmp_path / "far.nc")
    with pytest.raises(SafetyError) as err:
        pipeline.run_stage(job, "Post")
    raw = str(err.value)
    assert CLI_OPTION.search(raw)                      # the core speaks CLI ...
    text = for_gui(raw)
    assert not CLI_OPTION.search(text) and "Plan path" in text and "Auto-nest" in text, text
    assert for_gui("P2#0 overlaps P1#0 by 4.141e+04 mm2") == "P2#0 overlaps P1#0 by 41 410 mm²"
    assert readable_area(2.4) == "2.4 mm²"


def test_bad_dxf_through_the_importer_leaves_no_job(doc, tmp_path):
    empty = tmp_path / "empty.dxf"
    empty.write_text("")
    with pytest.raises(InputError):
        importer.insert(str(empty), doc.Name)
    assert objects.jobs(doc) == [] and doc.Objects == []
    before = set(FreeCAD.listDocuments())
    with pytest.raises(InputError):
        importer.open(str(empty))
    assert set(FreeCAD.listDocuments()) == before


def test_default_output_is_never_beside_the_source_dxf(doc, tmp_path):
    src = tmp_path / "shared" / "drawings"
    src.mkdir(parents=True)
    job = _job(doc, write_sample(str(src / "bag.dxf")), "Import")
    prefs = objects.preferences()
    prefs.SetString("OutputFolder", "")
    saved = tmp_path / "work"
    saved.mkdir()
    doc.saveAs(str(saved / "bag.FCStd"))
    assert pipeline.default_output(job) == str(saved / "bag.nc")
    try:
        prefs.SetString("OutputFolder", str(tmp_path / "cuts"))
        assert pipeline.default_output(job) == str(tmp_path / "cuts" / "bag.nc")
    finally:
        prefs.SetString("OutputFolder", "")


def test_every_deepnest_part_can_be_filled(doc, samples_dir):
    """Three DeepNest parts have arcs ending ~1e-5 mm from the next line: they
    used to be drawn as bare edges (placed parts without their fill)."""
    job = _job(doc, os.path.join(samples_dir, "deepnest_ReadMeExampleSmall.dxf"), "Import", "Recognise")
    rec = objects.load_data(objects.stage_object(job, "Recognition"))
    unfilled = [p.id for p in rec.parts for m in (False, True) if not pipeline.part_shape(p, m).Faces]
    assert len(rec.parts) == 13 and unfilled == []
    for p in rec.parts:   # the fill is the part: area within 0.1 % of the contour's
        face = pipeline.part_shape(p, False)
        assert face.Area == pytest.approx(p.net_area, rel=1e-3)


def test_simulate_plays_the_planners_estimated_time(doc, tmp_path):
    from LeatherCutWorkbench.commands.timeline import timeline_of
    job = _job(doc, write_sample(str(tmp_path / "s.dxf")), "Import", "Recognise")
    job.PlanMethod = "nn"
    job.PlanFromMachine = True
    pipeline.run_stage(job, "Plan")
    plan = pipeline.stored_plan(job)
    tl = timeline_of(job)
    assert plan.metrics["est_time_s"] > 0
    assert tl.duration == pytest.approx(plan.metrics["est_time_s"], rel=1e-3, abs=0.02)
    # the knife is home at both ends and on the first entry after the first idle move
    assert tl.at(0.0)[0] == plan.home and tl.at(tl.duration)[0] == plan.home


def test_part_objects_named_chosen_and_honoured(doc, tmp_path):
    """One object per part; its Include / Quantity reach nesting and planning
    and survive recognising again."""
    job = _job(doc, write_sample(str(tmp_path / "s.dxf")), "Import", "Recognise")
    objs = part_objects.part_objects(job)
    rec = pipeline.effective_recognition(job)
    assert [o.PartId for o in objs] == [p.id for p in rec.active_parts()]
    assert all(o.Label.startswith("layer PARTS (P") for o in objs)
    first, second = objs[0], objs[1]
    first.Quantity = 2
    second.Include = False
    pipeline.run_stage(job, "Recognise")         # choices kept
    objs = part_objects.part_objects(job)
    assert (objs[0].Quantity, objs[1].Include) == (2, False)
    active = pipeline.effective_recognition(job).active_parts()
    assert objs[1].PartId not in {p.id for p in active}
    job.NestContainer, job.NestSheetWidth, job.NestSheetHeight = "sheet", 400.0, 300.0
    job.NestTimeBudget = 1.0
    pipeline.run_stage(job, "Nest")
    placed = [o.PartId for o in pipeline.placed_objects(job)]
    assert placed.count(objs[0].PartId) == 2 and objs[1].PartId not in placed
    pipeline.run_stage(job, "Plan")
    cut = {it.part_id.split("#")[0] for it in pipeline.stored_plan(job).items if it.part_id}
    assert objs[0].PartId in cut and objs[1].PartId not in cut


def test_graded_aama_set_cuts_one_size_by_default(doc, samples_dir):
    job = _job(doc, os.path.join(samples_dir, "GMX1016S18_AAMA.DXF"), "Import", "Recognise")
    by_size = part_objects.by_size(job)
    assert len(by_size) == 15 and all(len(v) == 10 for v in by_size.values())
    chosen = {s for s, objs in by_size.items() if all(o.Include for o in objs)}
    assert chosen == {"50"}                      # the file's "Sample Size: 50"
    assert all(not o.Include for s, objs in by_size.items() if s != "50" for o in objs)
    assert by_size["42"][0].Label == "GMX1016S18FR size 42 (P1)"
    assert len(pipeline.effective_recognition(job).active_parts()) == 10
    part_objects.set_included(by_size["42"], True)
    assert len(pipeline.effective_recognition(job).active_parts()) == 20


def test_parts_drawn_in_blocks_are_named_by_their_block(doc, samples_dir):
    job = _job(doc, os.path.join(samples_dir, "dxf2gcode_Bogen_Ellipsen_Polylinien_Block.dxf"),
               "Import", "Recognise")
    labels = [o.Label for o in part_objects.part_objects(job)]
    assert labels and all(re.fullmatch(r"block Block_\d+ \(P\d+\)", t) for t in labels), labels
