"""``leathercut recognise FILE``: parts, holes, lead-ins, open chains and flags.

Runs the import with its options, then recognition, and reports what was found
(schema in docs/CLI.md, section ``recognise``).  Lengths mm, areas mm^2.
"""

from __future__ import annotations

import argparse
import math
from typing import Any, Dict, FrozenSet, List, Tuple

from ..core.gc_pause import collector_paused
from ..core.geometry import LineSeg, Segment
from ..core.model import Contour, Part, Recognition
from . import Report, add_common_options
from .stages import add_stage_options, job_options, progress_bar


def _tol(value: str) -> float:
    try:
        v = float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {value!r}") from None
    if not math.isfinite(v) or v < 0:
        raise argparse.ArgumentTypeError(f"must be a length >= 0 mm, got {value}")
    return v


def _ids(value: str) -> FrozenSet[str]:
    out = set()
    for part in value.replace(";", ",").split(","):
        p = part.strip().upper()
        if not p:
            continue
        if p[0] not in "CP" or not p[1:].isdigit():
            raise argparse.ArgumentTypeError(f"not a contour or part id (C3, P2): {part!r}")
        out.add(p)
    return frozenset(out)


def _flag_ids(value: str) -> FrozenSet[str]:
    out = set()
    for part in value.replace(";", ",").split(","):
        p = part.strip().upper()
        if not p:
            continue
        if p[0] != "F" or not p[1:].isdigit():
            raise argparse.ArgumentTypeError(f"not a flag id (F3): {part!r}")
        out.add(p)
    return frozenset(out)


def _size_list(text: str) -> List[str]:
    sizes = [t.strip() for t in text.split(",") if t.strip()]
    if not sizes:
        raise argparse.ArgumentTypeError(f"no size given: {text!r}")
    return sizes


def _quantities(text: str) -> Dict[str, int]:
    out: Dict[str, int] = {}
    for item in (t.strip() for t in text.split(",")):
        pid, eq, n = item.partition("=")
        if not eq or not pid.strip() or not n.strip().isdigit() or int(n) < 1:
            raise argparse.ArgumentTypeError(f"expected PART=N with N >= 1, e.g. P3=2: {item!r}")
        out[pid.strip()] = int(n)
    return out


def add_options(parser: argparse.ArgumentParser, primary: bool) -> None:
    """Recognition options; ``--include``/``--exclude`` become
    ``--recognise-include``/``--recognise-exclude`` on later verbs (not primary)."""
    g = parser.add_argument_group("recognition")
    g.add_argument("--join-tol", dest="recognise_join_tol", type=_tol, default=0.01, metavar="MM",
                   help="end points closer than this are joined (default 0.01 mm)")
    g.add_argument("--gap-tol", dest="recognise_gap_tol", type=_tol, default=0.5, metavar="MM",
                   help="open outlines whose gaps are all at most this long are flagged "
                        "'under' with bridging segments as the fix (default 0.5 mm)")
    g.add_argument("--close-gaps", dest="recognise_close_gaps", action="store_true",
                   help="apply the proposed bridges: flagged open outlines become contours")
    g.add_argument("--accept-fix", dest="recognise_accept_fixes", type=_flag_ids, default=None,
                   metavar="IDS", help="comma-separated ids of 'under' flags (as reported by a "
                                       "run with the same drawing and options) whose fix to "
                                       "apply, e.g. F2,F5; flag ids stay the same")
    g.add_argument("--reject-fix", dest="recognise_reject_fixes", type=_flag_ids, default=None,
                   metavar="IDS", help="comma-separated ids of 'under' flags whose fix is "
                                       "rejected (not applied even with --close-gaps)")
    pre = "" if primary else "recognise-"
    g.add_argument(f"--{pre}include", dest="recognise_include", type=_ids, default=frozenset(),
                   metavar="IDS", help="comma-separated contour/part ids to cut even if "
                                       "flagged over-recognised (e.g. C5,C9)")
    g.add_argument(f"--{pre}exclude", dest="recognise_exclude", type=_ids, default=frozenset(),
                   metavar="IDS", help="comma-separated contour/part ids not to cut")
    g.add_argument("--sizes", dest="recognise_sizes", type=_size_list, default=None,
                   metavar="SIZES", help="graded AAMA / ASTM sets: comma-separated sizes to cut, or "
                                         "'all' (default: the file's sample size, else its first size)")
    g.add_argument("--quantity", dest="recognise_quantities", type=_quantities, default=None,
                   metavar="PART=N,...", help="copies of a part to nest, e.g. P3=2,P5=4 "
                                              "(default: the quantity the drawing states, else 1)")
    g.add_argument("--no-unfold", dest="recognise_unfold", action="store_false",
                   help="keep pattern pieces drawn as a half against a fold (mirror) line "
                        "as drawn instead of unfolding them into the whole piece")
    g.add_argument("--chord-tol", dest="recognise_chord_tol", type=_tol, default=0.01,
                   metavar="MM", help="ellipses and splines become polylines within this "
                                      "deviation (default 0.01 mm)")


