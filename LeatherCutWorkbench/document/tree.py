"""Finding LeatherCut objects in a document: roles, the job of an object, stage
objects, stored stage values.

Imported by :mod:`.objects` (which re-exports these names), :mod:`.pipeline`
and the GUI's :mod:`.viewproviders`; it imports none of them, so the view
providers need not import the object definitions that create them.
"""

from __future__ import annotations

from typing import Any, Iterable, List

from . import codec


def role(obj) -> str:
    return getattr(obj, "Role", "") if obj is not None else ""


def is_job(obj) -> bool:
    return role(obj) == "Job"


def job_of(obj):
    """The Job that (directly or indirectly) contains ``obj`` (or ``obj`` itself)."""
    seen = set()
    while obj is not None and obj.Name not in seen:
        if is_job(obj):
            return obj
        seen.add(obj.Name)
        parents = [p for p in obj.InList if obj in (getattr(p, "Group", None) or [])]
        obj = parents[0] if parents else None
    return None


def jobs(doc) -> List[Any]:
    return [o for o in doc.Objects if is_job(o)] if doc is not None else []


def stage_object(job, role_name: str):
    """The job's child with the given role (``Drawing``, ``Recognition``, ...)."""
    if job is None:
        return None
    for o in job.Group:
        if role(o) == role_name:
            return o
    return None


def walk(obj) -> Iterable[Any]:
    """The object and everything in its groups, depth first."""
    yield obj
    for child in getattr(obj, "Group", []) or []:
        yield from walk(child)


def load_data(obj) -> Any:
    """The stage value stored in ``obj.Data`` (None when empty)."""
    if obj is None or "Data" not in obj.PropertiesList:
        return None
    return codec.loads(obj.Data)
