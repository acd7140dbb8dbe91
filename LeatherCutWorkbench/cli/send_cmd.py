"""``leathercut send``: stream a job live to a GRBL-family controller.

FILE is a drawing (``.dxf``: planned and posted like ``leathercut post``) or a
ready G-code file (``.nc``, ``.ngc``, ``.gcode``, ``.tap``).  Every
acknowledged line goes into the journal; after a stop the report names the
segment to resume from, and ``--resume-from`` continues there.  Ctrl-C stops
the job safely (feed hold, reset, knife up); SIGUSR1 toggles pause/resume.
Documented in docs/CLI.md (``send``) and docs/LINK.md.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import time

from . import Report, add_common_options
from ..core.errors import InputError
from . import post_cmd
from .stages import add_stage_options, positive

GCODE_EXT = (".nc", ".ngc", ".gcode", ".tap", ".cnc", ".txt")


def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    g = parser.add_argument_group("live link")
    g.add_argument("--port", dest="send_port", required=True, metavar="URL",
                   help="pyserial URL: /dev/ttyUSB0, COM3, socket://host:port, rfc2217://..., "
                        "or emulator:grbl / emulator:grblhal for the built-in fake controller")
    g.add_argument("--baud", dest="send_baud", type=int, default=None, metavar="BAUD",
                   help="baud rate (default: the profile's, 115200)")
    g.add_argument("--check", dest="send_check", action="store_true",
                   help="run the whole job in the controller's check mode ($C) first; "
                        "stream only when it passes")
    g.add_argument("--mode", dest="send_mode", choices=("send-response", "char-count"),
                   default="send-response",
                   help="send-response (one line, wait for ok) or char-count (fill the "
                        "controller's receive buffer; default send-response)")
    g.add_argument("--resume-from", dest="send_resume", metavar="SEGMENT",
                   help="continue an interrupted job at segment ITEM:SEG (e.g. 3:5), or 'auto' "
                        "for the first segment the journal does not show complete")
    g.add_argument("--journal", dest="send_journal", metavar="PATH",
                   help="job journal (default FILE.journal next to the job)")
    g.add_argument("--no-home", dest="send_no_home", action="store_true",
                   help="never send $H; refuse when the controller is locked in Alarm")
    g.add_argument("--link-timeout", dest="send_link_timeout", type=positive, default=3.0,
                   metavar="S", help="no status reply for S seconds (after two re-polls) = "
                                     "link lost (default 3)")
    g.add_argument("--confirm-work-zero", dest="send_confirm_zero", action="store_true",
                   help="resume after a stop that lost the machine position (power or reset, "
                        "lost link, ALARM:1/3) on a machine that does not home: you have set "
                        "the work zero again at the machine")
    g.add_argument("--cut-window", dest="send_cut_window", type=int, choices=range(0, 9),
                   default=0, metavar="N",
                   help="segments whose cutting lines may be in flight before a status "
                        "report proves them executed (default 0: no limit, full look-ahead; "
                        "after a power loss the re-cut is the interrupted segment plus at "
                        "most what was cut since the last status report; 2: at most the "
                        "segment before it too; 1: only the interrupted segment, the head "
                        "stops at every segment end)")
    g.add_argument("--allow-unsealed", dest="send_allow_unsealed", action="store_true",
                   help="stream a hand-written G-code file that has no LeatherCut end marker "
                        "(never a truncated LeatherCut job)")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("send", help="stream a job live to a GRBL / grblHAL controller",
                       description="Stream FILE (a DXF, planned and posted like 'post', or a "
                                   "ready .nc G-code file) to a GRBL-family controller, "
                                   "journaling every acknowledged line; stop safely on any "
                                   "error, alarm or lost link; resume from a segment.")
    p.add_argument("file", metavar="FILE", help="DXF drawing or G-code file (.nc/.ngc/.gcode)")
    add_common_options(p)
    add_stage_options(p, before="end")
    post_cmd.add_options(p, primary=False)
    add_options(p, primary=True)
    p.set_defaults(func=run)


def load_job(args: argparse.Namespace, profile):
    """The SendJob for FILE: G-code files as they are (safety-checked), drawings
    planned and posted for ``profile``."""
    from ..post import safety, tool_export
    from ..post.link import job_from_file, job_from_program

    if not os.path.isfile(args.file):
        raise InputError("no such file", source=args.file)
    if args.file.lower().endswith(GCODE_EXT):
        job = job_from_file(args.file, allow_unsealed=args.send_allow_unsealed)
        safety.check_program(job.source, profile, args.file)
        return job
    overrides = post_cmd.tool_overrides(args)
    tool_export.tool_map(profile, overrides)       # a bad --tool-map fails before planning
    result = post_cmd.plan_drawing(args, profile)
    prog = tool_export.program(result.plan, result.parts_to_cut, profile, overrides)
    name = os.path.splitext(os.path.basename(args.file))[0] + ".nc"
    return job_from_program(name, prog)


class TerminalProgress:
    """One self-overwriting status line on stderr, at most 10 updates per second."""

    def __init__(self, enabled: bool):
        self.enabled = enabled and sys.stderr.isatty()
        self.last = 0.0

    def __call__(self, info) -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if now - self.last < 0.1 and info["acked"] != info["total"]:
            return
        self.last = now
        sys.stderr.write(f"\r{info['percent']:5.1f}%  {info['acked']}/{info['total']} lines  "
                         f"{info['state'] or '-':8s} segment {info['segment'] or '-':8s}")
        sys.stderr.flush()

    def done(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")


def _open_port(url: str, profile):
    """(url to open, emulator or None): ``emulator:grbl``/``emulator:grblhal``
    start the built-in fake controller with the profile's axes."""
    if not url.startswith("emulator:"):
        return url, None
    from ..post.emulator import FakeController

    flavour = url.split(":", 1)[1] or "grblhal"
    if flavour not in ("grbl", "grblhal"):
        raise InputError("emulator flavour must be grbl or grblhal", source=url)
    emu = FakeController(flavour=flavour, axes=profile.axes, homing=profile.homing).start()
    return emu.port, emu


