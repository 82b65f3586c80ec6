"""The gripper mounting chosen from the pad's reading (``--mounting auto``; issue 45)."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning import choose_mounting
from softpad.planning._mounting import reach_m


def _reading(modules: dict[int, float]) -> list[float]:
    return [modules.get(k, 0.0) for k in range(1, 7)]


@pytest.mark.parametrize(
    ("modules", "mounting"),
    [
        ({3: 120.0, 6: 120.0}, "6/2"),  # object 1 on the 3-6 line: 45 mm across
        ({1: 100.0, 5: 100.0}, "6/2"),  # object 2's diagonal: its centres project together
        ({2: 150.0, 4: 300.0, 5: 300.0, 6: 300.0}, "10/4"),  # the limes: 135 mm along x
        ({2: 80.0}, "6/2"),  # one module
        ({}, "10/4"),  # nothing seen: the widest
    ],
    ids=["object-1", "object-2", "limes", "one-module", "nothing"],
)
def test_the_narrowest_mounting_that_opens_beyond_the_reach(
    modules: dict[int, float], mounting: str
) -> None:
    assert choose_mounting(_reading(modules)) == mounting


def test_only_installed_mountings_are_chosen() -> None:
    limes = _reading({2: 150.0, 4: 300.0, 5: 300.0, 6: 300.0})
    assert choose_mounting(limes, installed=("4/0", "6/2")) == "6/2"  # the widest at hand
    assert choose_mounting(_reading({2: 80.0}), installed=("4/0",)) == "4/0"
    assert choose_mounting(_reading({2: 80.0}), installed=("10/4", "4/0")) == "10/4"
    with pytest.raises(InputError, match="installed mountings"):
        choose_mounting(limes, installed=("7/3",))


@pytest.mark.parametrize(
    ("modules", "theta", "pitches"),
    [
        ((1,), 0.0, 1.0),
        ((1, 2, 3), 0.0, 3.0),
        ((1, 2, 3), 1.5707963, 1.0),
        ((1, 5), 0.7853982, 1.0),
    ],
    ids=["one", "row-along", "row-across", "diagonal-across"],
)
def test_reach_is_the_centres_span_plus_one_pitch(
    modules: tuple[int, ...], theta: float, pitches: float
) -> None:
    layout = PadLayout()
    assert reach_m(modules, theta, layout) == pytest.approx(pitches * layout.pitch_m, abs=1e-6)
