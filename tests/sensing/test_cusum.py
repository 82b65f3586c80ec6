"""The CUSUM contact detector: analytic detection delay, false alarms on idle noise, calibration."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.sensing import (
    CusumContactDetector,
    ThesisContactDetector,
    calibrate_cusum_threshold,
    cusum_peak_pa,
    make_contact_detector,
)


def _first_alarm(det, frames: np.ndarray) -> int | None:
    det.reset(np.zeros(frames.shape[1]))
    for i, f in enumerate(frames):
        if det.update(f):
            return i
    return None


@pytest.mark.parametrize("step_pa", [100.0, 200.0, 400.0], ids=["100Pa", "200Pa", "400Pa"])
def test_step_is_detected_after_threshold_over_step_minus_drift_samples(step_pa: float) -> None:
    """Noise-free step: g_k = k (s - drift) crosses h at k = floor(h / (s - drift)) + 1."""
    frames = np.zeros((50, 6))
    frames[10:, 2] = step_pa
    det = CusumContactDetector(drift_pa=30.0, threshold_pa=60.0)
    k = _first_alarm(det, frames)
    expected = 10 + int(np.floor(60.0 / (step_pa - 30.0))) + 1 - 1
    assert k == expected
    assert det.triggered_modules == (3,)


def test_cusum_is_faster_than_the_thesis_detector_on_a_ramp() -> None:
    """A fingertip pressing in: a ramp of 15 Pa per sample (about 1 kPa per 0.7 s at 100 Hz)."""
    frames = np.zeros((100, 6))
    frames[20:, 1] = 15.0 * np.arange(80)
    k_cusum = _first_alarm(CusumContactDetector(), frames)
    k_thesis = _first_alarm(ThesisContactDetector(), frames)
    assert k_cusum is not None and k_thesis is not None
    # thesis: 10-sample mean above 90 Pa -> 90 + 4.5 * 15 Pa reached at sample 20 + 11;
    # CUSUM: sum of (15 j - 30) over j > 2 exceeds 60 Pa at sample 20 + 5
    assert (k_thesis - 20, k_cusum - 20) == (11, 5)


@pytest.mark.parametrize("seed", range(20))
def test_no_false_alarm_on_white_noise_at_the_sensor_level(seed: int) -> None:
    """20 seeds x 10 min at 100 Hz of 8 Pa rms noise + 3 Pa rms offset: no alarm (the statistic
    needs about four-sigma samples in a row to reach 60 Pa)."""
    rng = np.random.default_rng(seed)
    frames = rng.normal(0.0, 8.0, (60_000, 6)) + rng.normal(0.0, 3.0, 6)
    assert _first_alarm(CusumContactDetector(), frames) is None


def test_calibration_is_margin_times_the_idle_peak() -> None:
    idle = np.zeros((10, 2))
    idle[3:6, 0] = 50.0  # three samples 20 Pa above the 30 Pa allowance -> peak 60 Pa
    assert cusum_peak_pa(idle, 30.0) == pytest.approx(60.0)
    assert calibrate_cusum_threshold(idle, 30.0, margin=2.0) == pytest.approx(120.0)
    with pytest.raises(InputError, match="margin"):
        calibrate_cusum_threshold(idle, 30.0, margin=0.5)


def test_bad_names_and_values_are_refused() -> None:
    with pytest.raises(InputError, match="unknown contact detector 'glr'"):
        make_contact_detector("glr")
    with pytest.raises(InputError, match="CUSUM threshold"):
        CusumContactDetector(threshold_pa=float("nan"))


def test_count_alarms_rearms_with_the_reference_after_each_alarm() -> None:
    from softpad.sensing import ThesisContactDetector, count_alarms

    reference = np.zeros(6)
    quiet, step = np.zeros(6), np.r_[200.0, np.zeros(5)]  # 200 Pa on module 1: above t_g
    frames = [quiet] * 5 + [step] * 40
    # the 10-sample average passes 90 Pa on the 5th step frame; re-armed, again 5 frames later
    assert count_alarms(ThesisContactDetector(window=10), reference, frames) == 8
    assert count_alarms(ThesisContactDetector(window=10), reference, [quiet] * 100) == 0
