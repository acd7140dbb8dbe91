"""LeatherCut: DXF drawing -> recognised parts -> nesting -> cut path -> machine.

``core`` holds the algorithms and the job model (no FreeCAD GUI; only
recognition imports FreeCAD ``Part``), ``post`` the writers and the machine
link, ``commands`` the thin FreeCAD GUI layer, ``cli`` the ``leathercut`` command.
"""

__version__ = "0.1.0"
