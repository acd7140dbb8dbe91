"""``leathercut inspect FILE``: what is in a DXF drawing (import stage only).

Also provides the import options every later verb accepts:
:func:`add_options` / :func:`options_from_args`.
"""

from __future__ import annotations

import argparse
from typing import Any, Dict, List, Optional, Tuple

from ..core.dxfimport import ImportOptions
from ..core.dxfimport.layers import DEFAULT_NOT_CUT
from ..core.dxfimport.options import PATTERN_MODES
from ..core.model import Drawing
from . import Report, add_common_options


def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    """Import options (names are unique across stages, so ``primary`` does not
    change them; dests are prefixed ``import_``)."""
    g = parser.add_argument_group("DXF import")
    g.add_argument("--units", dest="import_units", metavar="UNIT", default=None,
                   help="drawing unit: mm, cm, m, inch, foot, ... (overrides the file's "
                        "$INSUNITS / AAMA 'Units:' text; default: from the file, else mm)")
    g.add_argument("--pattern-mode", dest="import_pattern_mode", choices=PATTERN_MODES,
                   default="auto",
                   help="AAMA/ASTM D6673 pattern reading: auto-detect (default), force, or off")
    g.add_argument("--no-cleanup", dest="import_cleanup", action="store_false", default=True,
                   help="keep zero-length edges, duplicates and overlaps; no T-junction splits")
    g.add_argument("--cleanup-tol", dest="import_tolerance", type=float, default=0.01,
                   metavar="MM", help="clean-up tolerance in mm (default 0.01)")
    g.add_argument("--cut-layers", dest="import_cut_layers", metavar="PATTERNS", default=None,
                   help="comma-separated layer-name patterns (case-insensitive, * and ?): only "
                        "these layers are cut (plain drawings; default: every layer not matched "
                        "by --not-cut-layers)")
    g.add_argument("--not-cut-layers", dest="import_not_cut_layers", metavar="PATTERNS",
                   default=",".join(DEFAULT_NOT_CUT),
                   help="comma-separated layer-name patterns drawn but not cut (default "
                        f"{','.join(DEFAULT_NOT_CUT)}; '' cuts every layer)")


def options_from_args(args: argparse.Namespace) -> ImportOptions:
    """ImportOptions from parsed arguments (validated by read_drawing)."""
    return ImportOptions(units=getattr(args, "import_units", None),
                         pattern_mode=getattr(args, "import_pattern_mode", "auto"),
                         cleanup=getattr(args, "import_cleanup", True),
                         tolerance=getattr(args, "import_tolerance", 0.01),
                         cut_layers=_patterns(getattr(args, "import_cut_layers", None)),
                         not_cut_layers=_patterns(getattr(args, "import_not_cut_layers", None))
                         or ())


def _patterns(text: Optional[str]) -> Optional[Tuple[str, ...]]:
    """Comma-separated patterns -> tuple (None when the option was not given)."""
    if text is None:
        return None
    return tuple(p.strip() for p in text.split(",") if p.strip())


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "inspect", help="show what a DXF drawing contains",
        description="Read a DXF drawing and report its version, units, entity counts (as found "
                    "and after block explosion), layers, blocks, extents in mm, skipped entities, "
                    "clean-up counts, pattern pieces and warnings.")
    p.add_argument("FILE", help="DXF file (ASCII or binary)")
    add_common_options(p)
    add_options(p, primary=True)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> Report:
    from ..core.dxfimport import read_drawing
    drawing = read_drawing(args.FILE, options_from_args(args))
    data = inspect_report(drawing)
    return Report(data=data, text=_text(data))


