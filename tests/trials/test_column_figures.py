"""The demo report's figures a paper's column wide (issue 48: the multi-panel figures were sized
for a 7 in page, 3.25 pt once printed 3.5 in wide): each saved figure is 3.5 in wide by its
own resolution, every label prints at 6.5 pt or more at that width and lies inside the figure,
and the pad is drawn in millimetres with the module grid."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from softpad.layout import PadLayout
from softpad.trials import ExperimentResult, TrialResult

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

COLUMN_IN = 3.5
SMALLEST_PT = 6.5


@pytest.fixture
def saved(monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[Path, Any]]:
    """Every figure saved while the test runs, by its file."""
    from matplotlib.figure import Figure

    figures: dict[Path, Any] = {}
    save: Callable[..., None] = Figure.savefig

    def spy(fig: Any, path: Any, *args: Any, **kwargs: Any) -> None:
        save(fig, path, *args, **kwargs)
        figures[Path(path)] = fig

    monkeypatch.setattr(Figure, "savefig", spy)
    yield figures


def _check_readable_at_a_column(path: Path, fig: Any) -> dict[str, float]:
    """The PNG's width in inches (pixels / its dpi) is a column; every text's printed size
    at that width (points) is >= 6.5 and all that is drawn lies inside the figure. Returns the sizes."""
    from matplotlib.text import Text
    from PIL import Image

    with Image.open(path) as image:
        width_in = image.size[0] / image.info["dpi"][0]
        grey = np.asarray(image.convert("L"))
    # nothing cut at the edges of the saved picture: its outermost pixels are background
    edges = np.concatenate([grey[0], grey[-1], grey[:, 0], grey[:, -1]])
    assert edges.min() == 255, (path.name, "a label is cut at the figure's edge")
    assert width_in == pytest.approx(COLUMN_IN, abs=0.01), (path.name, width_in)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    scale = COLUMN_IN / width_in
    texts = [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]
    sizes = {t.get_text(): t.get_fontsize() * scale for t in texts}
    small = {k: v for k, v in sizes.items() if v < SMALLEST_PT - 1e-9}
    assert not small, (path.name, small)
    # everything drawn (tick labels within the axes' limits, titles, legends) on the page
    drawn, page = fig.get_tightbbox(renderer), fig.bbox_inches
    assert drawn.x0 >= -0.01 and drawn.y0 >= -0.01, (path.name, drawn)
    assert drawn.x1 <= page.x1 + 0.01 and drawn.y1 <= page.y1 + 0.01, (path.name, drawn)
    return sizes


def _check_mm_axes(ax: Any) -> None:
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x (mm)", "y (mm)")
    assert list(ax.get_xticks()) == [0.0, 45.0, 90.0, 135.0]  # the module boundaries
    assert list(ax.get_yticks()) == [0.0, 45.0, 90.0]


def test_the_reference_plans_each_read_a_column_wide(
    tmp_path: Path, saved: dict[Path, Any]
) -> None:
    from softpad.planning import TABLE_6_1, plan_grasps, plot_plan_columns

    layout = PadLayout()
    cases = [(c, plan_grasps(c.delta_pa, layout)[0]) for c in TABLE_6_1]
    paths = plot_plan_columns(cases, tmp_path, layout)
    assert [p.name for p in paths] == [f"plans_reference-{c.name}.png" for c in TABLE_6_1]
    assert set(saved) == set(paths)
    for path in paths:
        sizes = _check_readable_at_a_column(path, saved[path])
        assert {"PCOM", "COG", "fingertips, jaws open", "dP (kPa)"} <= set(sizes), path.name
        _check_mm_axes(saved[path].axes[0])
    # one colour scale for all cases: the largest increment of all tops every colour bar
    tops = [saved[p].axes[0].images[0].get_clim()[1] for p in paths]
    assert tops == pytest.approx([max(max(c.delta_pa) for c in TABLE_6_1) / 1e3] * len(paths))


def test_the_grasps_and_outcomes_each_read_a_column_wide(
    tmp_path: Path, saved: dict[Path, Any]
) -> None:
    from softpad.harness import resolve_objects
    from softpad.trials._plots import plot_grasp_columns

    def trial(name: str, ok: bool) -> TrialResult:
        return TrialResult(
            name, 0, 0, (0.07, 0.05, 0.0), "10/4", ok, None if ok else "contact_not_detected",
            (2, 5), (0.0,) * 6, (1.5, 1.0), 0.0, 0.1,
        )  # fmt: skip

    names = ["object-1", "banana", "toy", "limes"]
    result = ExperimentResult(tuple(trial(n, n != "toy") for n in names), seed=0)
    specs = {s.name: s for s in resolve_objects(names)}
    paths = plot_grasp_columns(result, specs, tmp_path)
    assert [p.name for p in paths] == [f"grasps-{n}.png" for n in names] + ["outcomes.png"]
    for path in paths[:-1]:
        sizes = _check_readable_at_a_column(path, saved[path])
        assert {"fingertips, approach opening", "module above t_o", "object"} <= set(sizes)
        _check_mm_axes(saved[path].axes[0])
    assert "contact not detected" in " ".join(_check_readable_at_a_column(*_at(saved, "toy")))
    chart = _check_readable_at_a_column(paths[-1], saved[paths[-1]])
    assert {"every trial: 3/4 held", "0/1", "banana"} <= set(chart)


def _at(saved: dict[Path, Any], name: str) -> tuple[Path, Any]:
    (path,) = [p for p in saved if p.name == f"grasps-{name}.png"]
    return path, saved[path]
