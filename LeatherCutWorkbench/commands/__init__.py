"""The workbench's commands: one small module per command, thin over the
document pipeline (:mod:`LeatherCutWorkbench.document.pipeline`), which in
turn calls the core stage functions.

``COMMAND_MODULES`` is the toolbar and menu order (the pipeline order); a
``None`` entry is a separator.  Importing this package is cheap (no Qt).
"""

from __future__ import annotations

import importlib
from typing import List, Optional

#: (module, command name) in toolbar / menu order; None = separator.
COMMAND_MODULES: List[Optional[tuple]] = [
    ("import_dxf", "LeatherCut_ImportDXF"),
    ("recognise", "LeatherCut_Recognise"),
    ("flag_over", "LeatherCut_FlagOver"),
    ("flag_under", "LeatherCut_FlagUnder"),
    None,
    ("auto_nest", "LeatherCut_AutoNest"),
    ("manual_nest", "LeatherCut_ManualNest"),
    None,
    ("plan_path", "LeatherCut_PlanPath"),
    ("simulate", "LeatherCut_Simulate"),
    None,
    ("post_process", "LeatherCut_PostProcess"),
    ("send_to_cutter", "LeatherCut_SendToCutter"),
    ("machine_profiles", "LeatherCut_MachineProfiles"),
    None,
    ("run_job", "LeatherCut_RunJob"),
]


def register_all() -> List[str]:
    """Register every command with FreeCAD; returns names for appendToolbar /
    appendMenu (``"Separator"`` between groups)."""
    import FreeCADGui as Gui
    names: List[str] = []
    for entry in COMMAND_MODULES:
        if entry is None:
            names.append("Separator")
            continue
        module, name = entry
        mod = importlib.import_module(f"{__name__}.{module}")
        Gui.addCommand(name, mod.COMMAND())
        names.append(name)
    return names


def command_names() -> List[str]:
    return [e[1] for e in COMMAND_MODULES if e is not None]


def context_commands() -> List[str]:
    """Commands offered in the 3D view / tree context menu."""
    return ["LeatherCut_Recognise", "LeatherCut_FlagOver", "LeatherCut_FlagUnder",
            "LeatherCut_ManualNest", "LeatherCut_PlanPath", "LeatherCut_Simulate"]
