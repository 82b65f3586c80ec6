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


class _Predicting:
    """A planner that says how likely its grasp is under each gripper (by max width)."""

    def __init__(self, success: dict[float, float]) -> None:
        self.success = success
        self.asked: list[float] = []

    def plan(self, increments_pa, objects, layout):
        return []

    def mounting_success(self, increments_pa, objects, layout, gripper):
        self.asked.append(gripper.max_width_m)
        return self.success[round(gripper.max_width_m, 3)]


def test_a_predicting_planner_decides_the_mounting() -> None:
    """With a MountingChooser the width rule is not used: the installed mounting with the
    highest predicted success wins, the narrowest of equals, only installed ones asked."""
    reading = _reading({3: 120.0, 6: 120.0})  # the width rule says 6/2
    assert choose_mounting(reading, planner=_Predicting({0.1: 0.9, 0.06: 0.5, 0.04: 0.1})) == "10/4"
    assert choose_mounting(reading, planner=_Predicting({0.1: 0.2, 0.06: 0.5, 0.04: 0.7})) == "4/0"
    tie = _Predicting({0.1: 0.6, 0.06: 0.6, 0.04: 0.3})
    assert choose_mounting(reading, planner=tie) == "6/2"
    only = _Predicting({0.1: 0.9, 0.06: 0.5, 0.04: 0.1})
    assert choose_mounting(reading, installed=("6/2", "4/0"), planner=only) == "6/2"
    assert sorted(only.asked) == [0.04, 0.06]
    # a planner without the hook: the width rule
    assert choose_mounting(reading, planner=object()) == "6/2"
