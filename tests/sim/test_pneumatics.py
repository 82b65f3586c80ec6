"""Gas physics of a channel: sealed chamber under load, valves, leaks."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from softpad.sim import (
    AnalyticCharacteristic,
    ChamberBank,
    PneumaticParams,
    sealed_sensitivity_pa_n,
)

CHAR = AnalyticCharacteristic()
PAR = PneumaticParams()
CLOSED = np.zeros(1, dtype=bool)
OPEN = np.ones(1, dtype=bool)


def _bank(p0: float = 1100.0) -> ChamberBank:
    b = ChamberBank(1, 1, CHAR, PAR)
    b.set_state(np.array([p0]))
    return b


@pytest.mark.parametrize("load_n", [0.05, 0.5, 3.0], ids=["light", "medium", "collapse"])
def test_sealed_chamber_matches_independent_root_find(load_n: float) -> None:
    """(p_atm + p)(V(p, F) + V_t) stays equal to the amount of air: solved here by brentq."""
    b = _bank()
    n0 = float(b.amount[0])
    b.step(0.01, CLOSED, CLOSED, np.array([load_n]), PAR.supply_pa, any_open=False)

    def f(p: float) -> float:
        v = float(CHAR.volume_m3(p, load_n))
        return (PAR.atmosphere_pa + p) * (v + PAR.tubing_volume_m3) - n0

    expected = brentq(f, 0.0, 50e3, xtol=1e-9)
    np.testing.assert_allclose(b.pressure_pa[0], expected, rtol=1e-8)
    np.testing.assert_allclose(b.amount[0], n0, rtol=1e-15)


def test_small_load_follows_the_linear_sensitivity() -> None:
    b = _bank()
    b.step(0.01, CLOSED, CLOSED, np.array([0.02]), PAR.supply_pa, any_open=False)
    np.testing.assert_allclose(
        (b.pressure_pa[0] - 1100.0) / 0.02, sealed_sensitivity_pa_n(CHAR), rtol=5e-3
    )


def test_stuck_inflation_valve_vented_settles_below_the_maximum() -> None:
    """Both valves open, turbulent orifices: A_i^2 (p_s - p) = A_d^2 p."""
    b = _bank()
    for _ in range(6000):
        b.step(0.01, OPEN, OPEN, np.zeros(1), PAR.supply_pa, any_open=True)
    ratio = (PAR.deflate_orifice_m2 / PAR.inflate_orifice_m2) ** 2
    np.testing.assert_allclose(b.pressure_pa[0], PAR.supply_pa / (1 + ratio), rtol=0.02)
    assert b.pressure_pa[0] < 3000.0


def test_inflation_rises_monotonically_towards_the_supply() -> None:
    b = _bank(0.0)
    trace = []
    for _ in range(1500):
        b.step(0.01, OPEN, CLOSED, np.zeros(1), PAR.supply_pa, any_open=True)
        trace.append(b.pressure_pa[0])
    assert (np.diff(trace) > 0).all()
    assert 1100.0 < trace[-1] < PAR.supply_pa


def test_leak_empties_a_sealed_module() -> None:
    b = _bank()
    b.set_leak(0, 1e-8)
    p = []
    for _ in range(500):
        b.step(0.01, CLOSED, CLOSED, np.zeros(1), PAR.supply_pa, any_open=False)
        p.append(b.pressure_pa[0])
    assert (np.diff(p) < 0).all() and p[-1] < 1000.0


def test_quiet_step_changes_nothing() -> None:
    b = _bank()
    assert not b.step(0.01, CLOSED, CLOSED, np.zeros(1), PAR.supply_pa, any_open=False)
