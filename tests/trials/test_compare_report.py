"""A comparison's pairs, table and figure (softpad.trials.parse_pairs, comparison_table,
plot_comparison), on a comparison written out by hand."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.trials import DEFAULT_PAIRS, comparison_table, parse_pairs, plot_comparison


def _combo(planner: str, detector: str, ok: int, delay_s: float | None) -> dict:
    objects = [
        {"name": "banana", "success": ok / 2, "success_interval": [0.1, 1.0]},
        {"name": "toy", "success": 1.0, "success_interval": [0.3, 1.0]},
    ]
    return {
        "planner": planner, "detector": detector, "successes": ok + 2, "trials": 4,
        "success": (ok + 2) / 4, "success_interval": [0.3, 0.99], "delay_s_median": delay_s,
        "delay_s_p95": None if delay_s is None else 2 * delay_s, "finger_travel_m_median": None,
        "false_alarms_per_hour": 0.5, "failures": {}, "objects": objects,
    }  # fmt: skip


COMPARISON = {
    "seeds": [3, 4, 5],
    "combinations": [
        _combo("thesis", "thesis", 1, 0.12),
        _combo("gripper-aware", "cusum", 2, None),
    ],
}


def test_the_table_has_one_row_per_pair() -> None:
    lines = comparison_table(COMPARISON).splitlines()
    assert lines[0] == "seeds 3..5 (3)"
    assert lines[3] == (
        "| thesis | thesis | 3/4 = 75.0 % | 30.0 % .. 99.0 % | 120 / 240 | - | 0.5 | - |"
    )
    assert lines[4].startswith("| gripper-aware | cusum | 4/4 = 100.0 % |") and "| - |" in lines[4]
    assert len(lines) == 5


def test_the_figure_has_a_bar_per_object_and_pair() -> None:
    fig = plot_comparison(COMPARISON)
    ax = fig.axes[0]
    heights = [p.get_height() for p in ax.patches]
    assert heights == pytest.approx([0.5, 1.0, 1.0, 1.0])
    assert "3 seeds (4 trials a pair)" in ax.get_title()


def test_pairs_are_registered_names() -> None:
    assert parse_pairs(None) == list(DEFAULT_PAIRS)
    assert parse_pairs(["gripper-aware:adaptive"]) == [("gripper-aware", "adaptive")]
    with pytest.raises(InputError, match=r"PLANNER:DETECTOR.*got 'thesis'"):
        parse_pairs(["thesis"])
    with pytest.raises(InputError, match="got 'nope:thesis'"):
        parse_pairs(["nope:thesis"])


def test_the_table_counts_a_catalogue_pairs_decisions() -> None:
    """A catalogue pair's recognised and unknown trials (summarise's counts) under the table;
    pairs without any (older documents, other planners) add no line."""
    catalogue = {**_combo("catalogue", "adaptive", 2, 0.1), "recognised_as": {"toy": 2}}
    catalogue["unknown"] = 1
    lines = comparison_table({"seeds": [3], "combinations": [catalogue]}).splitlines()
    assert lines[-1] == (
        "catalogue:adaptive: 2 trials recognised as a known object, 1 called unknown "
        "(handed on), of 4"
    )
    plain = {**_combo("thesis", "thesis", 1, 0.12), "recognised_as": {}, "unknown": 0}
    assert len(comparison_table({"seeds": [3], "combinations": [plain]}).splitlines()) == 4
