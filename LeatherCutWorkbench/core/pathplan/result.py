"""What every order search returns."""

from __future__ import annotations

from dataclasses import dataclass
from typing import List


@dataclass
class SearchResult:
    order: List[int]
    choice: List[int]
    cost: float
    iterations: int
    nn_cost: float
    stopped_by: str     # "converged", "iterations" or "time"


def stop_reason(converged: bool, iterations_done: bool) -> str:
    """Why a search loop ended (see :class:`SearchResult`)."""
    return "converged" if converged else "iterations" if iterations_done else "time"
