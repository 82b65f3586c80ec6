from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sensing import (
    RunningAverage,
    ThesisContactDetector,
    capture_reference,
    detect_objects,
    increments,
)


def test_running_average_matches_numpy_convolution() -> None:
    rng = np.random.default_rng(0)
    x = rng.normal(size=(50, 3))
    f = RunningAverage(10)
    out = np.array([f.update(row) for row in x])
    for i in range(9, 50):
        np.testing.assert_allclose(out[i], x[i - 9 : i + 1].mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(out[3], x[:4].mean(axis=0))


def test_reference_is_mean_of_reads_and_increments_subtract_it() -> None:
    reads = np.array([[1100.0, 1090.0], [1102.0, 1094.0], [1098.0, 1092.0]])
    ref = capture_reference(reads)
    np.testing.assert_allclose(ref, [1100.0, 1092.0])
    np.testing.assert_allclose(increments([1160.0, 1092.0], ref), [60.0, 0.0])


def test_increments_reject_wrong_count_and_nan() -> None:
    with pytest.raises(InputError, match="3 pressures but 2"):
        increments([1, 2, 3], [1, 2])
    with pytest.raises(InputError, match="module 2"):
        increments([1, np.nan], [1, 2])


def test_detect_objects_threshold_is_strict_and_groups_8_connected() -> None:
    layout = PadLayout()
    assert detect_objects([50.0, 0, 0, 0, 0, 0], layout) == []
    assert detect_objects([50.1, 0, 0, 0, 0, 0], layout) == [(1,)]
    assert detect_objects([60, 0, 60, 60, 0, 60], layout) == [(1, 4), (3, 6)]
    assert detect_objects([60, 0, 0, 0, 60, 0], layout) == [(1, 5)]


def test_detect_objects_rejects_negative_threshold() -> None:
    with pytest.raises(InputError, match=">= 0 kPa"):
        detect_objects([0] * 6, PadLayout(), -1.0)


def test_contact_detector_needs_the_filtered_value_above_threshold() -> None:
    det = ThesisContactDetector(threshold_pa=90.0, window=10, reference_pa=np.zeros(6))
    # A single spike of 500 Pa raises a 10-sample mean by 50 Pa only: no contact.
    assert not det.update([500, 0, 0, 0, 0, 0])
    for _ in range(8):
        assert not det.update([0] * 6)
    # A sustained 100 Pa step crosses 90 Pa once nine of ten samples carry it.
    hits = [det.update([0, 100, 0, 0, 0, 0]) for _ in range(10)]
    assert hits.index(True) == 9
    assert det.triggered_modules == (2,)
