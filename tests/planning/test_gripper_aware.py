"""The gripper-aware planner: the thesis's grasp where it is sensed, a sensed one where not."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import (
    TABLE_6_1,
    GripperAwarePlanner,
    PlannerParams,
    RetryPlanner,
    ThesisPlanner,
    across_pairs,
    along_load_axis,
    bridge_pairs,
    centred_on_load,
    landing_side,
    load_axis,
    make_planner,
    object_extent_m,
    plan_grasps,
    pressed_share,
    sensed_share,
)
from softpad.planning._records import GraspPlan
from softpad.sensing import detect_objects, make_contact_detector, sensing_ratio

LAYOUT = PadLayout()
GRIPPER = GripperSpec(max_width_m=0.06, min_width_m=0.02, tip_thickness_m=4e-3)


def _plans(name: str) -> tuple:
    case = next(c for c in TABLE_6_1 if c.name == name)
    objects = detect_objects(case.delta_pa, LAYOUT)
    planner = GripperAwarePlanner(GRIPPER)
    return (
        ThesisPlanner().plan(case.delta_pa, objects, LAYOUT)[0],
        planner.plan(case.delta_pa, objects, LAYOUT)[0],
        planner,
    )


def test_response_is_full_at_the_centre_and_none_on_the_seam() -> None:
    centre = LAYOUT.to_metres((1.5, 0.5))
    seam = LAYOUT.to_metres((1.0, 0.5))  # the line between modules 4 and 5
    assert sensed_share(tuple(centre), 0.0, GRIPPER, LAYOUT) > 0.9
    thin = GripperSpec(tip_width_m=4e-3, tip_thickness_m=4e-3)
    assert sensed_share(tuple(seam), 0.0, thin, LAYOUT) == 0.0
    off_pad = (-0.05, 0.02)
    assert sensed_share(off_pad, 0.0, GRIPPER, LAYOUT) == 0.0


@pytest.mark.parametrize(
    "name", [c.name for c in TABLE_6_1 if c.name not in ("object-1",)], ids=str
)
def test_reduces_to_the_thesis_where_a_tip_is_sensed(name: str) -> None:
    thesis, aware, planner = _plans(name)
    sensed = planner.tip_share(thesis.cog, thesis.theta, LAYOUT) >= planner.good_share
    if sensed and not planner._too_wide(thesis, thesis.theta, LAYOUT):
        assert aware == thesis
    else:  # kept unless a candidate scores better: never worse
        assert planner._score(aware, LAYOUT, aware.cog, aware.theta) >= planner._score(
            thesis, LAYOUT, thesis.cog, thesis.theta
        )


def test_object_1_tip_on_the_seam_is_moved_onto_a_module() -> None:
    """Object 1 (modules 3, 6): the thesis's (2.5, 1, 0) centres both tips on the 3|6 seam."""
    thesis, aware, planner = _plans("object-1")
    assert thesis.cog == pytest.approx((2.5, 1.0))
    before = planner.tip_share(thesis.cog, thesis.theta, LAYOUT)
    after = planner.tip_share(aware.cog, aware.theta, LAYOUT)
    assert before < 0.5 <= after
    assert LAYOUT.module_containing(*aware.cog) in (3, 6)
    assert aware.rule.endswith("+gripper") and aware.modules == thesis.modules


def test_cylinder_keeps_its_direction_and_moves_along_its_axis() -> None:
    """All six modules: the outline (90 mm across the rows) is wider than the 6 cm jaws in
    every direction, so the thesis's direction across the can is kept; the centre may move
    along the can (across the jaws) but only a third as far along the closing direction."""
    thesis, aware, planner = _plans("cylinder")
    assert object_extent_m(aware.modules, aware.theta, LAYOUT) > GRIPPER.max_width_m
    assert math.isclose(aware.theta, thesis.theta)
    dx, dy = aware.cog[0] - thesis.cog[0], aware.cog[1] - thesis.cog[1]
    assert abs(dy) <= planner.max_shift / 3 + 1e-9 and abs(dx) <= planner.max_shift + 1e-9
    assert planner.tip_share(aware.cog, aware.theta, LAYOUT) >= planner.tip_share(
        thesis.cog, thesis.theta, LAYOUT
    )


def test_planner_names() -> None:
    assert isinstance(make_planner("gripper-aware", gripper=GRIPPER), GripperAwarePlanner)
    with pytest.raises(InputError, match="unknown planner 'magic'"):
        make_planner("magic")


