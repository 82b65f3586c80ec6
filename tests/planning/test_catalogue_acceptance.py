"""Per-object acceptance (issue 47 item 3): each known object's tolerances narrowed to the
conformal quantile of its own readings' spread, so that its own variation is accepted at a
stated rate and a new object near it is not."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.planning import (
    CatalogueParams,
    LearnedTrial,
    acceptance_scale,
    learn_catalogue,
    own_scores,
)

VAR = 30.0
BASE = np.array([0.0, 0.0, 0.0, 120.0, 300.0, 120.0])  # a box on modules 4-6, 540 Pa


def _draw(rng: np.random.Generator, n: int, moved: float = 0.0) -> np.ndarray:
    """``n`` readings of the box: 8 % spread of the total load, 12 Pa on each loaded module
    (placement); ``moved`` of the total load shifted from module 5 to module 4 (a new object
    of the same weight whose load sits elsewhere)."""
    total = BASE.sum() * np.exp(rng.normal(0.0, 0.08, (n, 1)))
    r = BASE * total / BASE.sum() + rng.normal(0.0, 12.0, (n, 6)) * (BASE > 0)
    r[:, 3] += moved * r.sum(axis=1)
    r[:, 4] -= moved * r.sum(axis=1)
    return r


def _catalogue(rng: np.random.Generator, alpha: float | None, n: int = 39):
    held = [LearnedTrial("box", tuple(r), (1.5, 0.5, 0.0), True) for r in _draw(rng, n)]
    return learn_catalogue(held, VAR, CatalogueParams(acceptance_alpha=alpha))


def test_the_scale_is_the_stated_rank_of_the_scores_at_most_one() -> None:
    scores = np.arange(1, 20) / 40.0  # 19 scores 0.025 .. 0.475
    # n = 19, alpha 0.05: rank ceil(20 * 0.95) = 19, the largest; alpha 0.2: rank 16
    assert acceptance_scale(scores, 0.05) == pytest.approx(0.475)
    assert acceptance_scale(scores, 0.2) == pytest.approx(16 / 40)
    assert acceptance_scale(scores[:18], 0.05) == 1.0  # rank 19 > 18: too few to narrow
    assert acceptance_scale(scores * 10, 0.2) == 1.0  # never wider than the shared tolerances
    for alpha in (0.0, 1.0, -0.1, math.nan):
        with pytest.raises(InputError, match="acceptance alpha"):
            acceptance_scale(scores, alpha)


def test_own_scores_are_the_leave_one_out_nearest_in_tolerance_units() -> None:
    """Three readings: the third's nearest is the second (pattern 0.1 / 0.25 = 0.4 against a
    load ratio ln(1.1) / 0.3 = 0.32), scored by the larger of the two."""
    a = np.array([0.0, 0.0, 0.0, 100.0, 300.0, 100.0])
    b = a * 1.1
    c = b + np.array([0.0, 0.0, 0.0, 1.0, -1.0, 0.0]) * 0.05 * b.sum()
    s = own_scores([a, b, c], 0.25, 0.30)
    assert s[2] == pytest.approx(0.1 / 0.25)
    assert s[0] == pytest.approx(math.log(1.1) / 0.30)
    assert own_scores([a], 0.25, 0.30)[0] == math.inf


def test_an_objects_own_readings_are_accepted_at_the_stated_rate() -> None:
    """200 catalogues of 39 held readings each (alpha 0.1), 25 new readings of the same box
    each: the share accepted is at least 0.9 (split-conformal coverage) less 0.015, four
    standard errors of the mean over the catalogues (coverage given a catalogue has a
    standard deviation of about sqrt(0.1 * 0.9 / 41) = 0.047), and the scale narrows: the
    acceptance is below 0.97 (the shared tolerances accept about all of them)."""
    rng = np.random.default_rng(47)
    accepted, shared = [], []
    for _ in range(200):
        new = _draw(rng, 25)
        cat = _catalogue(rng, 0.1)
        accepted.append(np.mean([cat.recognise(r)[0] is not None for r in new]))
        if len(shared) < 20:
            wide = _catalogue(rng, None)
            shared.append(np.mean([wide.recognise(r)[0] is not None for r in new]))
    assert 0.9 - 0.015 <= float(np.mean(accepted)) < 0.97
    assert float(np.mean(shared)) > 0.99


def test_a_new_object_near_a_known_one_is_unknown() -> None:
    """A reading with 8 % of the load moved from module 5 to module 4 (L1 of the shares 0.16,
    within the shared tolerance 0.25): 40 catalogues, 25 such readings each; with the
    per-object scale at least 80 % are unknown, with the shared tolerances at most 20 %."""
    rng = np.random.default_rng(48)
    narrow, shared = [], []
    for _ in range(40):
        near = _draw(rng, 25, moved=0.08)
        cat, wide = _catalogue(rng, 0.1), _catalogue(rng, None)
        narrow.append(np.mean([cat.recognise(r)[0] is None for r in near]))
        shared.append(np.mean([wide.recognise(r)[0] is None for r in near]))
    assert float(np.mean(narrow)) >= 0.8 and float(np.mean(shared)) <= 0.2


def _box_reading(centre: tuple[float, float], half: tuple[float, float]) -> np.ndarray:
    """Each module's reading of a uniform box footprint (module units) through the planner's
    FEM pad model (relative response at each loaded point, summed per module, 1000 Pa for
    the whole box at full response): an independent model of where the load shows."""
    from softpad.layout import PadLayout
    from softpad.planning._model_based import packaged_pad_model

    layout = PadLayout()
    xs = np.linspace(-half[0], half[0], 41) + centre[0]
    ys = np.linspace(-half[1], half[1], 41) + centre[1]
    pts = np.stack(np.meshgrid(xs, ys, indexing="ij"), axis=-1).reshape(-1, 2)
    w = packaged_pad_model().on_pad(pts, layout) * 1000.0 / len(pts)
    centres = np.array(layout.center_table)
    module = np.argmin(((pts[:, None, :] - centres[None]) ** 2).sum(axis=2), axis=1)
    return np.bincount(module, weights=w, minlength=len(centres))


def test_a_learnt_grasp_moves_with_the_object() -> None:
    """A 2.0 x 1.2 module box learnt from nine placements within 0.2 module units of
    (1.5, 1.0), each grasped at its true centre; placed 0.15 module units (6.75 mm) to the
    right or up, the planned centre moves the same way by 0.5-1.25 times the shift and stays
    within 0.02 module units across, the direction unchanged. (Through the FEM pad model the
    load centre of this box follows its shift by about 1.0-1.4 times it, the grasp by the gain
    0.75 times that; a grasp reused as it was would not move at all.)"""
    from softpad.layout import PadLayout
    from softpad.planning import CataloguePlanner

    rng = np.random.default_rng(3)
    half = (1.0, 0.6)
    held = []
    for _ in range(9):
        c = (1.5 + rng.uniform(-0.2, 0.2), 1.0 + rng.uniform(-0.2, 0.2))
        held.append(LearnedTrial("box", tuple(_box_reading(c, half)), (*c, 0.0), True))
    planner = CataloguePlanner(learn_catalogue(held, VAR), fallback=None)  # type: ignore[arg-type]
    layout = PadLayout()

    def planned(c: tuple[float, float]) -> tuple[float, float, float]:
        (p,) = planner.plan(_box_reading(c, half), [(1, 2, 3, 4, 5, 6)], layout)
        assert planner.last_known == "box"
        return (*p.cog, p.theta)

    x0, y0, t0 = planned((1.5, 1.0))
    for axis in (0, 1):
        shift = np.eye(2)[axis] * 0.15
        x, y, t = planned((1.5 + shift[0], 1.0 + shift[1]))
        moved = np.array([x - x0, y - y0])
        assert 0.5 * 0.15 <= moved[axis] <= 1.25 * 0.15, (axis, moved)
        assert abs(moved[1 - axis]) <= 0.02 and t == t0
