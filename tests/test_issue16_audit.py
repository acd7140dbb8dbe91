"""Issue #16 audit: the items of the issue that had no test which would fail
if they regressed.  Where the others are tested:

1. old journal / per run -- test_link_regressions: a_fresh_run_never_inherits...,
   a_completed_job_then_a_new_stop..., a_resume_of_an_earlier_pass...
2. truncated job.nc -- a_truncated_or_edited_job_file_is_refused...,
   a_full_disk_leaves_no_truncated_job_file, writers_refuse_a_fifo...
3. profile lines past the check -- test_safety_output (line breaks, header/footer
   motion, every line checked), test_link_regressions: the_lines_the_link_makes...
4. garbled ok -- a_garbled_ok_stops_safely..., a_lost_ok_is_a_fault...
5. false "stopped safely" -- after_a_limit_alarm_the_report_never_says...,
   test_link_properties (check_stop on every "stopped safely")
6. spurious ok -- a_spurious_ok_never_overflows..., several_spurious_oks...,
   here: the_sender_never_counts_more_acks...
7. re-zero, port lock, swallowed sync -- a_resume_after_a_power_reset_needs...,
   two_senders_cannot_open_one_port, a_disconnect_that_swallows...,
   a_swallowed_item_sync_ok_repeats_at_most_the_interrupted_segment
8. hostile input -- test_hostile_import, test_hostile_corpus, test_safety_output
   (profile numbers); here: the import size limit
9. arc limit, $701, re-poll, stop report -- grbls_absolute_arc_radius_limit,
   grblhal_feed_on_linear_axes_only..., one_unanswered_status_poll...,
   the_stop_report_names_where_the_tool_is
Must have: the fault double and property tests (test_link_faults,
test_link_properties), journal per run and sealed job files (1, 2 above)."""

import time

from LeatherCutWorkbench.cli import main
from LeatherCutWorkbench.core.dxfimport import limits
from LeatherCutWorkbench.post.emulator import FakeController, Fault
from LeatherCutWorkbench.post.link import load_journal

from link_helpers import make_job, profile_for, send_until_done


def test_a_file_over_the_import_size_limit_is_refused_without_reading_it(tmp_path, capsys):
    """Issue #16, 8 (bounded memory and time): a drawing larger than the
    documented import limit is refused at once by its size (a sparse file:
    nothing is read), exit 2, one line naming the file."""
    big = tmp_path / "huge.dxf"
    with open(big, "wb") as fh:
        fh.truncate(limits.MAX_FILE_BYTES + 1)
    t0 = time.monotonic()
    assert main(["inspect", str(big)]) == 2
    assert time.monotonic() - t0 < 5
    err = capsys.readouterr().err.strip()
    assert "huge.dxf" in err and "MiB limit" in err and len(err.splitlines()) == 1
    assert "Traceback" not in err


def test_the_sender_never_counts_more_acks_than_lines_sent(tmp_path):
    """Issue #16, 6: acknowledgements beyond the lines sent are spurious --
    counted and journaled apart, never as acks of a line; every line is
    acknowledged once in the journal."""
    profile = profile_for("grblhal")
    job = make_job(profile, copies=1)
    extra = [Fault("spurious", 12), Fault("spurious", 12), Fault("spurious", 30)]
    emu = FakeController(flavour="grblhal", axes="XYZC", homing=True, faults=extra).start()
    jpath = str(tmp_path / "j")
    counts, outs, emus, stray = send_until_done(emu, job, profile, jpath, "send-response")
    res = outs[-1].result
    assert outs[-1].ok and res.acked == res.total == len(job.blocks)
    assert res.spurious_acks >= 1
    st = load_journal(jpath)
    assert sorted(st.acked) == sorted(i for i in job.index if i is not None)
    assert sum(1 for e in st.events if e["e"] == "spurious") == res.spurious_acks
