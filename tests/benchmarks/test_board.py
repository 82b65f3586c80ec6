"""The board's budget and the instruction count of the box loop (``softpad bench --only board``)."""

from __future__ import annotations

import shutil

import pytest

from softpad.benchmarks._board import (
    BOARD_CLOCK_HZ,
    CORTEX_A8_PEAK_IPC,
    PHASES,
    budget_per_tick,
    count_instructions,
)


def test_the_budget_is_clock_times_ipc_over_the_rate() -> None:
    # 1 GHz x 2 instructions per cycle / 1000 ticks per second = 2 million per tick
    assert budget_per_tick() == pytest.approx(2.0e6)
    assert budget_per_tick(0.5, 500.0) == pytest.approx(BOARD_CLOCK_HZ * 0.5 / 500.0)
    assert CORTEX_A8_PEAK_IPC == 2.0


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("valgrind") is None, reason="needs valgrind")
def test_the_whole_tick_costs_at_least_its_parts() -> None:
    """The counts are of real work: every phase executes instructions, and the whole tick
    (sampling, guard, signing, publishing and bookkeeping) at least the sum of sampling,
    guard and signing (publishing's network threads may run in a neighbouring phase)."""
    n = count_instructions(100)
    assert set(n) == set(PHASES)
    assert all(v > 1000 for v in n.values()), n
    assert n["tick"] >= n["sampling"] + n["guard"] + n["signing"], n
