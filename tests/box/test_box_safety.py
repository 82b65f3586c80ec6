"""Box-side safety: hard maximum per channel under every back-end, refused inflation, venting."""

from __future__ import annotations

import contextlib

import numpy as np
import pytest

from softpad.box import SafetyGuard, SafetyLimits, SafetyTrip, open_box, simulator_of
from softpad.errors import HardwareFault, InputError

MAX = 3000.0
#: True pressure may exceed the trip level by the sensor's offset (3 x 20 Pa rms), its noise
#: (3 x 8 Pa) and one frame of rise (530 Pa/s at 100 Hz): the stated margin over the maximum.
MARGIN_PA = 100.0


def _hold_inflate(box, channel: int, frames: int, true=None) -> float:
    box.set_valve(channel, "inflate")
    peak = 0.0
    for _ in range(frames):
        box.read()
        if true is not None:
            peak = max(peak, float(true()[channel - 1]))
    return peak


@pytest.mark.parametrize("seed", range(5), ids=lambda s: f"seed{s}")
def test_sim_client_holding_inflate_never_exceeds_max(seed: int) -> None:
    with open_box(f"sim://?seed={seed}&rate_hz=50") as box:
        assert simulator_of(box) is not None
        peak = _hold_inflate(box, 3, 50 * 40, lambda: box.true_pressures_pa)
        assert peak <= MAX + MARGIN_PA
        assert peak > MAX - 300  # it did go up to the trip, so the check is not vacuous
        assert box.safety.trips and box.safety.trips[0][1] == 3


def test_stuck_inflate_valve_is_held_below_max_by_venting() -> None:
    with open_box("sim://?faults=stuck:3:inflate&noise=0") as box:
        box.close_valves()  # the client thinks it is closed; the valve is stuck open
        peak = 0.0
        for _ in range(100 * 60):
            box.read()
            peak = max(peak, box.true_pressures_pa[2])
        assert peak <= MAX + MARGIN_PA
        # the deflation path outflows the stuck inflation: settles at supply / (1 + (3/1.6)^2)
        np.testing.assert_allclose(
            box.true_pressures_pa[2], 10e3 / (1 + (3.0 / 1.6) ** 2), rtol=0.05
        )


def test_inflate_refused_while_tripped_then_allowed_below_release() -> None:
    with open_box("sim://?noise=0&rate_hz=50") as box:
        box.set_valve(2, "inflate")
        while not box.safety.tripped[1]:
            box.read()
        with pytest.raises(SafetyTrip, match="channel 2: inflate refused"):
            box.set_valve(2, "inflate")
        box.set_valve(2, "closed")  # a tripped channel keeps venting
        assert box.valves[1].value == "deflate"
        while box.safety.tripped[1]:
            box.read()
        assert box.true_pressures_pa[1] < 2500.0 + 50
        box.set_valve(2, "inflate")  # released: allowed again


@pytest.mark.parametrize("fault", ["nan:4", "dropout:4"])
def test_invalid_reading_vents_and_refuses_inflate(fault: str) -> None:
    with open_box(f"sim://?faults={fault}@0.05") as box:
        box.set_valve(4, "inflate")
        box.read_many(10)
        assert box.valves[3].value == "deflate"
        with pytest.raises(SafetyTrip):
            box.set_valve(4, "inflate")


def test_zenoh_client_holding_inflate_never_exceeds_max(served) -> None:
    """Only the served box's guard protects the module: the client's own guard is relaxed."""
    with served("sim://?seed=2&rate_hz=50") as (daemon, url):
        inner = daemon.box
        assert simulator_of(inner) is not None
        with open_box(url) as box:
            box.safety_limits = SafetyLimits(max_pressure_pa=9000.0, release_pa=8000.0)
            with contextlib.suppress(HardwareFault):  # refused once the served box trips
                _hold_inflate(box, 1, 50 * 10)
            assert inner.safety.trips and inner.safety.trips[0][1] == 1
            assert float(inner.true_pressures_pa[0]) <= MAX + MARGIN_PA


def test_guard_trips_on_fast_rise_before_the_level() -> None:
    guard = SafetyGuard(2, SafetyLimits())
    assert guard.check(0.0, np.array([2500.0, 0.0])) == []
    # rising 400 Pa per frame: 2900 + 400 expected next frame is over the 2950 trip level
    assert guard.check(1.0, np.array([2900.0, 0.0])) == [1]
    # the cause names the rise: the reading itself is under the level
    assert guard.trips[-1][2] == (
        "2.900 kPa rising 0.400 kPa a frame: the trip level 2.950 kPa within a frame"
    )
    assert guard.check(2.0, np.array([2900.0, 3000.0])) == [2]
    assert guard.trips[-1][2] == "3.000 kPa over the trip level 2.950 kPa"


