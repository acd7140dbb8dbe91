"""The recognition stage: Drawing -> Recognition (parts, lead-ins, open chains, flags).

Per group of edges (the whole drawing, or one pattern piece of an AAMA/ASTM
file -- pieces are never merged):

1. cut edges -> segments (+ FreeCAD curves for ellipses/splines); zero-length and
   exactly duplicated edges dropped;
2. graph: end points snapped at ``join_tol``, edges split at T-junctions and at
   short overshoots, degree-1 edges peeled off into open chains;
3. under-recognition: open chains that close with bridges <= ``gap_tol``
   (applied when ``close_gaps`` or when their flag is in ``accept_fixes``);
4. closed loops: simple cycles -> closed paths (checked for self-crossing);
   components with junctions -> FreeCAD arrangement cells (common edges);
5. over-recognition evidence -> flags; person's include/exclude applied;
6. containment depth -> parts with holes, islands in holes as parts;
7. lead-ins / lead-outs / open chains; marks to the part containing them.
"""

from __future__ import annotations

from collections import defaultdict
from typing import Dict, List, Optional, Set

from ..dxfimport.grades import assign_grades, grade_of_texts
from ..gc_pause import collector_paused
from ..model import (Contour, Drawing, Finding, Flag, LeadIn, Mark, OpenChain, Part,
                     Recognition)
from ..progress import ProgressFn, report
from .build import Group, build_graph, build_loops
from .flags import frame_evidence
from .from_part import reverse
from .leadins import Chain, assign_lead_outs, classify
from .loops import Loop, mark_shared
from .nesting_depth import LoopIndex, depths, innermost, parents
from .options import RecogniseOptions
from .part_lines import place_lines
from .unfold import unfold_part


class _Ids:
    """Running id counters shared by all groups (P1.., C1.., L1.., O1.., F1..)."""

    def __init__(self) -> None:
        self.n: Dict[str, int] = defaultdict(int)

    def next(self, prefix: str) -> str:
        self.n[prefix] += 1
        return f"{prefix}{self.n[prefix]}"


def recognise(drawing: Drawing, options: RecogniseOptions = RecogniseOptions(),
              progress: Optional[ProgressFn] = None) -> Recognition:
    """Find the parts, holes, lead-ins, open chains and doubtful contours of a drawing.

    Units mm.  Outer contours come out counter-clockwise, holes clockwise; ids are
    stable for the same drawing and options (P, C, L, O, F + running number).

    Flag ids do not depend on which fixes are applied: the flags of gap and
    missed-contour proposals come first (F1.., numbered before any loop is
    built), then the stub (trim) flags, then the over-recognition flags, so a
    run with ``accept_fixes`` reports the ids of the proposal run."""
    options.validate()
    # The build allocates hundreds of thousands of small objects that live until
    # the end; the cyclic collector re-scanning them again and again doubled the
    # run time of a 10,000-part drawing (measured).  It runs again afterwards.
    with collector_paused():
        return _recognise(drawing, options, progress)


def _recognise(drawing: Drawing, options: RecogniseOptions,
               progress: Optional[ProgressFn]) -> Recognition:
    rec = Recognition(units="mm")
    ids = _Ids()
    groups = _groups(drawing)
    report(progress, 0.0, "recognising contours")

    def stepper(gi: int, a: float = 0.05, b: float = 1.0):
        """Progress of group ``gi`` within the overall span [a, b]."""
        lo = a + (b - a) * gi / len(groups)
        hi = a + (b - a) * (gi + 1) / len(groups)

        def step(f: float, msg: str) -> None:
            report(progress, lo + (hi - lo) * f, msg)
        return step

    for gi, grp in enumerate(groups):
        build_graph(drawing, grp, options, rec.findings, stepper(gi, 0.0, 0.05))
        for gp in grp.gaps + grp.misses:          # numbered before any fix is applied
            gp.flag_id = ids.next("F")
    over: List[Flag] = []
    for gi, grp in enumerate(groups):
        step = stepper(gi)
        build_loops(drawing, grp, options, rec.findings, step)
        step(0.8, "nesting depth, lead-ins and flags")
        over.extend(_emit(drawing, grp, options, ids, rec))
        step(1.0, f"recognised {gi + 1}/{len(groups)} groups")
    for f in over:
        f.id = ids.next("F")
    rec.flags.extend(over)
    rec.flags.sort(key=lambda f: _num(f.id))
    _apply_part_decisions(rec, options)
    _unknown_fixes(rec, options)
    rec.findings.extend(assign_grades(rec.parts, drawing.texts))
    return rec


