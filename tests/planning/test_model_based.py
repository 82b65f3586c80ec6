"""The model-based planner: footprints estimated from increments the simulator's FEM response
predicts (an independent implementation: softpad.sim.PadResponse), grasps chosen under them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import (
    TABLE_6_1,
    ModelBasedParams,
    ModelBasedPlanner,
    RetryPlanner,
    make_planner,
)
from softpad.planning._model_based import estimate, packaged_pad_model
from softpad.sensing import detect_objects, outline_objects

LAYOUT = PadLayout()
WIDE = GripperSpec.from_mounting("10/4")


def _increments(centre_mm, size_mm, yaw_deg, mass_g, layout=LAYOUT):
    """Sealed-chamber rises of an evenly loaded rectangle, Pa (the simulator's FEM model)."""
    from softpad.sim import PadResponse

    pad = PadResponse(layout)
    loads = pad.rect_equivalent_loads(
        np.asarray(centre_mm) * 1e-3,
        np.asarray(size_mm) * 1e-3,
        mass_g * 1e-3 * 9.80665,
        thesis.P0_PA,
        math.radians(yaw_deg),
    )
    return pad.sealed_rise_pa(loads, thesis.P0_PA)


#: Rectangles (centre mm, size mm, yaw deg, mass g) over the 2 x 3 pad (135 x 90 mm).
BOXES = [
    ((67.5, 45.0), (60.0, 30.0), 0.0, 120.0),
    ((40.0, 60.0), (40.0, 40.0), 20.0, 90.0),
    ((95.0, 40.0), (80.0, 25.0), 90.0, 180.0),
    ((70.0, 50.0), (100.0, 20.0), 30.0, 75.0),
    ((30.0, 25.0), (25.0, 25.0), 0.0, 45.0),
]


@pytest.mark.parametrize("box", BOXES)
def test_estimate_finds_the_centre_of_a_simulated_rectangle(box):
    centre, size, yaw, mass = box
    d = _increments(centre, size, yaw, mass)
    (obj,) = detect_objects(d, LAYOUT)
    post = estimate(d, obj, LAYOUT, packaged_pad_model(), ModelBasedParams())
    assert post.probs.sum() == pytest.approx(1.0)
    got = np.asarray(post.mean_centre()) * LAYOUT.pitch_m * 1e3
    # the hypotheses' centres lie on an 11 mm grid: the mean within a grid step
    assert math.dist(got, centre) < 11.25, (got, centre)


@pytest.mark.parametrize("box", BOXES)
def test_chosen_grasp_holds_the_simulated_rectangle(box):
    """The grasp centre lies on the rectangle, in the middle half across the jaws, and the
    open jaws clear it (its extent along the closing direction within the opening)."""
    centre, size, yaw, mass = box
    d = _increments(centre, size, yaw, mass)
    (plan,) = ModelBasedPlanner(WIDE).plan(d, detect_objects(d, LAYOUT), LAYOUT)
    c = np.asarray(plan.cog) * LAYOUT.pitch_m * 1e3 - np.asarray(centre)
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    phi = math.radians(yaw) - plan.theta
    e_u = (size[0] * abs(math.cos(phi)) + size[1] * abs(math.sin(phi))) / 2
    e_n = (size[0] * abs(math.sin(phi)) + size[1] * abs(math.cos(phi))) / 2
    along, across = float(c @ u), float(c @ np.array([-u[1], u[0]]))
    assert abs(along) + e_u < WIDE.max_width_m * 1e3 / 2, (plan, along, e_u)
    assert abs(across) < e_n, (plan, across, e_n)


def test_plan_is_a_retry_planner_and_one_plan_per_object():
    planner = make_planner("model-based", gripper=WIDE)
    assert isinstance(planner, RetryPlanner)
    d = _increments((30.0, 45.0), (25.0, 25.0), 0.0, 60.0) + _increments(
        (115.0, 45.0), (20.0, 20.0), 0.0, 60.0
    )
    objects = detect_objects(d, LAYOUT)
    plans = planner.plan(d, objects, LAYOUT)
    assert [p.modules for p in plans] == objects
    for p in plans:  # each grasped on its own side of the pad
        assert LAYOUT.module_containing(*p.cog) in p.modules


def test_landing_is_evidence_that_moves_the_grasp():
    """A landing on the side the pad felt pressed rules out the hypotheses under which the
    jaws clear the object: the grasp chosen again differs from the one that landed, and
    the same evidence twice is no weaker."""
    d = _increments(*BOXES[0])
    planner = ModelBasedPlanner(WIDE)
    (plan,) = planner.plan(d, detect_objects(d, LAYOUT), LAYOUT)
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    rise = np.clip((LAYOUT.centers - np.asarray(plan.cog)) @ u, 0.0, None) * 100.0
    after = planner.retry(plan, d, LAYOUT, rise, closed=True)
    assert after is not None and after.rule.endswith("+after-landing")
    moved = math.dist(after.cog, plan.cog) > 1e-6
    turned = abs(math.remainder(after.theta - plan.theta, math.pi)) > 1e-6
    assert moved or turned


def test_landing_before_closing_offers_a_different_grasp_or_none():
    """At the landing, before closing, the planner offers a grasp only when the evidence
    moves its choice (more than 2 mm or 5 degrees), else None: the loop closes."""
    planner = ModelBasedPlanner(WIDE)
    for box in BOXES:
        d = _increments(*box)
        (plan,) = planner.plan(d, detect_objects(d, LAYOUT), LAYOUT)
        for rise in (np.zeros(6), d):
            after = planner.retry(plan, d, LAYOUT, rise, closed=False)
            if after is not None:
                moved = math.dist(after.cog, plan.cog) * LAYOUT.pitch_m > 2e-3
                turned = abs(math.remainder(after.theta - plan.theta, math.pi)) > 0.087
                assert moved or turned


def test_table_6_1_plans_keep_the_centre_on_the_objects_modules():
    planner = ModelBasedPlanner(WIDE)
    for case in TABLE_6_1:
        d = np.asarray(case.delta_pa)
        for p in planner.plan(d, detect_objects(d, LAYOUT), LAYOUT):
            assert -math.pi / 2 < p.theta <= math.pi / 2
            assert 0 <= p.cog[0] <= LAYOUT.cols and 0 <= p.cog[1] <= LAYOUT.rows


def test_a_larger_pad_is_planned_the_same_way():
    big = PadLayout(rows=8, cols=8)
    d = _increments((200.0, 150.0), (60.0, 30.0), 0.0, 120.0, big)
    (plan,) = ModelBasedPlanner(WIDE).plan(d, detect_objects(d, big), big)
    assert math.dist(np.asarray(plan.cog) * 45.0, (200.0, 150.0)) < 20.0


@pytest.mark.parametrize(
    "change",
    [
        {"noise_pa": -1.0},
        {"model_error": math.nan},
        {"centre_steps": 0},
        {"sizes_mm": ()},
        {"sizes_mm": (10.0, 900.0)},
    ],
)
def test_bad_parameters_are_refused(change):
    with pytest.raises(InputError):
        ModelBasedParams(**change)


def test_bad_sensing_ratio_is_refused():
    with pytest.raises(InputError, match="sensing ratio"):
        ModelBasedPlanner(WIDE, sensing_ratio=0.0)


def test_one_landing_asked_about_twice_is_evidence_once():
    """The loop asks at the landing (before closing) and again after the miss: the same
    landing weighs once, so the second answer equals a first ask after the miss."""
    d = _increments(*BOXES[0])
    objects = detect_objects(d, LAYOUT)
    twice, once = ModelBasedPlanner(WIDE), ModelBasedPlanner(WIDE)
    (plan,) = twice.plan(d, objects, LAYOUT)
    once.plan(d, objects, LAYOUT)
    rise = np.zeros(6)
    twice.retry(plan, d, LAYOUT, rise, closed=False)
    assert twice.retry(plan, d, LAYOUT, rise, closed=True) == once.retry(
        plan, d, LAYOUT, rise, closed=True
    )


def _loglik_one_at_a_time(d, layout, params, model, masked, light=()):
    """Every footprint hypothesis (module, centre, halves, yaw) -> (log-likelihood, share of
    its area on the pad), each predicted on its own from the footprint (``_pattern``) and
    scored over the pad's modules: the definition, without the planner's tables. ``light``
    modules (a light part's) are left out of the fit and cost only where the footprint
    predicts more than they read."""
    from softpad.planning._model_based import _pattern, _templates

    t = _templates(layout.pitch_m, params, model)
    side = 2 * t.radius + 1
    grid = np.asarray(d, dtype=float).reshape(layout.rows, layout.cols)[::-1]  # bottom row 0
    w = 1.0 / (params.noise_pa**2 + (params.model_error * grid) ** 2)
    full = w.copy()
    for m in (*masked, *light):
        row, col = layout.row_col(m)
        w[layout.rows - 1 - row, col] = 0.0
    lit = np.zeros_like(grid, dtype=bool)
    for m in light:
        row, col = layout.row_col(m)
        lit[layout.rows - 1 - row, col] = True
    out = {}
    for k in range(len(t.yaws)):
        (hl, hw), yaw = t.halves[k], t.yaws[k]
        load, cover = _pattern(t.offsets[k], 2 * hl, 2 * hw, yaw, model, t.radius)
        for m in layout.modules:
            row, col = layout.rows - 1 - layout.row_col(m)[0], layout.row_col(m)[1]
            g, c = np.zeros_like(grid), np.zeros_like(grid)
            for i in range(layout.rows):
                for j in range(layout.cols):
                    di, dj = i - row + t.radius, j - col + t.radius
                    if 0 <= di < side and 0 <= dj < side:
                        g[i, j], c[i, j] = load[di * side + dj], cover[di * side + dj]
            b, a = (w * grid * g).sum(), (w * g * g).sum()
            s = max(b, 0.0) / a if a > 0 else 0.0
            centre = (col + 0.5 + t.offsets[k][0], row + 0.5 + t.offsets[k][1])
            short = np.where(lit, np.clip(s * g - grid, 0.0, None), 0.0)
            ll = -0.5 * (w * (grid - s * g) ** 2).sum() - 0.5 * (full * short**2).sum()
            out[(m, *centre, hl, hw, yaw)] = (ll, c.sum())
    return out


@pytest.mark.parametrize(
    ("name", "masked"), [("cylinder", frozenset()), ("limes", frozenset({6})), ("toy", frozenset())]
)
def test_estimate_is_the_likelihood_of_each_hypothesis_on_its_own(name, masked):
    """The tabulated, vectorised estimate against the definition, hypothesis by hypothesis:
    the same hypotheses kept (every one at most ``overhang`` off the pad and within
    ``log_floor`` of the best) with probabilities proportional to exp(log-likelihood). A
    footprint whose share on the pad is the limit itself (the area's sample points make
    that exact: 0.8 of them) is on either side of it in floating point; either is right.
    One part only here (``light_share`` 0); the two-part hypotheses in the next test."""
    params, model = ModelBasedParams(light_share=0.0), packaged_pad_model()
    d = np.asarray(next(c for c in TABLE_6_1 if c.name == name).delta_pa, dtype=float)
    modules = tuple(m for m in LAYOUT.modules if m not in masked and d[m - 1] > 0)
    post = estimate(d, modules, LAYOUT, model, params, masked)
    hyps = zip(post.centres, post.halves, post.yaws, post.probs, strict=True)
    got = {(*c, *h, y): p for c, h, y, p in hyps}
    ref = _loglik_one_at_a_time(d, LAYOUT, params, model, masked)
    limit = 1.0 - params.overhang
    on = {k[1:]: ll for k, (ll, share) in ref.items() if k[0] in modules and share > limit + 1e-9}
    edge = {
        k[1:]: ll
        for k, (ll, share) in ref.items()
        if k[0] in modules and abs(share - limit) <= 1e-9
    }
    assert all(k in on or k in edge for k in got)  # keys exact: the same arithmetic
    best = max([*on.values(), *(edge[k] for k in got if k in edge)])
    assert {k for k, ll in on.items() if ll > best - params.log_floor} == set(got) - set(edge)
    ll = np.array([on.get(k, edge.get(k)) for k in got])
    assert ll.min() > best - params.log_floor
    want = np.exp(ll - ll.max())
    np.testing.assert_allclose(list(got.values()), want / want.sum(), rtol=1e-9)


def test_pad_model_is_the_cast_pads_fem_response_relative_to_each_chambers_centre():
    """The planner's default pad model against the FEM table's own lookup
    (softpad.fem.CastPadResponse.influence), chamber by chamber, at p0."""
    from softpad.sim import default_cast_response

    cast = default_cast_response()
    assert cast is not None
    model = packaged_pad_model()
    pitch = float(cast.centers_m[1, 0] - cast.centers_m[0, 0])
    rng = np.random.default_rng(3)
    local = rng.uniform(-0.45, 0.45, (40, 2))
    expected = []
    for k, centre in enumerate(cast.centers_m):
        s = cast.influence(centre + local * pitch, thesis.P0_PA)[:, k]
        expected.append(s / cast.influence(centre[None], thesis.P0_PA)[0, k])
    # the table is sampled on a 91-point grid (1/90 module): nearest lookup, 2 % of the centre
    np.testing.assert_allclose(model.response(local), np.mean(expected, axis=0), atol=0.02)
    clamped = packaged_pad_model(pad="clamped")
    assert not np.allclose(clamped.table, model.table, atol=1e-3)
    with pytest.raises(InputError, match="pad model"):
        packaged_pad_model(pad="glass")


def _posterior(box, params=None):
    params = params or ModelBasedParams()
    d = _increments(*box)
    (obj,) = detect_objects(d, LAYOUT)
    post = estimate(d, obj, LAYOUT, packaged_pad_model(), params)
    return post.sample(params.kept_hypotheses)


def test_a_grasp_whose_jaw_would_land_on_the_footprint_scores_worse():
    """The landing term: the same direction across a 60 x 30 mm rectangle, centred and then
    shifted along the closing direction until the near jaw stands over the estimated
    footprint; the shifted grasp is the likelier to land and scores worse, step by step."""
    from softpad.planning._model_based import fit_chance, landing_chance, predicted_success

    params, model = ModelBasedParams(), packaged_pad_model()
    post = _posterior(BOXES[0], params)
    centre = np.asarray(post.mean_centre())
    shifts_mm = np.array([0.0, 10.0, 20.0, 30.0])
    centres = centre + np.column_stack([shifts_mm / 45.0, np.zeros(4)])
    thetas = np.zeros(4)  # along the 60 mm side, jaws 100 mm apart
    land = landing_chance(post, centres, thetas, WIDE, LAYOUT, params)
    fit = fit_chance(post, centres, thetas, WIDE, LAYOUT, params)
    score = predicted_success(post, centres, thetas, WIDE, LAYOUT, model, params, 1.0)
    assert (np.diff(land) > 0).all() and land[-1] > land[0] + 0.3, land
    assert (np.diff(fit) < 0).all(), fit
    assert score[0] > 0.1 and score[-1] < 0.2 * score[0], score


def test_landing_term_is_soft_near_the_edge():
    """The edge's position is uncertain (a logistic of the centre grid's rms): a jaw 1 mm
    clear of every hypothesis still lands now and then, one 20 mm clear almost never, so the
    planner prefers room to spare over a grasp that just fits."""
    from softpad.planning._model_based import Posterior, edge_scale, landing_chance

    params = ModelBasedParams(shape_weights=(1.0, 0.0, 0.0), centre_steps=4)
    post = Posterior(np.array([[1.5, 1.0]]), np.array([[0.5, 0.2]]), np.zeros(1), np.ones(1))
    # jaws along x open to 100 mm less 2 mm clearance each side; the footprint 45 mm long
    half_open_mm = 100.0 / 2 - 2.0
    gaps_mm = np.array([1.0, 5.0, 20.0])
    shift = (half_open_mm - 22.5 - gaps_mm) / 45.0  # near jaw's gap to the edge: gaps_mm
    centres = np.column_stack([1.5 + shift, np.ones(3)])
    land = landing_chance(post, centres, np.zeros(3), WIDE, LAYOUT, params)
    b_mm = edge_scale(params) * 45.0
    assert b_mm == pytest.approx(45.0 / 4 / math.sqrt(12) * math.sqrt(3) / math.pi)  # 1.79 mm
    expected = 1.0 - 1.0 / (1.0 + np.exp(-gaps_mm / b_mm))  # the far jaw is far clear
    np.testing.assert_allclose(land, expected, rtol=0.05, atol=1e-4)
    assert land[0] > 0.3 and land[-1] < 1e-3


def test_a_round_object_needs_room_a_box_does_not():
    """Curved objects: a small footprint may be a ball's contact disc (half its diameter).
    As a round object the same reading makes a landing of centred jaws likelier than as a
    box, with the 4/0 jaws (40 mm) and with the 10/4 jaws (100 mm) alike."""
    from softpad.planning._model_based import landing_chance

    box = ((67.5, 45.0), (20.0, 20.0), 0.0, 60.0)
    narrow = GripperSpec.from_mounting("4/0")
    out = {}
    for shapes in ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)):
        params = ModelBasedParams(shape_weights=shapes)
        post = _posterior(box, params)
        centre = np.asarray([post.mean_centre()])
        out[shapes] = [
            float(landing_chance(post, centre, np.zeros(1), g, LAYOUT, params)[0])
            for g in (narrow, WIDE)
        ]
    for k in range(2):
        assert out[(0.0, 0.0, 1.0)][k] > out[(1.0, 0.0, 0.0)][k] + 0.1, out


