"""The genetic algorithm over the visiting order (the planner's default).

The search itself is the island memetic GA of :mod:`.memetic` (compiled
kernels in :mod:`.kernels`); this module is its stable entry point.
"""

from __future__ import annotations

from typing import Callable, Optional

from .instance import Instance
from .memetic import run_memetic
from .result import SearchResult, stop_reason

__all__ = ["SearchResult", "run_ga", "stop_reason"]


def run_ga(inst: Instance, *, time_limit: float, seed: int, max_iterations: Optional[int] = None,
           progress: Optional[Callable[[float, str], None]] = None) -> SearchResult:
    """Genetic algorithm; returns the best tour found (anchor first).
    ``time_limit`` in seconds caps the run; ``max_iterations`` (generations
    per island, None = no limit) bounds it independently of machine speed."""
    return run_memetic(inst, time_limit=time_limit, seed=seed, max_iterations=max_iterations,
                       progress=progress)
