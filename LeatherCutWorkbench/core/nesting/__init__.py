"""Nesting stage: place part copies on sheets, a strip or leather hides.

Public entry points::

    from LeatherCutWorkbench.core.nesting import nest, NestOptions, placed_parts
    layout = nest(parts, NestOptions(container=ContainerSpec.sheet(1000, 600)))
    cut_parts = placed_parts(parts, layout)

Modules: :mod:`options` (NestOptions, ContainerSpec), :mod:`shapes` (parts as
polygons, orientation variants, spacing), :mod:`containers` (sheet / strip /
hide, hide DXF layer convention), :mod:`nfp` (no-fit / inner-fit polygons),
:mod:`convex` (convex pieces and sums for fast no-fit polygons),
:mod:`blf` (bottom-left fill), :mod:`search` (anytime local search over
order and orientations, one process per core; time budget in :class:`search.Budget`),
:mod:`checker` (independent validity check), :mod:`esicup` (benchmark
instance reader: strips, and hides with quality zones),
:mod:`sparrow_engine` (spyrrow in a subprocess), :mod:`outputs` (layout
JSON, DXF, SVG, remnant hides); strips: :mod:`strip_shrink` (shrink the strip and separate
the overlaps until the budget ends), :mod:`separation` (guided local search
over the weighted overlap), :mod:`overlap` (penetration depth from no-fit
polygons, numba kernels); hides: :mod:`hide_choice` (which hides to use and
their fill order), :mod:`hide_regions` (a hide's regions per grade, built when
the fill opens it), :mod:`part_regions` (part regions with their own grade).

Every layout :func:`nest` returns has passed :func:`checker.check_layout`;
a placement the checker rejects is moved to ``unplaced`` with an error
finding (that would be a bug; it never happens in the tests).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable, List, Optional, Sequence

from ..errors import InputError
from ..geometry import Transform2D
from ..model import Finding, Layout, Part
from ..progress import ProgressFn, report
from .checker import check_layout, problem_labels
from .containers import read_hide_dxf
from .options import ContainerSpec, NestOptions, parse_rotations

__all__ = ["nest", "placed_parts", "NestOptions", "ContainerSpec", "parse_rotations",
           "read_hide_dxf", "check_layout"]


def nest(parts: Sequence[Part], options: NestOptions, progress: Optional[ProgressFn] = None,
         on_best: Optional[Callable[[Layout], None]] = None,
         stop: Optional[Callable[[], bool]] = None) -> Layout:
    """Place every copy of every non-excluded part (see module doc).

    Anytime: ``options.time_budget`` seconds cover everything from this call
    on; ``on_best(layout)`` (own engine) receives every better layout found
    (unchecked, at most twice a second) so a view can show it live;
    ``stop()`` returning True ends the search early and keeps the best layout
    so far.  Raises InputError for unusable options or parts, CancelledError
    when ``progress`` returns False (Cancel discards)."""
    options.validate()
    active = [p for p in parts if not p.excluded]
    if options.grades:
        unknown = set(options.grades) - {p.id for p in active} - {p.name for p in active}
        if unknown:
            raise InputError(f"--grade names no part: {', '.join(sorted(unknown)[:5])}")
        active = [replace(p, grade=options.part_grade(p.id, p.name, p.grade)) for p in active]
    ids = [p.id for p in active]
    if len(set(ids)) != len(ids):
        dup = sorted({i for i in ids if ids.count(i) > 1})
        raise InputError(f"part ids must be unique, repeated: {', '.join(dup[:5])}")
    from .tail import session
    with session(active, options) as tail:
        if options.engine == "sparrow":
            from .sparrow_engine import run_sparrow
            layout = run_sparrow(active, options, progress)
        else:
            from .strip_shrink import nest_compacted     # the engine, then the strip phase
            layout = nest_compacted(active, options, progress, on_best, stop)
        report(progress, 0.99, "checking the layout")
        problems = tail.check(active, layout, options)   # once: the strip phase's verdict is kept
    if problems:
        _drop_invalid(active, layout, problems, options)
    layout.metrics["checked"] = True
    layout.metrics["tolerance_mm"] = options.tolerance
    report(progress, 1.0, "nesting done")
    return layout


def _drop_invalid(parts: Sequence[Part], layout: Layout, problems: List[str],
                  options: NestOptions) -> None:
    """Move placements named in ``problems`` to unplaced (a safety net)."""
    bad = problem_labels(problems)
    keep = []
    for pl in layout.placements:
        if f"{pl.part_id}#{pl.copy}" in bad:
            layout.unplaced.append((pl.part_id, pl.copy))
        else:
            keep.append(pl)
    layout.placements = keep
    for msg in problems[:20]:
        layout.findings.append(Finding("error", "invalid-placement-removed", msg))
    rest = check_layout(parts, layout, spacing=options.spacing, margin=options.margin,
                        tol=options.tolerance, chord_tol=options.chord_tol,
                        rotations_override=options.rotations_override,
                        mirror_override=options.mirror_override,
                        free_rotation=options.free_rotation)
    if rest:
        from ..errors import LeatherCutError
        raise LeatherCutError("nesting produced an invalid layout: " + "; ".join(rest[:3]))
    from .engine import fill_metrics
    fill_metrics(parts, layout, options)


def placed_parts(parts: Sequence[Part], layout: Layout) -> List[Part]:
    """Deep copies of the parts, one per placement, transformed into container
    coordinates (mirror about the part's Y axis, rotate about its origin,
    translate); ids ``"<part id>#<copy>"``, quantity 1, no parent (a copy lies
    where nesting put it, not in its drawing's hole)."""
    by_id = {p.id: p for p in parts}
    out: List[Part] = []
    for pl in layout.placements:
        src = by_id.get(pl.part_id)
        if src is None:
            raise InputError(f"layout places unknown part {pl.part_id!r}")
        xf = Transform2D(dx=pl.x, dy=pl.y, angle=pl.angle, mirrored=pl.mirrored)
        copy = src.transformed(xf, new_id=f"{src.id}#{pl.copy}")
        copy.quantity = 1
        copy.parent_id = None
        out.append(copy)
    return out