def test_finer_search_never_scores_worse_and_finds_more_room():
    """The finer search around the best coarse candidate: its grasp's predicted success is
    at least the coarse one's on every simulated rectangle, and higher on some."""
    params = ModelBasedParams()
    coarse = replace_params(params, refine_steps=0)
    gains = []
    for box in BOXES:
        d = _increments(*box)
        objs = detect_objects(d, LAYOUT)
        (fine,) = ModelBasedPlanner(WIDE, params).plan(d, objs, LAYOUT)
        (rough,) = ModelBasedPlanner(WIDE, coarse).plan(d, objs, LAYOUT)
        p_fine, p_rough = (float(p.rule.split("p=")[1]) for p in (fine, rough))
        assert p_fine >= p_rough - 0.005, (box, fine, rough)
        gains.append(p_fine - p_rough)
    assert max(gains) > 0.01, gains


def replace_params(params, **changes):
    from dataclasses import replace

    return replace(params, **changes)


def test_the_mounting_is_the_one_with_the_highest_predicted_success():
    """--mounting auto with the model-based planner: every installed mounting's predicted
    success is asked for, and the highest wins (a large object goes to the wide jaws; a
    narrow object to jaws whose minimum opening closes on it)."""
    from softpad.planning import MountingChooser, choose_mounting

    planner = ModelBasedPlanner(WIDE)
    assert isinstance(planner, MountingChooser)
    for box, expected in (
        (((67.5, 45.0), (80.0, 55.0), 0.0, 150.0), "10/4"),
        *((b, None) for b in BOXES),
    ):
        d = _increments(*box)
        objs = detect_objects(d, LAYOUT)
        p = {
            m: planner.mounting_success(d, objs, LAYOUT, GripperSpec.from_mounting(m))
            for m in ("10/4", "6/2", "4/0")
        }
        chosen = choose_mounting(d, LAYOUT, planner=planner)
        assert p[chosen] == max(p.values()), (p, chosen)
        assert chosen == expected or expected is None, p
        assert len(set(p.values())) == 3, p  # the mountings are told apart


