"""Cut path planning: order the cut, choose entry points, mark knife lifts.

The job is a generalised travelling-salesman problem with precedence: every
contour is a cluster of entry candidates (vertices and points every
``entry_spacing`` mm; a contour with a lead-in is entered only at the
lead-in's free end), the head starts and ends at machine zero, holes are cut
before their outline, parts inside a hole before that hole, and the edge two
parts share is cut once.  For a fixed order the entries are chosen exactly by
dynamic programming (:mod:`.dp`); the order comes from a genetic algorithm
(:mod:`.ga`, default), a max-min ant system (:mod:`.aco`) or nearest
neighbour (:mod:`.nn`).  Metrics include a certified lower bound
(:mod:`.bounds`).

Public API::

    plan(parts, open_chains, options=PlanOptions(), progress=None) -> CutPlan
    solve_gtsp(dist, clusters, *, time_limit, seed) -> list of node indices
"""

from .gtsp import solve_gtsp
from .options import PlanOptions
from .planner import plan

__all__ = ["plan", "PlanOptions", "solve_gtsp"]
