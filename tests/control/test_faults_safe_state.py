"""Fault monitoring in every phase and the verified safe state (issue 17)."""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest

from softpad.box import PressureFrame, SimBox, ValveCommand, open_box
from softpad.cli.main import main
from softpad.control import FaultMonitor, FaultThresholds, reach_safe_state

MAX = 3000.0
#: Stated margin of the true pressure over the maximum: sensor offset (3 x 20 Pa rms), noise
#: (3 x 8 Pa) and one frame of the fastest rise (530 Pa/s at 100 Hz).
MARGIN_PA = 100.0
CLOSED = [ValveCommand.CLOSED] * 6


def _frame(t: float, p: list[float], supply: float = 10e3) -> PressureFrame:
    return PressureFrame(t, np.array(p, dtype=float), supply)


@pytest.mark.parametrize(
    ("value", "cause"),
    [
        (float("nan"), "sensor_nan"),
        (-2000.0, "sensor_dropout"),
        (10e3, "sensor_range"),
        (2960.0, "over_pressure"),
    ],
    ids=["nan", "dropout", "full-scale", "over"],
)
def test_monitor_flags_bad_readings_at_once(value: float, cause: str) -> None:
    mon = FaultMonitor(6)
    p = [1100.0] * 6
    p[2] = value
    f = mon.update(_frame(0.01, p), CLOSED)
    assert f is not None and f.channel == 3 and f.cause == cause


def test_monitor_quiet_on_noise_and_load_steps() -> None:
    """Thesis-like noise (8 Pa) and drift plus a 400 Pa load step must raise nothing."""
    rng = np.random.default_rng(0)
    mon = FaultMonitor(6)
    mon.set_reference(np.full(6, 1100.0))
    for i in range(6000):
        t = (i + 1) * 0.01
        load = 400.0 if 20 <= t < 40 else 0.0
        p = 1100.0 + load + rng.normal(0, 8.0, 6) + 3.0 * np.sin(t / 2)
        assert mon.update(_frame(t, list(p)), CLOSED) is None


@pytest.mark.parametrize(
    ("slope", "cause"), [(-200.0, "falling"), (300.0, "rising")], ids=["leak", "stuck-inflate"]
)
def test_monitor_flags_a_sealed_channel_changing_without_command(slope: float, cause: str) -> None:
    mon = FaultMonitor(6)
    mon.set_reference(np.full(6, 1100.0))
    for i in range(1000):
        t = (i + 1) * 0.01
        p = [1100.0] * 6
        p[4] += slope * max(0.0, t - 1.0)
        f = mon.update(_frame(t, p), CLOSED)
        if f is not None:
            assert f.channel == 5 and f.cause == cause
            assert t - 1.0 < 2.0  # detection delay bound: 3 windows of 0.5 s + filter
            return
    pytest.fail("not detected")


def test_monitor_flags_supply_loss() -> None:
    mon = FaultMonitor(6)
    faults = [mon.update(_frame(i * 0.01, [1100.0] * 6, 0.0), CLOSED) for i in range(1, 12)]
    assert any(f is not None and f.cause == "supply_loss" for f in faults)


def test_bad_thresholds() -> None:
    from softpad.errors import InputError

    with pytest.raises(InputError, match="rise_pa_s"):
        FaultThresholds(rise_pa_s=-1.0)


def test_safe_state_vents_a_stuck_inflation_valve_and_verifies() -> None:
    box = SimBox(seed=3, initial_pressure_pa=1100.0)
    box.inject_fault(
        __import__("softpad.box", fromlist=["Fault"]).Fault("stuck", 3, 0.0, "inflate")
    )
    res = reach_safe_state(box, 6)
    assert res.verified, res.reason
    assert box.valves[2] is ValveCommand.DEFLATE
    assert any("vented channel 3" in s for s in res.tried)
    peak = 0.0
    for _ in range(3000):  # 30 s after: stays below the maximum
        box.read()
        peak = max(peak, float(box.true_pressures_pa[2]))
    assert peak <= MAX


def test_safe_state_names_a_channel_it_cannot_verify() -> None:
    box = open_box("sim://?inflated_kpa=1.1&faults=nan:2")
    res = reach_safe_state(box, 6, timeout_s=3.0)
    assert not res.verified and res.channel_unsafe == 2
    assert "no valid reading" in res.reason


