"""Pad designs and design spaces."""

from __future__ import annotations

import pytest

from softpad.design import (
    QUICK_DESIGNS,
    THESIS_DESIGN,
    DesignSpace,
    PadDesign,
    parse_grids,
    parse_values,
)
from softpad.errors import InputError


def test_thesis_design_is_the_prototype() -> None:
    d = THESIS_DESIGN
    assert (d.rows, d.cols, d.pitch_m, d.thickness_m, d.material, d.p0_pa) == (
        2,
        3,
        0.045,
        0.0015,
        "neo-hookean",
        1100.0,
    )
    assert d.is_thesis and d.n_modules == 6
    assert PadDesign(name="another name").is_thesis  # identity is the variables, not the name


def test_quick_designs_are_eight_distinct_with_the_baseline_first() -> None:
    assert len(QUICK_DESIGNS) >= 8
    assert QUICK_DESIGNS[0].is_thesis
    assert sum(d.is_thesis for d in QUICK_DESIGNS) == 1
    assert len({tuple(d.variables().items()) for d in QUICK_DESIGNS}) == len(QUICK_DESIGNS)


@pytest.mark.parametrize(
    ("changes", "named"),
    [
        ({"rows": 0}, "rows"),
        ({"cols": 17}, "cols"),
        ({"pitch_m": 0.005}, "pitch"),
        ({"thickness_m": 0.01}, "thickness"),
        ({"p0_pa": 3500.0}, "p0"),
        ({"p0_pa": float("nan")}, "p0"),
        ({"material": "rubber"}, "rubber"),
    ],
    ids=["rows", "cols", "pitch", "thickness", "p0", "p0-nan", "material"],
)
def test_bad_design_names_the_variable(changes: dict, named: str) -> None:
    with pytest.raises(InputError, match=named):
        PadDesign(**changes)


def test_space_is_the_product_with_the_baseline_once() -> None:
    space = DesignSpace(grids=((2, 3), (3, 4)), pitches_m=(0.035, 0.045), p0s_pa=(1100.0, 2000.0))
    designs = space.designs()
    assert space.size == 8
    # the baseline is in the product: listed once, first
    assert len(designs) == 8 and designs[0].is_thesis
    assert len({d.name for d in designs}) == 8


def test_parse_values_lists_and_ranges_in_si() -> None:
    assert parse_values("1,1.5", "--t", 1e-3, (5e-4, 5e-3)) == (0.001, 0.0015)
    assert parse_values("1:2:0.5", "--t", 1e-3, (5e-4, 5e-3)) == (0.001, 0.0015, 0.002)
    with pytest.raises(InputError, match="--t: 9 outside"):
        parse_values("9", "--t", 1e-3, (5e-4, 5e-3))
    with pytest.raises(InputError, match="--t: expected numbers"):
        parse_values("a", "--t", 1e-3, (5e-4, 5e-3))


def test_parse_grids() -> None:
    assert parse_grids("2x3, 3X4") == ((2, 3), (3, 4))
    with pytest.raises(InputError, match="--grid"):
        parse_grids("2by3")
    with pytest.raises(InputError, match="--grid"):
        parse_grids("0x3")
