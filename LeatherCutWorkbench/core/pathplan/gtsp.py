"""Library entry point for benchmarks: GTSP on a full distance matrix."""

from __future__ import annotations

from typing import List, Sequence, Tuple

import numpy as np

from ..errors import InputError
from .ga import run_ga
from .instance import MatrixInstance


def gtsp_instance(D: np.ndarray, clusters: Sequence[Sequence[int]]) -> Tuple[MatrixInstance, np.ndarray]:
    """The routing instance of a GTSP on matrix ``D``: candidate j is node
    ``node_of[j]``; the smallest cluster becomes the anchor (item 0) -- the
    DP closes the cycle over the anchor's candidates, so a small anchor is
    cheapest."""
    order = sorted(range(len(clusters)), key=lambda k: (len(clusters[k]), k))
    new_clusters, item_nodes, off = [], [], 0
    for k in order:
        sz = len(clusters[k])
        new_clusters.append(list(range(off, off + sz)))
        item_nodes.extend(int(v) for v in clusters[k])
        off += sz
    node_of = np.array(item_nodes)
    return MatrixInstance(D, new_clusters, start_node=node_of, end_node=node_of), node_of


def solve_gtsp(dist: np.ndarray, clusters: Sequence[Sequence[int]], *,
               time_limit: float = 10.0, seed: int = 1) -> List[int]:
    """Generalised TSP: visit exactly one node of every cluster on a closed tour
    of minimum total ``dist`` (may be asymmetric: ``dist[a, b]`` is the cost of
    going from a to b).

    ``dist`` is a full n x n numpy matrix, ``clusters`` a list of lists of node
    indices (a partition of the nodes that are used).  Returns one node per
    cluster in visiting order, starting with the node of ``clusters[0]``.
    Runs the memetic GA (see :mod:`.ga`) for at most ``time_limit`` seconds."""
    D = np.asarray(dist, dtype=float)
    if D.ndim != 2 or D.shape[0] != D.shape[1]:
        raise InputError(f"distance matrix must be square, got shape {D.shape}")
    if not clusters or any(len(c) == 0 for c in clusters):
        raise InputError("every cluster needs at least one node")
    flat = [int(v) for c in clusters for v in c]
    if len(set(flat)) != len(flat) or min(flat) < 0 or max(flat) >= D.shape[0]:
        raise InputError("clusters must be disjoint lists of valid node indices")
    inst, node_of = gtsp_instance(D, clusters)
    res = run_ga(inst, time_limit=time_limit, seed=seed)
    tour_nodes = [int(node_of[res.choice[it]]) for it in res.order]
    # rotate to start with clusters[0]
    first = set(int(v) for v in clusters[0])
    i0 = next(i for i, v in enumerate(tour_nodes) if v in first)
    return tour_nodes[i0:] + tour_nodes[:i0]