def inspect_report(d: Drawing) -> Dict[str, Any]:
    """The JSON dict of ``leathercut inspect`` (documented in docs/CLI.md)."""
    s = d.stats
    return {
        "file": d.path,
        "dxf_version": s["dxf_version"],
        "release": s["release"],
        "binary": s["file"].get("binary", False),
        "recovered": s["file"].get("recovered", False),
        "recover_fixes": s["file"].get("recover_fixes", 0),
        "units": {"unit": d.units, "source": d.units_source,
                  "mm_per_unit": s["units"]["mm_per_unit"],
                  "header_insunits": s["units"]["header_insunits"]},
        "pattern": s["pattern"],
        "entities": {"found": s["entities_found"],
                     "after_explosion": s["entities_after_explosion"],
                     "converted": s["entities_converted"]},
        "edges": s["edges"],
        "marks": s["marks"],
        "texts": s["texts"],
        "layers": s["layers"],
        "blocks": s["blocks"],
        "bbox_mm": s["bbox_mm"],
        "size_mm": s["size_mm"],
        "offset_mm": s["offset_mm"],
        "cleanup": s["cleanup"],
        "skipped": s["skipped"],
        "skipped_entities": s["skipped_entities"],
        "paper_space_ignored": s["paper_space_ignored"],
        "pieces": [p.to_json() for p in d.pieces.values()],
        "join_tolerance_hint_mm": s["join_tolerance_hint_mm"],
        "warnings": [f.message for f in d.findings if f.level in ("warning", "error")],
        "findings": [f.to_json() for f in d.findings],
    }


def _counts(c: Dict[str, int]) -> str:
    return ", ".join(f"{n} {k}" for k, n in c.items()) or "none"


def _text(r: Dict[str, Any]) -> str:
    u = r["units"]
    lines: List[str] = [
        f"{r['file']}: DXF {r['release']} ({r['dxf_version']})"
        f"{', binary' if r['binary'] else ''}"
        f"{', repaired (' + str(r['recover_fixes']) + ' fixes)' if r['recovered'] else ''}",
        f"units: {u['unit']} (from {u['source']}), 1 unit = {u['mm_per_unit']:g} mm",
        f"entities in model space: {_counts(r['entities']['found'])}",
        f"after block explosion: {_counts(r['entities']['after_explosion'])}",
        f"edges: {r['edges']['total']} ({_counts(r['edges']['by_kind'])}); roles: "
        f"{_counts(r['edges']['by_role'])}; marks: {r['marks']}; texts: {r['texts']}",
    ]
    if r["bbox_mm"]:
        b = r["bbox_mm"]
        lines.append(f"extents: x {b[0]:.3f} .. {b[2]:.3f}, y {b[1]:.3f} .. {b[3]:.3f} mm "
                     f"({r['size_mm'][0]:.1f} x {r['size_mm'][1]:.1f} mm)")
    if any(r["offset_mm"]):
        lines.append(f"local origin: coordinates moved by -({r['offset_mm'][0]:.0f}, "
                     f"{r['offset_mm'][1]:.0f}) mm")
    used = [f"{l['name']!r} ({l['edges']})" for l in r["layers"] if l["edges"] or l["marks"]]
    lines.append(f"layers: {len(r['layers'])}; with geometry: {', '.join(used[:20])}"
                 f"{' ...' if len(used) > 20 else ''}")
    if r["blocks"]:
        lines.append(f"blocks used: {len(r['blocks'])} ({sum(b['inserts'] for b in r['blocks'])} inserts)")
    c = r["cleanup"]
    if c:
        lines.append(f"clean-up: {c['zero_length_removed']} zero-length, {c['duplicates_removed']} "
                     f"duplicates, {c['overlaps_removed']} overlaps removed; "
                     f"{c['t_junction_splits']} T-junction splits")
    if r["pieces"]:
        lines.append(f"pattern pieces: {len(r['pieces'])} (AAMA/ASTM)")
        for p in r["pieces"][:10]:
            lines.append(f"  {p['key']}: {p['name']} size {p['size'] or '-'} x{p['quantity']}, "
                         f"{p['edges']} edges, grain {p['grain_angle']}")
        if len(r["pieces"]) > 10:
            lines.append(f"  ... {len(r['pieces']) - 10} more")
    for s in r["skipped"]:
        lines.append(f"skipped: {s['count']} {s['type']} ({s['reason']})")
    for w in r["warnings"]:
        if not w.startswith(tuple(s["type"] for s in r["skipped"])):
            lines.append(f"warning: {w}")
    return "\n".join(lines)
