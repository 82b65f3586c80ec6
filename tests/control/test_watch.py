"""The loop's object watch and planning step (:mod:`softpad.control._watch`), which the grasp
loop and a watching node share."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.control import ObjectWatch, plan_from_reads
from softpad.layout import PadLayout
from softpad.planning import ThesisPlanner
from softpad.sensing import ThesisObjectDetector

LAYOUT = PadLayout()
RATE_HZ = 100.0


def _watch(settle_s: float = 0.5) -> ObjectWatch:
    return ObjectWatch(np.full(6, 1100.0), ThesisObjectDetector(50.0), LAYOUT, 10, settle_s)


def test_an_object_is_seen_once_the_filter_passes_t_o_and_settles_later() -> None:
    w = _watch()
    load = np.array([0, 0, 200.0, 0, 0, 200.0])  # an object on modules 3 and 6 from frame 20
    states = []
    for i in range(200):
        p = 1100.0 + (load if i >= 20 else 0.0)
        states.append(w.update(p, i / RATE_HZ))
    seen = states.index("seen")
    # the running average of 10 crosses t_o = 50 Pa at the 3rd loaded frame (3 x 200 / 10 = 60)
    assert seen == 22 and w.seen_at == pytest.approx(0.22)
    assert w.objects == [(3, 6)]
    first_settled = states.index("settled")
    assert first_settled == seen + 50  # settle_s = 0.5 s at 100 Hz
    assert set(states[first_settled:]) == {"settled"}


def test_an_empty_pad_is_never_seen() -> None:
    w = _watch()
    rng = np.random.default_rng(0)
    states = {w.update(1100.0 + rng.normal(0, 8.6, 6), i / RATE_HZ) for i in range(500)}
    assert states == {None} and w.seen_at is None


def test_plan_from_reads_plans_the_mean_increment() -> None:
    reference = np.full(6, 1100.0)
    reads = [
        reference
        + np.array(
            [
                0,
                0,
                200.0 + e,
                0,
                0,
                200.0 - e,
            ]
        )
        for e in (-20, 0, 20)
    ]
    delta, plans = plan_from_reads(reads, reference, ThesisObjectDetector(50.0),
                                   ThesisPlanner(), LAYOUT)  # fmt: skip
    np.testing.assert_allclose(delta, [0, 0, 200.0, 0, 0, 200.0])
    (plan,) = plans
    assert plan.modules == (3, 6)
    direct = ThesisPlanner().plan(delta, [(3, 6)], LAYOUT)[0]
    assert plan.cog == pytest.approx(direct.cog) and plan.theta == pytest.approx(direct.theta)


def test_a_sighting_gone_by_the_settle_time_is_not_settled() -> None:
    """A peak under a threshold near the noise (or an object put down and taken away) is
    seen, but the watch waits on when the detector finds nothing at the settle time, and
    settles on an object that stays. (The watch settled on any sighting before.)"""
    w = _watch()
    states = []
    for i in range(300):
        p = np.full(6, 1100.0)
        if 20 <= i < 40:  # a 20-frame peak on module 1: filtered over 50 Pa, gone by 0.5 s
            p[0] += 200.0
        if i >= 150:  # an object on module 6 that stays
            p[5] += 200.0
        states.append(w.update(p, i / RATE_HZ))
    seen = [i for i, s in enumerate(states) if s == "seen"]
    assert seen[0] == 22 and len(seen) == 2 and seen[1] > 150
    first_settled = states.index("settled")
    assert first_settled == seen[1] + 50
    assert w.objects == [(6,)]
