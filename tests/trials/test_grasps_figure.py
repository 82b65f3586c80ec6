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


def test_grasps_figure_reads_a_page_wide_with_the_module_grid() -> None:
    """grasps.png: every label >= 6.5 pt when the figure is printed 7 in wide (it was 8 pt on
    an 18 in figure: 3.1 pt), each panel in mm with ticks at the module boundaries."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.text import Text

    from softpad.harness import resolve_objects
    from softpad.trials._plots import plot_grasps

    def trial(name: str, ok: bool) -> TrialResult:
        return TrialResult(
            name, 0, 0, (0.07, 0.05, 0.0), "10/4", ok, None if ok else "contact_not_detected",
            (2, 5), (0.0,) * 6, (1.5, 1.0), 0.0, 0.1,
        )  # fmt: skip

    names = ["object-1", "object-5", "banana", "toy", "limes"]
    result = ExperimentResult(tuple(trial(n, n != "toy") for n in names), seed=0)
    specs = {s.name: s for s in resolve_objects(names)}
    fig = plot_grasps(result, specs, "")
    try:
        fig.canvas.draw()
        scale = 7.0 / fig.get_figwidth()
        sizes = {
            t.get_text(): t.get_fontsize() * scale
            for t in fig.findobj(Text)
            if t.get_visible() and t.get_text().strip()
        }
        assert min(sizes.values()) >= 6.5 - 1e-9, {k: v for k, v in sizes.items() if v < 6.5}
        assert "contact not detected" in " ".join(sizes)
        pad = fig.axes[0]
        assert list(pad.get_xticks()) == [0.0, 45.0, 90.0, 135.0]
        assert pad.get_xlabel() == "x (mm)"
    finally:
        plt.close(fig)
