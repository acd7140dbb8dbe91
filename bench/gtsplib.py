"""GTSPLIB instances from TSPLIB coordinates (bench/data/tsplib/, see its README).

Clustering as Fischetti, Salazar-Gonzalez & Toth (Oper. Res. 45(3), 1997)
define it: m = ceil(n / 5) centres chosen by farthest-point selection -- the
first centre is the node farthest from node 1, each next centre maximises its
distance to the nearest chosen centre (lowest index on ties) -- and every node
assigned to its nearest centre (lowest centre index on ties); distances are
TSPLIB EUC_2D, nint(euclid).  Check: the cluster counts equal the instance
names, and the best tours found equal the proven optima; taking node 1 itself
as the first centre instead gives a 40kroA200 tour of 13389 < 13406 (the
proven optimum), so that variant is not the published instance.
"""

from __future__ import annotations

import math
import os
from typing import Dict, List, Tuple

import numpy as np

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "tsplib")

#: proven GTSP optima (Fischetti, Salazar-Gonzalez & Toth 1997)
OPTIMA: Dict[str, Tuple[str, int]] = {
    "39rat195": ("rat195", 854),
    "40d198": ("d198", 10557),
    "40kroa200": ("kroA200", 13406),
    "53pr264": ("pr264", 29549),
    "64lin318": ("lin318", 20765),
    "80rd400": ("rd400", 6361),
    "88pr439": ("pr439", 60099),
    "89pcb442": ("pcb442", 21657),
}


def read_tsp(name: str) -> np.ndarray:
    """Node coordinates (n x 2) of ``bench/data/tsplib/<name>.tsp``."""
    pts: List[Tuple[float, float]] = []
    with open(os.path.join(DATA, name + ".tsp")) as f:
        in_nodes = False
        for line in f:
            s = line.strip()
            if s.startswith("NODE_COORD_SECTION"):
                in_nodes = True
                continue
            if not in_nodes or not s or s == "EOF":
                continue
            _, x, y = s.split()[:3]
            pts.append((float(x), float(y)))
    return np.array(pts)


def euc2d(P: np.ndarray) -> np.ndarray:
    """TSPLIB EUC_2D matrix: nint of the Euclidean distance."""
    d = np.hypot(P[:, None, 0] - P[None, :, 0], P[:, None, 1] - P[None, :, 1])
    return np.floor(d + 0.5)


def fst_clusters(D: np.ndarray) -> List[List[int]]:
    """Farthest-point centres + nearest-centre assignment (see module doc)."""
    n = D.shape[0]
    m = math.ceil(n / 5)
    centres = [int(np.argmax(D[0]))]
    near = D[centres[0]].copy()
    for _ in range(m - 1):
        j = int(np.argmax(near))
        centres.append(j)
        near = np.minimum(near, D[j])
    lab = np.argmin(D[:, centres], axis=1)
    return [np.flatnonzero(lab == k).tolist() for k in range(m)]


def instance(gname: str) -> Tuple[np.ndarray, List[List[int]], int]:
    """(distance matrix, clusters, proven optimum) of a GTSPLIB instance."""
    tsp, opt = OPTIMA[gname]
    D = euc2d(read_tsp(tsp))
    return D, fst_clusters(D), opt


def available() -> List[str]:
    return [g for g, (tsp, _) in OPTIMA.items() if os.path.exists(os.path.join(DATA, tsp + ".tsp"))]


def tour_length(D: np.ndarray, tour) -> float:
    return float(sum(D[a, b] for a, b in zip(tour, list(tour[1:]) + list(tour[:1]))))


def check_pcb442_opt_tour() -> float:
    """Length of TSPLIB's optimal pcb442 tour on our coordinates and
    rounding (the published TSP optimum is 50778)."""
    with open(os.path.join(DATA, "pcb442.opt.tour")) as f:
        ids = [int(x) for x in f.read().split("TOUR_SECTION")[1].split() if x.lstrip("-").isdigit()]
    tour = [i - 1 for i in ids if i > 0]
    return tour_length(euc2d(read_tsp("pcb442")), tour)


if __name__ == "__main__":
    print("pcb442 along the TSPLIB optimal tour:", check_pcb442_opt_tour(), "(published 50778)")
    for g in available():
        D, cl, opt = instance(g)
        print(g, "nodes", len(D), "clusters", len(cl), "proven GTSP optimum", opt)
