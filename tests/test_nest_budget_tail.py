"""The end of a nest's time budget (core/nesting/tail.py): the reserve after
the search follows the measured cost of building and checking the layout and
the declared outputs, each layout is checked once, the strip phase counts
from the user's start, and the CLI's quick exit loses no output."""

import json
import os
import subprocess
import sys
import time

from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, nest, tail
from LeatherCutWorkbench.core.nesting.engine import _deadlines, _reserve, _reserve_floor
from LeatherCutWorkbench.core.nesting.esicup import read_esicup

from nest_shapes import l_shape, rect

DATA = os.path.join(os.path.dirname(__file__), "data", "nest")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _parts():
    return [rect("A", 40, 20, q=4, rotations=[0, 90]), l_shape("L", 30, 30, 10, q=3, rotations=[0, 90])]


def test_reserve_grows_with_the_measured_build_and_check_cost():
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    t = tail.Tail(parts, opts)
    prior = t.reserve(7)
    t.note_build(0.07, 7)                  # 10 ms per copy to build ...
    t.note_check(0.14, 7)                  # ... and 20 ms to check
    assert t.per_copy == 0.03
    measured = t.reserve(7)
    assert measured > prior and measured == tail.EXIT_S + tail.FACTOR * 0.03 * 7
    assert t.reserve(7, rounds=2) > measured and t.reserve(70) > measured
    t.note_check(10.0, 7)                  # only the first measurement counts
    assert t.reserve(7) == measured
    # the engine's search end moves earlier by the larger reserve
    early = _deadlines(0.0, 10.0, _reserve(10.0, 7, t))[0]
    fast = tail.Tail(parts, opts)
    fast.per_copy = 1e-4
    assert early < _deadlines(0.0, 10.0, _reserve(10.0, 7, fast))[0] < 10.0


def test_declared_outputs_are_kept_free_per_written_vertex():
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    with tail.session(parts, opts) as quiet:
        pass
    with tail.writing(["dxf", "layout"]):
        with tail.session(parts, opts) as loud:
            assert tail.current(parts, opts) is loud
    assert loud.reserve(7) > quiet.reserve(7)
    assert loud.outputs == ("dxf", "layout") and quiet.outputs == ()


def test_each_layout_is_checked_once(monkeypatch):
    """The strip phase checks its result, :func:`nest` used to check it again:
    every distinct layout reaches the checker once now, and nest's verdict is
    still the checker's (the layout is valid and marked checked)."""
    inst = read_esicup(os.path.join(DATA, "shapes0.json"))
    seen = []
    real = tail.check_layout

    def counting(parts, layout, **kw):
        seen.append(tail._layout_key(layout))
        return real(parts, layout, **kw)

    monkeypatch.setattr(tail, "check_layout", counting)
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=3, workers=1)
    lay = nest(inst.parts, opts)
    assert lay.metrics["checked"] and not lay.unplaced
    assert len(seen) >= 2                         # the engine's first layout, the final one
    assert len(seen) == len(set(seen))
    assert tail._layout_key(lay) in seen
    assert real(inst.parts, lay) == []


def test_strip_phase_counts_the_budget_from_the_users_start():
    """The engine run by the strip phase got options copied with
    ``dataclasses.replace``, which drops ``started_at``: both counted from the
    call, so the time spent before it (reading the drawing) was not in the
    budget and the call took the whole 5 s.  Now it ends 3 s earlier (the
    assertion leaves 1.5 s for a loaded machine)."""
    inst = read_esicup(os.path.join(DATA, "shapes0.json"))
    opts = NestOptions(container=ContainerSpec.strip(inst.strip_height), time_budget=5, workers=1)
    t_call = time.monotonic()
    opts.started_at = t_call - 3.0               # the user pressed Nest 3 s ago
    lay = nest(inst.parts, opts)
    assert time.monotonic() - t_call < 3.5
    assert lay.metrics["time_s"] >= 3.0          # counted from started_at
    assert not lay.unplaced and lay.metrics["checked"]


