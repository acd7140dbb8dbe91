"""core.job: the pipeline shared by the CLI, the workbench and freecadcmd."""

import os

import pytest

from LeatherCutWorkbench.core.geometry import path_points
from LeatherCutWorkbench.core.job import JobOptions, run_job
from LeatherCutWorkbench.core.pathplan import PlanOptions

from conftest import SAMPLES_DIR

# DeepNest's sheet lies partly at negative x (an arc bulges to x = -0.015 mm).
DEEPNEST = os.path.join(SAMPLES_DIR, "deepnest_ReadMeExampleSmall.dxf")


def plan_extent(result):
    pts = [p for it in result.plan.items for p in path_points(it.segments, 0.01)]
    return min(x for x, _ in pts), min(y for _, y in pts)


@pytest.fixture(scope="module")
def as_drawn():
    return run_job(DEEPNEST, JobOptions(plan=PlanOptions(method="nn")))


def test_drawing_is_cut_where_it_lies_by_default(as_drawn):
    xmin, _ = plan_extent(as_drawn)
    assert xmin < 0


def test_move_to_origin_puts_the_lower_left_corner_at_the_margin(as_drawn):
    moved = run_job(DEEPNEST, JobOptions(plan=PlanOptions(method="nn"), move_to_origin=10.0))
    xmin, ymin = plan_extent(moved)
    assert xmin == pytest.approx(10.0, abs=0.02) and ymin == pytest.approx(10.0, abs=0.02)
    # Same job, only translated: same cut length, same contours.
    assert sum(i.length for i in moved.plan.items) == pytest.approx(
        sum(i.length for i in as_drawn.plan.items), rel=1e-9)
    assert sorted(i.contour_id for i in moved.plan.items) == sorted(
        i.contour_id for i in as_drawn.plan.items)
