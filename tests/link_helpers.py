"""Shared by the link tests: a job, the operator's resume loop through
:class:`SendSession` and the accounting of which job lines the fake controller
executed (aligned with what each stream sent)."""

from LeatherCutWorkbench.post import gcode
from LeatherCutWorkbench.post.link import SendSession, job_from_program
from LeatherCutWorkbench.post.profiles import load_profile, profile_from_dict

from post_helpers import sample_plan

# link_timeout: not so short that a loaded 2-core test machine looks like a lost link
FAST = dict(status_interval=0.03, link_timeout=1.0, greet_timeout=3.0, hold_timeout=1.0,
            reset_timeout=1.0, command_timeout=3.0, min_poll_interval=0.005)


def profile_for(flavour, segment_sync=False):
    name = "grbl11_knife_z_servo" if flavour == "grbl" else "grblhal_tangential"
    prof = load_profile(name)
    if segment_sync:
        prof = profile_from_dict({**prof.to_json(), "sync_every_segment": True})
    return prof


def make_job(profile, copies=2):
    """``copies`` parts of the sample plan (4 items each) on the table."""
    spots = [(0, 0), (0, 400), (400, 0), (400, 400)][:copies]
    plan = sample_plan(*spots[0])
    for dx, dy in spots[1:]:
        plan.items += sample_plan(dx=dx, dy=dy).items
    return job_from_program("job.nc", gcode.build_program(plan, profile))


def cutting_lines(job):
    """Job line indices that cut: motion lines inside a segment."""
    return {job.index[k] for k, b in enumerate(job.blocks)
            if job.segs[k] and b.lstrip("N0123456789").startswith(("G1", "G2", "G3"))}


def stream_outcome(emu, mark, session, sent):
    """Job line indices the machine executed during one stream: the lines it
    processed in the stream's own controller session align 1:1 with the
    blocks sent; motion of the job in a later session is stray."""
    rows = emu.results[mark:]
    mine = [r for r in rows if r[0] == session]
    done = []
    for k, (_, block, reply, executed) in enumerate(mine[:len(sent.blocks)]):
        assert block == sent.blocks[k] or block.startswith("#"), (k, block, sent.blocks[k])
        if executed and sent.index[k] is not None:
            done.append(sent.index[k])
    stray = [r[1] for r in rows if r[0] != session and r[3] and ("X" in r[1] or "Y" in r[1])]
    return done, stray


def send_until_done(emu, job, profile, jpath, mode, power_lost=False, max_resumes=3,
                    on_stop=None, streams=None, link_options=None, unproven=None):
    """A fresh send, then ``--resume-from auto`` until the job is done, the
    operator reconnecting (after a lost port: ``emu.reconnect(power_lost)``),
    unlocking and re-zeroing at a machine that does not home (and confirming
    it).  Returns (executed count per job line, outcomes, every emulator,
    stray moves); every emulator is closed at the end.  ``streams`` (a list)
    collects, per stream, the job lines it executed in order; ``link_options``
    go to the link (e.g. ``cut_window``); ``unproven`` (a list) collects, per
    stream, :func:`after_last_report`."""
    emus, outs, stray_all, counts = [emu], [], [], {}
    try:
        _resume_loop(emus, outs, stray_all, counts, job, profile, jpath, mode, power_lost,
                     max_resumes, on_stop, streams, link_options or {}, unproven)
    finally:
        for e in emus:
            e.close()
    return counts, outs, emus, stray_all


def _resume_loop(emus, outs, stray_all, counts, job, profile, jpath, mode, power_lost,
                 max_resumes, on_stop, streams, link_options, unproven=None):
    emu = emus[0]
    resume, confirm = None, False
    for _ in range(max_resumes + 1):
        mark, session = len(emu.results), emu.session
        s = SendSession(job, profile, emu.port, jpath, mode=mode, resume_from=resume,
                        confirm_work_zero=confirm, **{**FAST, **link_options})
        try:
            out = s.run()
        except Exception as exc:
            if resume and "nothing to resume" in str(exc):
                break
            raise
        outs.append(out)
        done, stray = stream_outcome(emu, mark, session, s.streamed)
        stray_all += stray
        if streams is not None:
            streams.append(done)
        if unproven is not None:
            unproven.append(after_last_report(emu, mark, session, s.streamed))
        for i in done:
            counts[i] = counts.get(i, 0) + 1
        if on_stop is not None:
            on_stop(emu, out)
        if out.ok:
            break
        res = out.result
        if res.status == "lost" and emu._closed:
            emu = emu.reconnect(power_lost=power_lost).start()
            emus.append(emu)
        confirm = False
        if not profile.homing:
            emu.unlock()                 # $X at the machine after an alarm
            if res.position_lost:
                emu.rezero()             # the operator sets the work zero again
                confirm = True
        resume = "auto"


def after_last_report(emu, mark, session, sent):
    """Job line indices of a stream (as in :func:`stream_outcome`) that the
    machine executed after the last status report it made before the
    stream's last executed line (reports after the stop prove nothing the
    stream used): what no report of the stream could prove executed."""
    mine = [r for r in emu.results[mark:] if r[0] == session][:len(sent.blocks)]
    where = {id(r): sent.index[k] for k, r in enumerate(mine) if sent.index[k] is not None}
    at = [n for n, e in enumerate(emu.exec_log) if id(e) in where]
    if not at:
        return set()
    marks = [n for s, n in emu.report_marks if s == session and n <= at[-1]]
    last = marks[-1] if marks else 0
    return {where[id(e)] for e in emu.exec_log[last:] if id(e) in where}