def run(args: argparse.Namespace) -> Report:
    from ..post.link import LinkError
    from ..post.link.session import SendSession
    from ..post.profiles import load_profile

    profile = load_profile(args.post_machine)
    if not profile.is_gcode:
        raise InputError(f"profile {profile.name} is for {profile.dialect}; send streams G-code "
                         "to GRBL-family controllers", source=args.post_machine)
    job = load_job(args, profile)
    jpath = args.send_journal or os.path.splitext(args.file)[0] + ".journal"
    url, emu = _open_port(args.send_port, profile)
    progress = TerminalProgress(not args.json)
    session = SendSession(job, profile, url, jpath, mode=args.send_mode, check=args.send_check,
                          home=not args.send_no_home, resume_from=args.send_resume,
                          baud=args.send_baud, progress=progress,
                          confirm_work_zero=args.send_confirm_zero,
                          link_timeout=args.send_link_timeout,
                          cut_window=args.send_cut_window)
    old_int = signal.signal(signal.SIGINT, lambda *a: session.abort())
    old_usr = None
    if hasattr(signal, "SIGUSR1"):
        old_usr = signal.signal(signal.SIGUSR1,
                                lambda *a: (session.resume if session.paused else session.pause)())
    try:
        out = session.run()
    except LinkError as exc:
        raise InputError(exc.message, source=exc.source)
    finally:
        signal.signal(signal.SIGINT, old_int)
        if old_usr is not None:
            signal.signal(signal.SIGUSR1, old_usr)
        progress.done()
        if emu is not None:
            emu.close()
    data = {"file": args.file, "port": args.send_port, "machine": profile.name,
            "mode": args.send_mode, **out.to_json(), "findings": []}
    if out.check is not None and not out.check.ok:
        chk = out.check
        return Report(data=data, exit_code=1,
                      text=f"{args.file}: check mode refused the job at line {chk.line}: "
                           f"{chk.block} -> {chk.message}; nothing was cut")
    res = out.result
    if res.ok:
        return Report(data=data, text=f"{args.file}: job done, {res.acked} lines acknowledged "
                                      f"(journal {jpath})")
    where = f" at line {res.line} ({res.block}), segment {res.segment}" if res.line else ""
    tool = out.tool_at
    if tool and tool["how"] == "on":
        at = (f"The tool stopped on line {tool['line']} ({tool['block']}), segment "
              f"{tool['segment'] or '-'} (from the position the controller reported). ")
    elif tool and out.basis == "position":
        at = (f"The tool stopped at the end of line {tool['line']} ({tool['block']}), segment "
              f"{tool['segment'] or '-'} (from the position the controller reported). ")
    elif tool:
        at = (f"Last line known executed: {tool['line']} ({tool['block']}), segment "
              f"{tool['segment'] or '-'}. ")
    else:
        at = "No line of this run is known executed. "
    lost = (" The machine position was lost: home it, or set the work zero again and add "
            "--confirm-work-zero." if res.position_lost else "")
    text = (f"{args.file}: job stopped ({res.status}){where}: {res.message}. {at}"
            f"{res.stop_summary()}{lost} Journal {jpath}; resume with --resume-from "
            f"{out.resume_from}"
            + (" (from where the controller reported the tool stopped)." if out.basis == "position"
               else " (from the last point the status reports proved executed; the interrupted "
                    "segment may be cut again)." if out.basis == "status"
               else " (from the last point verified executed; part of the item being cut may "
                    "be cut again)."))
    return Report(data=data, text=text, exit_code=1)