def options_from_args(args: argparse.Namespace):
    """RecogniseOptions from parsed arguments (validated)."""
    from ..core.recognition import RecogniseOptions

    opts = RecogniseOptions(join_tol=args.recognise_join_tol, gap_tol=args.recognise_gap_tol,
                            close_gaps=args.recognise_close_gaps,
                            accept_fixes=getattr(args, "recognise_accept_fixes", None),
                            reject_fixes=getattr(args, "recognise_reject_fixes", None),
                            include=args.recognise_include, exclude=args.recognise_exclude,
                            chord_tol=args.recognise_chord_tol, unfold=args.recognise_unfold)
    opts.validate()
    return opts


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "recognise", help="find parts, holes, lead-ins, open chains and doubtful contours",
        description="Recognise closed part contours (with holes and islands), lead-ins / "
                    "lead-outs and open chains in a DXF drawing; flag contours that are "
                    "probably not parts (over) and outlines left open by small gaps (under).")
    p.add_argument("file", metavar="FILE", help="DXF drawing")
    add_common_options(p)
    add_stage_options(p, before="recognise_cmd")
    add_options(p, primary=True)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> Report:
    from ..core.job import load_and_recognise

    options = job_options(args, before="recognise_cmd")
    options.recognise = options_from_args(args)
    drawing, rec = load_and_recognise(args.file, options, None if args.json else progress_bar())
    data = recognition_json(rec, args.file)
    data["findings"] = [f.to_json() for f in list(drawing.findings) + list(rec.findings)]
    return Report(data=data, text=recognition_text(rec, args.file), rows=True)


# ----------------------------------------------------------------------
def _r(v: float) -> float:
    return round(float(v), 4)


def _pt(p) -> List[float]:
    return [_r(p[0]), _r(p[1])]


def _seg_json(s: Segment) -> Dict[str, Any]:
    return {"start": _pt(s.start), "end": _pt(s.end), "length": _r(s.length)}


def _contour_stats(c: Contour) -> Tuple[float, float, Tuple[float, float, float, float]]:
    """(area mm^2, length mm, bbox) of a contour, each computed once.

    Area is exact for lines and arcs (polyline area for flattened curves).  A
    contour made only of lines (most of a large drawing) is measured in one
    pass over its segments, with the same operations in the same order as
    ``signed_path_area``, ``Contour.length`` and ``Contour.bbox``, so the
    figures are bit for bit the same."""
    segs = c.segments
    if not segs or not all(type(s) is LineSeg for s in segs):
        from ..core.recognition.from_part import signed_path_area
        return abs(signed_path_area(segs)), c.length, c.bbox
    a = 0.0
    lengths = []
    for s in segs:
        (x0, y0), (x1, y1) = s.start, s.end
        a += x0 * y1 - x1 * y0
        lengths.append(math.hypot(x1 - x0, y1 - y0))
    # Contour.points(): the first start, then every end but the last one
    xs = [segs[0].start[0]] + [s.end[0] for s in segs[:-1]]
    ys = [segs[0].start[1]] + [s.end[1] for s in segs[:-1]]
    return abs(a / 2.0), sum(lengths), (min(xs), min(ys), max(xs), max(ys))


