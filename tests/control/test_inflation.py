"""Inflation and adjustment (Section 6.2.1.1), reference capture, and every fault."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softpad.box import ConnectionLost, Fault, SimBox, ValveCommand, compose_sim_box, open_box
from softpad.control import InflationParams, inflate_and_adjust
from softpad.errors import HardwareFault, InputError

N = 6


def _adjust(box: SimBox, params: InflationParams | None = None):
    frames = []
    result = inflate_and_adjust(box, N, params, on_frame=frames.append)
    return result, frames


def test_adjusts_every_module_within_tolerance_and_never_above_max() -> None:
    box = open_box("sim://?seed=2")
    res, frames = _adjust(box)
    p = np.array([f.pressures_pa[:N] for f in frames])
    assert p.max() < 3000.0
    np.testing.assert_allclose(res.reference_pa, 1100.0, atol=30.0)
    # reference = mean of the last 10 reads, taken with every valve closed
    np.testing.assert_allclose(res.reference_pa, p[-10:].mean(axis=0), rtol=1e-12)
    assert set(box.valves) == {ValveCommand.CLOSED}
    # the true pressures differ from the readings by the sensors' zero offsets (20 Pa rms)
    np.testing.assert_allclose(
        box.true_pressures_pa[:N] + box.sensors.offset_pa[:N], 1100.0, atol=30.0
    )


@pytest.mark.parametrize("target_kpa", [0.6, 1.1, 2.5], ids=["0.6", "1.1", "2.5"])
def test_adjusts_to_other_targets_from_above_and_below(target_kpa: float) -> None:
    box = SimBox(seed=1, initial_pressure_pa=1800.0)
    res, _ = _adjust(box, InflationParams(target_pa=target_kpa * 1e3))
    np.testing.assert_allclose(res.reference_pa, target_kpa * 1e3, atol=30.0)


def _assert_safe(box: SimBox) -> None:
    """Inflation valves closed (deflation only where venting) and no module above the max."""
    assert all(v is not ValveCommand.INFLATE for v in box.valves)
    assert box.true_pressures_pa[:N].max() <= 3000.0


@pytest.mark.parametrize(
    ("fault", "match"),
    [
        (Fault("leak", 3, 0.0, 1e-8), "channel 3"),
        (Fault("stuck", 4, 0.0, "closed"), "channel 4"),
        (Fault("stuck", 2, 0.0, "inflate"), "channel 2"),
        (Fault("stuck", 5, 0.0, "deflate"), "channel 5"),
        (Fault("supply_loss", None, 1.0), "supply pressure"),
        (Fault("nan", 6, 1.0), "channel 6.*NaN"),
        (Fault("dropout", 1, 1.0), "channel 1.*dropout"),
    ],
    ids=[
        "leak",
        "stuck-closed",
        "stuck-inflate",
        "stuck-deflate",
        "supply-loss",
        "sensor-nan",
        "sensor-dropout",
    ],
)
def test_fault_raises_naming_the_cause_and_leaves_the_box_safe(fault: Fault, match: str) -> None:
    box = compose_sim_box(SimBox(seed=3))  # sensor faults are layers around the plain box
    box.inject_fault(fault)
    frames: list = []
    with pytest.raises(HardwareFault, match=match):
        inflate_and_adjust(box, N, InflationParams(timeout_s=20.0), on_frame=frames.append)
    _assert_safe(box)
    assert len(frames) > 50  # everything read before the fault was handed to the logger


def test_the_leak_check_sits_six_sigma_above_the_sensor_noise() -> None:
    """The drift over the settle time is judged from two 10-sample means of the box sensor's
    white noise: its standard deviation is sqrt(2) x 8 Pa / sqrt(10) / 0.5 s = 7.2 Pa/s. At
    25 Pa/s (3.5 sigma, and time stamps add a little) one simulated adjustment in a hundred
    named a sound channel as leaking; the threshold keeps 6 sigma."""
    from softpad.sim import SensorParams

    params = InflationParams()
    sigma = math.sqrt(2) * SensorParams().noise_std_pa / math.sqrt(params.filter_length)
    assert params.max_drift_pa_s >= 6 * sigma / params.settle_s


def test_small_leak_after_adjustment_is_caught_by_the_drift_check() -> None:
    box = SimBox(seed=3, initial_pressure_pa=1100.0)
    box.inject_fault(Fault("leak", 2, 0.0, 8e-9))
    with pytest.raises(HardwareFault, match="channel 2"):
        inflate_and_adjust(box, N)
    _assert_safe(box)


def test_lost_connection_raises_connection_lost() -> None:
    box = compose_sim_box(SimBox(seed=1))
    box.inject_fault(Fault("disconnect", None, 0.5))
    with pytest.raises(ConnectionLost, match="stopped answering"):
        inflate_and_adjust(box, N)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"target_pa": float("nan")}, "target_pa"),
        ({"tolerance_pa": -1.0}, "tolerance_pa"),
        ({"target_pa": 2990.0}, "usable range"),
        ({"target_pa": 1.1}, "usable range 0.5..2.8 kPa, got 1.1 Pa"),
        ({"target_pa": 2800.0, "max_pressure_pa": 2800.0}, "below the maximum"),
        ({"max_pressure_pa": 1e6, "target_pa": 2000.0}, "full scale 10 kPa"),
        ({"reference_reads": 0}, "reference reads"),
    ],
    ids=["nan", "negative", "too-high", "kpa-as-pa", "over-own-max", "max-1e6", "reads"],
)
def test_bad_parameters(kwargs, match) -> None:
    with pytest.raises(InputError, match=match):
        InflationParams(**kwargs)


@pytest.mark.parametrize(
    "text",
    ["leak:2", "leak:2:0.01@3", "stuck:3:inflate@1.5", "supply_loss@5", "disconnect", "nan:1@0"],
)
def test_fault_url_syntax(text: str) -> None:
    f = Fault.parse(text)
    assert f.kind == text.split(":")[0].split("@")[0]


@pytest.mark.parametrize("text", ["stuck:x", "leak:2:big", "supply_loss:3", "stuck:2:open"])
def test_bad_fault_syntax(text: str) -> None:
    with pytest.raises(InputError):
        Fault.parse(text)


def test_controller_steps_through_its_states_frame_by_frame() -> None:
    from softpad.control import InflationController

    box = SimBox(seed=3)
    ctl = InflationController(N)
    states = ["adjust"]
    while ctl.result is None:
        for ch, cmd in ctl.step(box.read()):
            box.set_valve(ch, cmd)
        if ctl.state != states[-1]:
            states.append(ctl.state)
    assert states[-3:] == ["settle", "reference", "done"]
    assert ctl.result.reference_at_s > ctl.result.adjusted_at_s
    assert set(box.valves) == {ValveCommand.CLOSED}
    assert ctl.step(box.read()) == []  # done: no more commands


@pytest.mark.parametrize(
    ("fault", "start_s"),
    [("stuck:3:inflate", 2.5), ("leak:3:0.3", 2.5), ("stuck:3:deflate", 0.3)],
    ids=["stuck-inflate-filling", "leak-filling", "stuck-deflate-at-p0"],
)
@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
def test_valve_fault_during_the_adjustment_is_named_within_2_s(
    fault: str, start_s: float, rate_hz: float
) -> None:
    """Before: only at the 30 s timeout, as adjust_failed (issue 35 item 8). (A deflation
    valve sticking open while a module fills from empty: the next test.)"""
    start = "&inflated_kpa=1.1" if "deflate" in fault else ""
    box = open_box(f"sim://?seed=2&rate_hz={rate_hz:g}{start}&faults={fault}@{start_s}")
    frames: list = []
    with pytest.raises(HardwareFault, match="channel 3") as info:
        inflate_and_adjust(box, N, on_frame=frames.append, safe_state=False)
    assert frames[-1].t_s - start_s <= 2.0, str(info.value)
    assert box.true_pressures_pa.max() <= 3000.0


@pytest.mark.parametrize("start_s", [1.5, 2.5])
@pytest.mark.parametrize("rate_hz", [100.0, 1000.0], ids=["100Hz", "1kHz"])
def test_a_deflation_valve_stuck_open_while_filling_is_named_within_2_s(
    start_s: float, rate_hz: float
) -> None:
    """A deflation valve sticking open while the modules fill from empty only slows its
    module's fill (to 0.73 of it at 200 Pa, 0.53 at 600 Pa): no response window finds it.
    Compared with the rate the other channels filled at at the same pressure
    (:class:`~softpad.control.FillRates`) it is named within 1 s on 3 seeds; before, only
    once the module reached p0 and was sealed (issue 35: 4.7-7.2 s)."""
    for seed in range(3):
        fault = f"stuck:3:deflate@{start_s}"
        box = open_box(f"sim://?seed={seed}&rate_hz={rate_hz:g}&faults={fault}")
        frames: list = []
        with pytest.raises(HardwareFault, match="channel 3: fills at") as info:
            inflate_and_adjust(box, N, on_frame=frames.append, safe_state=False)
        assert frames[-1].t_s - start_s <= 1.0, str(info.value)
        assert info.value.fault.cause == "no_response"  # type: ignore[attr-defined]


def test_a_noisier_sensor_is_not_named_faulty() -> None:
    """A sound box whose sensor is twice as noisy as the nominal one (16 Pa: the top of the
    sourced range, softpad.sim.UNCERTAIN_PARAMETERS' sensor_noise_scale) adjusts without a
    fault on 30 of 30 seeds at 100 Hz. Before the thresholds followed the measured noise, the
    3-sample sealed-drift checks named sound channels ("loses pressure with its valves
    closed"): 7 of 100 randomized YCB evaluation trials (seeds 5001-5010) ended so."""
    from softpad.sim import LabVariation

    sensor = LabVariation.of({"sensor_noise_scale": 2.0}).sensor()
    faults = []
    for seed in range(30):
        box = SimBox(seed=seed, sensor=sensor)
        try:
            inflate_and_adjust(box, N, safe_state=False)
        except HardwareFault as exc:
            faults.append((seed, str(exc)))
    assert faults == []


def _settle_with_drift(noise_pa: float, drift_pa_s: float) -> object:
    """Step a controller with frames already at p0: channel 3 starts 15 Pa above it and
    drifts ``drift_pa_s``; every channel carries noise alternating +-a, whose 10-sample
    means are exactly 0 and whose measured white-noise sigma (SampleNoise) is ``noise_pa``.
    Returns the result, or the fault raised."""
    from softpad.box import PressureFrame
    from softpad.control import InflationController

    a = noise_pa * math.sqrt(2) / (2 * 1.4826)  # |difference| 2a: sigma 1.4826 x 2a / sqrt 2
    ctl = InflationController(N)
    for k in range(300):
        t = k / 100.0
        p = np.full(8, 1100.0) + (a if k % 2 else -a)
        p[2] += 15.0 + drift_pa_s * t
        try:
            ctl.step(PressureFrame(t, p, 10e3))
        except HardwareFault as exc:
            return exc
        if ctl.result is not None:
            return ctl.result
    raise AssertionError("the adjustment neither settled nor raised in 3 s")


def test_the_settle_leak_limit_follows_the_measured_noise() -> None:
    """A channel losing 60 Pa/s over the settle time: a leak on the nominal sensor (8 Pa:
    over the 50 Pa/s limit), but within a box twice as noisy, whose drift is judged against
    twice the limit (100 Pa/s) like the other sealed-drift checks. Before the settle check
    followed the measured noise, 5 of 1200 adjustments of a sound box at twice the noise
    (50-200 Hz, from 1 kPa) named a channel "loses ... kPa/s", and so did 3 of about 2000
    randomized development trials, all at noise scales of 1.96-1.99
    (docs/box-and-simulator.md)."""
    nominal = _settle_with_drift(8.0, -60.0)
    assert isinstance(nominal, HardwareFault)
    assert "channel 3: loses 0.060 kPa/s" in str(nominal) and "limit 0.050" in str(nominal)
    noisy = _settle_with_drift(16.0, -60.0)
    assert not isinstance(noisy, HardwareFault), str(noisy)
    fast = _settle_with_drift(16.0, -150.0)  # a fast leak is named on the noisy box too
    assert isinstance(fast, HardwareFault) and "channel 3" in str(fast)


def test_the_controller_measures_the_sensor_noise() -> None:
    """SampleNoise on sealed readings of white noise: sigma within 10 % at 8, 16 and 4 Pa
    (4000 differences; the median's relative error is about 2 %), nominal until enough."""
    from softpad.control import SampleNoise

    rng = np.random.default_rng(7)
    for sigma in (8.0, 16.0, 4.0):
        est = SampleNoise(size=4000)
        assert est.sigma_pa == 8.0 and est.scale() == 1.0
        for _ in range(4001):
            est.update(1100.0 + rng.normal(0.0, sigma, 6), np.ones(6, dtype=bool))
        assert est.sigma_pa == pytest.approx(sigma, rel=0.1)
        assert est.scale() == pytest.approx(max(1.0, sigma / 8.0), rel=0.1)


class _LateFrames:
    """A box whose first frames reach the controller 0.5 s (50 frames) after they were
    sampled, the lag then draining by a frame a read (a busy link or daemon in its first
    seconds: the arm node's served simulator on a loaded machine, docs/ros.md), while its
    valves act at once. ``seen_after`` False hides the box's report of when a command took
    effect (the old link)."""

    def __new__(cls, inner: SimBox, seen_after: bool, lag: int = 50, hold: int = 60):  # type: ignore[misc]
        from collections import deque

        from softpad.box import BoxWrapper

        class Late(BoxWrapper):
            def __init__(self) -> None:
                super().__init__(inner)
                self.queue: deque = deque()
                self.reads = 0

            def _read(self):
                self.reads += 1
                now_lag = lag if self.reads < hold else max(0, lag - (self.reads - hold))
                while len(self.queue) <= now_lag:
                    self.queue.append(self.inner.read())
                return self.queue.popleft()

            @property
            def command_seen_after_s(self):
                return self.queue[-1].t_s if seen_after and self.queue else None

        return Late()


@pytest.mark.parametrize("seen_after", [True, False], ids=["reported", "unreported"])
def test_frames_on_their_way_are_not_the_commands_effect(seen_after: bool) -> None:
    """The first frames 0.5 s late (50 at 100 Hz): with the box's report of when each command
    took effect, 10 of 10 sound boxes adjust; without it, the 0.75 s no-response window sees
    0.25 s of an empty module's slowest rise and names sound channels ('does not rise while
    inflating'), as runs on the arm node's served simulator did under load."""
    faults = []
    for seed in range(10):
        box = _LateFrames(SimBox(seed=seed), seen_after)
        try:
            inflate_and_adjust(box, N, safe_state=False)
        except HardwareFault as exc:
            faults.append(str(exc))
    if seen_after:
        assert faults == []
    else:
        assert len(faults) >= 5 and all("does not rise while inflating" in f for f in faults)


@pytest.mark.parametrize("n", [2, 3, 6, 8, 9])
def test_median_of_the_other_channels_is_numpys_bit_for_bit(n: int) -> None:
    """The fill check's expected rate: np.median of the other channels' finite rates, the
    same bits on plain floats (NaN and inf rates left out; fewer than two: NaN)."""
    from softpad.control._inflation import _median_of_others

    rng = np.random.default_rng(n)
    for _ in range(200):
        col = rng.normal(300.0, 80.0, n)
        col[rng.random(n) < 0.3] = np.nan
        col[rng.random(n) < 0.05] = np.inf
        for i in range(n):
            others = np.delete(col, i)
            others = others[np.isfinite(others)]
            want = float(np.median(others)) if others.size >= 2 else math.nan
            got = _median_of_others(col.tolist(), i)
            assert (math.isnan(want) and math.isnan(got)) or got == want
