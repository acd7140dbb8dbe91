"""Property tests of the live link over random faults (seeded, bounded).

Every case streams a real job (two parts, 8 items) through pyserial into the
fault-injecting fake controller, with one fault at a random line: an error,
a soft or hard limit alarm, a power cycle (at the line or 20 ms after it), a
stall (short: not a fault; long: the link is lost), a disconnect with or
without a power loss, a corrupted line, a garbled reply (``o\\xffk``), a
spurious ``ok`` (alone, or followed by a power cycle 20 ms later) or a lost
``ok``; replies arrive whole or byte by byte (split reads).  Then it resumes
with ``--resume-from auto`` through :class:`SendSession` (the code ``leathercut
send`` runs) until the job is done, re-zeroing at the machine and confirming
it when the position was lost on a machine that does not home.

Over the original run plus the resumes it asserts:

* every cutting line of the job was executed, at the right place (no line
  lost, none cut with a wrong work zero);
* lines executed more than once are only those of the documented re-cut: the
  segment the resume starts at with a sync after every segment, or the
  interrupted item from the resume point on with the shipped item syncs;
* the controller's receive buffer never held more than RX - 1 bytes (never
  overflowed);
* whenever the report says "stopped safely" the controller really is Idle
  with the knife up and the spindle off.

``test_fault_summary`` prints runs / lines lost / lines repeated / max bytes
in flight (run pytest with ``-s`` or ``-rA`` to see it).  28 cases by
default; ``LEATHERCUT_FAULT_RUNS=N`` runs N.
"""

import os
import random

import pytest

from LeatherCutWorkbench.post.emulator import FakeController, Fault

from link_helpers import cutting_lines, make_job, profile_for, send_until_done

# 28 cases (2 of each kind) keep the file near half a minute on a loaded 2-core
# machine; LEATHERCUT_FAULT_RUNS=200 runs more for a report
SEEDS = list(range(int(os.environ.get("LEATHERCUT_FAULT_RUNS", "28"))))
SUMMARY = {"runs": 0, "streams": 0, "faults fired": 0, "lines lost": 0, "lines repeated": 0,
           "misplaced": 0, "overflows": 0, "stopped safely": 0, "kinds": {}}

KINDS = ["error", "alarm2", "alarm1", "reset", "reset_after", "stall_short", "stall_long",
         "disconnect_keep", "disconnect_power", "garble", "garble_reply", "spurious",
         "spurious_reset", "drop_ack"]


def faults_for(kind, line, rnd):
    if kind == "error":
        return [Fault("error", line, code=rnd.choice([20, 33, 36]))]
    if kind in ("alarm1", "alarm2"):
        return [Fault("alarm", line, code=int(kind[-1]))]
    if kind == "reset":
        return [Fault("reset", line)]
    if kind == "reset_after":
        return [Fault("reset", line, after=0.02)]
    if kind == "stall_short":
        return [Fault("stall", line, seconds=0.2)]
    if kind == "stall_long":
        return [Fault("stall", line, seconds=1.6)]
    if kind.startswith("disconnect"):
        return [Fault("disconnect", line)]
    if kind == "spurious_reset":
        return [Fault("spurious", line), Fault("reset", line, after=0.02)]
    return [Fault(kind, line)]


def check_stop(emu, res, profile):
    if res is None or not res.stopped_safely:
        return 0
    assert "Stopped safely" in res.stop_summary()
    assert emu.state == "Idle" and emu.spindle == "M5", (emu.state, emu.spindle)
    if profile.lift_axis:
        assert emu.position[profile.lift_axis] >= profile.z_up - 1e-6
    return 1


def run_case(seed, tmp_path):
    rnd = random.Random(seed)
    flavour = rnd.choice(["grbl", "grblhal"])
    segment_sync = rnd.random() < 0.5
    profile = profile_for(flavour, segment_sync)
    job = make_job(profile)
    kind = KINDS[seed % len(KINDS)]
    mode = rnd.choice(["send-response", "char-count"])
    planner = rnd.choice([0, 6])
    line = rnd.randint(1, len(job.blocks))
    split = rnd.random() < 0.25
    axes = "XYZ" if flavour == "grbl" else "XYZC"
    jpath = str(tmp_path / "job.journal")
    emu = FakeController(flavour=flavour, axes=axes, homing=profile.homing,
                         planner_blocks=planner, block_time=0.002, split=split,
                         faults=faults_for(kind, line, rnd)).start()
    stopped = []
    counts, outs, emus, stray_all = send_until_done(
        emu, job, profile, jpath, mode, power_lost=kind == "disconnect_power",
        on_stop=lambda e, out: stopped.append(check_stop(e, out.result, profile)))
    if not outs[-1].ok and outs[-1].resume_from is not None:
        pytest.fail(f"seed {seed} ({kind}): not done after 3 resumes")
    SUMMARY["streams"] += len(outs)
    SUMMARY["stopped safely"] += sum(stopped)
    resumed = [o.resumed_from for o in outs if o.resumed_from]
    fired = all(f.fired for f in emus[0].faults)
    cut = cutting_lines(job)
    lost = sorted(i for i in cut if counts.get(i, 0) == 0)
    repeated = sorted(i for i in cut if counts.get(i, 0) > 1)
    # the documented re-cut: the segment (segment syncs) or the rest of the item
    # (item syncs) from each resume point; nothing else may be cut twice
    allowed = set()
    for seg in resumed:
        item = seg.split(":")[0]
        for k, sg in enumerate(job.segs):
            if sg == seg or (not segment_sync and sg.split(":")[0] == item
                             and job.segment_ids.index(sg) >= job.segment_ids.index(seg)):
                allowed.add(job.index[k])
    where = f"seed {seed}: {kind} at line {line}, {flavour} {mode} planner {planner} " \
            f"segment_sync {segment_sync} split {split}, resumed {resumed}"
    SUMMARY["lines lost"] += len(lost)
    assert not lost, f"{where}: lines never cut {[job.source[i] for i in lost][:5]}"
    assert set(repeated) <= allowed, f"{where}: cut twice {sorted(set(repeated) - allowed)}"
    assert not stray_all, f"{where}: job moves after the stop {stray_all}"
    misplaced = sum(e.misplaced for e in emus)
    assert misplaced == 0, f"{where}: {misplaced} lines cut in the wrong place"
    rx_max = max(e.max_rx for e in emus)
    assert rx_max <= emus[0].rx_size - 1 and sum(e.overflows for e in emus) == 0, where
    SUMMARY["runs"] += 1
    SUMMARY["faults fired"] += fired
    SUMMARY["lines repeated"] += sum(counts[i] - 1 for i in repeated)
    key = f"max bytes in flight (RX {emus[0].rx_size})"
    SUMMARY[key] = max(SUMMARY.get(key, 0), rx_max)
    SUMMARY["kinds"][kind] = SUMMARY["kinds"].get(kind, 0) + 1


@pytest.mark.parametrize("seed", SEEDS)
def test_fault_property(seed, tmp_path):
    run_case(seed, tmp_path)


def test_fault_summary():
    """Runs after the cases (same module, file order): prints the figures."""
    if SUMMARY["runs"] == 0:
        pytest.skip("no fault case ran")
    print("\nlink fault runs: " + ", ".join(f"{k} {v}" for k, v in SUMMARY.items()))
    assert SUMMARY["lines lost"] == 0 and SUMMARY["misplaced"] == 0
    assert SUMMARY.get("max bytes in flight (RX 128)", 0) <= 127
