"""The pad-density study's machinery (issue 47, item 5); the study's script at a tiny size is
run by tests/test_examples.py (``density_study.py``)."""

from __future__ import annotations

import pytest

from softpad.design import DENSITY_PADS, DensityStudy
from softpad.design._density import pareto_front
from softpad.errors import InputError


def _row(pad: str, modules: int, pair: str, ok: int, n: int = 10) -> dict:
    return {"set": "held", "pair": pair, "pad": pad, "modules": modules, "successes": ok,
            "trials": n, "success": ok / n}  # fmt: skip


def test_smallest_pad_is_the_fewest_modules_reaching_the_share() -> None:
    rows = (
        _row("2x3", 6, "mb", 7),
        _row("3x4", 12, "mb", 9),
        _row("4x6", 24, "mb", 10),
        _row("2x3", 6, "th", 8),
    )
    study = DensityStudy(rows, {}, {"sets": ["held"]})
    assert study.smallest_pad("mb", "held", 0.85)["pad"] == "3x4"
    assert study.smallest_pad("mb", "held", 0.85)["reached"] is True
    best = study.smallest_pad("th", "held", 0.85)
    assert (best["pad"], best["reached"]) == ("2x3", False)
    with pytest.raises(InputError, match="no rows for the pair 'x'"):
        study.smallest_pad("x", "held")


def test_pareto_front_keeps_the_undominated() -> None:
    # cost (modules) and gain (share): (12, 0.6) is dominated by (6, 0.7)
    assert pareto_front([6, 12, 24], [0.7, 0.6, 0.9]) == [0, 2]
    assert pareto_front([6, 12], [0.5, 0.5]) == [0]


def test_the_study_pads_cover_about_the_thesis_area() -> None:
    """Each pad within 15 % of the thesis's 90 x 135 mm (3x4 at 34 mm: +14 %), 6 to 24 modules."""
    area = 0.090 * 0.135
    for d in DENSITY_PADS:
        assert d.rows * d.cols * d.pitch_m**2 == pytest.approx(area, rel=0.15)
    assert [d.n_modules for d in DENSITY_PADS] == [6, 12, 15, 24]


def test_design_valves_option_names_its_choices(capsys: pytest.CaptureFixture[str]) -> None:
    from softpad.cli.main import main

    assert main(["design", "--valves", "tiny"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--valves" in err and "'sized'" in err
