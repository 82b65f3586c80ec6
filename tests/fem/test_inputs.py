"""The FEM studies' inputs checked in softpad.fem (not in the command line): ranges, the
footprint's text, the chamber study's detection threshold; the options' limits agree."""

from __future__ import annotations

import pytest

from softpad import thesis
from softpad.errors import InputError
from softpad.fem import (
    MASS_RANGE_KG,
    THICKNESS_RANGE_M,
    WIDTH_RANGE_M,
    ModuleCharacteristic,
    check_design_values,
    check_masses,
    check_study_pressures,
    detection_threshold_pa,
    parse_footprint,
)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: check_design_values("thickness", [1.5e-3, 0.05]), "50 mm is outside 0.1..20 mm"),
        (lambda: check_design_values("width", [0.001]), "1 mm is outside 5..500 mm"),
        (lambda: check_design_values("height", [0.01]), "thickness or width"),
        (lambda: check_study_pressures([500.0, 5e5], "--p"), "--p: 500 kPa exceeds"),
        (lambda: check_masses([0.0126, 6e-6], "--m"), "--m: 0.006 g.*kilograms given as grams"),
        (lambda: check_masses([20.0]), "20000 g is outside"),
        (lambda: parse_footprint("42by31", 0.045), "WxH or dD in mm, got '42by31'"),
        (lambda: parse_footprint("1,5x31", 0.045), "WxH or dD"),
        (lambda: parse_footprint("1_0x31", 0.045), "WxH or dD"),
        (lambda: parse_footprint("0.042x0.031", 0.045), "metres given as millimetres"),
        (lambda: parse_footprint("50x31", 0.045, "--f"), "--f '50x31' is wider than the module"),
        (lambda: detection_threshold_pa(0.0), r"detection threshold \(threshold\) must be > 0"),
        (lambda: detection_threshold_pa(50.0, -1.0), r"\(n_sigma x noise\) must be > 0"),
    ],
    ids=[
        "thickness-50mm", "width-1mm", "parameter", "pressure-pa-as-kpa", "mass-kg-as-g",
        "mass-20kg", "footprint-word", "footprint-comma", "footprint-separator",
        "footprint-metres", "footprint-wide", "threshold-zero", "noise-negative",
    ],
)  # fmt: skip
def test_bad_study_inputs_are_named_input_errors(call, match: str) -> None:
    with pytest.raises(InputError, match=match):
        call()


def test_good_study_inputs_pass_and_parse() -> None:
    check_design_values("thickness", [1e-3, 1.5e-3, 3e-3])
    check_study_pressures([500.0, thesis.MAX_PRESSURE_PA])
    check_masses([0.006, 0.0126, 0.05])
    rect, disc = parse_footprint("42x31", 0.045), parse_footprint("D30", 0.045)
    assert (rect.shape, rect.size_x_m, rect.size_y_m) == ("rectangle", 0.042, 0.031)
    assert (disc.shape, disc.size_x_m) == ("disc", pytest.approx(0.030))
    assert detection_threshold_pa(50.0) == (50.0, "threshold")
    assert detection_threshold_pa(50.0, 5.5, 3.0) == (pytest.approx(16.5), "n_sigma x noise")


def test_the_command_lines_limits_are_the_fem_ranges() -> None:
    from softpad.cli import _fem

    def mm(r: tuple[float, float]) -> tuple[float, float]:
        return (round(r[0] * 1e3, 9), round(r[1] * 1e3, 9))

    assert _fem.THICKNESS_RANGE_MM == mm(THICKNESS_RANGE_M)
    assert _fem.WIDTH_RANGE_MM == mm(WIDTH_RANGE_M)
    assert _fem.MASS_RANGE_G == mm(MASS_RANGE_KG)


def test_a_characteristic_writes_one_csv_row_per_pressure_and_load(tmp_path) -> None:
    import numpy as np

    c = ModuleCharacteristic(
        np.array([0.0, 1000.0]),
        np.array([0.0, 0.5]),
        np.array([[1e-6, 0.9e-6], [2e-6, 1.8e-6]]),
        np.array([[0.0, -1e-3], [9e-3, 8e-3]]),
    )
    lines = c.to_csv(tmp_path / "c.csv").read_text().splitlines()
    assert lines[0] == "pressure_kpa,load_n,volume_ml,height_mm"
    assert len(lines) == 5
    assert [float(v) for v in lines[4].split(",")] == pytest.approx([1.0, 0.5, 1.8, 8.0])