def test_a_wide_object_whose_tip_is_sensed_keeps_the_thesis_direction_centred_on_its_load() -> None:
    """A charger-like load on modules 1, 2, 4, 5, 6 (the simulated charger's increments, Pa):
    an outline wider than the 6 cm jaws whichever way they turn, a sensed fingertip: the
    thesis's direction and its position along the brick are kept, no shift is tried (a jaw
    would come down on a body that may fill the opening), and the centre moves across the row
    seam to the middle of the load under the jaws' path (modules 2 and 5, closing along y)."""
    delta = (305.0, 294.0, 3.0, 298.0, 297.0, 255.0)
    objects = detect_objects(delta, LAYOUT)
    planner = GripperAwarePlanner(GRIPPER)
    (thesis,) = ThesisPlanner().plan(delta, objects, LAYOUT)
    (aware,) = planner.plan(delta, objects, LAYOUT)
    assert planner.tip_share(thesis.cog, thesis.theta, LAYOUT) >= planner.good_share
    assert planner._too_wide(thesis, thesis.theta, LAYOUT)
    assert thesis.theta == pytest.approx(math.pi / 2) and thesis.cog[1] == pytest.approx(1.0)
    y = (294.0 * 1.5 + 297.0 * 0.5) / (294.0 + 297.0)  # modules 2 (y 1.5) and 5 (y 0.5)
    assert aware.theta == thesis.theta and aware.modules == thesis.modules
    assert aware.cog == pytest.approx((thesis.cog[0], y), abs=1e-12)
    assert aware.rule == thesis.rule + "+load-centred"


@pytest.mark.parametrize(("top", "bottom"), [(420.0, 310.0), (250.0, 460.0)])
def test_the_jaws_follow_a_wide_object_off_the_row_seam(top: float, bottom: float) -> None:
    """The same brick pushed towards one row loads that row's module more: the centre of grasp
    follows it (the thesis's rule keeps y on the seam, 2.1 mm median off the simulated
    charger on development seeds, where its 60 mm jaws leave 2.5 mm a side)."""
    delta = (400.0, top, 3.0, 300.0, bottom, 255.0)
    objects = detect_objects(delta, LAYOUT)
    (thesis,) = ThesisPlanner().plan(delta, objects, LAYOUT)
    (aware,) = GripperAwarePlanner(GRIPPER).plan(delta, objects, LAYOUT)
    assert thesis.cog[1] == pytest.approx(1.0)
    x = thesis.cog[0]
    assert LAYOUT.module_containing(x, 1.5) == 2  # the jaws' path crosses modules 2 and 5
    assert aware.cog == pytest.approx((x, (top * 1.5 + bottom * 0.5) / (top + bottom)))
    assert (aware.cog[1] > 1.0) is (top > bottom)


def test_centring_needs_load_under_the_jaws_path() -> None:
    """A plan whose path crosses none of its loaded modules is left as it is."""
    plan = GraspPlan((1, 4), (0.5, 1.0), (0.5, 1.0), math.pi / 2, "n2-vertical", (1, 4))
    assert centred_on_load(plan, LAYOUT, (0, 0, 0, 0, 0, 0)) == plan
    moved = centred_on_load(plan, LAYOUT, (100, 0, 0, 300, 0, 0))
    assert moved.cog == pytest.approx((0.5, (100 * 1.5 + 300 * 0.5) / 400))
    across = replace(plan, theta=0.0)  # closing along x: the path y = 1 runs on the seam
    assert centred_on_load(across, LAYOUT, (100, 0, 0, 300, 0, 0)) == across


#: A toy's plan increments with its foot loading module 6 above the outline threshold but
#: under t_o (compared seed 3, trial 2: one of three trials the toy was lost in this way).
TOY_FOOT_PA = (321.53, -5.13, 316.41, 3.91, 449.22, 29.79)


def test_centring_counts_only_load_above_t_o() -> None:
    """The toy on modules 1, 3 and 5 with its foot on module 6 (30 Pa) is outlined as four
    modules and gets Table 6.1's own toy grasp (2, 1, -pi/4). Its path crosses module 6 and
    the unloaded module 2 only, and the outline is wider than the jaws that way: centred on
    the foot, the centre went to module 6's centre and then to (2.29, 0.29), 18 mm beside the
    toy. Only modules above t_o count, and the path has none: the thesis's grasp stays."""
    objects = detect_objects(TOY_FOOT_PA, LAYOUT)
    assert objects == [(1, 3, 5)]
    (aware,) = GripperAwarePlanner(GripperSpec()).plan(TOY_FOOT_PA, objects, LAYOUT)
    assert aware.modules == (1, 3, 5, 6)
    assert aware.cog == pytest.approx(TABLE_6_1_TOY[:2]) and aware.theta == TABLE_6_1_TOY[2]
    plan = replace(aware, cog=(2.0, 1.0))
    assert centred_on_load(plan, LAYOUT, TOY_FOOT_PA) == plan
    # the same foot at t_o or above is load: the centre moves onto it
    heavy = (*TOY_FOOT_PA[:5], 60.0)
    assert centred_on_load(plan, LAYOUT, heavy).cog == pytest.approx((2.5, 0.5))


TABLE_6_1_TOY = (2.0, 1.0, -math.pi / 4)


