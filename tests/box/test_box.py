"""Box interface: conformance of every back-end, URL registry, determinism, frames."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import (
    Box,
    ConformanceError,
    PressureFrame,
    SimBox,
    ValveCommand,
    available_box_backends,
    check_conformance,
    open_box,
)
from softpad.errors import InputError

SIM_URLS = [
    "sim://",
    "sim://?seed=7&noise=0",
    "sim://?channels=6&rate_hz=1000",
    "sim://?inflated_kpa=1.1&object=banana",
    "sim://?layout=3x3&channels=9&pitch_mm=30",
    "sim://?faults=leak:2:0.01",
]


@pytest.mark.parametrize(
    "url", SIM_URLS, ids=["default", "ideal", "6ch-1khz", "banana", "3x3", "leak"]
)
def test_sim_backend_passes_conformance(url: str) -> None:
    check_conformance(open_box(url))


def test_zenoh_backend_passes_conformance(served) -> None:
    """The zenoh back-end, against a simulated box served on loopback by the daemon."""
    with served("sim://?seed=5") as (daemon, url):
        check_conformance(open_box(url))
        assert daemon.controller is None  # closing gave control back


def test_a_box_wrapper_passes_conformance_and_closes_what_it_owns() -> None:
    from softpad.box import BoxWrapper

    inner = open_box("sim://?seed=3")
    check_conformance(BoxWrapper(inner))
    assert inner.closed  # the wrapper owned it
    view_of = open_box("sim://?seed=3")
    with BoxWrapper(view_of, owns_inner=False) as view:
        view.set_valve(2, "inflate")
        assert view.valves == view_of.valves and view_of.valves[1] is ValveCommand.INFLATE
    assert not view_of.closed and view_of.valves[1] is ValveCommand.CLOSED
    view_of.close()


def test_every_registered_backend_is_checked() -> None:
    """A new scheme must be added to the conformance cases (replay://, offered by softpad.record
    through the entry point, is checked in tests/record/test_replay.py; hw://, the real box on
    fake lines, in tests/box/test_hardware.py)."""
    assert available_box_backends() == ("sim", "zenoh", "hw", "replay")


class _BrokenBox(Box):
    """Violates the contract: time does not advance."""

    channels = 2
    sample_rate_hz = 10.0

    def _read(self) -> PressureFrame:
        return PressureFrame(0.0, np.zeros(2), 0.0)

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        pass

    def _close(self) -> None:
        pass


def test_conformance_catches_a_broken_backend() -> None:
    with pytest.raises(ConformanceError, match="time stamps must increase"):
        check_conformance(_BrokenBox())


@pytest.mark.parametrize(
    ("url", "match"),
    [
        ("serial:///dev/ttyUSB0", "unknown box URL scheme 'serial'"),
        ("sim://?sead=1", "unknown sim:// option 'sead'"),
        ("sim://?seed=one", "seed='one' must be an integer"),
        ("sim://?rate_hz=nan", "rate_hz='nan' must be finite"),
        ("sim://?channels=4", "channels must be an integer from 6"),
        ("sim://?object=teapot", "unknown object 'teapot'"),
        ("sim://?faults=melt:3", "unknown fault 'melt'"),
        ("sim://?noise=2", "noise='2' must be 0 or 1"),
        ("sim://host", "takes no host"),
        ("banana", "scheme://"),
        ("sim://?seed=1&seed=2", "given twice"),
    ],
    ids=[
        "scheme",
        "option",
        "int",
        "nan",
        "channels",
        "object",
        "fault",
        "noise",
        "host",
        "no-scheme",
        "dup",
    ],
)
def test_bad_urls_raise_input_error_naming_the_problem(url: str, match: str) -> None:
    with pytest.raises(InputError, match=match):
        open_box(url)


def test_same_seed_same_frames_and_different_seed_differs() -> None:
    def frames(url: str) -> np.ndarray:
        with open_box(url) as b:
            return np.array([f.pressures_pa for f in b.read_many(50)])

    a, b, c = frames("sim://?seed=3"), frames("sim://?seed=3"), frames("sim://?seed=4")
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_read_advances_virtual_clock_by_one_period() -> None:
    with open_box("sim://?rate_hz=250") as b:
        t = [f.t_s for f in b.read_many(5)]
    np.testing.assert_allclose(np.diff(t), 1 / 250, rtol=1e-9)


def test_valve_commands_by_name_and_member_and_context_manager() -> None:
    with open_box("sim://") as b:
        b.set_valve(3, "inflate")
        b.set_valve(4, ValveCommand.DEFLATE)
        assert b.valves[2] is ValveCommand.INFLATE and b.valves[3] is ValveCommand.DEFLATE
    # closing closes inflation; a channel being vented keeps venting (issue 35)
    assert b.closed and b.valves[2] is ValveCommand.CLOSED
    assert b.valves[3] is ValveCommand.DEFLATE and set(b.valves[4:]) == {ValveCommand.CLOSED}
    with pytest.raises(InputError, match="closed"):
        b.read()


def test_unconnected_channels_stay_at_atmosphere() -> None:
    with SimBox(channels=8, sensor=None, seed=0) as b:
        b.set_valves(["inflate"] * 8)
        b.read_many(200)
        p = b.true_pressures_pa
    assert (p[:6] > 100).all()
    np.testing.assert_array_equal(p[6:], 0.0)


def test_frame_to_dict_in_kpa_with_nan_as_null() -> None:
    f = PressureFrame(1.5, np.array([1100.0, np.nan]), 10e3)
    assert f.to_dict() == {"t_s": 1.5, "pressures_kpa": [1.1, None], "supply_kpa": 10.0}
    assert f.channels == 2


def test_realtime_paces_reads_to_the_wall_clock(monkeypatch) -> None:
    """Each read waits until its virtual time has come (sleep is recorded, not performed)."""
    import softpad.box._sim_layers as layers

    clock = [100.0]
    sleeps: list[float] = []
    monkeypatch.setattr(layers.time, "perf_counter", lambda: clock[0])
    monkeypatch.setattr(layers.time, "sleep", lambda s: sleeps.append(s))
    with open_box("sim://?realtime=1&rate_hz=50") as b:
        b.read_many(4)
    np.testing.assert_allclose(sleeps, [0.02, 0.04, 0.06], rtol=1e-9)


@pytest.mark.parametrize("rate_hz", [100, 1000], ids=["100Hz", "1kHz"])
def test_ideal_readings_follow_the_true_pressures_while_inflating(rate_hz: int) -> None:
    """The precomputed ramp of readings stays on the gas state frame by frame."""
    from softpad.sim import SensorParams

    with SimBox(
        sample_rate_hz=rate_hz, sensor=SensorParams.ideal(), initial_pressure_pa=300.0
    ) as b:
        b.set_valves(["inflate"] * 3 + ["deflate"] * 3 + ["closed"] * 2)
        for k in range(300):
            f = b.read()
            np.testing.assert_allclose(f.pressures_pa, b.true_pressures_pa, atol=1e-6)
            if k == 150:
                b.set_valve(2, "closed")  # a command in the middle of a ramp
