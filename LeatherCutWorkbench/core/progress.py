"""Progress reporting shared by long stages (import, recognition, nesting, planning).

A stage takes an optional ``progress`` callable ``progress(fraction, message)``
with ``fraction`` in [0, 1]; it returns False when the user asked to cancel, and
the stage then raises :class:`~LeatherCutWorkbench.core.errors.CancelledError`.
The CLI passes a terminal bar, the workbench FreeCAD's progress indicator.
"""

from typing import Callable, Optional

from .errors import CancelledError

ProgressFn = Callable[[float, str], bool]


def report(progress: Optional[ProgressFn], fraction: float, message: str) -> None:
    """Call ``progress`` if given; raise CancelledError when it asks to stop."""
    if progress is not None and progress(min(max(fraction, 0.0), 1.0), message) is False:
        raise CancelledError(f"cancelled during: {message}")