@pytest.mark.parametrize("box", BOXES)
def test_grid_scoring_equals_scoring_grasp_by_grasp(box):
    """The planner scores its candidates as a grid (the landing term per shift along, the
    balance per shift across); the same grasps scored one by one give the same figures."""
    from softpad.planning._model_based import (
        candidate_grid,
        grid_success,
        predicted_success,
        refined_grid,
    )

    params, model = ModelBasedParams(), packaged_pad_model()
    post = _posterior(box, params)
    for grid in (candidate_grid(post, params), refined_grid(np.array([1.4, 1.1]), 0.3, params)):
        score, centres, thetas = grid_success(post, grid, WIDE, LAYOUT, model, params, 1.3)
        one_by_one = predicted_success(
            post, centres.reshape(-1, 2), thetas.ravel(), WIDE, LAYOUT, model, params, 1.3
        )
        np.testing.assert_allclose(score.ravel(), one_by_one, rtol=1e-9, atol=1e-12)
        assert score.max() > 0  # not a comparison of zeros


@pytest.mark.parametrize("box", BOXES)
@pytest.mark.parametrize("ratio", [0.4, 1.3, 3.0])
def test_best_on_grid_is_the_argmax_of_the_grid(box, ratio):
    """The planner looks fingertips up only where they may decide (the sensed share is at
    most 1); its choice is the first maximum of the full grid's scores, at sensing ratios
    where few and where many fingertips fall short."""
    from softpad.planning._model_based import (
        best_on_grid,
        candidate_grid,
        grid_success,
        refined_grid,
    )

    params, model = ModelBasedParams(), packaged_pad_model()
    post = _posterior(box, params)
    for grid in (candidate_grid(post, params), refined_grid(np.array([1.4, 1.1]), 0.3, params)):
        score, centres, thetas = grid_success(post, grid, WIDE, LAYOUT, model, params, ratio)
        i = np.unravel_index(int(np.argmax(score)), score.shape)
        best, centre, theta = best_on_grid(post, grid, WIDE, LAYOUT, model, params, ratio)
        assert best == score[i]
        np.testing.assert_array_equal(centre, centres[i])
        assert theta == thetas[i]