#: Plan increments of simulated trials (MuJoCo, experiment seeds 100-103, not among the
#: compared seeds 0-19), pascals.
TOY_PA = (402.34, 78.37, 310.3, -0.49, 312.74, -0.73)  # hands on 1 and 3, body on 5
BANANA_PA = (-1.0, 33.0, 176.0, 212.0, 2.0, 1.0)  # middle on module 2 under t_o


def test_a_banana_split_at_t_o_is_planned_as_one_object() -> None:
    """t_o sees the banana's two ends as two objects and the thesis plans two grasps, one on
    each end; outlined at the noise floor it is one object on modules 2, 3, 4, planned by the
    thesis's own rule for that shape (the seed's banana: (1, 1, -pi/4))."""
    objects = detect_objects(BANANA_PA, LAYOUT)
    thesis = ThesisPlanner().plan(BANANA_PA, objects, LAYOUT)
    assert [p.modules for p in thesis] == [(3,), (4,)]
    (aware,) = GripperAwarePlanner(GRIPPER).plan(BANANA_PA, objects, LAYOUT)
    (whole,) = ThesisPlanner().plan(BANANA_PA, [(2, 3, 4)], LAYOUT)
    assert aware.modules == (2, 3, 4)
    assert aware.cog == pytest.approx(whole.cog) and aware.theta == pytest.approx(whole.theta)
    assert aware.cog == pytest.approx((1.0, 1.0)) and aware.theta == pytest.approx(-math.pi / 4)


#: Object 2 (a plate bridging two bricks, diagonal from module 1 to 5; development seed 140,
#: trial 2): the plate crosses module 2's corner, 33 Pa, under t_o, pascals.
BRIDGE_PA = (60.0, 33.0, 0.0, 3.0, 110.0, 0.0)


def test_a_diagonal_pair_is_not_outlined_into_an_l() -> None:
    """At t_o object 2 is the diagonal pair (1, 5), which the thesis grasps across the
    diagonal. The outline would add module 2, the corner the plate crosses, and the L's
    corner rule closes along a row, onto a brick (the trial was lost); the pair is kept.
    A module beside the pair that is not a corner between its two still joins it."""
    objects = detect_objects(BRIDGE_PA, LAYOUT)
    assert objects == [(1, 5)]
    (aware,) = GripperAwarePlanner(GRIPPER).plan(BRIDGE_PA, objects, LAYOUT)
    (pair,) = ThesisPlanner().plan(BRIDGE_PA, objects, LAYOUT)
    assert aware.modules == (1, 5) and aware.theta == pytest.approx(math.pi / 4)
    assert aware.cog == pytest.approx(pair.cog) and aware.rule == pair.rule
    (l_shape,) = ThesisPlanner().plan(BRIDGE_PA, [(1, 2, 5)], LAYOUT)
    assert l_shape.theta == pytest.approx(0.0)  # what the outline gave
    beside = (60.0, 0.0, 0.0, 3.0, 110.0, 33.0)  # module 6, next to 5 only
    (grown,) = GripperAwarePlanner(GRIPPER).plan(beside, detect_objects(beside, LAYOUT), LAYOUT)
    assert grown.modules == (1, 5, 6)


def test_a_shift_off_the_seam_goes_towards_the_load() -> None:
    """The toy's thesis grasp (1.5, ~1.0, 0) puts both fingertips on the row seam. Both
    shifts across it reach sensed area; the load term picks the side of the toy's body
    (module 5, 313 Pa), not the gap between its arms over module 2 (78 Pa), where the
    unweighted score went (and the trial lost the toy: its COG lay outside the object)."""
    objects = detect_objects(TOY_PA, LAYOUT)
    (thesis,) = ThesisPlanner().plan(TOY_PA, objects, LAYOUT)
    assert abs(thesis.cog[1] - 1.0) < 0.1 and thesis.theta == 0.0
    (aware,) = GripperAwarePlanner(GRIPPER).plan(TOY_PA, objects, LAYOUT)
    (blind,) = GripperAwarePlanner(GRIPPER, load_cost=0.0).plan(TOY_PA, objects, LAYOUT)
    assert LAYOUT.module_containing(*aware.cog) == 5
    assert LAYOUT.module_containing(*blind.cog) == 2
    planner = GripperAwarePlanner(GRIPPER)
    assert planner.tip_share(aware.cog, aware.theta, LAYOUT) >= planner.good_share


def _adaptive_ratio() -> float:
    ratio = sensing_ratio(make_contact_detector("adaptive", 100.0), 100.0)
    assert ratio is not None
    return ratio


