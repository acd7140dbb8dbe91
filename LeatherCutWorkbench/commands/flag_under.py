"""*Flag under-recognised*: review outlines left open by small gaps."""

import FreeCAD
import FreeCADGui as Gui

from . import base, flags

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP


class FlagUnder(base.Command):
    NAME = "LeatherCut_FlagUnder"
    ICON = "FlagUnder"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_FlagUnder", "Flag under-recognised")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_FlagUnder",
                            "Step through outlines left open by a small gap and accept or reject "
                            "the proposed bridging segment for each")

    def active(self) -> bool:
        return not Gui.Control.activeDialog() and bool(flags.flags_of_kind(base.active_job(), "under"))

    def run(self) -> None:
        flags.open_flag_panel("under")


COMMAND = FlagUnder