def test_footprint_room_is_the_gap_to_the_nearer_jaw():
    """One 45 x 18 mm footprint, jaws along it: the room a side is half the opening less the
    clearance, the shift of the centre and half the footprint (m)."""
    from softpad.planning._model_based import Posterior, footprint_room

    params = ModelBasedParams()
    post = Posterior(np.array([[1.5, 1.0]]), np.array([[0.5, 0.2]]), np.zeros(1), np.ones(1))
    for shift_mm in (0.0, 4.5, -9.0):
        centre = np.array([1.5 + shift_mm / 45.0, 1.0])
        room = footprint_room(post, centre, 0.0, WIDE, LAYOUT, params)
        assert room == pytest.approx((50.0 - 2.0 - abs(shift_mm) - 22.5) * 1e-3, abs=1e-9)
    across = footprint_room(post, np.array([1.5, 1.0]), math.pi / 2, WIDE, LAYOUT, params)
    assert across == pytest.approx((50.0 - 2.0 - 9.0) * 1e-3, abs=1e-9)


#: A box whose short side nearly fills the 6/2 jaws' 60 mm opening, and one with room in
#: the 10/4 jaws' 100 mm.
TIGHT_BOX = ((50.0, 40.0), (60.0, 45.0), 20.0, 120.0)
LOOSE_BOX = ((67.5, 45.0), (30.0, 20.0), 10.0, 60.0)


