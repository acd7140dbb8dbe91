"""FreeCAD's progress indicator as a stage ``progress(fraction, message)`` callback.

In ``freecadcmd`` it prints percentages, in the GUI it drives the status-bar
progress bar; ``next(True)`` lets the user abort (Esc), which we turn into
``False`` (cancel) for the stage.  Use only from the main thread.
"""

from __future__ import annotations

import FreeCAD

STEPS = 100


class FreeCADProgress:
    """Context manager yielding a ``progress(fraction, message) -> bool`` callable."""

    def __init__(self, title: str):
        self.title = title
        self.done = 0
        self.bar = None

    def __enter__(self):
        self.bar = FreeCAD.Base.ProgressIndicator()
        self.bar.start(self.title, STEPS)
        return self

    def __call__(self, fraction: float, message: str) -> bool:
        target = int(round(max(0.0, min(1.0, fraction)) * STEPS))
        try:
            while self.done < target:
                self.done += 1
                self.bar.next(True)
        except Exception:  # FreeCAD raises when the user pressed Esc
            return False
        return True

    def __exit__(self, *exc):
        self.bar.stop()
        return False