@pytest.mark.parametrize(
    ("spec", "channel", "cause"),
    [
        ("stuck:3:inflate", 3, "rising"),  # sealed at the start: named at once, not at the timeout
        ("stuck:3:deflate@12", 3, "falling"),
        ("supply_loss@12", None, "supply_loss"),
        ("leak:3:0.5@12", 3, "falling"),
        ("stuck:3:closed@12", 3, "no_response"),
        ("stuck:2:inflate@12", 2, "rising"),
        ("nan:5@8", 5, "sensor_nan"),
    ],
    ids=lambda v: str(v),
)
def test_run_fault_detected_reported_and_safe(capsys, spec, channel, cause) -> None:
    code = main(["run", "--box", f"sim://?faults={spec}", "--object", "banana", "--json"])
    assert code == 3
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "fault"
    assert [(f["channel"], f["cause"]) for f in d["faults"]] == [(channel, cause)]
    s = d["safe_state"]
    if cause == "sensor_nan":
        assert not s["verified"] and s["channel_unsafe"] == channel
    else:
        assert s["verified"], s
        assert max(s["pressures_pa"]) <= MAX


def test_a_rise_under_the_robot_s_load_is_not_a_stuck_valve_but_over_pressure_still_is() -> None:
    """While the robot presses (descend, close, lift) a sealed module rises because of the load:
    300 Pa/s for 5 s raises no "rising" fault; the same rise past the maximum still trips."""
    mon = FaultMonitor(6)
    mon.set_reference(np.full(6, 1100.0))
    mon.loads_expected = mon.robot_pressing = True
    faults = []
    for i in range(1, 1000):
        t = i * 0.01
        p = [1100.0] * 6
        p[4] += 300.0 * max(0.0, t - 1.0)  # 1.1 kPa + 300 Pa/s: 2.95 kPa at t = 7.2 s
        f = mon.update(_frame(t, p), CLOSED)
        if f is not None:
            faults.append((t, f.cause))
            break
    assert faults and faults[0][1] == "over_pressure" and faults[0][0] > 6.0


def _ramp_run(mon: FaultMonitor, rate_hz: float, p_at, pressing=lambda t: False) -> float | None:
    """Feed ``mon`` 20 s of frames with channel 5 at ``p_at(t)`` (the others at 1.1 kPa), all
    with 8 Pa noise; the time of the first fault on channel 5 (a fault elsewhere fails)."""
    rng = np.random.default_rng(int(rate_hz))
    mon.set_reference(np.full(6, 1100.0))
    for i in range(1, int(20 * rate_hz)):
        t = i / rate_hz
        mon.robot_pressing = pressing(t)
        p = 1100.0 + rng.normal(0.0, 8.0, 6)
        p[4] += p_at(t)
        f = mon.update(_frame(t, list(p)), CLOSED)
        if f is not None:
            assert f.channel == 5, f
            return t
    return None


@pytest.mark.parametrize("rate_hz", [50.0, 100.0, 1000.0])
def test_a_stuck_inflation_valve_while_an_object_may_land_is_named_within_1_2_s(
    rate_hz: float,
) -> None:
    """While loads are expected (waiting for the object, the descent) a sealed module filling
    at 300 Pa/s is named within 1.2 s by the steady-rise judgement (rising evenly between four
    0.25 s levels); before, only after three whole 0.5 s windows above 150 Pa/s (1.5-2 s), and
    not at all once the robot pressed. Filling on through the robot's press (closing, lifting:
    not judged), it is named on the first frame after it."""
    mon = FaultMonitor(6)
    mon.loads_expected = True
    t = _ramp_run(mon, rate_hz, lambda t: 300.0 * max(0.0, t - 1.0))
    assert t is not None and t - 1.0 <= 1.2, t
    mon = FaultMonitor(6)
    mon.loads_expected = True
    t = _ramp_run(mon, rate_hz, lambda t: 300.0 * max(0.0, t - 1.0), lambda t: 1.3 < t < 2.4)
    assert t is not None and 2.4 <= t <= 2.4 + 2.0 / rate_hz, t


def _settling(t: float, at_s: float, step_pa: float, tau_s: float, rock_pa: float) -> float:
    """An object landing at ``at_s``: ``step_pa`` settling with ``tau_s``, rocking at 3.7 Hz
    with ``rock_pa`` (undamped, as object 5 on the MuJoCo pad), a bounce spike on landing."""
    if t < at_s:
        return 0.0
    s = t - at_s
    spike = step_pa if s < 0.05 else 0.0
    return step_pa * (1.0 - np.exp(-s / tau_s)) + rock_pa * np.sin(2 * np.pi * 3.7 * s) + spike