@pytest.mark.parametrize("starts", [1, 2])
def test_tight_search_runs_where_the_fit_is_tight_and_never_scores_worse(starts):
    """With the tight-fit search on (``tight_room_m``), a box that nearly fills the opening
    is searched further: the chosen grasp's predicted success is at least the one found
    without the search; a box with room is planned exactly as without it."""
    from dataclasses import replace

    off = ModelBasedParams()
    on = replace(off, tight_room_m=10e-3, tight_rounds=2, tight_starts=starts)
    for box, tight, jaws in ((TIGHT_BOX, True, "6/2"), (LOOSE_BOX, False, "10/4")):
        gripper = GripperSpec.from_mounting(jaws)
        d = _increments(*box)
        objs = detect_objects(d, LAYOUT)
        plans, scores = [], []
        for params in (off, on):
            planner = ModelBasedPlanner(gripper, params)
            plans.append(planner.plan(d, objs, LAYOUT)[0])
            scores.append(planner.mounting_success(d, objs, LAYOUT, gripper))
        if tight:
            assert scores[1] >= scores[0] > 0
            assert plans[1] != plans[0]  # the search moved the grasp
        else:
            assert plans[1] == plans[0] and scores[1] == scores[0]


def test_polished_climbs_the_predicted_success():
    """The pattern search from a grasp off the best: each round keeps the best so far, so
    its result scores at least the start and the finer search's own best near it."""
    from dataclasses import replace

    from softpad.planning._model_based import best_on_grid, polished, refined_grid

    params = replace(ModelBasedParams(), tight_rounds=4)
    model, narrow = packaged_pad_model(), GripperSpec.from_mounting("6/2")
    post = _posterior(TIGHT_BOX, params)
    start = np.asarray(post.mean_centre()) + np.array([0.05, -0.04])
    args = (narrow, LAYOUT, model, params, 1.0)
    found = best_on_grid(post, refined_grid(start, 0.3, params), *args)
    score, centre, theta = polished(post, found, *args)
    assert score >= found[0]
    again = best_on_grid(post, refined_grid(centre, theta, params, 2), *args)
    assert score >= again[0] - 0.05  # a local optimum, up to the finer grid's step