def test_cli_quick_exit_writes_the_whole_report_and_outputs(tmp_path):
    lay = tmp_path / "lay.json"
    exe = os.path.join(os.path.dirname(sys.executable), "leathercut")
    r = subprocess.run([exe, "nest", "--esicup", os.path.join(DATA, "shapes0.json"), "--time", "3",
                        "--workers", "1", "--json", "--layout-out", str(lay)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)                      # complete: flushed before os._exit
    assert d["metrics"]["placed_count"] == 43 and d["outputs"] == {"layout": str(lay)}
    assert len(json.loads(lay.read_text())["items"]) == 43


def test_started_at_survives_replace_and_is_no_document_property():
    """``started_at`` was ``field(init=False)`` to keep it out of the job's
    properties, so ``dataclasses.replace`` dropped it and every copy of the
    options counted its budget from the copy.  It is transient field metadata
    now: copies keep it and the Auto-nest panel's properties still leave it out."""
    import dataclasses
    from LeatherCutWorkbench.document import options as doc_options
    opts = NestOptions(time_budget=7, started_at=123.5)
    assert dataclasses.replace(opts, spacing=2.0).started_at == 123.5
    nest_stage = next(st for st in doc_options.STAGE_OPTIONS if st.key == "Nest")
    names = [f[0] for f in doc_options.fields_of(nest_stage)]
    assert "started_at" not in names and "time_budget" in names


def test_the_tail_timed_during_the_search_is_kept_as_it_will_be_at_the_end(monkeypatch):
    """The build and check are timed while the workers search: two workers on
    two cores make them ~1.5x slower than at the end, when the workers have
    stopped.  The wall kept is the CPU time times max(1, wall/CPU - workers/cores);
    what other programs take stays counted, and so do the outputs."""
    monkeypatch.setattr(tail, "_cores", lambda: 2)
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    quiet = tail.Tail(parts, opts)
    quiet.busy = 2
    quiet.note_build(0.3, 3, cpu=0.2)          # wall / CPU 1.5: only the workers' share
    assert abs(quiet.per_copy - 2 * 0.2 / 3) < 1e-12 and quiet.contention == 1.0
    loaded = tail.Tail(parts, opts)
    loaded.busy = 2
    loaded.note_build(0.6, 3, cpu=0.1)         # wall / CPU 6: other programs take 5 - 1
    assert abs(loaded.contention - 5.0) < 1e-12
    assert abs(loaded.per_copy - 2 * 0.5 / 3) < 1e-12
    alone = tail.Tail(parts, opts)             # one worker: the search waited for it
    alone.note_build(0.6, 3, cpu=0.1)
    assert abs(alone.per_copy - 2 * 0.2) < 1e-12 and abs(alone.contention - 6.0) < 1e-12
    with tail.writing(["dxf"]):
        with tail.session(parts, opts) as out:
            prior = out.reserve(7) - out.reserve(7, outputs=False)
            out.busy = 2
            out.note_build(0.3, 3, cpu=0.2)
            now = out.reserve(7) - out.reserve(7, outputs=False)
            # the outputs' CPU time at the measured 1.0, not the prior 2.5
            assert abs(now - prior / tail.PRIOR_CONTENTION) < 1e-9
            assert now > tail.OUTPUT_CPU_S["dxf"][0]


def test_the_prior_tail_of_a_hide_job_follows_its_hides_and_parts():
    """Before the first layout is timed the reserve per copy was 15 ms on every
    hide job: 4.2 s for Baldacci Test7's 280 small rectangles, so at a high
    load its first fill gave up on every copy.  Now it grows with the hides'
    vertices (outline, holes, zones) times the parts' segments."""
    def prior(name):
        inst = read_esicup(os.path.join(DATA, name))
        opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=10)
        return tail.Tail(inst.parts, opts).reserve(1) - tail.EXIT_S
    small = prior("Test8.json")                      # 31 vertices per hide, 6 per part
    large = prior("Test10_items13_15_hide7.json")    # a hide of 27 holes and 14 zones
    assert 0 < small < 0.002 < 20 * small < large <= tail.PRIOR_HIDE_MAX_S


