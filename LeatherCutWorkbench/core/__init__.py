"""Algorithms and the job model.  Must not import FreeCAD GUI modules."""