def _contour_json(c: Contour, stats) -> Dict[str, Any]:
    area, length, box = stats
    return {"id": c.id, "area": _r(area), "length": _r(length),
            "bbox": [_r(v) for v in box], "segments": len(c.segments),
            "shared": list(c.shared), "layer": c.layer}


def _part_json(p: Part) -> Dict[str, Any]:
    outer = _contour_stats(p.outer)
    holes = [_contour_stats(h) for h in p.holes]
    return {
        "id": p.id, "name": p.name, "size": p.size, "excluded": p.excluded, "quantity": p.quantity,
        "rotations": p.rotations, "parent": p.parent_id,
        "net_area": _r(outer[0] - sum(h[0] for h in holes)),
        "outer_length": _r(outer[1]),
        "bbox": [_r(v) for v in outer[2]],
        "outer": _contour_json(p.outer, outer),
        "holes": [_contour_json(h, st) for h, st in zip(p.holes, holes)],
        "lead_ins": [{"id": li.id, "contour": li.contour_id, "role": li.role,
                      "start": _pt(li.start), "end": _pt(li.end), "length": _r(li.length)}
                     for li in p.lead_ins],
        "marks": [{"kind": m.kind, "position": _pt(m.position)} for m in p.marks],
    }


def recognition_json(rec: Recognition, path: str) -> Dict[str, Any]:
    """The ``--json`` report of ``leathercut recognise`` (see docs/CLI.md)."""
    with collector_paused():    # a quarter of a million acyclic dicts: no cycle search
        return _recognition_json(rec, path)


def _recognition_json(rec: Recognition, path: str) -> Dict[str, Any]:
    parts = [_part_json(p) for p in rec.parts]
    return {
        "input": path,
        "units": "mm",
        "counts": {
            "parts": len(rec.parts),
            "parts_excluded": sum(1 for p in rec.parts if p.excluded),
            "holes": sum(len(p.holes) for p in rec.parts),
            "lead_ins": sum(len(p.lead_ins) for p in rec.parts),
            "open_chains": len(rec.open_chains),
            "flags_over": sum(1 for f in rec.flags if f.kind == "over"),
            "flags_under": sum(1 for f in rec.flags if f.kind == "under"),
        },
        "parts": parts,
        "open_chains": [{"id": c.id, "length": _r(c.length), "start": _pt(c.start),
                         "end": _pt(c.end), "layer": c.layer, "segments": len(c.segments)}
                        for c in rec.open_chains],
        "flags": [{"id": f.id, "kind": f.kind, "ids": list(f.ids),
                   "gap": None if f.gap is None else round(f.gap, 6), "reason": f.reason,
                   "fix": [_seg_json(s) for s in f.fix], "action": f.action,
                   "accepted": f.accepted}
                  for f in rec.flags],
    }


def recognition_text(rec: Recognition, path: str) -> str:
    """Human summary: counts, then one line per flag."""
    active = rec.active_parts()
    lines = [f"{path}: {len(active)} parts to cut"
             + (f" ({len(rec.parts) - len(active)} excluded)" if len(active) != len(rec.parts)
                else "")
             + f", {sum(len(p.holes) for p in active)} holes, "
             f"{sum(len(p.lead_ins) for p in active)} lead-ins, "
             f"{len(rec.open_chains)} open chains, {len(rec.flags)} flags"]
    for f in rec.flags:
        gap = f" gap {f.gap:.4g} mm" if f.gap is not None else ""
        state = {None: "undecided", True: "accepted", False: "rejected"}[f.accepted]
        lines.append(f"  {f.id} {f.kind:5s} {','.join(f.ids)}{gap} [{state}]: {f.reason}")
    for fd in rec.findings:
        if fd.level != "info":
            lines.append(f"  {fd.level}: {fd.message}")
    return "\n".join(lines)