def test_a_detector_that_senses_the_seam_keeps_object_1s_grasp() -> None:
    """Object 1's thesis grasp lays both 16 mm soles across the 3|6 row seam: 0.31 of a
    centred fingertip's rise. The thesis detector needs 0.5 (moved, test above); the adaptive
    CUSUM at 100 Hz catches steps 0.44 as small, so it needs 0.22: the thesis's grasp stays."""
    case = next(c for c in TABLE_6_1 if c.name == "object-1")
    objects = detect_objects(case.delta_pa, LAYOUT)
    (thesis,) = ThesisPlanner().plan(case.delta_pa, objects, LAYOUT)
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=_adaptive_ratio())
    assert planner.needed_share == pytest.approx(0.5 * planner.sensing_ratio)
    assert planner.needed_share < planner.tip_share(thesis.cog, thesis.theta, LAYOUT) < 0.5
    (aware,) = planner.plan(case.delta_pa, objects, LAYOUT)
    assert aware == thesis


@pytest.mark.parametrize(("y", "moved"), [(0.0, True), (0.05, True), (0.1, False)])
def test_a_fingertip_half_off_the_pad_is_moved_for_any_detector(y: float, moved: bool) -> None:
    """A grasp on the pad's edge (closing along x at y): its soles hang off the pad (shares
    0.15, 0.22, 0.33 of a centred one). Under the adaptive CUSUM's 0.22 the grasp moves onto
    the module, from it it stays."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=_adaptive_ratio())
    plan = GraspPlan((5,), (1.5, y), (1.5, y), 0.0, "edge", (5,))
    aware = planner.improve(plan, LAYOUT)
    assert (aware != plan) is moved
    after = planner.tip_share(aware.cog, aware.theta, LAYOUT)
    assert after >= planner.needed_share
    assert LAYOUT.module_containing(*aware.cog) == 5


@pytest.mark.parametrize("ratio", [0.0, -0.5, math.nan, math.inf])
def test_a_bad_sensing_ratio_is_named(ratio: float) -> None:
    with pytest.raises(InputError, match="sensing ratio"):
        GripperAwarePlanner(GRIPPER, sensing_ratio=ratio)


def test_planner_for_a_detector_measures_its_ratio_only_for_the_gripper_aware_planner() -> None:
    from softpad.planning import planner_for
    from softpad.sensing import ThesisContactDetector

    class Unprobed(ThesisContactDetector):
        @property
        def floor_key(self) -> tuple[object, ...]:
            raise AssertionError("the thesis planner needs no step floor")

    assert isinstance(planner_for("thesis", GRIPPER, None, Unprobed(), 100.0), ThesisPlanner)
    detector = make_contact_detector("adaptive", 100.0)
    aware = planner_for("gripper-aware", GRIPPER, None, detector, 100.0)
    assert isinstance(aware, GripperAwarePlanner)
    assert aware.sensing_ratio == pytest.approx(_adaptive_ratio())


#: Plan increments of a simulated can trial (MuJoCo, development seed 100): its heavy end on
#: modules 1 and 4, its light tinplate body barely loading column 3, pascals.
CAN_PA = (138.0, 28.0, -1.0, 102.0, 60.0, 7.0)


def test_a_missed_square_is_retried_a_quarter_turn_across_its_load() -> None:
    """The can seen as a square of modules 1, 2, 4, 5: planned at the square's centre closing
    along x (the thesis's default direction); after a miss, closing along y, the centre's x
    kept and its y moved to the load centroid's (the PCOM's)."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    (plan,) = planner.plan(CAN_PA, detect_objects(CAN_PA, LAYOUT), LAYOUT)
    assert plan.modules == (1, 2, 4, 5) and plan.theta == pytest.approx(0.0)
    assert plan.cog == pytest.approx((1.0, 1.0))
    turned = planner.retry(plan, CAN_PA, LAYOUT, CAN_PA)
    assert turned is not None and turned.theta == pytest.approx(math.pi / 2)
    # rows at y = 1.5 (modules 1, 2) and 0.5 (4, 5), weighted by their increments
    y = (1.5 * (138.0 + 28.0) + 0.5 * (102.0 + 60.0)) / (138.0 + 28.0 + 102.0 + 60.0)
    assert turned.cog == pytest.approx((1.0, y), abs=1e-12)
    assert turned.cog[1] == pytest.approx(plan.pcom[1], abs=1e-12)
    assert turned.modules == plan.modules
    assert turned.rule == plan.rule + "+turned-after-miss+load-centred"
    # a second miss turns back: a quarter turn each time, wrapped to (-pi/2, pi/2]
    again = planner.retry(turned, CAN_PA, LAYOUT, CAN_PA)
    assert again is not None and again.theta == pytest.approx(0.0)
    assert again.cog == pytest.approx(plan.pcom, abs=1e-12)


#: Plan increments of a simulated can trial (MuJoCo, development seed 116, trial 2), pascals:
#: the heavy end on module 4 by the row seam, the body on the top row (1, 2, 3).
CAN_L_PA = (72.75, 92.53, 27.83, 192.38, -1.22, -2.93)
#: Where that can's axis crossed x = 22.5 mm (the plan's x) once it had settled, metres
#: (MuJoCo: the can's geom centre and yaw read when the retry landed on it).
CAN_L_AXIS_Y_M = 0.0437


