"""The job summary written as ``report.json`` by ``leathercut run``.

Schema (documented in docs/CLI.md, section ``run``): counts of what was
recognised and cut, cut length and idle travel in mm, the planner's metrics,
the nesting figures when nested, and every finding of every stage.
"""

from __future__ import annotations

from typing import Any, Dict

from .job import JobResult


def job_report(result: JobResult) -> Dict[str, Any]:
    """JSON-able summary of a finished job."""
    rec = result.recognition
    plan = result.plan
    items = plan.items
    report: Dict[str, Any] = {
        "input": result.path,
        "units": "mm",
        "source_units": result.drawing.units,
        "counts": {
            "edges": len(result.drawing.edges),
            "parts": len(rec.parts),
            "parts_excluded": sum(1 for p in rec.parts if p.excluded),
            "holes": sum(len(p.holes) for p in rec.active_parts()),
            "lead_ins": sum(len(p.lead_ins) for p in rec.active_parts()),
            "open_chains": len(rec.open_chains),
            "flags": len(rec.flags),
            "parts_cut": len(result.parts_to_cut),
            "cut_items": len(items),
        },
        "cut_length_mm": round(sum(it.length for it in items), 3),
        "idle_travel_mm": round(sum(_len(a, b) for a, b in plan.idle_moves()), 3),
        "lifts": sum(len(it.lifts) for it in items),
        "plan": {"method": plan.method, "home": [c + 0.0 for c in plan.home],  # no -0.0
                 **plan.metrics},
        "order": [{"n": n, "contour": it.contour_id, "part": it.part_id, "kind": it.kind,
                   "entry": [round(it.entry[0], 4), round(it.entry[1], 4)]}
                  for n, it in enumerate(items, start=1)],
        "nesting": None,
        # problems of the layout cut despite the gate (--allow-invalid-layout); [] = none
        "layout_override": [f.message for f in result.findings if f.code == "layout-override"],
        "warnings": [f.to_json() for f in result.findings if f.level != "info"],
        "findings": [f.to_json() for f in result.findings],
    }
    if result.layout is not None:
        report["nesting"] = {
            "containers": [c.id for c in result.layout.containers],
            "placed": len(result.layout.placements),
            "unplaced": [list(u) for u in result.layout.unplaced],
            **result.layout.metrics,
        }
    return report


def _len(a, b) -> float:
    return ((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5