# ----------------------------------------------------------------------
def _groups(drawing: Drawing) -> List[Group]:
    if not drawing.pieces:
        return [Group(None, list(range(len(drawing.edges))))]
    out = []
    seen: Set[int] = set()
    for key, info in drawing.pieces.items():
        idx = list(getattr(info, "edges", info))
        out.append(Group(key, idx, info if hasattr(info, "edges") else None))
        seen.update(idx)
    rest = [i for i in range(len(drawing.edges)) if i not in seen]
    if rest:
        out.append(Group(None, rest))
    return out


def _emit(drawing: Drawing, grp: Group, options: RecogniseOptions, ids: _Ids,
          rec: Recognition) -> List[Flag]:
    """Steps 5-7 for one group, appending to ``rec``.  Returns the group's
    over-recognition flags, not yet numbered (they come after all under flags)."""
    loops = grp.loops
    for lp in loops:
        lp.contour_id = ids.next("C")
    _outline_findings(grp, rec, drawing.path)
    par, depth = _decide(loops, options)
    layer = _layer_of(drawing)
    over: List[Flag] = []
    part_of_loop = _make_parts(drawing, grp, options, ids, over, par, depth, layer)
    node_loops = _attach_chains(grp, options, ids, rec, part_of_loop, layer)
    _under_flags(grp, options, ids, rec, node_loops)
    _place_marks(drawing, grp, loops, part_of_loop, depth, options.join_tol, rec)
    place_lines(drawing, grp, loops, part_of_loop, depth, options, rec)
    line = getattr(grp.info, "mirror_line", None) if grp.info is not None else None
    if line is not None:
        _unfold(grp, line, part_of_loop, depth, options, ids, rec, drawing.path)
    rec.parts.extend(sorted({id(p): p for p in part_of_loop.values()}.values(),
                            key=lambda p: _num(p.id)))
    return over


def _outline_findings(grp: Group, rec: Recognition, path: str) -> None:
    for lp, why in grp.crossing:
        rec.findings.append(Finding("warning", "self-intersecting-contour",
                                    f"contour {lp.contour_id} crosses itself ({why}); it is cut "
                                    "as drawn", path))
    for a, b in grp.overlapping:
        rec.findings.append(Finding("warning", "crossing-contours",
                                    f"contours {a.contour_id} and {b.contour_id} cross each "
                                    "other: the parts overlap", path))


def _decide(loops: List[Loop], options: RecogniseOptions):
    """Frame evidence, exclusions (automatic, then a person's), containment of
    the active loops, depth, orientation (outers CCW, holes CW), shared edges.
    Returns (parent index per loop, depth per loop)."""
    tol = options.join_tol
    par = parents(loops, tol)
    children: Dict[int, List[int]] = defaultdict(list)
    for i, p in enumerate(par):
        if p is not None:
            children[p].append(i)
    for i, lp in enumerate(loops):
        kids = children.get(i, [])
        why = frame_evidence(sum(1 for k in kids if children.get(k)), len(kids))
        if why:
            lp.auto_over = True
            lp.evidence.append(why)
    changed = False
    for lp in loops:
        cid = lp.contour_id
        lp.excluded = (lp.auto_over and cid not in options.include) or cid in options.exclude
        changed |= lp.excluded
    if changed:
        active = [i for i, lp in enumerate(loops) if not lp.excluded]
        sub_par = parents([loops[i] for i in active], tol)
        par = [None] * len(loops)
        for k, i in enumerate(active):
            par[i] = None if sub_par[k] is None else active[sub_par[k]]
    depth = depths(par, loops)
    for i, lp in enumerate(loops):
        ccw = lp.excluded or depth[i] % 2 == 0
        if (lp.signed_area > 0) != ccw:
            lp.segs = reverse(lp.segs)
            lp.signed_area = -lp.signed_area
    mark_shared(loops, max(tol, 1e-6))
    return par, depth


def _make_parts(drawing: Drawing, grp: Group, options: RecogniseOptions, ids: _Ids,
                over: List[Flag], par, depth, layer) -> Dict[int, Part]:
    """Over flags, then one part per even-depth (or excluded) loop with the
    odd-depth loops inside it as holes.  Returns loop index -> its part."""
    loops = grp.loops
    decided = options.include | options.exclude
    for lp in loops:
        if lp.evidence:
            accepted = None if lp.contour_id not in decided else lp.contour_id in options.exclude
            over.append(Flag("", "over", [lp.contour_id],
                                  "; ".join(lp.evidence), accepted=accepted, action="exclude"))
    contour_of = {i: Contour(lp.contour_id, lp.segs, layer(lp.srcs), list(lp.shared_idx))
                  for i, lp in enumerate(loops)}
    part_of_loop: Dict[int, Part] = {}
    order = sorted(range(len(loops)), key=lambda i: _num(loops[i].contour_id))
    for i in order:
        if loops[i].excluded or depth[i] % 2 == 0:
            part = Part(ids.next("P"), contour_of[i], excluded=loops[i].excluded)
            if grp.name is not None:
                _piece_fields(part, drawing, grp)
            part_of_loop[i] = part
    for i in order:
        if not loops[i].excluded and depth[i] % 2 == 1:
            owner = part_of_loop[par[i]]
            owner.holes.append(contour_of[i])
            part_of_loop[i] = owner
    for i, part in part_of_loop.items():
        p = par[i]
        if part.outer is contour_of[i] and p is not None and depth[i] > 0:
            part.parent_id = part_of_loop[p].id
    return part_of_loop


