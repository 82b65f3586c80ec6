"""grasps.png: every trial of every object counted beside the drawn plan, with intervals."""

from __future__ import annotations

import math

import pytest

from softpad.trials._plots import success_chart, wilson_interval
from softpad.trials._records import ExperimentResult, TrialResult


def _wilson(k: int, n: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """The Wilson score interval written out (independent of scipy)."""
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return centre - half, centre + half


@pytest.mark.parametrize(("k", "n"), [(0, 5), (2, 5), (5, 5), (52, 55)])
def test_wilson_interval_matches_the_formula(k: int, n: int) -> None:
    assert wilson_interval(k, n) == pytest.approx(_wilson(k, n), abs=1e-9)


def test_success_chart_counts_every_trial_of_every_object() -> None:
    from matplotlib.figure import Figure

    def trial(name: str, k: int, ok: bool) -> TrialResult:
        return TrialResult(
            name, k, k, (0.0, 0.0, 0.0), "6/2", ok, None if ok else "slipped_during_hold"
        )

    # the banana held 2 of 5 although its first trial held: the chart says 2/5
    trials = [trial("banana", k, k in (0, 3)) for k in range(5)]
    trials += [trial("object-5", k, True) for k in range(5)]
    ax = Figure().add_subplot()
    success_chart(ax, ExperimentResult(tuple(trials), seed=0))
    assert [t.get_text() for t in ax.get_yticklabels()] == ["banana", "object-5"]
    assert [t.get_text() for t in ax.texts] == ["2/5", "5/5"]
    assert ax.get_title() == "every trial: 7/10 held"
    assert [b.get_width() for b in ax.patches] == [0.4, 1.0]
