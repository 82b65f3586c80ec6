"""The hardware box on a fake sysfs IIO tree and in-memory GPIO lines (gpio-sim where present)."""

from __future__ import annotations

import glob
import os
from pathlib import Path

import numpy as np
import pytest

from softpad.box import FakeValveLines, HardwareBox, IIOReader, ValveCommand, check_conformance
from softpad.config import parse_installation


def _fake_iio(root: Path, counts: list[int]) -> None:
    dev = root / "iio:device0"
    dev.mkdir(parents=True)
    for k, c in enumerate(counts):
        (dev / f"in_voltage{k}_raw").write_text(f"{c}\n")
    (dev / "in_voltage_scale").write_text("0.439453125\n")


def _settings(
    root: Path,
    n: int = 3,
    supply: bool = True,
    deflate: str = "normally_closed",
    rate_hz: float = 1000.0,
):
    chans = [
        {
            "gpiochip": "/dev/gpiochip9",
            "inflate_line": 2 * k,
            "deflate_line": 2 * k + 1,
            "iio_device": 0,
            "iio_channel": k,
            "offset_pa": -100.0,
            "gain": 2.0,
            "pa_per_count": 0.5,
        }
        for k in range(n)
    ]
    box: dict = {
        "channel": chans,
        "iio_root": str(root),
        "sample_rate_hz": rate_hz,
        "inflate_valves": "normally_closed",
        "deflate_valves": deflate,
    }
    if supply:
        box["supply"] = {"iio_device": 0, "iio_channel": n, "pa_per_count": 10.0}
    return parse_installation({"box": box, "pad": {"rows": 1, "cols": n}}).box


def _lines(settings) -> FakeValveLines:
    return FakeValveLines(
        (w.gpiochip, o) for w in settings.channels for o in (w.inflate_line, w.deflate_line)
    )


def test_iio_reader_reads_counts_and_scale(tmp_path: Path) -> None:
    _fake_iio(tmp_path, [10, 20, 4095])
    r = IIOReader(tmp_path, [(0, 0), (0, 1), (0, 2)])
    np.testing.assert_array_equal(r.read_raw(), [10, 20, 4095])
    (tmp_path / "iio:device0" / "in_voltage1_raw").write_text("33\n")
    assert r.read_raw()[1] == 33  # re-read from the open file each time
    (tmp_path / "iio:device0" / "in_voltage2_raw").write_text("garbage\n")
    assert np.isnan(r.read_raw()[2])
    assert r.scale(0) == pytest.approx(0.439453125e-3)
    r.close()


def test_calibration_and_valve_lines(tmp_path: Path) -> None:
    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    s = _settings(tmp_path)
    lines = _lines(s)
    box = HardwareBox(s, lines=lines)
    f = box.read()
    # p = offset + gain * pa_per_count * raw = -100 + 1.0 * raw
    np.testing.assert_allclose(f.pressures_pa, [1000, 1100, 1200])
    assert f.supply_pa == pytest.approx(500)
    box.set_valve(2, ValveCommand.INFLATE)
    assert lines.get("/dev/gpiochip9", 2) and not lines.get("/dev/gpiochip9", 3)
    box.set_valve(2, ValveCommand.DEFLATE)
    assert not lines.get("/dev/gpiochip9", 2) and lines.get("/dev/gpiochip9", 3)
    # never both valves of a channel open in any single step
    for step in lines.history:
        for ch in range(3):
            assert not (
                step.get(("/dev/gpiochip9", 2 * ch)) and step.get(("/dev/gpiochip9", 2 * ch + 1))
            )
    box.close()  # channel 2 was venting: it keeps venting (issue 49), nothing else is open
    assert lines.released
    assert [k for k, on in lines.values.items() if on] == [("/dev/gpiochip9", 3)]


