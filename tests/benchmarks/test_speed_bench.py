"""``softpad bench --only speed``: the issue-50 figures carry their target and the load of each
run (figures only: speed is never asserted here)."""

from __future__ import annotations

import math

from softpad.benchmarks import BENCH_MODULES
from softpad.benchmarks._speed import BOX_TARGET, _box, load_average


def test_speed_is_a_bench_module() -> None:
    assert "speed" in BENCH_MODULES


def test_load_average_is_the_machines() -> None:
    load = load_average()
    assert math.isnan(load) or load >= 0.0


def test_box_figure_names_its_target_and_the_load_of_its_run() -> None:
    r = _box(quick=True)
    assert r.unit == "x real time" and r.value > 0.0
    assert r.target == f">= {BOX_TARGET:g}x"
    assert r.met == (r.value >= BOX_TARGET)
    assert "(load " in r.detail and "1 runs of 2 s simulated" in r.detail
