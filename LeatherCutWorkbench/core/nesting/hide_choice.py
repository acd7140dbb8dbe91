"""Which hides to use, and in which order the bottom-left fill opens them.

A leather cutter wants the fewest hides, then the best utilisation of the
hides used (placed part area / net area of those hides).  With every copy
placed on the same number of hides, utilisation is highest when the hides
used have the smallest total net area, so a hide layout's cost is
``(area left unplaced, hides used, net area of the hides used (mm^2),
part area on the least-filled hide, extent of the last hide)``, compared in that order (:func:`hide_cost`).

The fill opens hides in an *order* (a permutation of the available hides).
It starts with the largest net area first (the fewest hides for a job that
needs several) and the search changes it by :func:`swap_hides`: swap a used
hide with an unused one (typically a smaller or cleaner one: a better
utilisation, or -- the worst-used hide moved behind an unused one -- its
parts re-placed on the others) or two used hides (a different hide gets the
large parts).  Only the copies from the first one the fill put on a moved
hide onward are placed again.

Placements inside the search name hide *positions* in the order;
:func:`as_hide_indices` turns them into indices of the available hides
before they leave the worker.
"""

from __future__ import annotations

import random
from typing import List, Sequence, Tuple

Placements = List[Tuple[int, int, int, int, int]]


def initial_order(net_areas: Sequence[float]) -> List[int]:
    """Hide indices, largest net area (outline minus holes) first; ties keep file order."""
    return sorted(range(len(net_areas)), key=lambda i: (-net_areas[i], i))


def used_positions(placements: Placements) -> List[int]:
    """Sorted positions (in the fill order) of the hides holding a copy."""
    return sorted({b for (_si, b, _vi, _tx, _ty) in placements if b >= 0})


def hide_cost(placements: Placements, order: Sequence[int], net_areas: Sequence[float],
              unplaced_area: float, extent_of_last: int,
              part_areas: Sequence[float] = ()) -> Tuple[float, int, float, float, int]:
    """(area left unplaced, hides used, net mm^2 of the hides used, part mm^2
    on the least-filled hide used, extent of the last one): lower is better,
    compared in that order.  ``part_areas``: the area of each placement's
    part (same order as ``placements``; empty: that term is 0).  Emptying the
    least-filled hide is the way to one hide fewer, or to a smaller hide in
    its place, so the search is steered towards it."""
    used = used_positions(placements)
    net = sum(net_areas[order[b]] for b in used)
    on: dict = {}
    for (_si, b, _vi, _tx, _ty), a in zip(placements, part_areas):
        if b >= 0:
            on[b] = on.get(b, 0.0) + a
    least = min(on.values()) if on else 0.0
    return (round(unplaced_area, 6), len(used), round(net, 1), round(least, 1), extent_of_last)


def swap_hides(rng: random.Random, order: Sequence[int], placements: Placements,
               net_areas: Sequence[float] = (), part_areas: Sequence[float] = ()
               ) -> Tuple[List[int], int]:
    """A neighbour of the hide ``order`` and the first fill position it changes.

    Swaps a used hide with an unused one (70 % when there is one), else two
    used hides.  Given ``net_areas`` (per hide) and ``part_areas`` (per
    placement), half of the used-unused swaps put an unused hide of smaller
    net area in the place of the least-filled hide used that has a smaller
    unused one: the likeliest swap to keep every copy placed on less
    material.  Returns the unchanged order and -1 when no swap changes
    anything."""
    n = len(order)
    used = used_positions(placements)
    if n < 2 or not used:
        return list(order), -1
    unused = [p for p in range(n) if p not in set(used)]
    i = rng.choice(used)
    if unused and part_areas and net_areas and rng.random() < 0.5:
        on = {b: 0.0 for b in used}
        for (_si, b, _vi, _tx, _ty), a in zip(placements, part_areas):
            if b >= 0:
                on[b] += a
        # the least-filled of the used hides that a smaller unused one could replace
        smallest = min(net_areas[order[p]] for p in unused)
        movable = [b for b in used if net_areas[order[b]] > smallest]
        if movable:
            least = min(movable, key=lambda b: (on[b], b))
            smaller = [p for p in unused if net_areas[order[p]] < net_areas[order[least]]]
            new = list(order)
            j = rng.choice(smaller)
            new[least], new[j] = new[j], new[least]
            return new, min(least, j)
    if unused and (len(used) < 2 or rng.random() < 0.7):
        j = rng.choice(unused)
    elif len(used) >= 2:
        j = rng.choice([p for p in used if p != i])
    else:
        return list(order), -1
    new = list(order)
    new[i], new[j] = new[j], new[i]
    return new, min(i, j)


def first_affected(placements: Placements, position: int) -> int:
    """Index of the first copy the fill put on a hide at ``position`` or later
    (or left unplaced): every copy before it is placed exactly as before."""
    for k, (_si, b, _vi, _tx, _ty) in enumerate(placements):
        if b < 0 or b >= position:
            return k
    return len(placements)


def as_hide_indices(placements: Placements, order: Sequence[int]) -> Placements:
    """Placements with hide positions replaced by indices of the available hides."""
    return [(si, order[b] if b >= 0 else b, vi, tx, ty) for (si, b, vi, tx, ty) in placements]


def tight_order(net_areas: Sequence[float], k: int) -> List[int]:
    """The ``k`` hides of the smallest net area first (largest of them first),
    then the others, largest first: a fill that places every copy on those k
    has the best utilisation k hides can give; what does not fit spills over."""
    small = sorted(range(len(net_areas)), key=lambda i: (net_areas[i], i))[:max(k, 0)]
    rest = [i for i in initial_order(net_areas) if i not in set(small)]
    return sorted(small, key=lambda i: (-net_areas[i], i)) + rest