def test_the_workers_may_search_until_any_measured_tail_allows():
    """The workers used to get the search end of the prior tail and the
    measured one could only move it earlier: Baldacci Test7 and Test1 ended
    at 5.7-8 s of 10 with the tail measured at 0.1 s.  Now they get the latest
    end a tail can give (the shutdown and the exit) and the parent ends them at
    the measured one: no tail, measured or not, ends the search after that."""
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    for budget in (0.5, 3.0, 10.0, 60.0):
        latest = _deadlines(0.0, budget, _reserve_floor(budget))[0]
        assert budget - 0.5 - tail.EXIT_S <= latest < budget
        for per_copy in (None, 0.0, 1e-4, 0.05):
            t = tail.Tail(parts, opts)
            t.per_copy = per_copy
            for outputs in (True, False):
                assert _deadlines(0.0, budget, _reserve(budget, 7, t, outputs))[0] <= latest


def test_the_files_of_the_outputs_are_kept_free_from_the_first_fill_too():
    """A first fill given up at its last resort end left the outputs out:
    Baldacci Test1 at load ~9 then ended 0.8 s past T + 10 % + 1 s.  Opening
    the declared files (importing ezdxf, the document) is counted now."""
    inst = read_esicup(os.path.join(DATA, "Test8.json"))
    opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=10)
    assert tail.Tail(inst.parts, opts).files_s() == 0.0
    with tail.writing(["dxf", "layout"]):
        with tail.session(inst.parts, opts) as t:
            files = t.files_s()
    assert abs(files - tail.PRIOR_CONTENTION * (tail.FILE_WORST_CPU_S["dxf"]
                                                + tail.FILE_WORST_CPU_S["layout"])) < 1e-12
    hard = _deadlines(0.0, 10.0, _reserve(10.0, 79, t), True, 12.0,
                      _reserve(10.0, 79, t, outputs=False) + files)[4]
    assert hard < _deadlines(0.0, 10.0, _reserve(10.0, 79, t), True, 12.0,
                             _reserve(10.0, 79, t, outputs=False))[4]


def test_the_contention_at_the_end_follows_the_other_programs_sampled_during_the_search(
        monkeypatch):
    """The tail runs alone once the workers stop: it shares the cores with the
    other programs' runnable tasks, sampled while the search runs (the
    nest's own -- the parent and its busy workers -- left out), not with the
    workers it was timed next to.  Before, at T = 60 the hide searches ended
    7-10 s early of T + 10 % + 1 s for a 1-2 s real tail."""
    monkeypatch.setattr(tail, "_cores", lambda: 2)
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    running = [3]
    monkeypatch.setattr(tail, "runnable", lambda: running[0])
    quiet = tail.Tail(parts, opts)
    quiet.busy = 2
    quiet.note_build(0.6, 3, cpu=0.1)          # timed at wall / CPU 6 next to the workers
    loaded_guess = quiet.contention
    quiet.note_load(3)                         # the parent and two workers: nobody else
    assert loaded_guess == 5.0 and quiet.contention == 1.0
    assert abs(quiet.per_copy - 2 * 0.1 / 3) < 1e-12    # the CPU time, at contention 1
    busy = tail.Tail(parts, opts)
    busy.note_build(0.3, 3, cpu=0.1)
    running[0] = 8                             # five other programs' tasks
    busy.note_load(3)
    assert busy.contention == 3.0 and abs(busy.per_copy - 2 * 0.3 / 3) < 1e-12
    running[0] = 3                             # a running mean: one quiet sample moves it a little
    busy._sampled_at = -1e9
    busy.note_load(3)
    assert 2.9 < busy.contention < 3.0
    assert busy.reserve(7) > quiet.reserve(7)


