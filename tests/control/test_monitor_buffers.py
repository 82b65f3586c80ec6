"""The fault monitor's buffers: the last rows oldest first after any number of appends, and
their mean equal, bit for bit, to NumPy's mean of the same rows kept in a deque (the monitor's
former bookkeeping)."""

from collections import deque

import numpy as np
import pytest

from softpad.control._safety import _LastRows


@pytest.mark.parametrize("length", [1, 3, 10])
def test_last_rows_are_the_last_appended_oldest_first(length: int) -> None:
    rng = np.random.default_rng(length)
    rows = _LastRows(length, 4)
    kept: deque[np.ndarray] = deque(maxlen=length)
    for _ in range(5 * length + 2):
        row = rng.normal(1100.0, 30.0, 4)
        rows.append(row)
        kept.append(row)
        assert rows.count == len(kept)
        np.testing.assert_array_equal(rows.rows(), np.array(kept))
        if rows.count == length:
            mean = np.add.reduce(rows.rows(), axis=0) / length
            assert np.array_equal(mean, np.mean(kept, axis=0))


def test_unbalanced_rises_equal_the_nan_to_num_formula_bit_for_bit() -> None:
    """_unbalanced (NaN as 0 without np.nan_to_num's wrapper) gives the formula's bits, NaN
    and infinite rates included."""
    from softpad.control._safety import _unbalanced

    rng = np.random.default_rng(7)
    for _ in range(300):
        slope = rng.normal(0.0, 200.0, (4, 6))
        slope[rng.random((4, 6)) < 0.2] = np.nan
        if rng.random() < 0.1:
            slope[0, 2] = np.inf
        sealed = rng.random(6) < 0.7
        moved = np.where(sealed, np.nan_to_num(slope), 0.0)
        want = slope + np.minimum(moved.sum(axis=-1, keepdims=True) - moved, 0.0)
        np.testing.assert_array_equal(_unbalanced(slope, sealed), want)
