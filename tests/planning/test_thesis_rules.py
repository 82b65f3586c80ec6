"""The planner against the thesis's Table 6.1, Fig. 6.7 and one hand-worked case per rule."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning import (
    FIG_6_7,
    RULE_CASES,
    TABLE_6_1,
    PlanCase,
    PlannerParams,
    pcom,
    plan_grasps,
)

LAYOUT = PadLayout()
TOL_UNITS = 0.01  # Table 6.1 prints two decimals


def _single_plan(case: PlanCase):
    plans = plan_grasps(case.delta_pa, LAYOUT)
    assert len(plans) == 1, plans
    return plans[0]


@pytest.mark.parametrize("case", TABLE_6_1 + FIG_6_7, ids=lambda c: c.name)
def test_thesis_plans_are_reproduced(case: PlanCase) -> None:
    plan = _single_plan(case)
    np.testing.assert_allclose(plan.cog, case.cog, atol=TOL_UNITS)
    assert plan.theta == case.theta  # exact: 0, pi/2 or +-pi/4
    assert plan.rule == case.rule


@pytest.mark.parametrize("case", RULE_CASES, ids=lambda c: c.name)
def test_each_rule_on_its_hand_worked_case(case: PlanCase) -> None:
    plan = _single_plan(case)
    np.testing.assert_allclose(plan.cog, case.cog, atol=1e-4)
    assert plan.theta == case.theta
    assert plan.rule == case.rule
    assert not plan.tie_break


def test_banana_lies_on_modules_2_3_4_and_grasps_at_the_corner_of_module_4() -> None:
    (plan,) = plan_grasps(next(c for c in TABLE_6_1 if c.name == "banana").delta_pa, LAYOUT)
    assert plan.modules == (2, 3, 4)
    assert plan.cog == (1.0, 1.0)
    assert plan.theta == -math.pi / 4


def test_limes_drop_the_farthest_extremity_module_but_never_a_central_one() -> None:
    (plan,) = plan_grasps(next(c for c in TABLE_6_1 if c.name == "limes").delta_pa, LAYOUT)
    assert plan.modules == (2, 4, 5, 6)
    assert plan.reduced_modules == (2, 5, 6)


def test_pcom_is_the_weighted_mean_of_module_centres() -> None:
    d = np.array([10.0, 30.0, 0, 60.0, 0, 0])
    x, y = pcom(d, (1, 2, 4), LAYOUT)
    assert x == pytest.approx((10 * 0.5 + 30 * 1.5 + 60 * 0.5) / 100)
    assert y == pytest.approx((10 * 1.5 + 30 * 1.5 + 60 * 0.5) / 100)


def test_separate_objects_are_planned_in_module_order() -> None:
    plans = plan_grasps([100, 0, 100, 100, 0, 100], LAYOUT)
    assert [p.modules for p in plans] == [(1, 4), (3, 6)]
    assert [p.cog for p in plans] == [(0.5, 1.0), (2.5, 1.0)]


def test_no_object_gives_no_plan() -> None:
    assert plan_grasps([10, 20, 0, 0, 49.9, 0], LAYOUT) == []


def test_exact_tie_is_flagged() -> None:
    # V shape 1-5-3 with equal weights: PCOM exactly on the vertical bisector.
    (plan,) = plan_grasps([100, 0, 100, 0, 100, 0], LAYOUT)
    assert plan.tie_break


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [({"object_threshold_pa": -1.0}, ">= 0"), ({"safety_shift": 0.7}, "safety shift")],
    ids=["negative-threshold", "shift-too-large"],
)
def test_bad_parameters(kwargs: dict, match: str) -> None:
    with pytest.raises(InputError, match=match):
        PlannerParams(**kwargs)


def test_wrong_channel_count() -> None:
    with pytest.raises(InputError, match="needs 6 increments"):
        plan_grasps([1.0] * 5, LAYOUT)


# --- general R x C pads -----------------------------------------------------------------


def test_rectangle_on_a_3x4_pad_is_a_big_two_module_object() -> None:
    layout = PadLayout(3, 4)
    d = np.zeros(12)
    d[[0, 1, 2, 4, 5, 6]] = [100, 100, 300, 100, 100, 300]  # rows 0-1, columns 0-2
    (plan,) = plan_grasps(d, layout)
    assert plan.rule == "n6-major-axis"  # a 2 x 3 block, as the thesis pad
    assert plan.theta == math.pi / 2
    np.testing.assert_allclose(plan.cog, (1.9, 2.0))


def test_diagonal_line_on_a_3x3_pad() -> None:
    layout = PadLayout(3, 3)
    d = np.zeros(9)
    d[[0, 4, 8]] = 100.0
    (plan,) = plan_grasps(d, layout)
    assert plan.rule == "n3-diagonal-line"
    assert plan.theta == math.pi / 4
    np.testing.assert_allclose(plan.cog, (1.5, 1.5))


def test_large_object_on_a_4x4_pad_reduces_to_a_known_case() -> None:
    layout = PadLayout(4, 4)
    d = np.zeros(16)
    d[[0, 1, 2, 3, 5, 9]] = [100, 100, 100, 100, 100, 100]  # a T
    (plan,) = plan_grasps(d, layout)
    assert plan.rule.startswith("n6-drop-farthest")
    assert set(plan.reduced_modules) <= {1, 2, 3, 4, 6, 10}
    assert 0 <= plan.cog[0] <= 4 and 0 <= plan.cog[1] <= 4


# --- properties ---------------------------------------------------------------------------

_patterns = st.lists(
    st.one_of(st.just(0.0), st.floats(min_value=60.0, max_value=2000.0, allow_nan=False)),
    min_size=6,
    max_size=6,
).filter(lambda v: any(x > 0 for x in v))


def _mirror(v: list[float]) -> list[float]:
    return [v[2], v[1], v[0], v[5], v[4], v[3]]


@settings(max_examples=300, deadline=None)
@given(_patterns)
def test_mirroring_left_right_mirrors_the_plan(v: list[float]) -> None:
    plans = plan_grasps(v, LAYOUT)
    mirrored = plan_grasps(_mirror(v), LAYOUT)
    assume(not any(p.tie_break for p in plans + mirrored))
    assert len(plans) == len(mirrored)
    by_modules = {
        tuple(sorted({3: 1, 1: 3, 2: 2, 6: 4, 4: 6, 5: 5}[m] for m in p.modules)): p for p in plans
    }
    for q in mirrored:
        p = by_modules[q.modules]
        np.testing.assert_allclose((3.0 - q.cog[0], q.cog[1]), p.cog, atol=1e-9)
        t = -q.theta if not math.isclose(q.theta, math.pi / 2) else q.theta
        assert math.isclose(t, p.theta, abs_tol=1e-12)


@settings(max_examples=200, deadline=None)
@given(_patterns, st.floats(min_value=1.0, max_value=50.0))
def test_scaling_all_increments_leaves_the_plan_unchanged(v: list[float], k: float) -> None:
    assume(max(abs(x) for x in v) * k <= 10_000.0)  # within the sensor's full scale
    plans = plan_grasps(v, LAYOUT)
    scaled = plan_grasps([k * x for x in v], LAYOUT)
    assume(not any(p.tie_break for p in plans + scaled))
    assert [(p.modules, p.rule, p.theta) for p in plans] == [
        (p.modules, p.rule, p.theta) for p in scaled
    ]
    for p, q in zip(plans, scaled, strict=True):
        np.testing.assert_allclose(p.cog, q.cog, atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(_patterns, st.lists(st.floats(min_value=-500.0, max_value=50.0), min_size=6, max_size=6))
def test_increments_below_threshold_never_change_the_plan(
    v: list[float], noise: list[float]
) -> None:
    noisy = [x if x > 0 else n for x, n in zip(v, noise, strict=True)]
    assert plan_grasps(v, LAYOUT) == plan_grasps(noisy, LAYOUT)