def test_a_can_missed_along_its_length_is_retried_across_its_axis() -> None:
    """The L of modules 1-4 is planned along the top row (the corner-shift rule, 36 mm up);
    closing across the can about that centre put a jaw on it 7.7 mm off its axis, more than
    the 5 mm a side a 50 mm can leaves between 60 mm jaws. Centred on the load, the turned
    grasp lies within that clearance."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    (plan,) = planner.plan(CAN_L_PA, detect_objects(CAN_L_PA, LAYOUT), LAYOUT)
    assert plan.modules == (1, 2, 3, 4) and plan.theta == pytest.approx(0.0)
    clearance_m = (GRIPPER.max_width_m - 0.050) / 2
    assert abs(plan.cog[1] * LAYOUT.pitch_m - CAN_L_AXIS_Y_M) > clearance_m
    turned = planner.retry(plan, CAN_L_PA, LAYOUT, CAN_L_PA)
    assert turned is not None and turned.theta == pytest.approx(math.pi / 2)
    assert turned.cog[0] == pytest.approx(plan.cog[0], abs=1e-12)
    assert abs(turned.cog[1] * LAYOUT.pitch_m - CAN_L_AXIS_Y_M) < clearance_m / 2


@pytest.mark.parametrize(
    ("modules", "theta", "turned"),
    [
        ((1, 2, 3, 4), 0.0, math.pi / 2),  # an L along the top row: 90 mm across, 135 along
        ((1, 2, 4, 5, 6), math.pi / 2, None),  # the charger's outline: turning it is wider
        ((2, 3, 4), -math.pi / 4, None),  # the banana's diagonal: 95 mm, 159 mm turned
    ],
)
def test_a_retry_turns_only_where_the_outline_is_no_wider(
    modules: tuple[int, ...], theta: float, turned: float | None
) -> None:
    """Where turning is wider and the landing pressed nothing, the retry after a miss is the
    same grasp again (nothing says where else), and there is none at the landing."""
    plan = GraspPlan(modules, (1.0, 1.0), (1.0, 1.0), theta, "given", modules)
    planner = GripperAwarePlanner(GRIPPER)
    got = planner.retry(plan, (100.0,) * 6, LAYOUT, (0.0,) * 6)
    before = object_extent_m(modules, theta, LAYOUT)
    after = object_extent_m(modules, theta + math.pi / 2, LAYOUT)
    assert (after <= before) is (turned is not None)
    assert got is not None
    if turned is None:
        assert got == replace(plan, rule="given+again-after-miss")
        assert planner.retry(plan, (100.0,) * 6, LAYOUT, (0.0,) * 6, closed=False) is None
    else:
        assert got.theta == pytest.approx(turned)


def test_a_balanced_miss_is_retried_as_it_was_unless_tentative() -> None:
    """A miss whose landing pressed both sides of the jaws' centre alike (object 6's rocking
    stack sensed above its top; a banana nudged by the jaws) is tried once more as it was;
    a tentative grasp (between two one-module objects, which may be two objects) is not."""
    planner = GripperAwarePlanner(GRIPPER)
    row = GraspPlan((4, 5, 6), (1.48, 0.5), (1.48, 0.5), math.pi / 2, "n3-row", (4, 5, 6))
    rise = (4.0, 2.0, -2.0, 108.0, 142.0, 125.0)  # development seed 122, trial 1: even
    assert landing_side(row, LAYOUT, rise) == 0
    again = planner.retry(row, (2.0, -5.0, -2.0, 226.0, 244.0, 211.0), LAYOUT, rise)
    assert again == replace(row, rule="n3-row+again-after-miss")
    bridge = replace(row, tentative=True)
    assert planner.retry(bridge, (2.0, -5.0, -2.0, 226.0, 244.0, 211.0), LAYOUT, rise) is None


@pytest.mark.parametrize(("top", "bottom", "side"), [(180.0, 20.0, 1), (15.0, 160.0, -1)])
def test_a_brick_missed_across_its_width_is_retried_towards_the_pressed_side(
    top: float, bottom: float, side: int
) -> None:
    """The charger's outline (1, 2, 4, 5, 6) closed along y: turning would close across its
    75 mm, so after a miss the centre moves half a fingertip sole (6.5 mm thick: 3.25 mm)
    along y towards the row the landing jaw pressed into the pad, direction kept."""
    gripper = GripperSpec(max_width_m=0.06, min_width_m=0.02)
    plan = GraspPlan((1, 2, 4, 5, 6), (1.2, 1.0), (1.2, 1.0), math.pi / 2, "n5", (1, 2, 4, 5, 6))
    rise = (top, top, 0.0, bottom, bottom, bottom / 2)
    assert landing_side(plan, LAYOUT, rise) == side
    got = GripperAwarePlanner(gripper).retry(plan, (300.0,) * 6, LAYOUT, rise)
    assert got is not None and got.theta == plan.theta
    assert gripper.tip_thickness_m == pytest.approx(6.5e-3)
    step = side * 3.25e-3 / LAYOUT.pitch_m
    assert got.cog == pytest.approx((1.2, 1.0 + step), abs=1e-12)
    assert got.rule == "n5+shifted-after-miss"
    # a landing that pressed both rows alike says nothing of the side
    assert landing_side(plan, LAYOUT, (100, 100, 0, 67, 67, 66)) == 0


#: A can along the row seam, its heavy end on module 1 (development seed 120, trial 3):
#: plan increments, the rise when a jaw landed on it, and where its settled axis crossed the
#: plan's x (45.2 mm; MuJoCo, the can's geom centre and yaw at the landing), pascals, metres.
CAN_SEAM_PA = (200.2, 3.2, -5.1, 58.1, 94.2, 55.9)
CAN_SEAM_LANDING_PA = (617.0, 8.0, 13.0, 394.0, 552.0, 563.0)
CAN_SEAM_AXIS_Y_M = 0.0441


def test_a_can_landed_on_far_from_its_axis_is_retried_on_the_load_under_the_path() -> None:
    """The corner-side rule grasps the can across on the bottom row's centre line, 21.6 mm
    from its axis; half a sole's shift (the brick's retry) would land on it again. The
    retry goes to the middle of the load under the fingertips' path instead: the path runs
    along the seam between columns 1 and 2, so modules 1, 4 and 5 count (2 is under t_o),
    and the centre lands within the 5 mm a side a 50 mm can leaves in 60 mm jaws."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    (plan,) = planner.plan(CAN_SEAM_PA, detect_objects(CAN_SEAM_PA, LAYOUT), LAYOUT)
    assert plan.modules == (1, 4, 5, 6) and plan.theta == pytest.approx(math.pi / 2)
    clearance_m = (GRIPPER.max_width_m - 0.050) / 2
    half_sole_m = GRIPPER.tip_thickness_m / 2
    assert CAN_SEAM_AXIS_Y_M - (plan.cog[1] * LAYOUT.pitch_m + half_sole_m) > clearance_m
    assert landing_side(plan, LAYOUT, CAN_SEAM_LANDING_PA) == 1
    got = planner.retry(plan, CAN_SEAM_PA, LAYOUT, CAN_SEAM_LANDING_PA)
    assert got is not None and got.theta == plan.theta and got.cog[0] == plan.cog[0]
    y = (1.5 * 200.2 + 0.5 * (58.1 + 94.2)) / (200.2 + 58.1 + 94.2)
    assert got.cog[1] == pytest.approx(y, abs=1e-9)
    assert abs(got.cog[1] * LAYOUT.pitch_m - CAN_SEAM_AXIS_Y_M) < clearance_m
    assert got.rule == plan.rule + "+shifted-after-miss"