def test_the_outputs_cost_the_import_of_their_writer_only_when_it_is_not_imported(monkeypatch):
    """The CLI imports ezdxf at start-up: a DXF output then costs the document,
    not the 0.25 s of the import the reserve used to keep for every DXF file."""
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    with tail.writing(["dxf"]):
        with tail.session(parts, opts) as t:
            pass
    module, cpu = tail.OUTPUT_IMPORT["dxf"]
    monkeypatch.setitem(sys.modules, module, sys.modules.get(module) or object())
    imported = t.reserve(7)
    monkeypatch.delitem(sys.modules, module)
    cold = t.reserve(7)
    assert abs(cold - imported - tail.FACTOR * t.contention * cpu) < 1e-9


def test_the_other_workers_wait_for_the_first_layout_only_on_a_busy_machine(monkeypatch):
    """Worker 0's quick first fill shared the cores with worker 1's exact one
    (Baldacci Test10 at load ~2 on 2 cores: 2 s of CPU took 4 s wall): with
    more busy processes than cores the other workers wait for the first layout."""
    from LeatherCutWorkbench.core.nesting import engine
    monkeypatch.setattr(tail, "_cores", lambda: 2)
    monkeypatch.setattr(engine, "runnable", lambda: 1)      # this process alone
    assert not engine._busy(2)
    monkeypatch.setattr(engine, "runnable", lambda: 2)      # one other program
    assert engine._busy(2) and not engine._busy(1)
    monkeypatch.setattr(engine, "runnable", lambda: None)   # unknown: never wait
    assert not engine._busy(8)


def test_the_writer_of_a_declared_output_is_imported_during_the_search():
    """A hide benchmark file reads no DXF, so ezdxf is not imported before the
    first layout; with a DXF output declared the engine's parent imports it
    while the workers search, and the reserve drops by its import cost."""
    code = ("import sys, os\n"
            "from LeatherCutWorkbench.core.nesting import ContainerSpec, NestOptions, nest, tail\n"
            "from LeatherCutWorkbench.core.nesting.esicup import read_esicup\n"
            f"inst = read_esicup({os.path.join(DATA, 'Test8.json')!r})\n"
            "opts = NestOptions(container=ContainerSpec.hide(*inst.hides), time_budget=3, workers=2)\n"
            "assert 'ezdxf' not in sys.modules\n"
            "with tail.writing(['dxf']):\n"
            "    lay = nest(inst.parts, opts)\n"
            "print('ezdxf' in sys.modules, lay.metrics['placed_count'])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         env=dict(os.environ, PYTHONPATH=ROOT), timeout=120)
    assert out.returncode == 0, out.stderr
    loaded, placed = out.stdout.split()
    assert loaded == "True" and int(placed) > 0


def test_before_the_first_layout_a_loaded_machine_only_raises_the_prior_contention(monkeypatch):
    """One sample before the deadlines: a machine busier than the prior
    assumes makes the prior tail (and the first fill's last resort) larger, a
    quiet one leaves the prior; once the tail is timed the samples decide."""
    monkeypatch.setattr(tail, "_cores", lambda: 2)
    parts = _parts()
    opts = NestOptions(container=ContainerSpec.sheet(200, 100), time_budget=10)
    for running, expected in ((1, tail.PRIOR_CONTENTION), (9, 4.5)):
        monkeypatch.setattr(tail, "runnable", lambda: running)
        t = tail.Tail(parts, opts)
        t.note_load(1)
        assert t.contention == expected
    t = tail.Tail(parts, opts)
    monkeypatch.setattr(tail, "runnable", lambda: 1)
    t.note_load(1)
    t.note_build(0.1, 3, cpu=0.1)
    assert t.contention == 1.0
