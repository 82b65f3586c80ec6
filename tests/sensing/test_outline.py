"""Objects outlined at the noise floor: light parts next to an object join it, nothing else."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sensing import (
    DEFAULT_OUTLINE_THRESHOLD_PA,
    detect_objects,
    outline_objects,
)

LAYOUT = PadLayout()

#: A simulated banana's plan increments (MuJoCo, experiment seed 101): its middle on module 2
#: stays under t_o, so t_o alone sees two objects, its two ends on modules 3 and 4.
BANANA_PA = (-1.0, 33.0, 176.0, 212.0, 2.0, 1.0)


def test_a_light_middle_joins_two_ends_into_one_object() -> None:
    split = detect_objects(BANANA_PA, LAYOUT)
    assert split == [(3,), (4,)]
    assert outline_objects(BANANA_PA, split, LAYOUT) == [(2, 3, 4)]


def test_only_neighbours_above_the_threshold_join() -> None:
    delta = (300.0, 24.0, 30.0, 26.0, 0.0, 0.0)
    # module 2 (24 Pa) is under the threshold, module 3 (30 Pa) is not next to module 1,
    # module 4 (26 Pa) is
    assert outline_objects(delta, [(1,)], LAYOUT) == [(1, 4)]
    assert outline_objects(delta, [(1,)], LAYOUT, threshold_pa=20.0) == [(1, 2, 4)]
    assert outline_objects(delta, [], LAYOUT) == []  # it outlines objects, it finds none


def test_unloaded_neighbours_stay_out_over_many_seeds() -> None:
    """An object on module 1 and noise of the stated size (5.5 Pa rms: 10-read mean and
    reference, plus drift) on the others: the outline grows in about 1 plan in 10^5
    (Gaussian tail beyond 4.5 sigma, 3.4e-6, times module 1's three neighbours). 20 000
    seeded plans: at most 3 grown (Poisson, expected 0.2; 4 or more has probability 6e-5).
    Three times that noise: 1 - (1 - P(z > 1.52))^3 = 0.18 of the plans grow, 0.12..0.25
    allowed (binomial, 2000 plans: 7 standard deviations either side)."""
    grown = 0
    for seed in range(20_000):
        noise = np.random.default_rng(seed).normal(0.0, 5.5, 6)
        noise[0] = 400.0
        grown += outline_objects(noise, [(1,)], LAYOUT) != [(1,)]
    assert grown <= 3
    # the same noise three times larger is seen: the threshold is what keeps it out
    loud = sum(
        outline_objects(np.r_[400.0, np.random.default_rng(s).normal(0, 16.5, 5)], [(1,)], LAYOUT)
        != [(1,)]
        for s in range(2000)
    )
    assert 0.12 * 2000 < loud < 0.25 * 2000
    assert DEFAULT_OUTLINE_THRESHOLD_PA == pytest.approx(4.5 * 5.5, abs=0.5)


@pytest.mark.parametrize(
    ("delta", "objects", "match"),
    [
        (BANANA_PA[:5], [(3,)], "6 increments"),
        ((np.nan, 0, 0, 0, 0, 0), [(1,)], "nan"),
        (BANANA_PA, [(7,)], "from 1 to 6 on a 2x3 pad, got 7"),
    ],
)
def test_bad_input_is_named(delta: tuple, objects: list, match: str) -> None:
    with pytest.raises(InputError, match=match):
        outline_objects(delta, objects, LAYOUT)


def test_a_negative_threshold_is_refused() -> None:
    with pytest.raises(InputError, match="outline threshold"):
        outline_objects(BANANA_PA, [(3,)], LAYOUT, threshold_pa=-1.0)
