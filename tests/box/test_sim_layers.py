"""The simulated box as a plain physical box in layers (issue 36, item 4): the order of the
layers, where each fault goes, one guard and one set of valve states for them all."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import (
    Box,
    BoxWrapper,
    ConnectionLost,
    Fault,
    PressureFrame,
    SafetyLimits,
    SensorFaults,
    SensorZeroShift,
    SimBox,
    Unreachable,
    ValveCommand,
    WallClock,
    compose_sim_box,
    open_box,
    simulator_of,
)
from softpad.errors import InputError


def _chain(box: Box) -> list[type]:
    out = []
    while isinstance(box, BoxWrapper):
        out.append(type(box))
        box = box.inner
    return [*out, type(box)]


@pytest.mark.parametrize(
    ("options", "layers"),
    [
        ("", [Unreachable, SensorFaults, SimBox]),
        ("disturbances=1", [Unreachable, SensorFaults, SensorZeroShift, SimBox]),
        ("realtime=1", [WallClock, Unreachable, SensorFaults, SimBox]),
        (
            "disturbances=1&realtime=1",
            [WallClock, Unreachable, SensorFaults, SensorZeroShift, SimBox],
        ),
    ],
)
def test_sim_url_composes_the_layers_in_their_documented_order(options: str, layers: list) -> None:
    with open_box(f"sim://?{options}") as box:
        assert _chain(box) == layers


def test_the_plain_box_takes_physical_faults_only() -> None:
    plain = SimBox(seed=1)
    plain.inject_fault(Fault("leak", 2, 0.0, 1e-8))
    plain.inject_fault(Fault("stuck", 3, 1.0, "inflate"))
    plain.inject_fault(Fault("supply_loss", None, 2.0))
    for fault in (Fault("nan", 2), Fault("dropout", 2), Fault("disconnect")):
        with pytest.raises(InputError, match=f"a {fault.kind} fault .*compose_sim_box"):
            plain.inject_fault(fault)
    with pytest.raises(InputError, match="channel 7 has no module"):
        plain.inject_fault(Fault("stuck", 7, 0.0, "inflate"))
    layered = compose_sim_box(SimBox(seed=1))
    with pytest.raises(InputError, match="channel must be an integer from 1 to 8, got 9"):
        layered.inject_fault(Fault("nan", 9))


def test_simulator_of_finds_the_plain_box_behind_layers_and_views() -> None:
    box = open_box("sim://?disturbances=1&realtime=1")
    plain = simulator_of(box)
    assert isinstance(plain, SimBox)
    assert simulator_of(BoxWrapper(box, owns_inner=False)) is plain
    assert simulator_of(plain) is plain

    class NotSimulated(BoxWrapper):
        pass

    other = NotSimulated(_Constant())
    assert simulator_of(other) is None
    # what the layers do not define reads through to the plain box
    assert box.world is plain.world and box.time_s == plain.time_s == 0.0
    box.close()
    assert plain.closed


class _Constant(Box):
    """A box that is not simulated: 1 kPa on 2 channels."""

    channels = 2  # type: ignore[assignment]
    sample_rate_hz = 10.0  # type: ignore[assignment]

    def _read(self) -> PressureFrame:
        return PressureFrame(0.0, np.full(2, 1e3), 0.0)

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        pass

    def _close(self) -> None:
        pass


def test_one_guard_and_one_set_of_valve_states_for_all_layers() -> None:
    with open_box("sim://?seed=2&disturbances=1") as box:
        plain = simulator_of(box)
        assert plain is not None
        limits = SafetyLimits(max_pressure_pa=1500.0, release_pa=1000.0)
        box.safety_limits = limits
        assert plain.safety_limits is limits and box.safety is plain.safety
        box.set_valve(1, "inflate")
        assert plain.valves[0] is ValveCommand.INFLATE
        for _ in range(1000):
            box.read()
        # the guard checked the outermost layer's frames once each and vented channel 1
        assert [ch for _t, ch, _why in plain.safety.trips] == [1]
        assert box.valves[0] is plain.valves[0] is ValveCommand.DEFLATE


def _lose_a_held_channel(faults: str) -> tuple[Box, float]:
    """Channel 1 inflated to 1 kPa and sealed, the link lost at 8 s, then 5 s of reads tried:
    (the box, channel 1's true pressure when the link was lost)."""
    box = open_box(f"sim://?seed=3&noise=0&faults=disconnect@8,{faults}")
    box.set_valve(1, "inflate")
    for _ in range(700):
        if box.read().pressures_pa[0] > 1000.0:
            break
    box.set_valve(1, "closed")
    with pytest.raises(ConnectionLost):
        for _ in range(700):
            box.read()
    held = float(box.true_pressures_pa[0])
    assert held > 950.0
    for _ in range(500):
        with pytest.raises(ConnectionLost, match="stopped answering"):
            box.read()
    return box, held


@pytest.mark.parametrize("nan", [True, False], ids=["nan", "sound"])
def test_the_guard_of_a_lost_box_sees_its_sensor_faults(nan: bool) -> None:
    """Behind the lost link the box's own guard checks the faulted readings: a NaN from 9 s
    on channel 1 trips it and the firmware vents the channel (the client cannot); a sound
    sensor leaves the sealed channel as it was."""
    box, held = _lose_a_held_channel("nan:1@9" if nan else "nan:2@30")
    assert box.valves[0] is ValveCommand.CLOSED  # commanded closed: the firmware vents
    assert bool(box.safety.tripped[0]) is nan
    now = float(box.true_pressures_pa[0])
    assert now < 0.3 * held if nan else abs(now - held) < 0.05 * held
    box.close()


def _run(url: str, shortcut: bool, monkeypatch: pytest.MonkeyPatch, seed: int) -> list:
    """Frames, valve states, trips and errors of a seeded valve-command sequence, with faults
    injected into the layers while it runs."""
    with monkeypatch.context() as m:
        if not shortcut:  # every layer's read called, as before the shortcut
            m.setattr(SensorFaults, "_passes_through", lambda self: False)
            m.setattr(Unreachable, "_passes_through", lambda self: False)
        rng = np.random.default_rng(seed)
        out: list = []
        with open_box(url) as box:
            for i in range(1500):
                if i % 50 == 0:
                    cmd = [str(rng.choice(["inflate", "closed", "deflate"])) for _ in range(8)]
                    try:
                        box.set_valves(cmd)
                    except Exception as exc:  # a tripped channel refusing inflate
                        out.append(repr(exc))
                if i == 400:
                    box.inject_fault(
                        Fault("nan", channel=2, at_s=box.time_s + 30 / box.sample_rate_hz)
                    )
                if i == 900:
                    box.inject_fault(Fault("disconnect", at_s=box.time_s + 50 / box.sample_rate_hz))
                try:
                    f = box.read()
                    out.append((f.t_s, f.pressures_pa.tobytes(), f.supply_pa, box.valves))
                except ConnectionLost as exc:
                    out.append(str(exc))
            out.append(list(box.safety.trips))
    return out


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("rate", [100, 1000])
def test_layers_passing_frames_on_are_skipped_without_a_difference(
    seed: int, rate: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """While no layer has a fault, the plain box reads and checks the frames itself; the
    frames, valve states, trips and errors are those of the read through every layer, also
    after a sensor fault and a lost link are injected at run time (their layers act again)."""
    url = f"sim://?seed={seed}&rate_hz={rate}&inflated_kpa=2.5"
    fast = _run(url, True, monkeypatch, seed)
    assert fast == _run(url, False, monkeypatch, seed)
    assert any(isinstance(x, str) and "stopped answering" in x for x in fast)  # link lost
    assert any(isinstance(x, tuple) and np.isnan(np.frombuffer(x[1])[1]) for x in fast)  # nan
    assert fast[-1]  # the guard tripped channels: the comparison covers vents


def test_a_read_set_on_the_outer_layer_by_a_wrapper_is_kept() -> None:
    """The layers' shortcut (the outermost layer reads straight from the plain box while
    every layer passes frames on) must not replace a ``read`` that somebody else set on the
    layer: a wrapper that counts or limits reads (the fuzz campaign's) saw only the first
    frame and then none, and ``box read --count`` ran past its bound."""
    box = open_box("sim://")
    own = box.read
    calls = []

    def counted() -> object:
        calls.append(1)
        return own()

    box.read = counted  # type: ignore[method-assign]
    for _ in range(5):
        box.read()
    assert len(calls) == 5
    assert box.read is counted
