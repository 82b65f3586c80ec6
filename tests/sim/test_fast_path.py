"""The simulator's fast paths reproduce the reference implementation of the same physics.

The sim box skips work on its hot paths (steps along a stretch applied lazily, readings
precomputed along the stretch, drift filtered by lfilter, rint/min/max quantisation). These tests pin
the results against straightforward implementations written here:

* the whole box, ideal sensors, against an independent integrator of the documented scheme
  (exact exponential relaxation along the secant through the open orifices' equilibrium,
  restarted with an exact solve at least every 20 ms, the solves done by brentq per
  channel): within 1e-3 Pa (the box's Newton tolerance is 1e-4 Pa);
* the box read without ever touching its gas state (fully lazy) against the same box whose
  true pressures are read every step (eager): identical noisy readings, true pressures within
  1e-8 Pa (the lazy path adds k steps as one product);
* the sensor's drift and quantisation against the plain recursion and np.round/np.clip:
  bitwise equal.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from softpad.box import SimBox, open_box, simulator_of
from softpad.sim import AnalyticCharacteristic, PneumaticParams, SensorParams
from softpad.sim._sensor import SensorBank

#: valve scripts: frame index -> commands of the 6 modules (the 2 spare channels stay closed)
SCRIPT = {
    0: ["inflate"] * 3 + ["deflate"] * 2 + ["closed"],
    700: ["closed", "inflate", "deflate", "inflate", "closed", "deflate"],
    1400: ["closed"] * 6,
    1700: ["deflate"] * 6,
}


def _reference_trajectory(
    rate_hz: float, frames: int, p0_pa: float, script: dict[int, list[str]]
) -> np.ndarray:
    """The documented gas scheme, written out channel by channel (no object, no leak):
    stretches of 20 ms, each starting with an exact solve (brentq), the equilibrium of the
    open orifices found by brentq, exact exponential relaxation along the secant through it."""
    char, par = AnalyticCharacteristic(), PneumaticParams()
    patm, vt, rt = par.atmosphere_pa, par.tubing_volume_m3, par.gas_constant_rt
    k = rt * math.sqrt(2 * par.air_density_kg_m3)
    dt = 1.0 / rate_hz
    steps = max(1, round(20e-3 / dt))

    def volume(p: float) -> float:
        return float(char.volume_m3(np.array([p]), np.array([0.0]))[0])

    def dn_dp(p: float) -> float:
        dv = float(char.volume_slope_m3_pa(np.array([p]), np.array([0.0]))[0])
        return volume(p) + vt + (patm + p) * dv

    def orifice(area: float, dp: float) -> float:
        return k * area * dp / math.sqrt(abs(dp) + par.laminar_pa)

    def flow(cmd: str, p: float) -> float:
        if cmd == "inflate":
            return orifice(par.inflate_orifice_m2, par.supply_pa - p)
        if cmd == "deflate":
            return -orifice(par.deflate_orifice_m2, p)
        return 0.0

    def solve(n: float) -> float:
        return brentq(lambda p: (patm + p) * (volume(p) + vt) - n, -5e3, 2e4, xtol=1e-9)

    p = np.full(6, p0_pa)
    n = np.array([(patm + x) * (volume(x) + vt) for x in p])
    start = np.zeros((6, 4))  # p0, n0, C, p_eq of each channel's stretch
    lam = np.zeros(6)
    j = 0  # steps taken along the current stretch (0: none running)
    cmds: list[str] = ["closed"] * 6
    out = np.empty((frames, 6))
    for i in range(frames):
        changed = i in script
        if changed:
            cmds = script[i]
        sealed = all(c == "closed" for c in cmds)
        if j and not changed and not sealed and j < steps:  # along the stretch
            j += 1
        elif sealed and not j:
            out[i] = p  # sealed and unloaded: nothing moves
            continue
        else:  # a new stretch (or the end of the last one, when sealed): exact solve
            for c in range(6):
                if j:
                    p0, n0, cap, p_eq = start[c]
                    n[c] = n0 + cap * (p[c] - p0)
                    p[c] = solve(n[c])
                    if (p[c] - p_eq) * (p0 - p_eq) < 0:
                        p[c] = p_eq
                        n[c] = (patm + p_eq) * (volume(p_eq) + vt)
                if cmds[c] == "inflate":
                    p_eq = par.supply_pa
                elif cmds[c] == "deflate":
                    p_eq = 0.0
                else:
                    p_eq = p[c]
                d = p[c] - p_eq
                lam[c] = -flow(cmds[c], p[c]) / d / dn_dp(p[c]) if d else 0.0
                start[c] = p[c], n[c], dn_dp(p[c]), p_eq
            j = 0 if sealed else 1
        if j:
            p = start[:, 3] + (start[:, 0] - start[:, 3]) * np.exp(-lam * j * dt)
        out[i] = p
    return out


@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
def test_ideal_box_matches_the_reference_integrator(rate_hz: float) -> None:
    frames = int(2.0 * rate_hz) + 10
    scaled = {round(k * rate_hz / 1000.0): v for k, v in SCRIPT.items()}
    ref = _reference_trajectory(rate_hz, frames, 500.0, scaled)
    with SimBox(
        sample_rate_hz=rate_hz,
        sensor=SensorParams.ideal(),
        characteristic=AnalyticCharacteristic(),
        initial_pressure_pa=500.0,
    ) as box:
        got = np.empty((frames, 6))
        for i in range(frames):
            if i in scaled:
                box.set_valves([*scaled[i], "closed", "closed"])
            got[i] = box.read().pressures_pa[:6]
    assert np.ptp(ref, axis=0).min() > 100.0  # every channel really moved
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-3)


@pytest.mark.parametrize(
    "url",
    [
        "sim://?rate_hz=1000&inflated_kpa=0.5&seed=3",
        "sim://?rate_hz=100&seed=4",
        "sim://?rate_hz=1000&inflated_kpa=1.1&object=toy&faults=leak:2:0.02&seed=5",
    ],
    ids=["1kHz-open", "100Hz-from-empty", "1kHz-object-leak"],
)
def test_lazy_gas_state_gives_the_eager_results(url: str) -> None:
    def run(eager: bool) -> tuple[np.ndarray, np.ndarray]:
        with open_box(url) as box:
            assert simulator_of(box) is not None
            reads, trues = [], []
            for i in range(2500):
                if i in SCRIPT:
                    box.set_valves([*SCRIPT[i], "closed", "closed"])
                reads.append(box.read().pressures_pa)
                if eager or i % 97 == 0:
                    true = box.true_pressures_pa
                    if i % 97 == 0:
                        trues.append(true)
            return np.array(reads), np.array(trues)

    lazy_reads, lazy_true = run(eager=False)
    eager_reads, eager_true = run(eager=True)
    np.testing.assert_array_equal(lazy_reads, eager_reads)
    np.testing.assert_allclose(lazy_true, eager_true, rtol=0, atol=1e-8)


def test_drift_filter_equals_the_plain_recursion() -> None:
    params = SensorParams()
    bank = SensorBank(8, 1e-3, params, np.random.default_rng(11), block=512)
    d0 = bank._drift.copy()
    state = bank.rng.bit_generator.state
    bank._refill()
    rng = np.random.default_rng()
    rng.bit_generator.state = state
    noise = rng.normal(0.0, params.noise_std_pa, (512, 8))
    innov = rng.normal(0.0, bank._drift_innov, (512, 8))
    d = d0
    for k in range(512):
        d = bank._a * d + innov[k]
        innov[k] = d
    np.testing.assert_array_equal(bank._noise, noise + innov + bank.offset_pa)
    np.testing.assert_array_equal(bank._drift, d)


def test_drift_without_scipy_is_lfilter_to_the_last_bit() -> None:
    """The plain-float recursion (a box whose noise block lasts 10 s or more: no scipy.signal
    import) and lfilter give the same drift, bit for bit, over blocks and from any start."""
    from scipy.signal import lfilter

    from softpad.sim._sensor import drift_recursion

    rng = np.random.default_rng(5)
    for a in (SensorBank(8, 1e-2, SensorParams(), rng)._a, 0.5, 1.0 - 1e-9):
        d0 = rng.normal(0.0, 3.0, 8)
        innov = rng.normal(0.0, 0.1, (4096, 8))
        expected = lfilter([1.0], [1.0, -a], innov, axis=0, zi=(a * d0)[None, :])[0]
        np.testing.assert_array_equal(drift_recursion(innov, d0, a), expected)
    # a 100 Hz bank and a 1 kHz bank: each path, the plain recursion's readings
    for dt in (1e-2, 1e-3):
        bank = SensorBank(8, dt, SensorParams(), np.random.default_rng(11), block=4096)
        assert bank._lfilter is (dt == 1e-3)
        d0, state = bank._drift.copy(), bank.rng.bit_generator.state
        bank._refill()
        ref = np.random.default_rng()
        ref.bit_generator.state = state
        noise = ref.normal(0.0, bank.params.noise_std_pa, (4096, 8))
        innov = ref.normal(0.0, bank._drift_innov, (4096, 8))
        d = d0
        for k in range(4096):
            d = bank._a * d + innov[k]
            innov[k] = d
        np.testing.assert_array_equal(bank._noise, noise + innov + bank.offset_pa)


def test_quantisation_equals_round_and_clip() -> None:
    params = SensorParams()
    bank = SensorBank(4, 1e-3, params, np.random.default_rng(0))
    x = np.random.default_rng(1).uniform(-3e3, 11e3, (1000, 4))
    x[0, 0] = np.nan
    x[1, :] = np.array([0.5, 1.5, -0.5, 2.5]) * params.quantization_pa  # ties: half to even
    q = params.quantization_pa
    expected = np.clip(np.round(x * (1.0 / q)) * q, params.range_min_pa, params.range_max_pa)
    np.testing.assert_array_equal(bank._quantise(x.copy()), expected)
    assert np.isnan(bank._quantise(x.copy())[0, 0])


def test_a_collapsed_module_fills_without_a_spike() -> None:
    """With the disturbances' creep an empty module rests a little below ambient, where the
    layer's volume no longer changes with pressure; opening its inflation valve then jumped
    the true pressure to 606 Pa for one 10 ms step and back (a linearised step from the flat
    side of the characteristic), and the controller named the channel faulty at 0.22 s. Now
    every step of the fill is within 1 Pa of the same fill from exactly ambient."""
    from softpad.box import open_box, simulator_of

    fills = []
    for disturbances in (0, 1):
        box = open_box(f"sim://?seed=3&disturbances={disturbances}")
        sim = simulator_of(box)
        box.read_many(10)
        box.set_valves(["inflate"] * box.channels)
        fill = []
        for _ in range(50):
            box.read()
            fill.append(float(sim.true_pressures_pa[0]))
        fills.append(np.array(fill))
        box.close()
    assert np.all(np.diff(fills[1]) > 0)
    np.testing.assert_allclose(fills[1], fills[0], atol=1.0)