#: Landing rises of development trials (seeds 101 and 104, pascals): a jaw on the charger's
#: brick edge (the top row pressed, the bottom row unloaded as the brick tips), and a jaw on
#: the toy's right arm (module 3) with its body pressing module 5, on the jaws' centre line.
CHARGER_LANDING_PA = (684.0, 683.0, 377.0, -93.0, -93.0, 3.0)
TOY_LANDING_PA = (-5.0, 232.0, 648.0, 9.0, 314.0, 0.0)


def test_pressed_share_is_the_rise_on_one_side_of_the_centre_line() -> None:
    brick = GraspPlan((1, 2, 4, 5, 6), (1.33, 1.05), (1.33, 1.05), math.pi / 2, "n6", ())
    assert pressed_share(brick, LAYOUT, CHARGER_LANDING_PA) == pytest.approx(1744 / 1747)
    # along x about column 2: modules 2 and 5 lie on the line and count on neither side
    toy = GraspPlan((1, 2, 3, 5), (1.5, 0.98), (1.5, 0.98), 0.0, "n4", ())
    assert pressed_share(toy, LAYOUT, TOY_LANDING_PA) == pytest.approx(648 / 1203)
    assert pressed_share(toy, LAYOUT, (0.0, -3.0, 0.0, 0.0, 0.0, 0.0)) == 0.0
    half = (100.0, 0.0, 0.0, 0.0, 0.0, 100.0)  # module 1 (x 0.5) and module 6 (x 2.5)
    assert pressed_share(toy, LAYOUT, half) == pytest.approx(0.5)