#: The two-part hypotheses on (light modules under 0.3 of the largest increment).
PARTS = ModelBasedParams(light_share=0.3)


def test_two_part_hypotheses_are_their_definition():
    """The limes' reading (Table 6.1) has light modules: the posterior holds one-part
    footprints centred on every module of the object and two-part ones (a dense footprint
    centred on the heavier modules, the light modules free to read more than it predicts,
    ``part_cost`` nats a light module), each with the probability its likelihood gives."""
    from softpad.planning._model_based import light_modules

    params, model = PARTS, packaged_pad_model()
    d = np.asarray(next(c for c in TABLE_6_1 if c.name == "limes").delta_pa, dtype=float)
    modules = tuple(m for m in LAYOUT.modules if d[m - 1] > 0)
    light = light_modules(d, modules, LAYOUT, params)
    assert light and set(light) < set(modules)
    heavy = tuple(m for m in modules if m not in light)
    post = estimate(d, modules, LAYOUT, model, params)
    one = _loglik_one_at_a_time(d, LAYOUT, params, model, frozenset())
    two = _loglik_one_at_a_time(d, LAYOUT, params, model, frozenset(), light)
    limit = 1.0 - params.overhang - 1e-9  # a share of exactly the limit: either is right
    ref = {(1.0, *k[1:]): (ll, a) for k, (ll, a) in one.items() if k[0] in modules}
    cost = params.part_cost * len(light)
    ref |= {(2.0, *k[1:]): (ll - cost, a) for k, (ll, a) in two.items() if k[0] in heavy}
    ref = {k: v for k, v in ref.items() if v[1] > limit}
    hyps = zip(post.parts, post.centres, post.halves, post.yaws, post.probs, strict=True)
    got = {(n, *c, *h, y): p for n, c, h, y, p in hyps}
    best = max(ll for k, (ll, a) in ref.items() if k in got or a > limit + 2e-9)
    likely = {k for k, (ll, a) in ref.items() if ll > best - params.log_floor}
    assert {k for k in likely if ref[k][1] > limit + 2e-9} <= set(got) <= likely
    ll = np.array([ref[k][0] for k in got])
    want = np.exp(ll - ll.max())
    np.testing.assert_allclose(list(got.values()), want / want.sum(), rtol=1e-9)
    assert 0.5 < post.part_share() < 1.0


