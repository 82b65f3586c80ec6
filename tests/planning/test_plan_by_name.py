"""softpad.planning.plan_by_name (what ``softpad plan`` calls): the thesis's planner is
plan_grasps itself, a registered one plans the same reading, unknown names are refused."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning import PlannerParams, check_planner_choice, plan_by_name, plan_grasps

DELTA = [120.0, 110.0, 0.0, 0.0, 0.0, 0.0]  # one object on modules 1 and 2, Pa


def test_the_thesis_planner_is_plan_grasps() -> None:
    layout, params = PadLayout(), PlannerParams()
    assert plan_by_name("thesis", "10/4", DELTA, layout, params) == plan_grasps(
        DELTA, layout, params
    )


def test_a_registered_planner_plans_the_reading() -> None:
    (plan,) = plan_by_name("gripper-aware", "10/4", DELTA, PadLayout(), PlannerParams())
    assert set(plan.modules) == {1, 2}


@pytest.mark.parametrize(
    ("planner", "mounting", "message"),
    [("nope", "10/4", "--planner must be one of"), ("thesis", "9/9", "--gripper must be one of")],
    ids=["planner", "mounting"],
)
def test_unknown_choices_are_refused(planner: str, mounting: str, message: str) -> None:
    with pytest.raises(InputError, match=message):
        check_planner_choice(planner, mounting)
    with pytest.raises(InputError, match=message):
        plan_by_name(planner, mounting, DELTA, PadLayout(), PlannerParams())