def test_a_landing_is_retried_before_closing_only_when_one_sided() -> None:
    """At the landing (``closed=False``) the planner offers its retry only when the rise lies
    on one side of the jaws' centre line (a tipped brick); after a miss, whatever the rise."""
    gripper = GripperSpec(max_width_m=0.06, min_width_m=0.02)
    planner = GripperAwarePlanner(gripper)
    brick = GraspPlan((1, 2, 4, 5, 6), (1.33, 1.05), (1.33, 1.05), math.pi / 2, "n6", ())
    early = planner.retry(brick, (300.0,) * 6, LAYOUT, CHARGER_LANDING_PA, closed=False)
    assert early == planner.retry(brick, (300.0,) * 6, LAYOUT, CHARGER_LANDING_PA)
    assert early is not None and early.rule == "n6+shifted-after-miss"
    assert early.cog[1] > brick.cog[1]  # towards the pressed top row
    balanced = (300.0, 300.0, 0.0, 280.0, 290.0, 100.0)
    assert planner.retry(brick, (300.0,) * 6, LAYOUT, balanced, closed=False) is None
    toy = GraspPlan((1, 2, 3, 5), (1.5, 0.98), (1.5, 0.98), 0.0, "n4", (1, 2, 3, 5))
    assert planner.retry(toy, (300.0,) * 6, LAYOUT, TOY_LANDING_PA, closed=False) is None
    assert planner.retry(toy, (300.0,) * 6, LAYOUT, TOY_LANDING_PA) is not None


def test_only_the_gripper_aware_planner_retries() -> None:
    assert isinstance(GripperAwarePlanner(GRIPPER), RetryPlanner)
    assert not isinstance(ThesisPlanner(), RetryPlanner)
    plan = GraspPlan((1, 4), (0.5, 1.0), (0.5, 1.0), 0.0, "n2-vertical", (1, 4))
    with pytest.raises(InputError, match="6"):
        GripperAwarePlanner(GRIPPER).retry(plan, (1.0, 2.0), LAYOUT, (0.0,) * 6)


#: A simulated banana resting on its ends (development seed 105): its middle arches over
#: modules 2 and 5 and loads nothing, so t_o and the outline see two one-module objects.
SPLIT_BANANA_PA = (-1.0, -4.0, 227.0, 239.0, -2.0, -2.0)