def test_a_dense_part_with_a_light_part_is_read_as_two_parts():
    """A 200 g brick with a 25 g cable beside it (the simulator's FEM response, the two loads
    added): the two-part hypotheses explain the reading better than any one footprint (most
    of the posterior), and put the grasp's footprint on the brick, where one part alone
    would put it between the brick and the cable."""
    from softpad.sim import PadResponse

    pad = PadResponse(LAYOUT)

    def loads(centre_mm, size_mm, mass_g):
        c, s = np.asarray(centre_mm) * 1e-3, np.asarray(size_mm) * 1e-3
        return pad.rect_equivalent_loads(c, s, mass_g * 9.80665e-3, thesis.P0_PA, 0.0)

    brick = (30.0, 60.0)
    d = pad.sealed_rise_pa(loads(brick, (50, 50), 200) + loads((90, 60), (70, 8), 25), thesis.P0_PA)
    (obj,) = outline_objects(d, detect_objects(d, LAYOUT), LAYOUT, 25.0)
    model = packaged_pad_model()
    post = estimate(d, obj, LAYOUT, model, PARTS)
    alone = estimate(d, obj, LAYOUT, model, ModelBasedParams(light_share=0.0))
    assert post.part_share() > 0.5 and alone.part_share() == 0.0
    err = math.dist(np.asarray(post.mean_centre()) * 45.0, brick)
    err_alone = math.dist(np.asarray(alone.mean_centre()) * 45.0, brick)
    assert err < 8.0 and err_alone > 15.0, (err, err_alone)


