"""Inflation matched to the approach: the study's physics and the recommendation rule."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.harness import InflationPoint, inflation_study, recommend_p0


def test_a_faster_approach_is_detected_sooner_with_about_the_same_travel() -> None:
    """Detection needs about a fixed indentation: delay ~ travel / speed (1 kHz, 2 seeds)."""
    slow, fast = inflation_study([1100.0], [0.02, 0.1], seeds=(1, 2))
    assert slow.held == fast.held == 2
    assert fast.delay_s is not None and slow.delay_s is not None
    assert fast.delay_s < slow.delay_s / 2
    assert fast.travel_m == pytest.approx(fast.delay_s * 0.1, abs=1.5e-4)
    assert slow.force_n is not None and 0 < slow.force_n < 1.0


def test_recommendation_respects_both_bounds() -> None:
    pts = [
        InflationPoint(600.0, 0.05, 0.010, 5e-4, 0.12, 3, 3),
        InflationPoint(1100.0, 0.05, 0.011, 5e-4, 0.10, 3, 3),
        InflationPoint(1700.0, 0.05, 0.030, 6e-4, 0.05, 3, 3),  # too slow
        InflationPoint(2300.0, 0.05, 0.010, 6e-4, 0.01, 2, 3),  # dropped once
    ]
    best = recommend_p0(pts, 0.05, max_delay_s=0.02, max_force_n=0.2)
    assert best is not None and best.p0_pa == 1100.0
    assert recommend_p0(pts, 0.05, max_delay_s=0.02, max_force_n=0.05) is None


def test_p0_outside_the_seed_range_is_refused() -> None:
    with pytest.raises(InputError, match=r"0\.5 to 2\.8 kPa"):
        inflation_study([3000.0])
