"""The planner's hot-path shortcuts give what the plain code gives (issue 38: 20 us a plan)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning import FIG_6_7, RULE_CASES, TABLE_6_1, PlannerParams, plan_grasps
from softpad.planning._records import GraspPlan, new_plan
from softpad.planning._thesis_rules import plan_with_rules
from softpad.sensing._objects import check_increments, increments_list


def test_new_plan_equals_the_constructors_plan() -> None:
    values = ((1, 2), (0.5, 1.0), (0.6, 1.0), 0.25, "n2-horizontal", (1,), True, False)
    fast, plain = new_plan(*values), GraspPlan(*values)
    assert fast == plain and repr(fast) == repr(plain) and hash(fast) == hash(plain)
    with pytest.raises(dataclasses.FrozenInstanceError):
        fast.theta = 0.0  # type: ignore[misc]
    with pytest.raises(TypeError, match="all 8 fields"):
        new_plan(*values[:-1])


@pytest.mark.parametrize(
    "delta",
    [
        (300.0, 0, 0, 0, 0, 0),
        [0.0] * 6,
        (1e4, -1e4, 0, 0, 0, 0),
        (np.float32(50.0), 0, 0, 0, 0, 1),
        (float("nan"), 0, 0, 0, 0, 0),
        (float("inf"), -float("inf"), 0, 0, 0, 0),
        (1.0001e4, 0, 0, 0, 0, 0),
        (0.5, 0, 0, 0, 0, 0),
        (1, 2, 3),
        ("a", 0, 0, 0, 0, 0),
        ((1, 2), 0, 0, 0, 0, 0),
    ],
)
def test_increments_list_accepts_and_refuses_what_check_increments_does(delta) -> None:
    layout = PadLayout()
    try:
        expected = check_increments(delta, layout).tolist()
    except InputError as exc:
        with pytest.raises(InputError) as got:
            increments_list(delta, layout)
        assert str(got.value) == str(exc)
    else:
        assert increments_list(delta, layout) == expected


def test_plans_from_lists_equal_plans_from_arrays() -> None:
    """Every reference case and 900 random vectors on three pads: the list path (plan_grasps)
    and the array path (plan_with_rules on the checked array) give equal plans."""
    rng = np.random.default_rng(38)
    params = PlannerParams()
    for layout in (PadLayout(), PadLayout(3, 4), PadLayout(4, 4)):
        vectors = [
            rng.uniform(0, 400, layout.n_modules) * (rng.random(layout.n_modules) < 0.6)
            for _ in range(1000)
        ]
        if layout == PadLayout():
            vectors += [np.asarray(c.delta_pa, float) for c in TABLE_6_1 + FIG_6_7 + RULE_CASES]
        for d in vectors:
            if 0 < np.abs(d).max() < 1:
                continue
            got = plan_grasps(tuple(d.tolist()), layout)
            touched = [k + 1 for k, v in enumerate(d) if v > params.object_threshold_pa]
            want = [plan_with_rules(d, g, layout, params) for g in layout.connected_groups(touched)]
            assert got == want
