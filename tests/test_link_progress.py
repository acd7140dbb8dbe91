"""What a status report proves executed, and the cut window
(post/link/progress.py), on a small job with known geometry."""

from LeatherCutWorkbench.post.link import job_from_lines
from LeatherCutWorkbench.post.link.progress import ExecutionProof, is_cut
from LeatherCutWorkbench.post.profiles import load_profile

LINES = ["G21 G90 G17 G94", "(seg 1:1)", "G0 X10 Y0", "G1 X20 Y0 F1000", "G1 X20 Y10",
         "(seg 1:2)", "G1 X10 Y10", "(seg 1:3)", "G1 X10 Y0", "G0 X0 Y0", "M2"]


def proof(window=2):
    profile = load_profile("grbl11_knife_z_servo")          # axes XYZ, Z = knife angle
    job = job_from_lines("p.nc", LINES)
    return job, ExecutionProof(job, profile, window)


def at(x, y):
    return {"X": x, "Y": y, "Z": 0.0}


def test_cut_blocks_are_feed_moves_inside_segments_only():
    assert is_cut("G1X20Y0F1000", "1:1") and is_cut("N12G2X1Y1I1J0", "1:1")
    assert not is_cut("G0X10Y0", "1:1") and not is_cut("G17G21", "1:1")
    assert not is_cut("G1X1", "")


def test_a_position_proves_the_blocks_before_the_move_it_lies_on():
    job, p = proof()
    sent = len(job.blocks)
    # blocks: 0 G21.., 1 G0 X10, 2 G1 X20 Y0, 3 G1 X20 Y10, 4 G1 X10 Y10, 5 G1 X10 Y0, ...
    assert p.update(at(15, 0), sent) == [0, 2]              # on block 2: 0, 1 executed
    assert p.proven == 2
    assert p.update(at(20, 10), sent) == [3, 4]             # at the very end of block 3
    assert p.update(at(20, 10), sent) == []                  # nothing new
    assert p.update(at(55, 55), sent) == []                  # on no path: proves nothing
    assert p.proven == 4


def test_a_position_on_two_paths_proves_only_the_first():
    job, p = proof()
    # (10, 0) ends block 1 (G0 X10 Y0) and ends block 5 (G1 X10 Y0): the tool may be
    # at either; only block 1 is proven
    assert p.update(at(10, 0), len(job.blocks)) == [0, 2]
    assert p.proven == 2


def test_idle_proves_what_the_controller_read_but_the_last_line():
    job, p = proof()
    read = p.ends[3]                                          # blocks 0..3 read
    p.update(None, len(job.blocks), idle=True, read_bytes=read)
    assert p.proven == 3                                      # block 3 may still run
    p.update(None, len(job.blocks), idle=True, answered=5)   # all 5 answered, none spurious
    assert p.proven == 5


def test_an_error_stops_the_proofs():
    job, p = proof()
    p.stopped = True
    assert p.update(at(20, 10), len(job.blocks)) == [] and p.proven == 0


def test_the_cut_window_holds_the_first_cut_of_a_third_segment():
    job, p = proof(window=2)
    # sent: blocks 0..4 (cuts of 1:1 and 1:2 in flight, none proven)
    assert p.allows(4, 4)                       # 1:2's first cut: second open segment
    assert not p.allows(5, 5)                   # 1:3's first cut: a third segment
    p.update(at(20, 10), 5)                     # 1:1 proven executed
    assert p.allows(5, 5)
    job, p1 = proof(window=1)
    assert p1.allows(3, 3) and not p1.allows(4, 4)
    job, p0 = proof(window=0)
    assert p0.allows(5, 5)                      # no window
    job.fence = False                           # foreign G-code: no window either
    assert ExecutionProof(job, load_profile("grbl11_knife_z_servo"), 1).allows(5, 5)


def test_a_clean_stop_on_a_closed_contour_is_located_after_the_proven_lines():
    """A closed contour ends where it started: a stop position at its end also
    lies on its first line.  Looked for from the first acknowledged line, the
    tool was placed at the contour's start and the last line was cut again
    (found with cut window 0 in the fault runs); the lines a status report
    proved executed are behind the tool, so the search starts there."""
    from LeatherCutWorkbench.post.link.recovery import _tolerances, executed_in_run
    source = ["G21 G90", "G0 X0 Y0 Z0", "G1 X10 Y0 F1000", "G1 X10 Y10", "G1 X0 Y10",
              "G1 X0 Y0", "G1 X20 Y0"]
    run = {"acked": list(range(7)), "syncs": [], "proofs": [0, 1, 2, 3, 4],
           "end": {"e": "garbled", "position": {"X": 0.0, "Y": 0.0, "Z": 0.0},
                   "position_trusted": True}}
    done, basis = executed_in_run(run, source, "XYZ", "", 360.0, _tolerances("XYZ", ""))
    assert basis == "position" and done == {0, 1, 2, 3, 4, 5}      # line 6 not yet
