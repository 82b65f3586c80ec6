"""Ranking, Pareto front and the outputs of a sweep (synthetic rows: no simulation)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from softpad.design import COLUMNS, THESIS_DESIGN, DesignRow, PadDesign, SweepResult, rank_rows


def _row(design: PadDesign, ok: int, n: int, mass_g: float) -> DesignRow:
    return DesignRow(
        design=design,
        response={
            "height_mm": 8.0,
            "rise_kpa_per_n": 0.5,
            "min_detectable_mass_g": mass_g,
            "sensitive_fraction": 0.5,
        },
        successes=ok,
        trials=n,
        success_interval=(0.0, 1.0),
        detection_delay_ms=70.0,
        failures={"missed": n - ok} if ok < n else {},
    )


@pytest.fixture
def result() -> SweepResult:
    rows = [
        _row(THESIS_DESIGN, 8, 10, 9.0),
        _row(PadDesign(3, 4, 0.034), 9, 10, 5.0),  # better in success and mass, dearer
        _row(PadDesign(2, 3, 0.045, p0_pa=2000.0), 8, 10, 10.0),  # dominated by the thesis's
        _row(PadDesign(4, 6, 0.023), 2, 10, 2.0),  # worst success, lightest: on the front
    ]
    return SweepResult(tuple(rank_rows(rows)), "synthetic", {"seeds": [0]})


def test_ranking_and_pareto_flags(result: SweepResult) -> None:
    names = [r.design.name for r in result.rows]
    assert names[0] == "3x4-34mm-t1.5-neo-hookean-p1.1"
    assert [r.rank for r in result.rows] == [1, 2, 3, 4]
    front = {r.design.name: r.pareto for r in result.rows}
    assert front == {
        "3x4-34mm-t1.5-neo-hookean-p1.1": True,
        "thesis 2x3 45 mm": True,  # fewer modules than the 3x4
        "2x3-45mm-t1.5-neo-hookean-p2": False,
        "4x6-23mm-t1.5-neo-hookean-p1.1": True,
    }
    assert result.baseline.design.is_thesis and result.baseline.rank == 2


def test_json_csv_parquet_png_report(
    result: SweepResult, tmp_path: Path, design_keys: frozenset[str]
) -> None:
    d = result.to_dict()
    assert design_keys <= set(d["designs"][0])
    with result.to_csv(tmp_path / "t.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == list(COLUMNS) and rows[1]["baseline"] == "True"
    pq = pytest.importorskip("pyarrow.parquet")
    table = pq.read_table(result.to_parquet(tmp_path / "t.parquet"))
    assert table.num_rows == 4 and table.column("success").to_pylist()[0] == pytest.approx(0.9)
    result.plot(tmp_path / "p.png")
    assert (tmp_path / "p.png").stat().st_size > 1000
    assert "ranks 2" in result.report()


def test_design_rows_count_each_objects_held_grasps() -> None:
    from softpad.design._results import _per_object

    trials = [
        {"object": "a", "success": True},
        {"object": "b", "success": False},
        {"object": "a", "success": False},
        {"object": "a", "success": True},
    ]
    assert _per_object(trials) == {"a": (2, 3), "b": (0, 1)}


def test_pareto_rank_labels_do_not_overlap(result: SweepResult) -> None:
    """Two designs a hair apart (the thesis's 8/10 at 9.0 g and one at 9.05 g): one label names
    both; no label's box overlaps another's; every rank is written once."""
    import matplotlib.pyplot as plt

    from softpad.design import THESIS_DESIGN

    rows = [*result.rows, _row(PadDesign(2, 3, 0.045, thickness_m=0.0025), 8, 10, 9.05)]
    crowded = SweepResult(tuple(rank_rows([r for r in rows])), "synthetic", {})
    assert any(r.design == THESIS_DESIGN for r in crowded.rows)
    fig = crowded.plot()
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    ax = fig.axes[0]
    labels = [t for t in ax.texts if t.get_text()[:1].isdigit()]
    boxes = [t.get_window_extent(renderer) for t in labels]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not a.overlaps(b)
    ranks = sorted(int(v) for t in labels for v in t.get_text().split(", "))
    assert ranks == list(range(1, len(crowded.rows) + 1))
    plt.close(fig)