def _attach_chains(grp: Group, options: RecogniseOptions, ids: _Ids, rec: Recognition,
                   part_of_loop: Dict[int, Part], layer) -> Dict[int, List[int]]:
    """Lead-ins / lead-outs onto their parts, the other chains to open chains.
    Returns graph node -> loops through it (active loops first)."""
    loops = grp.loops
    node_loops: Dict[int, List[int]] = defaultdict(list)
    for i in sorted(range(len(loops)), key=lambda i: loops[i].excluded):
        for n in loops[i].nodes:
            node_loops[n].append(i)
    classify(grp.chains, grp.graph, node_loops, options.gap_tol, loops,
             lead_ins=grp.name is None)
    by_loop: Dict[int, List[Chain]] = defaultdict(list)
    for ch in grp.chains:
        if ch.kind == "lead_in":
            by_loop[ch.contour].append(ch)
    assign_lead_outs(by_loop, {i: loops[i].segs for i in by_loop})
    for li, chs in sorted(by_loop.items(), key=lambda t: _num(loops[t[0]].contour_id)):
        part = part_of_loop[li]
        for ch in sorted(chs, key=lambda c: min(c.srcs) if c.srcs else 0):
            ch.id = ids.next("L")
            part.lead_ins.append(LeadIn(ch.id, loops[li].contour_id, ch.segs, ch.kind))
    opens = [ch for ch in grp.chains if ch.kind in ("open", "overshoot", "gap")]
    opens.sort(key=lambda c: (min(c.srcs) if c.srcs else 1 << 60))
    for ch in opens:
        if ch.kind == "overshoot":
            ch.flag_id = ids.next("F")
            if options.fix_decision(ch.flag_id):
                continue                              # trimmed
        ch.id = ids.next("O")
        rec.open_chains.append(OpenChain(ch.id, ch.segs, layer(ch.srcs)))
    return node_loops


def _under_flags(grp: Group, options: RecogniseOptions, ids: _Ids, rec: Recognition,
                 node_loops: Dict[int, List[int]]) -> None:
    """Flags for gaps, chains missing a contour and stubs; the applied fixes'
    flags are accepted and name what the fix made, the rejected ones are
    accepted False, the others are proposals (accepted None)."""
    loops = grp.loops
    closed = {id(gp): k for k, gp in enumerate(grp.closed_gaps)}
    for gp in grp.gaps + grp.misses:
        action = "join" if gp in grp.misses else "close"
        k = closed.get(id(gp))
        if k is not None:
            made = [loops[i].contour_id for i in range(len(loops)) if (-1 - k) in loops[i].srcs]
            made += [ch.id for ch in grp.chains if (-1 - k) in ch.srcs and ch.id]
            reason = (f"gap of {gp.gap:.4g} mm closed with {len(gp.bridges)} bridging "
                      "segment(s) (fix accepted)")
            rec.flags.append(Flag(gp.flag_id, "under", made, reason, gap=gp.gap,
                                  fix=list(gp.bridges), accepted=True, action=action))
            continue
        if action == "close":
            reason = (f"open outline of {len(gp.chains)} chain(s) closes with "
                      f"{len(gp.bridges)} bridging segment(s), largest gap {gp.gap:.4g} mm "
                      f"(gap tolerance {options.gap_tol} mm)")
            flagged = sorted((c.id for c in gp.chains if c.id), key=_num)
        else:
            reason = (f"open chain ends {gp.gap:.4g} mm short of a contour (a lead-in that "
                      "misses it?); the bridge joins it to the nearest contour point")
            flagged = [c.id for c in gp.chains[:1] if c.id]
        rec.flags.append(Flag(gp.flag_id, "under", flagged, reason, gap=gp.gap,
                              fix=list(gp.bridges), accepted=options.fix_decision(gp.flag_id),
                              action=action))
    for ch in grp.chains:
        if ch.kind != "overshoot":
            continue
        trimmed = bool(options.fix_decision(ch.flag_id))
        cont = [loops[i].contour_id for i in node_loops.get(ch.b, [])][:1]
        reason = (f"{ch.length:.4g} mm stub hangs off the contour (a line running past a corner "
                  "or a drawing artefact, no longer than the gap tolerance); fix: trim it")
        rec.flags.append(Flag(ch.flag_id, "under", cont if trimmed else [ch.id],
                              reason, gap=ch.length, fix=[], action="trim",
                              accepted=options.fix_decision(ch.flag_id)))


