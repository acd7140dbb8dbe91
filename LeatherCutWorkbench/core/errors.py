"""Errors a user can act on.

Stages raise :class:`InputError` (bad or unusable input) or
:class:`LeatherCutError` (anything else a person must know about).  The message
names the file, entity or line concerned; the CLI prints it as one line on
stderr and exits non-zero, the GUI shows it in a dialog.  Never raise bare
exceptions for user mistakes.
"""

from typing import Optional


class LeatherCutError(Exception):
    """A failure with a message meant for the user.

    ``source`` names what it is about (file path, entity handle, line number)
    and is put in front of the message."""

    def __init__(self, message: str, source: Optional[str] = None):
        super().__init__(message)
        self.message = message
        self.source = source

    def __str__(self) -> str:
        return f"{self.source}: {self.message}" if self.source else self.message


class InputError(LeatherCutError):
    """The input (file, option, geometry) cannot be used."""


class SafetyError(LeatherCutError):
    """Output would drive the machine outside its limits; nothing was written."""


class CancelledError(LeatherCutError):
    """The user cancelled a long operation."""