def test_two_one_module_objects_are_grasped_across_the_line_joining_them() -> None:
    """Each end is grasped at its module's centre (the thesis's N = 1 rule), closing across the
    line from module 4 to module 3 (direction (2, 1)): theta = atan2(1, 2) - 90 degrees,
    not the default 0, which closes along the banana and onto it."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    objects = detect_objects(SPLIT_BANANA_PA, LAYOUT)
    assert objects == [(3,), (4,)]
    thesis = ThesisPlanner().plan(SPLIT_BANANA_PA, objects, LAYOUT)
    bridge, *plans = planner.plan(SPLIT_BANANA_PA, objects, LAYOUT)
    assert bridge.tentative and not any(p.tentative for p in plans)
    expected = math.atan2(1.0, 2.0) - math.pi / 2
    for t, p in zip(thesis, plans, strict=True):
        assert t.theta == 0.0 and p.cog == t.cog and p.modules == t.modules
        assert p.theta == pytest.approx(expected, abs=1e-12)
        assert p.rule == t.rule + "+across-pair"


def test_only_one_module_objects_beside_others_are_turned() -> None:
    """A lone one-module object keeps the default direction; an N = 2 object keeps its rule's
    direction; a one-module object beside it closes across the line to its PCOM."""
    lone = GraspPlan((4,), (0.5, 0.5), (0.5, 0.5), 0.0, "n1-module-centre", (4,))
    pair = GraspPlan((3, 6), (2.5, 1.2), (2.5, 1.2), 0.0, "n2-vertical", (3, 6))
    assert across_pairs([lone]) == [lone]
    turned, kept = across_pairs([lone, pair])
    assert kept == pair
    assert turned.theta == pytest.approx(math.atan2(0.7, 2.0) - math.pi / 2)


def test_a_pair_of_ends_is_first_grasped_between_them() -> None:
    """The split banana: before its two ends, a tentative grasp on modules 3 and 4 at the
    mean of their centres weighted by their increments (a rigid body on two supports has its
    centre of mass where their forces balance), closing across the line joining them."""
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    bridge = planner.plan(SPLIT_BANANA_PA, detect_objects(SPLIT_BANANA_PA, LAYOUT), LAYOUT)[0]
    w3, w4 = SPLIT_BANANA_PA[2], SPLIT_BANANA_PA[3]
    x = (w3 * 2.5 + w4 * 0.5) / (w3 + w4)
    y = (w3 * 1.5 + w4 * 0.5) / (w3 + w4)
    assert bridge.modules == (3, 4) and bridge.rule == "bridge-pair"
    assert bridge.cog == pytest.approx((x, y), abs=1e-12) and bridge.pcom == bridge.cog
    assert bridge.theta == pytest.approx(math.atan2(1.0, 2.0) - math.pi / 2, abs=1e-12)
    assert bridge.to_dict(LAYOUT)["tentative"] is True


def test_only_mutually_nearest_one_module_objects_are_bridged() -> None:
    """A lone one-module object, or one beside a larger object, gets no bridge; of three
    one-module objects in a row (1 apart, then 1.5), only the two closer ones are bridged."""
    d = (100.0, 0.0, 100.0, 100.0, 0.0, 100.0)
    a = GraspPlan((1,), (0.0, 0.0), (0.0, 0.0), 0.0, "n1", (1,))
    b = GraspPlan((3,), (1.0, 0.0), (1.0, 0.0), 0.0, "n1", (3,))
    c = GraspPlan((4,), (2.5, 0.0), (2.5, 0.0), 0.0, "n1", (4,))
    big = GraspPlan((3, 6), (1.0, 0.5), (1.0, 0.5), 0.0, "n2", (3, 6))
    assert bridge_pairs([a], d) == [a]
    assert bridge_pairs([a, big], d) == [a, big]
    bridge, *rest = bridge_pairs([a, b, c], d)
    assert rest == [a, b, c]
    assert bridge.modules == (1, 3) and bridge.cog == pytest.approx((0.5, 0.0))
    assert bridge.theta == pytest.approx(math.pi / 2)  # across the line along x
    # the weights move the centre towards the heavier end; no weight at all: the middle
    heavy = bridge_pairs([a, b], (300.0, 0.0, 100.0, 0.0, 0.0, 0.0))[0]
    assert heavy.cog == pytest.approx((0.25, 0.0))
    assert bridge_pairs([a, b], (0.0,) * 6)[0].cog == pytest.approx((0.5, 0.0))


def test_the_load_axis_of_modules() -> None:
    """Equal loads on two modules: the line through their centres; a square of equal loads
    or no load: no axis; a lighter third module turns the axis towards it."""
    d = np.zeros(6)
    d[[2, 3]] = 200.0  # modules 3 and 4
    assert load_axis((3, 4), LAYOUT, d) == pytest.approx(math.atan2(1.0, 2.0), abs=1e-12)
    assert load_axis((1, 2, 4, 5), LAYOUT, np.full(6, 100.0)) is None
    assert load_axis((3, 4), LAYOUT, np.zeros(6)) is None
    d[1] = 60.0  # module 2, above the 4-3 line
    assert math.atan2(1.0, 2.0) < load_axis((2, 3, 4), LAYOUT, d) < math.pi / 4


#: A simulated banana on modules 2, 3 and 4 (development seed 105, trial 1): its centre of
#: mass over the pad's centre, the PCOM 0.01 module units right of the bisector through 2.
DIAGONAL_BANANA_PA = (-2.7, 60.3, 206.8, 201.7, 4.2, -1.0)


def test_a_diagonal_linked_object_is_planned_on_the_side_of_its_load_axis() -> None:
    """The thesis takes side module 3 (the PCOM right of the bisector): (1.71, 1.5), closing
    along y, 27 degrees off the banana's 4-3 chord. The load's axis (27 degrees) lies nearer
    the 2-4 diagonal (45) than the 2-3 row (0): side module 4, the thesis's own Table 6.1
    plan for the banana, (1, 1) closing at -45 degrees. Mirrored so that the PCOM falls left
    of the bisector, the thesis already takes side 4 and the plan is the thesis's."""
    thesis = plan_grasps(DIAGONAL_BANANA_PA)[0]
    assert thesis.rule == "n3-diagonal-shift" and thesis.theta == pytest.approx(math.pi / 2)
    turned = along_load_axis(thesis, LAYOUT, DIAGONAL_BANANA_PA, PlannerParams())
    assert turned.rule == "n3-diagonal-corner+load-axis"
    assert turned.cog == pytest.approx((1.0, 1.0)) and turned.theta == pytest.approx(-math.pi / 4)
    assert turned.pcom == thesis.pcom and turned.modules == thesis.modules
    planner = GripperAwarePlanner(GRIPPER, sensing_ratio=0.44)
    objects = detect_objects(DIAGONAL_BANANA_PA, LAYOUT)
    assert planner.plan(DIAGONAL_BANANA_PA, objects, LAYOUT)[0].rule.startswith(turned.rule)
    left = (-2.7, 60.3, 201.7, 206.8, 4.2, -1.0)  # PCOM left of the bisector
    kept = plan_grasps(left)[0]
    assert kept.rule == "n3-diagonal-corner"
    assert along_load_axis(kept, LAYOUT, left, PlannerParams()) is kept
    # not diagonal-linked (a row, an L): as it is
    for d in ((100.0, 100.0, 100.0, 0, 0, 0), (100.0, 100.0, 0, 100.0, 0, 0)):
        p = plan_grasps(d)[0]
        assert along_load_axis(p, LAYOUT, d, PlannerParams()) is p


def test_bridge_pairs_names_bad_increments() -> None:
    a = GraspPlan((1,), (0.5, 1.5), (0.5, 1.5), 0.0, "n1", (1,))
    b = GraspPlan((6,), (2.5, 0.5), (2.5, 0.5), 0.0, "n1", (6,))
    with pytest.raises(InputError, match="module 6"):
        bridge_pairs([a, b], (1.0, 2.0))
    with pytest.raises(InputError, match="finite"):
        bridge_pairs([a, b], (1.0, float("nan"), 0, 0, 0, 1.0))