def _unknown_fixes(rec: Recognition, options: RecogniseOptions) -> None:
    """A warning for accepted / rejected fix ids that name no under flag."""
    asked = set(options.accept_fixes or ()) | set(options.reject_fixes or ())
    unknown = sorted(asked - {f.id for f in rec.flags if f.kind == "under"},
                     key=lambda t: (len(t), t))
    if unknown:
        rec.findings.append(Finding("warning", "unknown-id",
                                    "flags with no fix to accept or reject: "
                                    + ", ".join(unknown), "--accept-fix"))


def _unfold(grp: Group, line, part_of_loop: Dict[int, Part], depth: List[int],
            options: RecogniseOptions, ids: _Ids, rec: Recognition, path: str) -> None:
    """Unfold the top-level parts of a half piece about its fold line."""
    where = f"{path} piece {grp.name!r}"
    if not options.unfold:
        rec.findings.append(Finding("warning", "half-piece",
                                    "piece is drawn as a half against a fold line and was not "
                                    "unfolded (unfolding is off)", where))
        return
    tol = max(options.join_tol, 1e-3)
    for i, part in part_of_loop.items():
        if depth[i] != 0 or part.excluded or part.outer.id != grp.loops[i].contour_id:
            continue
        why = unfold_part(part, line, tol, lambda: ids.next("C"))
        if why is None:
            rec.findings.append(Finding("info", "unfolded",
                                        f"{part.id} unfolded about the fold line", where))
        else:
            rec.findings.append(Finding("warning", "half-piece",
                                        f"{part.id} has a fold line but was not unfolded: {why}",
                                        where))


def _place_marks(drawing: Drawing, grp: Group, loops: List[Loop],
                 part_of_loop: Dict[int, Part], depth: List[int], tol: float,
                 rec: Recognition) -> None:
    if grp.info is not None:
        marks: List[Mark] = [drawing.marks[i] for i in grp.info.marks
                             if drawing.marks[i].src.role in ("mark", "cut", "")]
    elif drawing.pieces:
        marks = [m for m in drawing.marks if not getattr(m.src, "piece", "")
                 and m.src.role not in ("ignore", "annotation")]
    else:
        marks = [m for m in drawing.marks if m.src.role not in ("ignore", "annotation")]
    if not marks:
        return
    active = {i for i, lp in enumerate(loops) if not lp.excluded}
    index = LoopIndex(loops)
    for i, lp in enumerate(loops):
        index.add(i, lp.bbox)
    lost = 0
    for m in marks:
        j = innermost(loops, index, m.position, tol, active)
        if j is None or depth[j] % 2 == 1:
            lost += 1
            continue
        part_of_loop[j].marks.append(m)
    if lost:
        rec.findings.append(Finding("info", "mark-outside-parts",
                                    f"{lost} marks lie outside every part and were not assigned",
                                    drawing.path + (f" piece {grp.name!r}" if grp.name else "")))


def _apply_part_decisions(rec: Recognition, options: RecogniseOptions) -> None:
    """Part ids in include/exclude decide the whole part (with its holes)."""
    for p in rec.parts:
        if p.id in options.exclude:
            p.excluded = True
        elif p.id in options.include:
            p.excluded = False
    known = {p.id for p in rec.parts} | {c.id for p in rec.parts for c in p.contours()}
    unknown = sorted((set(options.include) | set(options.exclude)) - known)
    if unknown:
        rec.findings.append(Finding("warning", "unknown-id",
                                    "include/exclude ids not found: " + ", ".join(unknown),
                                    "--include/--exclude"))


def _layer_of(drawing: Drawing):
    def layer(srcs) -> str:
        real = [s for s in srcs if s >= 0]
        return drawing.edges[min(real)].src.layer if real else ""
    return layer


def _piece_fields(part: Part, drawing: Drawing, grp: Group) -> None:
    """Name, quantity and allowed rotations of a pattern piece's part: with a
    grain line the piece may only turn by 0 or 180 degrees (grain kept parallel)."""
    info = grp.info
    if info is None:
        part.name = grp.name or ""
        if grp.has_grain:
            part.rotations = [0.0, 180.0]
        return
    part.name = info.name + (f" size {info.size}" if getattr(info, "size", "") else "")
    part.quantity = max(1, int(getattr(info, "quantity", 1) or 1))
    part.size = getattr(info, "size", "") or ""
    part.grade = grade_of_texts(drawing.texts[i].text for i in info.texts) or 0
    if getattr(info, "grain_angle", None) is not None or grp.has_grain:
        part.rotations = [0.0, 180.0]


def _num(ident: str) -> int:
    return int(ident[1:])
