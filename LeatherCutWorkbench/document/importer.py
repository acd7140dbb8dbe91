"""File > Open / File > Import hook for DXF drawings (``FreeCAD.addImportType``).

FreeCAD calls ``open(filename)`` (new document) or ``insert(filename, docname)``
(into an existing document).  Both create a LeatherCut Job for the file and
import the drawing into it, grouped by layer, with FreeCAD's progress bar.

A file that cannot be imported (empty, not a DXF, unreadable) leaves nothing
behind: the job -- and the document ``open`` made for it -- is removed again.
In the GUI the reason is shown in a dialog (FreeCAD would print a traceback
for an exception raised from here); headless, the
:class:`~LeatherCutWorkbench.core.errors.LeatherCutError` is raised.
"""

from __future__ import annotations

import os

import FreeCAD

from ..core.errors import LeatherCutError
from . import objects, pipeline
from .progress import FreeCADProgress

if FreeCAD.GuiUp:
    # FreeCAD's own importers keep a reference to the built-in open()
    pythonopen = open  # noqa: A001


def _import_into(doc, filename: str):
    """The job made for ``filename`` in ``doc``, or None (GUI) when the file
    cannot be imported; nothing of the failed job is left in ``doc``."""
    job = pipeline.make_job(doc, os.path.splitext(os.path.basename(filename))[0], filename)
    try:
        with FreeCADProgress(f"LeatherCut: importing {os.path.basename(filename)}") as progress:
            pipeline.run_stage(job, "Import", progress)
    except (LeatherCutError, OSError) as exc:
        objects.remove_tree(job)
        doc.recompute()
        if not FreeCAD.GuiUp:
            FreeCAD.Console.PrintError(f"LeatherCut: {exc}\n")
            raise
        from ..commands import base  # GUI only: the workbench's error dialog
        base.show_error("Import DXF", base.file_error_text(exc) if isinstance(exc, OSError)
                        else str(exc))
        return None
    doc.recompute()
    return job


def open(filename: str):  # noqa: A001 - name required by FreeCAD's import machinery
    """Open ``filename`` in a new document; returns the document (None when the
    file could not be imported: the new document is closed again)."""
    name = os.path.splitext(os.path.basename(filename))[0]
    doc = FreeCAD.newDocument(_doc_name(name))
    doc.Label = name
    try:
        job = _import_into(doc, filename)
    except LeatherCutError:
        FreeCAD.closeDocument(doc.Name)
        raise
    if job is None:
        FreeCAD.closeDocument(doc.Name)
        return None
    return doc


def insert(filename: str, docname: str):
    """Import ``filename`` into the document ``docname`` (created when missing);
    returns the job (None when the file could not be imported)."""
    try:
        doc = FreeCAD.getDocument(docname)
    except NameError:
        doc = FreeCAD.newDocument(docname)
    FreeCAD.setActiveDocument(doc.Name)
    return _import_into(doc, filename)


def _doc_name(label: str) -> str:
    clean = "".join(ch if ch.isalnum() else "_" for ch in label) or "Job"
    return clean if not clean[0].isdigit() else "_" + clean
