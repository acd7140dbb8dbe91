"""File > Open / File > Import hook for DXF drawings (``FreeCAD.addImportType``).

FreeCAD calls ``open(filename)`` (new document) or ``insert(filename, docname)``
(into an existing document).  Both create a LeatherCut Job for the file and
import the drawing into it, grouped by layer, with FreeCAD's progress bar.
Bad files raise :class:`~LeatherCutWorkbench.core.errors.InputError` after a
one-line message in the report view.
"""

from __future__ import annotations

import os

import FreeCAD

from ..core.errors import LeatherCutError
from . import pipeline
from .progress import FreeCADProgress

if FreeCAD.GuiUp:
    # FreeCAD's own importers keep a reference to the built-in open()
    pythonopen = open  # noqa: A001


def _import_into(doc, filename: str):
    job = pipeline.make_job(doc, os.path.splitext(os.path.basename(filename))[0], filename)
    try:
        with FreeCADProgress(f"LeatherCut: importing {os.path.basename(filename)}") as progress:
            pipeline.run_stage(job, "Import", progress)
    except LeatherCutError as exc:
        FreeCAD.Console.PrintError(f"LeatherCut: {exc}\n")
        raise
    doc.recompute()
    return job


def open(filename: str):  # noqa: A001 - name required by FreeCAD's import machinery
    """Open ``filename`` in a new document; returns the document."""
    name = os.path.splitext(os.path.basename(filename))[0]
    doc = FreeCAD.newDocument(_doc_name(name))
    doc.Label = name
    _import_into(doc, filename)
    return doc


def insert(filename: str, docname: str):
    """Import ``filename`` into the document ``docname`` (created when missing)."""
    try:
        doc = FreeCAD.getDocument(docname)
    except NameError:
        doc = FreeCAD.newDocument(docname)
    FreeCAD.setActiveDocument(doc.Name)
    return _import_into(doc, filename)


def _doc_name(label: str) -> str:
    clean = "".join(ch if ch.isalnum() else "_" for ch in label) or "Job"
    return clean if not clean[0].isdigit() else "_" + clean
