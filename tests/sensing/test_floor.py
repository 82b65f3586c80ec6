"""The step floor: the smallest step of one module a contact detector catches."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.sensing import (
    AdaptiveCusumDetector,
    CusumContactDetector,
    CusumLimit,
    LatchingContactDetector,
    ThesisContactDetector,
    make_contact_detector,
    sensing_ratio,
    step_floor_pa,
)
from softpad.sensing._floor import DEFAULT_FLOOR_NOISE_PA
from softpad.sim import SensorParams


def test_noise_free_thesis_floor_is_the_first_step_above_t_g() -> None:
    """A step above t_g fills the 10-sample average in 10 frames: the 2 Pa grid's first
    amplitude strictly above 90 Pa."""
    assert step_floor_pa(ThesisContactDetector(), 100.0, noise_std_pa=0.0) == 92.0


@pytest.mark.parametrize(("rate", "window_s", "expected"), [(100.0, 0.2, 36.0), (100.0, 0.5, 34.0)])
def test_noise_free_cusum_floor_is_allowance_plus_threshold_over_window(
    rate: float, window_s: float, expected: float
) -> None:
    """Page's CUSUM (no baseline) on a step r reaches n (r - d) after n frames: caught within
    N frames when r > d + h / N (d = 30, h = 100: 35 Pa for 20 frames, 32 for 50; the grid's
    next amplitude above)."""
    det = CusumContactDetector(CusumLimit(30.0, 100.0), None, 0.0)
    floor = step_floor_pa(det, rate, noise_std_pa=0.0, window_s=window_s)
    assert floor == expected


def test_noise_raises_the_floor_of_a_detector_without_averaging() -> None:
    det = AdaptiveCusumDetector(CusumLimit(15.0, 23.1), 100.0)
    quiet = step_floor_pa(det, 100.0, noise_std_pa=0.0)
    noisy = step_floor_pa(det, 100.0, noise_std_pa=8.0)
    # noise-free: the envelope takes a step after its 50 ms lag, so (r - 15) 5 > 23.1
    assert quiet == pytest.approx(20.0, abs=2.0)
    # 8 Pa of white noise puts about 2.6 sigma (the largest of 30 samples) into the envelope
    assert noisy == pytest.approx(quiet + 2.6 * 8.0, abs=8.0)


def test_thesis_floor_with_noise_stays_near_t_g() -> None:
    """Averaged over 10 samples the 8 Pa noise is 2.5 Pa: the 50 % point within 6 Pa of t_g."""
    for rate in (100.0, 1000.0):
        assert step_floor_pa(ThesisContactDetector(), rate) == pytest.approx(90.0, abs=6.0)


@pytest.mark.parametrize("rate", [100.0, 1000.0])
def test_the_shipped_cusums_need_less_than_the_thesis_detector(rate: float) -> None:
    thesis = sensing_ratio(make_contact_detector("thesis", rate), rate)
    cusum = sensing_ratio(make_contact_detector("cusum", rate), rate)
    adaptive = sensing_ratio(make_contact_detector("adaptive", rate), rate)
    assert thesis == 1.0
    assert cusum is not None and adaptive is not None
    assert 0.0 < adaptive <= cusum < 1.0
    # the delay target's own figure: the adaptive CUSUM within a third to a half of t_g
    assert adaptive < 0.5


def test_a_detector_that_cannot_be_probed_has_no_ratio() -> None:
    class Stub:
        triggered_modules = ()

        def reset(self, reference_pa: object) -> None: ...

        def update(self, pressures_pa: object) -> bool:
            return False

    assert sensing_ratio(Stub(), 100.0) is None  # type: ignore[arg-type]
    with pytest.raises(InputError, match="Stub is not a LatchingContactDetector"):
        step_floor_pa(Stub(), 100.0)  # type: ignore[arg-type]

    class Unstated(LatchingContactDetector):
        def _restart(self, modules: int) -> None: ...

        def _exceeds(self, rise_pa: np.ndarray) -> np.ndarray:
            return rise_pa > 50.0

    assert sensing_ratio(Unstated(), 100.0) is None
    with pytest.raises(InputError, match="Unstated states no floor_key"):
        step_floor_pa(Unstated(), 100.0)


def test_a_detector_that_never_fires_has_an_infinite_floor() -> None:
    det = ThesisContactDetector(threshold_pa=5000.0)
    assert math.isinf(step_floor_pa(det, 100.0, noise_std_pa=0.0))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"sample_rate_hz": 0.0}, "sample rate"),
        ({"sample_rate_hz": np.nan}, "sample rate"),
        ({"sample_rate_hz": 100.0, "noise_std_pa": -1.0}, "sensor noise"),
        ({"sample_rate_hz": 100.0, "window_s": 0.0}, "window"),
        ({"sample_rate_hz": 100.0, "settle_s": math.inf}, "settling time"),
    ],
)
def test_bad_settings_are_named(kwargs: dict, match: str) -> None:
    with pytest.raises(InputError, match=match):
        step_floor_pa(ThesisContactDetector(), **kwargs)


def test_the_floors_noise_is_the_simulated_sensors() -> None:
    """The probe's noise is the box sensor's (kept apart so that sensing need not import sim)."""
    assert DEFAULT_FLOOR_NOISE_PA == SensorParams().noise_std_pa
