"""``softpad plan``'s ASCII pad: its legend names every marker drawn (issue 51: a ``*`` the
legend did not explain)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from softpad.layout import parse_layout
from softpad.planning import format_plans, plan_grasps

LAYOUT = parse_layout("2x3")


@pytest.mark.parametrize(
    "delta_kpa",
    [
        pytest.param([0.2, 0, 0, 0, 0, 0], id="one-module-PCOM-on-COG"),
        pytest.param([0, 0.124, 0.078, 0.109, 0, 0], id="banana-P-and-G"),
        pytest.param([0.1, 0, 0.1, 0, 0, 0], id="two-objects"),
        pytest.param([0, 0, 0, 0, 0, 0], id="nothing"),
    ],
)
def test_the_legend_names_every_marker_on_the_pad(delta_kpa: list[float]) -> None:
    delta = np.array(delta_kpa) * 1e3
    plans = plan_grasps(delta, LAYOUT)
    lines = format_plans(delta, plans, LAYOUT, 50.0).splitlines()
    legend = lines[1]
    pad = "\n".join(ln for ln in lines[2:] if ln[:1] in "+|")
    drawn = set(re.sub(r"[+|\-\s.0-9]", "", pad))  # frame, module numbers, increments aside
    named = set(re.findall(r"(\S) = ", legend))
    assert drawn <= named, f"{sorted(drawn - named)} drawn but not in the legend {legend!r}"
    if "*" in pad:
        assert "* = PCOM and centre of grasp in one character" in legend
