"""Sensor model: noise statistics, drift, quantisation, range, determinism."""

from __future__ import annotations

import numpy as np

from softpad.sim import SensorBank, SensorParams


def _reads(params: SensorParams, n: int = 20000, seed: int = 1, dt: float = 0.01) -> np.ndarray:
    bank = SensorBank(8, dt, params, np.random.default_rng(seed))
    return np.array([bank.sample(np.full(8, 1100.0), 10e3)[0] for _ in range(n)])


def test_white_noise_and_quantisation() -> None:
    p = SensorParams(noise_std_pa=8.0, drift_std_pa=0.0, offset_std_pa=0.0)
    x = _reads(p)
    np.testing.assert_allclose(
        x.std(axis=0), np.hypot(8.0, p.quantization_pa / np.sqrt(12)), rtol=0.05
    )
    np.testing.assert_allclose(x / p.quantization_pa, np.round(x / p.quantization_pa), atol=1e-9)


def test_drift_is_slow_with_its_stationary_std() -> None:
    p = SensorParams(
        noise_std_pa=0.0, drift_std_pa=3.0, drift_time_s=0.5, quantization_pa=0.0, offset_std_pa=0.0
    )
    x = _reads(p, n=50000)
    np.testing.assert_allclose(x.std(axis=0).mean(), 3.0, rtol=0.1)
    lag1 = np.mean([np.corrcoef(x[:-1, k], x[1:, k])[0, 1] for k in range(8)])
    np.testing.assert_allclose(lag1, np.exp(-0.01 / 0.5), atol=0.01)


def test_offset_drawn_once_per_seed_and_deterministic() -> None:
    a, b = _reads(SensorParams(), n=100, seed=5), _reads(SensorParams(), n=100, seed=5)
    np.testing.assert_array_equal(a, b)


def test_range_saturates_and_ideal_is_exact() -> None:
    bank = SensorBank(2, 0.01, SensorParams(), np.random.default_rng(0))
    assert bank.sample(np.array([50e3, -50e3]), 0.0)[0].tolist() == [10e3, -2e3]
    ideal = SensorBank(2, 0.01, SensorParams.ideal(), np.random.default_rng(0))
    np.testing.assert_array_equal(ideal.sample(np.array([1234.5, 0.1]), 7.0)[0], [1234.5, 0.1])


def test_refill_between_samples_draws_the_same_readings() -> None:
    """Drawing the next noise block ahead (refill_if_due, what a box daemon does between
    ticks) gives bitwise the same readings as drawing it on demand, over changing, static and
    ramping true pressures and 8 seeds; it draws only when the block is used up."""
    params = SensorParams()
    path = np.linspace(0.0, 900.0, 40)[:, None] * np.ones(3)
    for seed in range(8):
        banks = [
            SensorBank(3, 1e-3, params, np.random.default_rng(seed), block=16) for _ in range(2)
        ]
        out: list[list[float]] = [[], []]
        refills = 0
        for k in range(200):
            phase = (k // 25) % 3  # changing, then static, then along a ramp, repeated
            for b, bank in enumerate(banks):
                if phase == 0:
                    r, sup = bank.sample(np.full(3, 100.0 + k), 5000.0, changed=True)
                elif phase == 1:
                    r, sup = bank.sample(np.full(3, 300.0), 5000.0, changed=False)
                else:
                    r, sup = bank.sample_path(path, k % 25, key=k // 25, supply_pa=5000.0)
                out[b].extend([*r.tolist(), sup])
            refills += banks[1].refill_if_due()
        assert out[0] == out[1]
        assert refills == 200 // 16  # once per used-up block, never a block early


def test_a_still_box_reads_as_each_sample_alone() -> None:
    """An unchanged box's readings, computed several samples at a time (32, then twice as many
    each time, to the block's end), are each sample's own: the true pressures plus that
    sample's noise row, quantised and clipped, bit for bit, with the row's lowest and highest
    (as numbers) for the guard; over still periods of 1 to 400 samples, across blocks."""
    rng = np.random.default_rng(7)
    bank = SensorBank(8, 0.01, SensorParams(), np.random.default_rng(3), block=300)
    true = np.full(8, 1100.0)
    computed = still = 0
    for _ in range(60):
        if rng.random() < 0.5:  # a change: a new true pressure, then a still period
            true = rng.normal(1100.0, 300.0, 8)
            bank.sample(true, 1e4, changed=True)
        for _ in range(int(rng.choice([1, 3, 30, 33, 100, 400]))):
            noise_row = bank._noise[bank._i if bank._i < bank.block else 0].copy()
            reading, _ = bank.sample(true, 1e4, changed=False)
            if bank._i == 1:  # a new block was drawn for this sample: its first row
                noise_row = bank._noise[0].copy()
            want = bank._quantise(true + noise_row)
            assert reading.tobytes() == want.tobytes()
            still += 1
            if bank.span is not None:
                computed += 1
                assert bank.span[0] is reading
                assert (bank.span[1], bank.span[2]) == (want.min(), want.max())
    assert computed > 0.8 * still  # most still samples from the rows computed ahead
    assert bank._static is None or bank._static.shape[0] <= bank.block
