"""Internal and stitch lines travel with their part.

Edges with role ``"internal"`` (AAMA layers 8 and 14, or the stitch / sew
layers of a plain drawing, see core/dxfimport/layers.py) are drawn, not cut.
Post-processing may still draw them with a pen or crease them, so each is kept
on the part whose material contains it (``Part.lines``), moved and turned
with the part by nesting.  Consecutive edges of one layer that meet end to
start (within the join tolerance) form one line.  Lengths mm.
"""

from __future__ import annotations

from typing import Dict, List

from ..errors import InputError
from ..geometry import Segment, dist
from ..model import Drawing, Finding, OpenChain, Part, Recognition
from .loops import Loop
from .nesting_depth import LoopIndex, innermost
from .options import RecogniseOptions
from .to_part import to_segment


def place_lines(drawing: Drawing, grp, loops: List[Loop], part_of_loop: Dict[int, Part],
                depth: List[int], options: RecogniseOptions, rec: Recognition) -> None:
    """Append the internal lines of group ``grp`` to the parts that contain them
    (by the mid-point of the line's first segment); lines in no part are
    reported, never dropped silently."""
    tol = options.join_tol
    chains: List[tuple] = []            # (layer, segments)
    for i in grp.indices:
        e = drawing.edges[i]
        if e.src.role != "internal":
            continue
        try:
            seg, _ = to_segment(e, options.chord_tol)
        except InputError:
            continue                    # reported by the cut-edge pass for cut edges only
        if seg.length < tol:
            continue
        if chains and chains[-1][0] == e.src.layer and dist(chains[-1][1][-1].end, seg.start) <= tol:
            chains[-1][1].append(seg)
        else:
            chains.append((e.src.layer, [seg]))
    if not chains:
        return
    index = LoopIndex(loops)
    for i, lp in enumerate(loops):
        index.add(i, lp.bbox)
    active = {i for i, lp in enumerate(loops) if not lp.excluded}
    lost = 0
    for layer, segs in chains:
        first: Segment = segs[0]
        j = innermost(loops, index, first.point_at(first.length / 2.0), tol, active)
        if j is None or depth[j] % 2 == 1 or j not in part_of_loop:
            lost += 1
            continue
        part = part_of_loop[j]
        part.lines.append(OpenChain(f"{part.id}/I{len(part.lines) + 1}", segs, layer))
    if lost:
        rec.findings.append(Finding("info", "line-outside-parts",
                                    f"{lost} internal line(s) lie outside every part and are not "
                                    "drawn", drawing.path + (f" piece {grp.name!r}" if grp.name else "")))