def _by_rate(rates: list[float], cases: dict[str, Any], fast_at_1khz: set[str]) -> list[Any]:
    """Every case at every rate (id ``CASE-RATE``); at 1 kHz (about 1.2 CPU s a case) only the
    cases of ``fast_at_1khz`` run in ``make test``, the others in ``make test-slow`` (issue 50)."""
    out = []
    for rate in rates:
        for name, case in cases.items():
            slow = rate == 1000.0 and name not in fast_at_1khz
            marks = [pytest.mark.slow] if slow else []
            out.append(pytest.param(rate, *case, marks=marks, id=f"{name}-{rate}"))
    return out


_LANDINGS = {
    "step": (600.0, 0.1, 0.0, 1),
    "step-twice": (600.0, 0.1, 0.0, 2),
    "slow-settle": (400.0, 0.3, 0.0, 1),
    "rocking": (150.0, 0.02, 80.0, 1),
    "rocking-twice": (150.0, 0.02, 80.0, 2),
    "heavy": (800.0, 0.15, 120.0, 1),
    "heavy-twice": (800.0, 0.15, 120.0, 2),
}


@pytest.mark.parametrize(
    ("rate_hz", "step_pa", "tau_s", "rock_pa", "landings"),
    _by_rate([50.0, 180.0, 1000.0], _LANDINGS, {"step-twice", "rocking-twice"}),
)
def test_objects_landing_settling_and_rocking_are_no_stuck_valve(
    rate_hz: float, step_pa: float, tau_s: float, rock_pa: float, landings: int
) -> None:
    """Loads as the MuJoCo trials show them when objects are placed or put back (a step with
    a bounce, settling within 0.3 s, rocking for ever at about 4 Hz), landing once or twice
    0.25 s apart (an object put down bouncing off once: two even steps whose windows' levels
    rise evenly, named a stuck valve before the rates within each window were judged too):
    no fault at 50 Hz to 1 kHz. (Three even steps 0.25 s apart already rose 150 Pa/s over
    three 0.5 s windows: the judgement before this one named them.)"""

    def load(t: float) -> float:
        n = landings
        return sum(
            _settling(t, 1.0 + 0.25 * i, step_pa / n, tau_s, rock_pa if i == 0 else 0.0)
            for i in range(n)
        )

    mon = FaultMonitor(6)
    mon.loads_expected = True
    assert _ramp_run(mon, rate_hz, load) is None


def _rolling_run(rate_hz: float, shape, stuck_pa_s: float = 0.0) -> tuple[float, int] | None:
    """20 s of frames while loads are expected: an object's load of 1.2 kPa moving from
    channel 1 to channel 4 between 1 and 3 s along ``shape`` (0 -> 1), 8 Pa noise, and
    channel 5 filling at ``stuck_pa_s`` from 1 s on; the first fault's time and channel."""
    rng = np.random.default_rng(int(rate_hz))
    mon = FaultMonitor(6)
    mon.loads_expected = True
    mon.set_reference(np.full(6, 1100.0))
    for i in range(1, int(20 * rate_hz)):
        t = i / rate_hz
        moved = shape(min(1.0, max(0.0, (t - 1.0) / 2.0)))
        p = 1100.0 + rng.normal(0.0, 8.0, 6)
        p[0] += 1200.0 * (1.0 - moved)
        p[3] += 1200.0 * moved
        p[4] += stuck_pa_s * max(0.0, t - 1.0)
        f = mon.update(_frame(t, list(p)), CLOSED)
        if f is not None:
            return t, f.channel
    return None


_ROLLS = {
    "even": (lambda x: x,),
    "speeding-up": (lambda x: x * x,),
    "smooth": (lambda x: 0.5 - 0.5 * np.cos(np.pi * x),),
}


@pytest.mark.parametrize(("rate_hz", "shape"), _by_rate([50.0, 100.0, 1000.0], _ROLLS, {"even"}))
def test_a_load_rolling_onto_another_module_is_no_stuck_valve(rate_hz: float, shape) -> None:
    """An object rolling from one module onto another while it is placed raises the second
    module for seconds (600 Pa/s here, evenly, or speeding up as a can rolling down a dome's
    flank) as the first falls as much: no fault, at 50 Hz to 1 kHz. Before the rise was judged
    net of the other modules' fall, the even roll was named a stuck inflation valve (a YCB
    tomato soup can rolling across the pad in a randomized trial was). A stuck valve filling
    another module at 300 Pa/s meanwhile is still named, within 1.2 s."""
    assert _rolling_run(rate_hz, shape) is None
    hit = _rolling_run(rate_hz, shape, stuck_pa_s=300.0)
    assert hit is not None and hit[1] == 5 and hit[0] - 1.0 <= 1.2, hit
