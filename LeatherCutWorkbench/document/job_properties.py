"""Job properties that are not plain fields of a stage's options dataclass.

The nesting container as separate properties (kind, sheet, strip, hide), the
un-nested move to the origin, the machine profile as the planner's source of
speeds, the layout gate override and Run job's re-nest choice.  Added when a
job is made and again when a saved job is reopened (newer properties appear
with their defaults).  Used by :mod:`.objects` and :mod:`.pipeline`; imports
neither.
"""

from __future__ import annotations

CONTAINER_KINDS = ["none", "sheet", "strip", "hide"]


def add_nest_container_properties(job) -> None:
    """The nesting container as separate properties (kind, sheet, strip, hide)."""
    props = [
        ("App::PropertyEnumeration", "NestContainer",
         "what to nest on: none (cut the drawing where it lies), sheet, strip or hide"),
        ("App::PropertyFloat", "NestSheetWidth", "sheet width (X), mm"),
        ("App::PropertyFloat", "NestSheetHeight", "sheet height (Y), mm"),
        ("App::PropertyInteger", "NestSheetCount", "at most this many sheets (0 = open sheets as needed)"),
        ("App::PropertyFloat", "NestStripWidth", "strip width (Y), mm; the length along X is minimised"),
        ("App::PropertyFile", "NestHideFile", "DXF with the hide outline, defects and quality zones"),
    ]
    for ptype, name, tip in props:
        if name not in job.PropertiesList:
            job.addProperty(ptype, name, "Nest", tip)
            if name == "NestContainer":
                job.NestContainer = CONTAINER_KINDS
                job.NestContainer = "none"
    if job.NestSheetWidth == 0 and job.NestSheetHeight == 0:
        job.NestSheetWidth, job.NestSheetHeight = 1000.0, 1000.0
    if job.NestStripWidth == 0:
        job.NestStripWidth = 1000.0
    if "PlanMoveToOrigin" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "PlanMoveToOrigin", "Plan",
                        "without nesting: move the drawing so its lower-left corner lies "
                        "PlanOriginOffset from machine zero (drawings often lie far from it)")
        job.addProperty("App::PropertyFloat", "PlanOriginOffset", "Plan",
                        "distance of the moved drawing's lower-left corner from machine zero, mm")
        job.PlanOriginOffset = 10.0
    if "AllowInvalidLayout" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "AllowInvalidLayout", "Plan",
                        "experts: plan, post and send a layout with overlaps, spacing or margin "
                        "violations, parts outside the container or on a defect anyway "
                        "(every problem is logged in the report view)")
    if "RunNestAgain" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "RunNestAgain", "Nest",
                        "Run job nests the parts again, replacing the current (maybe hand-placed) "
                        "layout; off: Run job cuts the current layout as it stands")
    if "PlanFromMachine" not in job.PropertiesList:
        job.addProperty("App::PropertyBool", "PlanFromMachine", "Plan",
                        "take speeds, acceleration and the knife lift angle from the machine profile "
                        "(PostMachine) instead of the Plan options")
        job.PlanFromMachine = True
