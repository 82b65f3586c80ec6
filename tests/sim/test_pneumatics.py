"""Gas physics of a channel: sealed chamber under load, valves, leaks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from softpad.sim import (
    AnalyticCharacteristic,
    ChamberBank,
    PneumaticParams,
    default_characteristic,
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


class _RigidVessel:
    """A chamber whose volume does not change (for the analytic decay)."""

    def __init__(self, volume_m3: float) -> None:
        self.v = volume_m3

    def volume_m3(self, p, f):
        return np.full(np.shape(p), self.v)

    def volume_slope_m3_pa(self, p, f):
        return np.zeros(np.shape(p))

    def height_m(self, p, f):
        return np.full(np.shape(p), 0.01)


def _orifice_decay_time_s(p0: float, p: float, c: float, laminar_pa: float) -> float:
    """Time for an isothermal ideal gas in a rigid vessel to fall from p0 to p through an
    orifice ``dp/dt = -c p / sqrt(p + p_lam)`` (c = R T sqrt(2 rho) Cd A / V): with
    ``u = sqrt(p + p_lam)``, ``a = sqrt(p_lam)``, ``t = (F(u0) - F(u)) / c`` where
    ``F(u) = 2 u + a ln((u - a) / (u + a))`` (and ``u - a = p / (u + a)``)."""
    a = math.sqrt(laminar_pa)

    def big_f(x: float) -> float:
        u = math.sqrt(x + laminar_pa)
        return 2 * u + a * (math.log(x) - 2 * math.log(u + a))

    return (big_f(p0) - big_f(x=p)) / c


def _sealed_leak(bank: ChamberBank, rate_hz: float, seconds: float, load_n: float) -> np.ndarray:
    out = []
    for _ in range(round(seconds * rate_hz)):
        bank.step(1 / rate_hz, CLOSED, CLOSED, np.array([load_n]), PAR.supply_pa, any_open=False)
        out.append(bank.pressure_pa[0])
    return np.array(out)


@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
@pytest.mark.parametrize("area_m2", [1e-8, 1e-7, 1e-6], ids=["0.01mm2", "0.1mm2", "1mm2"])
def test_rigid_vessel_leak_follows_the_analytic_orifice_decay(
    rate_hz: float, area_m2: float
) -> None:
    """Against the closed-form isothermal orifice decay, from mild (time constant ~ 0.1 s) to
    stiff (1 mm^2: ~ 0.1 ms, ten to a hundred times shorter than a sample period): within
    1.5 % of the initial pressure at every sample (the secant's error, bounded by
    ``relaxation_per_stretch`` = 0.1), never below the ambient, never rising (1e-6 Pa: rounding)."""
    volume, p0 = 2e-6, 1100.0
    bank = ChamberBank(1, 1, _RigidVessel(volume), PAR)
    bank.set_state(np.array([p0]))
    bank.set_leak(0, area_m2)
    got = _sealed_leak(bank, rate_hz, 1.0, 0.0)
    c = bank.orifice_gain * area_m2 / (volume + PAR.tubing_volume_m3)
    t = np.arange(1, got.size + 1) / rate_hz

    def exact(ti: float) -> float:
        f = lambda p: _orifice_decay_time_s(p0, p, c, PAR.laminar_pa) - ti  # noqa: E731
        return 0.0 if f(1e-300) < 0 else brentq(f, 1e-300, p0, xtol=1e-12)

    want = np.array([exact(ti) for ti in t])
    np.testing.assert_allclose(got, want, rtol=0, atol=0.015 * p0)
    assert got.min() >= 0.0 and np.diff(got).max() <= 1e-6


@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
@pytest.mark.parametrize("area_m2", [1e-8, 1e-6, 1e-5], ids=["0.01mm2", "1mm2", "10mm2"])
def test_loaded_sealed_module_with_a_leak_decays_monotonically_to_ambient(
    rate_hz: float, area_m2: float
) -> None:
    """The case that was unstable (object 5 on a module, 1 mm^2 leak: -75 to +12.7 kPa):
    a module of the FEM characteristic under 2 N decays without overshoot."""
    bank = ChamberBank(1, 1, default_characteristic())
    bank.set_state(np.array([1100.0]), np.array([2.0]))
    p_start = float(bank.pressure_pa[0])
    bank.set_leak(0, area_m2)
    got = _sealed_leak(bank, rate_hz, 20.0, 2.0)
    assert 0.0 <= got.min() and got.max() <= p_start
    assert np.diff(got).max() <= 1e-6
    if area_m2 >= 1e-6:
        assert got[-1] < 1.0


@pytest.mark.parametrize("area_m2", [1e-8, 1e-7, 1e-6], ids=["0.01mm2", "0.1mm2", "1mm2"])
def test_leak_decay_agrees_between_100_hz_and_1_khz(area_m2: float) -> None:
    """The same physics at both sample rates: at the common sample times within 1 % of the
    initial pressure (the secant's error, which the sub-steps bound at any rate)."""
    runs = []
    for rate in (100.0, 1000.0):
        bank = ChamberBank(1, 1, default_characteristic())
        bank.set_state(np.array([1100.0]), np.array([2.0]))
        bank.set_leak(0, area_m2)
        runs.append(_sealed_leak(bank, rate, 5.0, 2.0))
    slow, fast = runs
    np.testing.assert_allclose(slow, fast[9::10], rtol=0, atol=0.01 * 1100.0)


@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
def test_object_5_on_a_leaking_module_stays_within_ambient_and_supply(rate_hz: float) -> None:
    """The whole simulated box with object 5 resting and a 1 mm^2 leak on module 1: the true
    pressure of every channel stays within 0 .. supply and the leaking module reaches the
    ambient (loads move as the object settles, so a sealed neighbour may rise)."""
    from softpad.box import open_box

    url = f"sim://?rate_hz={rate_hz:g}&inflated_kpa=1.1&object=object-5&noise=0&faults=leak:1:1@1"
    with open_box(url) as box:
        true = []
        for _ in range(round(5.0 * rate_hz)):
            box.read()
            true.append(box.true_pressures_pa[:6].copy())  # type: ignore[attr-defined]
    true = np.array(true)
    assert true.min() >= 0.0 and true.max() <= PAR.supply_pa
    assert true[-1, 0] < 1.0


def test_equilibrium_of_both_valves_matches_an_independent_root() -> None:
    from softpad.sim._pneumatics import equilibrium_pa

    def g(x: float) -> float:
        return x / math.sqrt(abs(x) + PAR.laminar_pa)

    a_i, a_o = PAR.inflate_orifice_m2, PAR.deflate_orifice_m2 + 1e-8
    want = brentq(lambda p: a_i * g(PAR.supply_pa - p) - a_o * g(p), 0.0, PAR.supply_pa)
    got = equilibrium_pa(
        np.array([a_i, a_i, 0.0]), np.array([a_o, 0.0, a_o]), PAR.supply_pa, PAR.laminar_pa
    )
    np.testing.assert_allclose(got, [want, PAR.supply_pa, 0.0], rtol=0, atol=1e-5)