def test_a_curved_object_may_span_more_than_its_contact():
    """A narrow contact strip (30 x 12 mm) may be a lying cylinder's: across it the object
    spans the diameters of ``curved_diameters`` (shares of the opening: 18, 36 and 54 mm
    with the 60 mm jaws), so jaws closing across the strip land likelier than closing along
    it (at 54 mm about 2 in 3 of the times: 1 mm to spare each side, the edge's logistic
    error 1.8 mm; a third of the diameters: about 0.2); read as a strip twice its width (no
    diameters) across is as safe, and a box is safe either way."""
    from softpad.planning._model_based import Posterior, landing_chance

    post = Posterior(
        np.array([[1.5, 1.0]]), np.array([[15.0, 6.0]]) / 45.0, np.zeros(1), np.ones(1)
    )
    jaws = GripperSpec.from_mounting("6/2")
    centre, thetas = np.array([[1.5, 1.0], [1.5, 1.0]]), np.array([math.pi / 2, 0.0])
    cylinder = ModelBasedParams(shape_weights=(0.0, 1.0, 0.0))
    across, along = landing_chance(post, centre, thetas, jaws, LAYOUT, cylinder)
    assert 0.15 < across < 0.25 and along < 0.01, (across, along)
    flat = replace_params(cylinder, curved_diameters=())
    assert landing_chance(post, centre, thetas, jaws, LAYOUT, flat)[0] < 0.01
    box = replace_params(cylinder, shape_weights=(1.0, 0.0, 0.0))
    assert landing_chance(post, centre, thetas, jaws, LAYOUT, box).max() < 0.01
