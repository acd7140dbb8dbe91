"""Messages from the core written for the GUI.

The core's errors and findings are worded for the command line: they name CLI
options (``--move-to-origin MM``, ``--sheet/--hide``) the GUI does not have.
:func:`for_gui` rewrites them into the panel or property where the GUI keeps
the same setting, and prints areas readably (``4.141e+04 mm2`` ->
``41 410 mm²``).  Every message a panel, dialog or the report view shows goes
through it.  No Qt here: plain text in, plain text out.
"""

from __future__ import annotations

import re
from typing import List, Tuple

from ..core.readable import readable_area

#: (CLI wording, GUI wording), most specific first; applied in order.
OPTION_TEXT: List[Tuple[str, str]] = [
    (r"with --move-to-origin MM, or nest it with --sheet/--hide",
     "by ticking 'Move the drawing to the machine origin' in Plan path, or nest it on a "
     "sheet, strip or hide with Auto-nest"),
    (r"--move-to-origin(?: MM)?", "'Move the drawing to the machine origin' in Plan path"),
    (r"--sheet/--hide", "Auto-nest (sheet, strip or hide)"),
    (r"use --cut-layers / --not-cut-layers to change this",
     "change the job's ImportCutLayers / ImportNotCutLayers properties to cut it"),
    (r"--cut-layers", "ImportCutLayers"),
    (r"--not-cut-layers", "ImportNotCutLayers"),
    (r"choose the unit with --units if it is wrong", "choose the Units in Import DXF if it is wrong"),
    (r"--units ([A-Za-z]+)", r"Units = \1 in Import DXF"),
    (r"--units", "Units (Import DXF)"),
    (r"--pattern-mode", "Pattern files (Import DXF)"),
    (r"--cleanup-tol", "Clean-up tolerance (Import DXF)"),
    (r"--accept-fix", "Accept fix (Flag under-recognised)"),
    (r"--include/--exclude", "the parts list and Flag over-recognised"),
    (r"--close-gaps", "Accept fix (Flag under-recognised)"),
    (r"--join-tol", "Join tolerance (Recognise)"),
    (r"--gap-tol", "Gap tolerance (Recognise)"),
    (r"--chord-tol", "Chord tolerance (Recognise)"),
    (r"--rotations", "Rotations (Auto-nest)"),
    (r"--strip W", "a strip (Auto-nest)"),
    (r"--engine own", "Engine = own (Auto-nest)"),
    (r"--resume-from", "Resume from (Send to cutter)"),
    (r"--confirm-work-zero", "'The work zero was set again at the machine' ticked (Send to cutter)"),
    (r"--journal file", "journal file"),
]
_COMPILED = [(re.compile(a), b) for a, b in OPTION_TEXT]
#: a CLI option left over: ``--foo-bar`` -> ``'foo bar'``
_ANY_OPTION = re.compile(r"(?<![\w-])--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)")
_AREA = re.compile(r"(-?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?) ?mm(?:2|\^2|²)")


def for_gui(text: str) -> str:
    """``text`` with CLI option names replaced by GUI settings and areas readable."""
    for pattern, repl in _COMPILED:
        text = pattern.sub(repl, text)
    text = _ANY_OPTION.sub(lambda m: "'" + m.group(1).replace("-", " ") + "'", text)
    return _AREA.sub(lambda m: readable_area(float(m.group(1))), text)
