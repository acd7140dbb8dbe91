"""Contour recognition: which imported edges form closed part contours (outer
outlines with holes, islands in holes), lead-ins / lead-outs and stray open
chains, with flags for over- and under-recognised contours.

Public entry point::

    from LeatherCutWorkbench.core.recognition import recognise, RecogniseOptions
    recognition = recognise(drawing, RecogniseOptions(join_tol=0.01, gap_tol=0.5))

Geometry is built with FreeCAD ``Part`` (faces, arrangement of common edges);
the result holds only plain :mod:`core.geometry` segments (mm, degrees).
"""

from .options import RecogniseOptions
from .recognise import recognise

__all__ = ["recognise", "RecogniseOptions"]
