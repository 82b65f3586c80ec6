"""softpad.sim's pad reports (what ``softpad pad probe|map|sensitivity`` print): a block off
the pad is refused naming the pad's size, the probe's dict and lines agree, and the map's
figures come from its grid."""

from __future__ import annotations

import numpy as np
import pytest

from softpad import thesis
from softpad.box import open_box
from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sim import PadMap, probe_report, sensitivity_lines

URL = "sim://?inflated_kpa=1.1&noise=0"


def test_a_block_off_the_pad_names_the_pads_size() -> None:
    with open_box(URL) as box, pytest.raises(InputError, match=r"off the 2x3 pad \(x 0..3"):
        probe_report(box, (2.0, 2.5), (0.01, 0.01), 0.2, URL)


def test_the_probes_lines_show_its_dict_per_module() -> None:
    with open_box(URL) as box:
        d, lines = probe_report(box, (1.5, 1.5), (0.01, 0.01), 0.2, URL)
    assert d["at"] == [1.5, 1.5] and len(d["delta_kpa"]) == 6
    assert lines[0] == f"block 10 x 10 mm, 0.2 N at (1.5, 1.5) module units on {URL}"
    rows = [line.split() for line in lines[2:]]
    assert [float(r[1]) for r in rows] == pytest.approx(d["delta_kpa"], abs=1e-4)
    assert [float(r[2]) for r in rows] == pytest.approx(d["delta_kpa_per_n"], abs=1e-3)
    assert max(d["delta_kpa"]) == d["delta_kpa"][1]  # module 2 is under the block


def test_a_maps_figures_are_its_grids() -> None:
    top = np.array([[10.0, 60.0], [100.0, 40.0]])
    m = PadMap(np.array([0.01, 0.02]), np.array([0.01, 0.02]), top, PadLayout(), (0.01, 0.01),
               0.2, thesis.P0_PA)  # fmt: skip
    d = m.to_dict()
    assert d["largest_kpa"] == pytest.approx(0.1) and d["smallest_kpa"] == pytest.approx(0.01)
    assert d["share_above_object_threshold"] == pytest.approx(0.5)  # 60 and 100 Pa >= 50 Pa


def test_sensitivity_lines_name_line_and_corner() -> None:
    out = {
        "pad_model": "cast", "line_gain": 1.0, "loads": {"centre": {"rise_pa_n": [1, 2, 3, 4, 5, 6]}},
        "line_pa_n": 123.4, "corner_pa_n": 56.7, "min_detectable_mass_g": {"centre": 1.234},
    }  # fmt: skip
    lines = sensitivity_lines(out, 1.1)
    assert lines[0] == "cast pad at 1.1 kPa, line gain 1: sealed rise per newton (Pa/N)"
    assert "line sensitivity (can strip, least of modules 1, 4): 123 Pa/N" in lines
    assert lines[-1] == "minimum detectable mass at t_o = 50 Pa, centre: 1.23 g"
