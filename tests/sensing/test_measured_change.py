"""Measured changes handed to the object detector and the planners."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sensing import SMALLEST_PLAUSIBLE_INCREMENT_PA, detect_objects, measured_change


def test_a_measured_change_under_a_pascal_everywhere_is_no_change() -> None:
    """What the loop measured on a quiet pad (an average under the converter's step on every
    module) is zeros, which the planners' unit check accepts; the raw vector is refused, as a
    typed one should be; a change of a pascal or more anywhere is kept as measured."""
    layout = PadLayout()
    quiet = np.array([0.976562, -0.5, 0.2, 0.0, 0.9, -0.97])
    with pytest.raises(InputError, match="below 1 Pa"):
        detect_objects(quiet, layout)
    np.testing.assert_array_equal(measured_change(quiet), np.zeros(6))
    assert detect_objects(measured_change(quiet), layout) == []
    moved = quiet.copy()
    moved[2] = SMALLEST_PLAUSIBLE_INCREMENT_PA
    np.testing.assert_array_equal(measured_change(moved), moved)
    bad = quiet.copy()
    bad[1] = np.nan
    assert np.isnan(measured_change(bad)[1])
