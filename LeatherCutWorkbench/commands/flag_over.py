"""*Flag over-recognised*: review closed regions that are probably not parts."""

import FreeCAD
import FreeCADGui as Gui

from . import base, flags

QT_TRANSLATE_NOOP = FreeCAD.Qt.QT_TRANSLATE_NOOP


class FlagOver(base.Command):
    NAME = "LeatherCut_FlagOver"
    ICON = "FlagOver"
    MENU = QT_TRANSLATE_NOOP("LeatherCut_FlagOver", "Flag over-recognised")
    TIP = QT_TRANSLATE_NOOP("LeatherCut_FlagOver",
                            "Step through closed regions that are probably not parts "
                            "(scrap between common-edge parts, group outlines) and include or exclude each")

    def active(self) -> bool:
        return not Gui.Control.activeDialog() and bool(flags.flags_of_kind(base.active_job(), "over"))

    def run(self) -> None:
        flags.open_flag_panel("over")


COMMAND = FlagOver