@pytest.mark.parametrize(
    "kw",
    [
        {"max_pressure_pa": 1e6},
        {"max_pressure_pa": float("nan")},
        {"release_pa": 2990.0},
        {"trip_margin_pa": -1.0},
        {"rise_window": 1},
    ],
    ids=["max-1e6", "max-nan", "release-over-trip", "margin-negative", "window-1"],
)
def test_bad_limits_rejected(kw: dict) -> None:
    with pytest.raises(InputError):
        SafetyLimits(**kw)


@pytest.mark.parametrize(
    "url", ["sim://?faults=leak:3:-1", "sim://?faults=leak:3:0", "sim://?faults=leak:3:nan"]
)
def test_bad_leak_rejected(url: str) -> None:
    with pytest.raises(InputError, match="leak area"):
        open_box(url)


def _reference_trips(
    limits: SafetyLimits, frames: list[tuple[float, np.ndarray]]
) -> list[tuple[list[int], list[bool]]]:
    """The guard's rule applied channel by channel to every frame, independently of its hot
    paths: (channels newly tripped, tripped states) after each frame."""
    window: list[tuple[float, list[float]]] = []
    tripped = [False] * len(frames[0][1])
    out = []
    for t, p in frames:
        if window and t == window[-1][0]:
            out.append(([], list(tripped)))  # the same frame seen again
            continue
        window = [*window, (t, p.tolist())][-limits.rise_window :]
        n, first = len(window), window[0][1]
        per_frame = 1.0 / (n - 1) if n >= 2 and window[-1][0] > window[0][0] else 0.0
        new = []
        for k, v in enumerate(p.tolist()):
            invalid = not np.isfinite(v) or not limits.sensor_min_pa < v < limits.sensor_max_pa
            rise = (v - first[k]) * per_frame
            rise = rise if np.isfinite(rise) and rise > 0 else 0.0
            if tripped[k] and v < limits.release_pa and not invalid:
                tripped[k] = False
            if (invalid or v + rise > limits.trip_pa) and not tripped[k]:
                tripped[k] = True
                new.append(k + 1)
        out.append((new, list(tripped)))
    return out


def _random_frames(
    rng: np.random.Generator, channels: int, n: int
) -> list[tuple[float, np.ndarray]]:
    """Every channel up and down between 1.8 and 3.2 kPa (a triangle of its own period and
    phase: channels tripped, held above the release level, released and rising again while
    others are tripped), with sensor noise, now and then a NaN or a rail reading, a jump, or
    the same time stamp again."""
    period = rng.integers(60, 400, channels)
    phase = rng.integers(0, 400, channels)
    t, frames = 0.0, []
    for i in range(n):
        x = (i + phase) % period / period
        p = 1800.0 + 1400.0 * np.minimum(2 * x, 2 - 2 * x) + rng.normal(0.0, 8.0, channels)
        if rng.random() < 0.01:
            p[rng.integers(channels)] = rng.choice([np.nan, -2000.0, 10000.0, np.inf, 2960.0])
        if rng.random() > 0.03:  # else the same time stamp again
            t += 0.01
        frames.append((t, p))
    return frames


@pytest.mark.parametrize("seed", range(40))
def test_guard_hot_paths_decide_as_the_per_channel_rule(seed: int) -> None:
    """The guard's shortcuts (nothing can trip; tripped channels not yet released), with the
    readings' lowest and highest value found by the guard (check) or given (check_span), trip
    and release exactly the channels, on exactly the frames, that the rule checked channel by
    channel gives (fails if a shortcut skips a frame where something changes)."""
    rng = np.random.default_rng(seed)
    channels = int(rng.integers(1, 9))
    limits = SafetyLimits(rise_window=int(rng.integers(2, 12)))
    frames = _random_frames(rng, channels, 1500)
    guard, spans = SafetyGuard(channels, limits), SafetyGuard(channels, limits)
    expected = _reference_trips(limits, frames)
    changes = 0
    for (t, p), (new, tripped) in zip(frames, expected, strict=True):
        assert guard.check(t, p) == new, t
        assert guard.tripped.tolist() == tripped, t
        # the simulated box's way: lowest and highest reading given (NaN with a NaN)
        assert spans.check_span(t, p, float(np.min(p)), float(np.max(p))) == new, t
        assert spans.tripped.tolist() == tripped, t
        changes += len(new)
    assert spans.trips == guard.trips
    assert changes > 5  # the walks do trip channels: the test is not vacuous