def test_hardware_box_passes_conformance_and_stamps_monotonic_frames(tmp_path: Path) -> None:
    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    # 50 Hz: the median period must be within 20 % (conformance), which a 1 ms period does not
    # survive on a loaded two-core machine (the suite's own workers); 4 ms of lateness here does
    s = _settings(tmp_path, rate_hz=50.0)
    box = HardwareBox(s, lines=_lines(s))
    stamps = [box.read().t_s for _ in range(5)]
    assert np.all(np.diff(stamps) > 0)
    check_conformance(HardwareBox(s, lines=_lines(s)), frames=10)
    box.close()


def test_a_sample_taken_after_its_period_counts_as_missed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The box's schedule counts a tick as missed when its sample was not taken within its
    period: a sleep that wakes 3.5 ms late misses ticks 3..5 (tick 3's late sample and the
    two skipped at the next read), a read 0.5 ms late misses none."""
    from softpad.box import _hardware

    now = [50.0]
    stall = [0.0]

    def sleep(s: float) -> None:
        now[0] += s + stall[0]
        stall[0] = 0.0

    monkeypatch.setattr(_hardware.time, "monotonic", lambda: now[0])
    monkeypatch.setattr(_hardware.time, "sleep", sleep)
    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    s = _settings(tmp_path)
    box = HardwareBox(s, lines=_lines(s))
    box.read()
    now[0] += 0.5e-3 + 1e-3  # tick 2 read 0.5 ms late: in its period
    box.read()
    assert box.missed_ticks == 0
    stall[0] = 3.5e-3  # tick 3's sleep wakes 3.5 ms late (at 6.5 ms)
    box.read()
    assert box.missed_ticks == 1
    box.read()  # ticks 4 and 5 skipped, tick 6 (6 ms) read at 6.5 ms
    assert box.missed_ticks == 3
    assert box.read().t_s == pytest.approx(7e-3)
    assert box.missed_ticks == 3
    box.close()


def test_missing_sensor_file_is_a_named_fault(tmp_path: Path) -> None:
    from softpad.errors import HardwareFault

    _fake_iio(tmp_path, [1, 2])
    with pytest.raises(HardwareFault, match="in_voltage2_raw"):
        HardwareBox(_settings(tmp_path, 3, supply=False), lines=FakeValveLines([]))


@pytest.mark.skipif(
    not glob.glob("/sys/kernel/config/gpio-sim") or os.geteuid() != 0,
    reason="gpio-sim (configfs) not available or not root",
)
def test_gpiod_lines_on_gpio_sim() -> None:  # pragma: no cover - needs the kernel module
    from softpad.box import GpiodValveLines

    base = Path("/sys/kernel/config/gpio-sim/softpad-test")
    (base / "bank0").mkdir(parents=True)
    (base / "bank0" / "num_lines").write_text("4")
    (base / "live").write_text("1")
    try:
        chip = "/dev/" + (base / "bank0" / "chip_name").read_text().strip()
        lines = GpiodValveLines([(chip, 0), (chip, 1)])
        lines.set({(chip, 0): True})
        assert lines.get(chip, 0)
        lines.release()
    finally:
        (base / "live").write_text("0")
        (base / "bank0").rmdir()
        base.rmdir()


def test_a_box_without_a_supply_sensor_never_trips_supply_loss(tmp_path: Path) -> None:
    """Issue 35 item 10: without [box.supply] the frames report 0 Pa; the run's fault monitor
    must not call that a supply loss (it did after 10 frames, on every run)."""
    from softpad.control._safety import RunSafety

    _fake_iio(tmp_path, [2000, 2100, 2200])
    settings = _settings(tmp_path, 3, supply=False)
    with HardwareBox(settings, lines=_lines(settings)) as box:
        assert box.supply_sensor is False
        safety = RunSafety(box, 3, 3000.0, 50.0)
        for _ in range(30):
            safety.watch(box.read())  # raises MonitoredFault on a fault
    _fake_iio(tmp_path / "wired", [2000, 2100, 2200, 0])
    wired = _settings(tmp_path / "wired", 3, supply=True)
    with HardwareBox(wired, lines=_lines(wired)) as box:
        assert box.supply_sensor is True
        safety = RunSafety(box, 3, 3000.0, 50.0)
        with pytest.raises(Exception, match="supply"):
            for _ in range(30):
                safety.watch(box.read())


def _venting_box(tmp_path: Path, deflate: str) -> tuple[HardwareBox, FakeValveLines]:
    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    s = _settings(tmp_path, deflate=deflate)
    lines = _lines(s)
    box = HardwareBox(s, lines=lines)
    box.set_valve(1, ValveCommand.INFLATE)
    box.set_valve(2, ValveCommand.DEFLATE)
    return box, lines


def test_closing_a_hardware_box_leaves_a_vented_channel_venting(tmp_path: Path) -> None:
    """Issue 49: releasing the lines drove them inactive, which closed the normally-closed
    deflation valve of a channel being vented (True -> False): with a stuck inflation valve
    the module then filled with no guard running."""
    box, lines = _venting_box(tmp_path, "normally_closed")
    assert lines.get("/dev/gpiochip9", 3)  # channel 2's deflation valve open
    box.close()
    assert lines.get("/dev/gpiochip9", 3)  # still venting
    assert not lines.get("/dev/gpiochip9", 0)  # channel 1's inflation valve closed


def test_stopping_the_daemon_leaves_a_vented_channel_venting(tmp_path: Path) -> None:
    from softpad.box import BoxDaemon
    from softpad.box._auth import Sealer

    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    s = _settings(tmp_path)
    lines = _lines(s)
    daemon = BoxDaemon(HardwareBox(s, lines=lines))
    sealer = Sealer(bytes.fromhex(daemon._on_take({"client": "ctl"})["key"]))
    for ch, cmd in ((1, "inflate"), (2, "deflate")):
        msg = sealer.seal("query", "valves", {"client": "ctl", "channel": ch, "command": cmd})
        daemon._on_valves({**msg, "_key": "softpad/box/valves"})
    assert lines.get("/dev/gpiochip9", 3)
    daemon.close()
    assert lines.released
    assert lines.get("/dev/gpiochip9", 3) and not lines.get("/dev/gpiochip9", 0)


def test_normally_open_deflation_valves_are_driven_active_to_close(tmp_path: Path) -> None:
    """A normally-open deflation valve is closed with its line active and opened (venting)
    with it inactive: the box starts with every valve closed, and a vented channel's line is
    inactive at release, so it vents whatever the GPIO driver then does."""
    _fake_iio(tmp_path, [1100, 1200, 1300, 50])
    s = _settings(tmp_path, deflate="normally_open")
    lines = _lines(s)
    box = HardwareBox(s, lines=lines)
    deflate_lines = [("/dev/gpiochip9", 2 * k + 1) for k in range(3)]
    assert all(lines.values[k] for k in deflate_lines)  # all closed: lines active
    assert box.valves == (ValveCommand.CLOSED,) * 3
    box.set_valve(2, ValveCommand.DEFLATE)
    assert not lines.get("/dev/gpiochip9", 3)  # open: line inactive
    box.close()
    assert not lines.get("/dev/gpiochip9", 3)


@pytest.mark.parametrize(
    ("box", "named"),
    [
        ({"deflate_valves": "normally_closed"}, "box.inflate_valves is missing"),
        ({"inflate_valves": "normally_closed"}, "box.deflate_valves is missing"),
        (
            {"inflate_valves": "normally_open", "deflate_valves": "normally_open"},
            "inflate_valves = 'normally_open' is refused",
        ),
        ({"inflate_valves": "normally_closed", "deflate_valves": "nc"}, "deflate_valves must be"),
    ],
    ids=["no-inflate-kind", "no-deflate-kind", "normally-open-inflation", "unknown-kind"],
)
def test_a_file_that_does_not_say_how_its_valves_are_built_is_refused(
    tmp_path: Path, box: dict, named: str
) -> None:
    from softpad.config import ConfigError

    chans = [
        {"inflate_line": 2 * k, "deflate_line": 2 * k + 1, "iio_device": 0, "iio_channel": k}
        for k in range(6)
    ]
    with pytest.raises(ConfigError, match=named):
        parse_installation({"box": {"channel": chans, **box}})
