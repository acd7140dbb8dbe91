"""GUI workflow run inside the real FreeCAD GUI (started by tests/test_gui_workbench.py).

Runs as a macro once the GUI is up: activates the LeatherCut workbench and
drives every command through its task panel on a sample job -- Import DXF,
Recognise, both flag reviews, Auto-nest, Manual nest (with a collision),
Plan path, Simulate, Machine profiles, Post-process, Send to cutter (into the
project's fake GRBL controller on a pseudo-terminal) and Run job -- then
undoes, saves, closes and reopens the document.  Each check prints
``CHECK <name> ok`` or ``CHECK <name> FAILED: ...``; the results also go to
``$LC_OUT/result.json``.  Ends with ``os._exit(0)`` only when every check passed.

Environment: ``LC_SAMPLE`` (DXF), ``LC_OUT`` (output folder).
"""

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, pump  # noqa: E402

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

OUT = os.environ["LC_OUT"]
SAMPLE = os.environ["LC_SAMPLE"]


def steps():
    from LeatherCutWorkbench.commands import base, import_dxf, panel
    from LeatherCutWorkbench.document import objects, pipeline

    Gui.activateWorkbench("LeatherCutWB")
    pump()
    check("workbench active", Gui.activeWorkbench().name() == "LeatherCutWB", Gui.activeWorkbench().name())
    from LeatherCutWorkbench import commands
    names = commands.command_names()
    registered = set(Gui.listCommands())
    check("all commands registered", all(n in registered for n in names),
          [n for n in names if n not in registered])
    mw = Gui.getMainWindow()
    bars = [t for t in mw.findChildren(QtGui.QToolBar) if t.windowTitle() == "LeatherCut"]
    check("toolbar present", bars and len([a for a in bars[0].actions() if not a.isSeparator()]) == len(names),
          [a.text() for a in bars[0].actions()] if bars else "no toolbar")

    # Import DXF (the command's panel, after the file dialog)
    p = import_dxf.open_import_panel(SAMPLE)
    check("import preview", p.preview(), p.status.text())
    check("import panel accepted", p.accept())
    doc = FreeCAD.ActiveDocument
    job = objects.jobs(doc)[-1]
    check("drawing imported", objects.stage_object(job, "Drawing") is not None)
    base.focus_job(job)

    def command_panel(name):
        check(f"{name} active", Gui.Command.get(name).isActive())
        panel.CURRENT = None
        Gui.runCommand(name)
        pump(0.1)
        check(f"{name} opened a panel", panel.CURRENT is not None and Gui.Control.activeDialog())
        return panel.CURRENT

    p = command_panel("LeatherCut_Recognise")
    check("recognise preview", p.preview(), p.status.text())
    check("recognise accepted", p.accept())
    rec = objects.stage_object(job, "Recognition")
    check("recognition objects", rec is not None and len(rec.Group) >= 6)
    outer = [o for o in rec.Group if getattr(o, "Kind", "") == "outer"][0]
    check("parts coloured blue", tuple(round(c, 2) for c in outer.ViewObject.LineColor[:3]) ==
          (0.12, 0.37, 0.75), outer.ViewObject.LineColor)

    # flags: each decision one undo step
    p = command_panel("LeatherCut_FlagOver")
    n_undo = len(doc.UndoNames)
    p.decide("Include")
    flag = p.flags[0]
    check("over flag included", flag.Decision == "Include")
    check("decision is one undo step", len(doc.UndoNames) == n_undo + 1, doc.UndoNames[:3])
    doc.undo()
    check("undo decision", flag.Decision == "Undecided", flag.Decision)
    doc.redo()
    check("redo decision", flag.Decision == "Include", flag.Decision)
    p.step(1)
    p.reject()
    p = command_panel("LeatherCut_FlagUnder")
    p.decide("Accept")
    check("under flag accepted", p.flags[0].Decision == "Accept")
    p.reject()

    # Auto-nest with the panel's progress
    p = command_panel("LeatherCut_AutoNest")
    for prop, value in (("NestContainer", "sheet"), ("NestSheetWidth", 400.0), ("NestSheetHeight", 300.0),
                        ("NestMargin", 2.0), ("NestSpacing", 2.0), ("NestTimeBudget", 1.0),
                        ("NestWorkers", "")):   # all cores: worker processes forked from the GUI
        p.set_widget(prop, value)
    check("nest options bound", job.NestContainer == "sheet" and job.NestSheetWidth == 400.0, job.NestContainer)
    # a long search, cancelled from the panel while it runs: the GUI keeps serving events
    p.set_widget("NestTimeBudget", 60.0)
    QtCore.QTimer.singleShot(1500, p.reject)
    t0 = time.monotonic()
    ran = p.preview()
    elapsed = time.monotonic() - t0
    check("nest cancelled from the panel", not ran and elapsed < 20 and Gui.Control.activeDialog(),
          f"{ran} after {elapsed:.1f} s: {p.status.text()}")
    # Stop while the 60 s search runs: the best layout so far is kept, soon
    stop = p.form.findChild(QtGui.QPushButton, "stopButton")
    QtCore.QTimer.singleShot(2500, stop.click)
    t0 = time.monotonic()
    ran = p.preview()
    elapsed = time.monotonic() - t0
    check("nest stopped keeps the best layout", ran and elapsed < 15 and
          len(pipeline.placed_objects(job)) == 7, f"{ran} after {elapsed:.1f} s: {p.status.text()}")
    p.set_widget("NestTimeBudget", 1.0)
    check("nest preview", p.preview(), p.status.text())
    check("progress bar reached", p.progress_bar.value() >= 90, p.progress_bar.value())
    check("nest accepted", p.accept())
    placed = pipeline.placed_objects(job)
    check("parts placed", len(placed) == 7, len(placed))

    # Manual nest: push one part onto another -> red; cancel restores
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(placed[0])
    p = command_panel("LeatherCut_ManualNest")
    before = placed[0].Placement.Base
    shift = placed[1].Shape.BoundBox.Center - placed[0].Shape.BoundBox.Center
    p.move(shift.x, shift.y)
    problems = p.check()
    check("collision reported", problems and placed[0].Collides, problems)
    check("collision shown red", tuple(round(c, 2) for c in placed[0].ViewObject.ShapeColor[:3]) == (0.9, 0.22, 0.21),
          placed[0].ViewObject.ShapeColor)
    p.rotate(90)
    p.reject()
    pump()
    check("manual nest cancelled", placed[0].Placement.Base == before and not placed[0].Collides,
          placed[0].Placement.Base)
    p = command_panel("LeatherCut_ManualNest")
    p.move(0.5, 0.0)
    check("small move keeps layout valid", not p.check(), p.check())
    check("manual nest accepted", p.accept())

    p = command_panel("LeatherCut_PlanPath")
    p.set_widget("PlanMethod", "ga")
    p.set_widget("PlanTimeLimit", 1.0)
    check("plan preview", p.preview(), p.status.text())
    table = p.form.findChild(QtGui.QTableWidget, "metricsTable")
    labels = [table.item(r, 0).text() for r in range(table.rowCount())]
    check("metrics in panel", "Idle travel" in labels and "Knife lifts" in labels, labels)
    ended = [table.item(r, 1).text() for r in range(table.rowCount())
             if table.item(r, 0).text() == "Search ended"]
    check("panel says why the search ended",
          ended and ended[0] in ("converged", "iteration budget reached",
                                 "time budget reached (not converged)"), ended)
    check("plan accepted", p.accept())
    cut = objects.stage_object(job, "CutPath")
    check("cut path drawn", cut is not None and len(cut.Shape.Edges) > 20 and cut.IdleTravel > 0)
    vp = cut.ViewObject.Proxy
    # holes, lead-ins, idle moves, entry points, order numbers (no open chains after nesting)
    check("order numbers and idle moves drawn", vp.overlay.getNumChildren() == 5, vp.overlay.getNumChildren())

    p = command_panel("LeatherCut_Simulate")
    p.speed.setValue(50.0)
    p.seek(p.timeline.duration / 2)
    p.play()
    pump(0.3)
    check("simulation runs", p.t > p.timeline.duration / 2, p.label.text())
    p.reject()

    p = command_panel("LeatherCut_MachineProfiles")
    check("profiles listed", p.list.count() >= 5, p.list.count())
    details = p.details.toPlainText()
    check("profile shows the drag-knife and tool fields",
          all(f'"{k}"' in details for k in ("blade_offset", "swivel_angle", "tools", "tool_map",
                                            "tool_select", "notch_length")), details[-300:])
    # edit a user copy: the editor checks every field like a profile file
    import json
    copied = p.copy()
    names = [e["name"] for e in p.entries]
    p.list.setCurrentRow(names.index(os.path.splitext(os.path.basename(copied))[0]))
    data = json.loads(p.details.toPlainText())
    p.details.setPlainText(json.dumps(dict(data, blade_offset=0.3)))
    check("editor refuses a blade offset on a tangential knife",
          p.save() == "" and "blade_offset" in p.status.text(), p.status.text())
    p.details.setPlainText(json.dumps(dict(data, tool_map={"stitch": "pen"})))
    check("editor refuses a role mapped to a missing tool",
          p.save() == "" and "tool_map" in p.status.text(), p.status.text())
    pen = [{"name": "pen", "kind": "pen", "select": ["M0"], "offset": [-30, 0]}]
    p.details.setPlainText(json.dumps(dict(data, tools=pen, tool_map={"stitch": "pen"},
                                           swivel_angle=12.0)))
    saved = p.save()
    from LeatherCutWorkbench.post.profiles import load_profile as _load
    check("editor saves the new fields", bool(saved) and _load(saved).tool_map == {"stitch": "pen"}
          and _load(saved).tools[0]["offset"] == [-30, 0], p.status.text())
    p.reject()

    p = command_panel("LeatherCut_PostProcess")
    tools_label = p.form.findChild(QtGui.QLabel, "toolMapLabel")
    check("post panel shows the tool map", "knife" in tools_label.text(), tools_label.text())
    p.set_widget("PostToolMap", "stitch=pen")
    p.show_tools()
    check("a tool the machine lacks is named", "'pen'" in tools_label.text()
          and "PostToolMap" in tools_label.text(), tools_label.text())
    p.set_widget("PostToolMap", "")
    p.show_tools()
    out_nc = os.path.join(OUT, "job.nc")
    p.set_widget("PostOutputFile", out_nc)
    check("post accepted", p.accept())
    check("machine file written", os.path.isfile(out_nc) and open(out_nc).read().count("G1") > 20)

    # the layout gate: a part pushed onto another is refused by Plan, Post and Send
    a0, a1 = pipeline.placed_objects(job)[:2]
    keep = a0.Placement
    shift = a1.Shape.BoundBox.Center - a0.Shape.BoundBox.Center
    shift.z = 0
    a0.Placement = FreeCAD.Placement(keep.Base + shift, keep.Rotation)
    for name, run in (("LeatherCut_PlanPath", lambda q: q.preview()),
                      ("LeatherCut_PostProcess", lambda q: q.accept()),
                      ("LeatherCut_SendToCutter", lambda q: q.start() is not None)):
        p = command_panel(name)
        if name == "LeatherCut_SendToCutter":
            p.port.setText("emulator:grblhal")
        check(f"{name} refuses the unsafe layout", not run(p) and "not safe to cut" in p.status.text()
              and f"{a0.PartId}#{a0.Copy}" in p.status.text(), p.status.text())
        p.reject()
        pump()
    a0.Placement = keep

    # Send to cutter: stream into the fake controller (off the GUI thread)
    from LeatherCutWorkbench.post.emulator import FakeController
    from LeatherCutWorkbench.post.profiles import load_profile
    prof = load_profile(job.PostMachine)
    ctrl = FakeController(flavour="grblhal", axes=prof.axes, wrapped=prof.rotary_axis if prof.rotary_wrap else "")
    ctrl.start()
    try:
        p = command_panel("LeatherCut_SendToCutter")
        p.port.setText(ctrl.port)
        p.check.setChecked(True)
        session = p.start()
        t0 = time.monotonic()
        while session.running and time.monotonic() - t0 < 60:
            pump(0.1)
        pump(0.3)
        check("streamed to the controller", session.result is not None and session.result.ok,
              session.error or (session.result.to_json() if session.result else "no result"))
        check("controller executed the job", len(ctrl.executed) > 20, len(ctrl.executed))
        check("journal written", os.path.isfile(out_nc + ".journal"))
        p.reject()
    finally:
        ctrl.close()

    # a slow controller: feed hold, cycle start, stop safely, then resume from the journal
    os.remove(out_nc + ".journal")
    ctrl = FakeController(flavour="grblhal", axes=prof.axes, line_time=0.015,
                          wrapped=prof.rotary_axis if prof.rotary_wrap else "")
    ctrl.start()
    try:
        p = command_panel("LeatherCut_SendToCutter")
        p.port.setText(ctrl.port)
        p.check.setChecked(False)
        session = p.start()

        def wait_for(cond, limit=30.0):
            t0 = time.monotonic()
            while not cond() and time.monotonic() - t0 < limit:
                pump(0.05)
            return cond()

        check("streaming started", wait_for(lambda: session.progress.get("acked", 0) > 10), session.progress)
        p.pause()
        check("feed hold", wait_for(lambda: ctrl.state.startswith("Hold"), 5), ctrl.state)
        p.resume_motion()
        check("cycle start", wait_for(lambda: not ctrl.state.startswith("Hold"), 8), ctrl.state)
        p.stop()
        check("stopped safely", wait_for(lambda: not session.running, 20) and session.result is not None
              and session.result.status == "aborted" and session.result.stopped_safely,
              session.result.to_json() if session.result else session.error)
        pump(0.3)
        resume_at = p.resume.currentData()
        check("resume point suggested", bool(resume_at), [p.resume.itemText(i) for i in range(p.resume.count())])
        session2 = p.start()
        check("resumed job finished", wait_for(lambda: not session2.running, 60) and session2.result is not None
              and session2.result.ok, session2.error or (session2.result.to_json() if session2.result else ""))
        p.reject()
    finally:
        ctrl.close()

    # Run job: the whole pipeline in one undo step
    n_undo = len(doc.UndoNames)
    os.remove(out_nc)
    # Run job cuts the hand-placed layout as it stands (RunNestAgain would nest again)
    planned_by_hand = objects.stage_object(job, "CutPath").Data
    by_hand = sorted((o.PartId, o.Copy, round(o.Placement.Base.x, 6), round(o.Placement.Base.y, 6))
                     for o in pipeline.placed_objects(job))
    Gui.runCommand("LeatherCut_RunJob")
    pump()
    check("run job wrote the machine file", os.path.isfile(out_nc) and os.path.getsize(out_nc) > 500)
    check("run job is one undo step", len(doc.UndoNames) == n_undo + 1, doc.UndoNames[:3])
    kept = sorted((o.PartId, o.Copy, round(o.Placement.Base.x, 6), round(o.Placement.Base.y, 6))
                  for o in pipeline.placed_objects(job))
    check("run job kept the hand-placed layout", kept == by_hand, kept)
    run_path = objects.stage_object(job, "CutPath").Data
    doc.undo()
    check("undo run job restores the earlier path", objects.stage_object(job, "CutPath").Data == planned_by_hand)
    doc.redo()
    check("redo run job", objects.stage_object(job, "CutPath").Data == run_path)

    path = os.path.join(OUT, "job.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    pump()
    doc = FreeCAD.openDocument(path)
    pump()
    job = objects.jobs(doc)[-1]
    states = objects.stage_states(job)
    check("reopened with every stage", states == {"Drawing": "current", "Recognition": "current",
                                                  "Layout": "current", "CutPath": "current"}, states)
    cut = objects.stage_object(job, "CutPath")
    check("cut path view restored", type(cut.ViewObject.Proxy).__name__ == "CutPathViewProvider"
          and cut.ViewObject.Proxy.overlay.getNumChildren() == 5)
    check("flag decisions restored", sorted(f.Decision for f in pipeline.flag_objects(job)) == ["Accept", "Include"])
    check("options restored", job.NestContainer == "sheet" and job.NestSheetWidth == 400.0)
    Gui.runCommand("LeatherCut_PostProcess")
    pump()
    p = panel.CURRENT
    check("post after reopen", p.accept())


def main():
    finish(steps, OUT)


QtCore.QTimer.singleShot(500, main)
