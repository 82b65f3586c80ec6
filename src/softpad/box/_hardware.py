"""The real Pneumaticbox: valves on GPIO lines, sensors on Linux IIO (seed, Section 6.1.1).

Two small interfaces keep the hardware replaceable in tests:

* :class:`ValveLines`: set GPIO output lines. :class:`GpiodValveLines` uses libgpiod 2.x
  (``gpiod.request_lines``, two lines per channel); :class:`FakeValveLines` keeps the line
  values in memory (same interface). Releasing the lines leaves their values as they are.
* :class:`IIOReader`: reads ``<root>/iio:deviceN/in_voltageK_raw`` (and its ``_scale``), the
  files the BeagleBone's own ADC and external SPI/I2C ADCs expose; a test points ``root`` at a
  fake tree in a temporary folder.

:class:`HardwareBox` combines them with the wiring and calibration of the installation file
(:class:`softpad.config.BoxSettings`) into a :class:`~softpad.box.Box` that samples at a fixed
rate on the monotonic clock.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Iterable
from pathlib import Path
from typing import IO, Any, Protocol

import numpy as np

from softpad.box._base import Box, PressureFrame, ValveCommand
from softpad.errors import HardwareFault, InputError


class ValveLines(Protocol):
    """GPIO output lines, addressed by (chip path, line offset)."""

    def set(self, values: dict[tuple[str, int], bool]) -> None:
        """Drive every given line active (True) or inactive (False)."""

    def get(self, chip: str, line: int) -> bool:
        """Last value driven on a line."""

    def release(self) -> None:
        """Release the lines, leaving each at its last value (the box decides the final state
        before: inflation closed, vented channels venting)."""


class FakeValveLines:
    """:class:`ValveLines` in memory (tests, dry runs): records every line value and change."""

    def __init__(self, lines: Iterable[tuple[str, int]]) -> None:
        self.values: dict[tuple[str, int], bool] = dict.fromkeys(lines, False)
        #: Every ``set`` call, in order.
        self.history: list[dict[tuple[str, int], bool]] = []
        self.released = False

    def set(self, values: dict[tuple[str, int], bool]) -> None:
        if self.released:
            raise HardwareFault("GPIO lines already released")
        for key in values:
            if key not in self.values:
                raise InputError(f"GPIO line {key[1]} of {key[0]} was not requested")
        self.values.update(values)
        self.history.append(dict(values))

    def get(self, chip: str, line: int) -> bool:
        return self.values[(chip, line)]

    def release(self) -> None:
        self.released = True  # the values stay: what the kernel does with a released output


class FileValveLines:
    """:class:`ValveLines` in a file, one byte per line (0 inactive, 1 active), shared with
    other processes: the fake GPIO a wall-clock hardware simulation reads its valves from, and
    the compiled guard writes to (:meth:`native`).

    Parameters
    ----------
    path
        The file (created or truncated, every line inactive).
    lines
        (chip path, offset) of every line, in the order of their bytes.
    """

    def __init__(self, path: str | Path, lines: Iterable[tuple[str, int]]) -> None:
        self.path = Path(path)
        self.index = {key: k for k, key in enumerate(dict.fromkeys(lines))}
        self.path.write_bytes(bytes(len(self.index)))
        self._fd = os.open(self.path, os.O_RDWR | os.O_CLOEXEC)
        self.released = False

    def set(self, values: dict[tuple[str, int], bool]) -> None:
        if self.released:
            raise HardwareFault("GPIO lines already released")
        for key, on in values.items():
            if key not in self.index:
                raise InputError(f"GPIO line {key[1]} of {key[0]} was not requested")
            os.pwrite(self._fd, b"\x01" if on else b"\x00", self.index[key])

    def get(self, chip: str, line: int) -> bool:
        return os.pread(self._fd, 1, self.index[(chip, line)]) == b"\x01"

    def native(self, chip: str, line: int) -> tuple[int, int, int]:
        """``(kind, fd, index)`` of a line for the compiled guard (kind 0: a shared file)."""
        return 0, self._fd, self.index[(chip, line)]

    def release(self) -> None:
        if not self.released:
            self.released = True  # the values stay, as with GPIO lines
            os.close(self._fd)


class GpiodValveLines:
    """:class:`ValveLines` on the Linux GPIO character device through libgpiod 2.x.

    Parameters
    ----------
    lines
        (chip path, offset) of every valve line; each chip's lines are requested at once as
        outputs driven inactive (valves closed).
    consumer
        Name shown by ``gpioinfo`` for the requested lines.
    """

    def __init__(self, lines: Iterable[tuple[str, int]], consumer: str = "softpad") -> None:
        try:
            import gpiod
            from gpiod.line import Direction, Value
        except ImportError:
            raise InputError(
                "the hardware box needs libgpiod's Python bindings: pip install 'softpad[box]'"
            ) from None
        self._active, self._inactive = Value.ACTIVE, Value.INACTIVE
        by_chip: dict[str, list[int]] = {}
        for chip, line in lines:
            by_chip.setdefault(chip, []).append(line)
        self._requests = {}
        self._values: dict[tuple[str, int], bool] = {}
        settings = gpiod.LineSettings(direction=Direction.OUTPUT, output_value=Value.INACTIVE)
        try:
            for chip, offsets in by_chip.items():
                self._requests[chip] = gpiod.request_lines(
                    chip, consumer=consumer, config={tuple(offsets): settings}
                )
                self._values.update(dict.fromkeys(((chip, o) for o in offsets), False))
        except (OSError, ValueError) as exc:
            self.release()
            raise HardwareFault(f"cannot request GPIO lines {by_chip}: {exc}") from None

    def set(self, values: dict[tuple[str, int], bool]) -> None:
        per_chip: dict[str, dict[int | str, Any]] = {}
        for (chip, line), on in values.items():
            per_chip.setdefault(chip, {})[line] = self._active if on else self._inactive
        try:
            for chip, vals in per_chip.items():
                self._requests[chip].set_values(vals)
        except (OSError, KeyError, ValueError) as exc:
            raise HardwareFault(f"cannot drive GPIO lines {values}: {exc}") from None
        self._values.update(values)

    def get(self, chip: str, line: int) -> bool:
        return self._values[(chip, line)]

    def native(self, chip: str, line: int) -> tuple[int, int, int]:
        """``(kind, fd, index)`` of a line for the compiled guard: kind 1, the line request's
        file descriptor and the line's index in it (GPIO_V2_LINE_SET_VALUES_IOCTL)."""
        req = self._requests[chip]
        return 1, int(req.fd), list(req.offsets).index(line)

    def release(self) -> None:
        # not driven inactive first: that closed a normally-closed deflation valve and sealed a
        # channel being vented (issue 49). What a released line does next is the GPIO driver's
        # business: only a normally-open deflation valve vents whatever it does.
        for req in self._requests.values():
            req.release()
        self._requests.clear()


class IIOReader:
    """Raw counts of IIO voltage channels (``in_voltageK_raw``), files kept open for speed.

    Parameters
    ----------
    root
        Folder holding ``iio:deviceN`` (``/sys/bus/iio/devices`` on Linux).
    channels
        (device N, channel K) pairs, in the order :meth:`read_raw` returns them.
    """

    def __init__(self, root: str | Path, channels: Iterable[tuple[int, int]]) -> None:
        self.root = Path(root)
        self.channels = tuple(channels)
        self._files: list[IO[str]] = []
        for dev, ch in self.channels:
            path = self.root / f"iio:device{dev}" / f"in_voltage{ch}_raw"
            try:
                self._files.append(open(path, encoding="ascii"))
            except OSError as exc:
                self.close()
                raise HardwareFault(f"cannot open IIO channel {path}: {exc.strerror}") from None

    def scale(self, index: int) -> float:
        """Volts-per-count factor of channel ``index`` from ``in_voltageK_scale`` (mV/count in
        the kernel ABI, converted to V), or ``in_voltage_scale``; NaN when neither exists."""
        dev, ch = self.channels[index]
        for name in (f"in_voltage{ch}_scale", "in_voltage_scale"):
            path = self.root / f"iio:device{dev}" / name
            if path.exists():
                return float(path.read_text().strip()) / 1e3
        return math.nan

    def read_raw(self) -> np.ndarray:
        """One raw count per channel (float64; NaN where a read failed or gave garbage)."""
        out = np.empty(len(self._files))
        for i, f in enumerate(self._files):
            try:
                f.seek(0)
                out[i] = float(f.read().strip())
            except (OSError, ValueError):
                out[i] = math.nan
        return out

    def close(self) -> None:
        """Close the sysfs files. Idempotent."""
        for f in self._files:
            f.close()
        self._files = []


class HardwareBox(Box):
    """The Pneumaticbox on GPIO and IIO, wired and calibrated as the installation file says.

    Parameters
    ----------
    settings
        :class:`softpad.config.BoxSettings` (channels with their lines, ADC channels and
        calibration; the supply sensor; the sampling rate).
    lines
        Valve lines; by default :class:`GpiodValveLines` on the configured chips.
    iio
        Sensor reader; by default :class:`IIOReader` under ``settings.iio_root``.

    Notes
    -----
    :meth:`read` blocks until the next tick of a fixed-rate schedule on the monotonic clock
    (``t_k = t_0 + k / sample_rate_hz``); when the caller is late by whole periods the missed
    ticks are skipped and counted in :attr:`missed_ticks`, and so is a tick whose sample was
    taken more than a period after its deadline (the thread woke late). Frame time is seconds
    since opening.

    Line levels follow ``settings.inflate_valves`` / ``deflate_valves`` (active opens a
    normally-closed valve, closes a normally-open one); every valve starts closed. Closing the
    box closes every inflation valve and releases the lines as they are: a vented channel keeps
    venting. :meth:`start_guard` runs the over-pressure guard in compiled code, off the GIL.
    """

    self_paced = True

    def __init__(
        self,
        settings: object,
        lines: ValveLines | None = None,
        iio: IIOReader | None = None,
    ) -> None:
        from softpad.config import BoxSettings

        if not isinstance(settings, BoxSettings):
            raise InputError(f"HardwareBox needs BoxSettings, got {type(settings).__name__}")
        if not settings.channels:
            raise InputError("the installation file wires no channel ([[box.channel]] tables)")
        super().__init__()
        self.settings = settings
        wiring = list(settings.channels)
        valve_lines = [(w.gpiochip, o) for w in wiring for o in (w.inflate_line, w.deflate_line)]
        sensors = [(w.iio_device, w.iio_channel) for w in wiring]
        if settings.supply is not None:
            sensors.append((settings.supply.iio_device, settings.supply.iio_channel))
        self._lines = lines if lines is not None else GpiodValveLines(valve_lines)
        try:
            self._iio = iio if iio is not None else IIOReader(settings.iio_root, sensors)
        except BaseException:
            self._lines.release()
            raise
        try:  # every valve closed, whatever it does unpowered (the state the box reports)
            for ch in range(1, len(wiring) + 1):
                self._lines.set(self._levels(ch, False, False))
        except BaseException:
            self._lines.release()
            self._iio.close()
            raise
        cal = [*wiring, *([settings.supply] if settings.supply else [])]
        self._offset = np.array([w.offset_pa for w in cal])
        self._factor = np.array([w.gain * w.pa_per_count for w in cal])
        self._compiled: Any = None
        self._period = 1.0 / settings.sample_rate_hz
        self._t0 = time.monotonic()
        self._tick = 0
        #: Ticks whose sample was not taken within their period (skipped because the caller
        #: read late, or sampled after the period: the process woke late).
        self.missed_ticks = 0

    @property
    def channels(self) -> int:
        return len(self.settings.channels)

    @property
    def sample_rate_hz(self) -> float:
        return float(self.settings.sample_rate_hz)

    @property
    def supply_sensor(self) -> bool:
        """False without a ``[box.supply]`` sensor (frames then report 0 Pa)."""
        return self.settings.supply is not None

    def _read(self) -> PressureFrame:
        self._tick += 1
        due = self._t0 + self._tick * self._period
        now = time.monotonic()
        if now < due:
            time.sleep(due - now)
        elif now - due > self._period:
            late = int((now - due) / self._period)
            self.missed_ticks += late
            self._tick += late
        now = time.monotonic()
        if now - self._t0 - self._tick * self._period >= self._period:
            self.missed_ticks += 1  # woke more than a period late: sampled outside its period
        t = now - self._t0
        pa = self._offset + self._factor * self._iio.read_raw()
        n = self.channels
        supply = float(pa[n]) if self.settings.supply is not None else math.nan
        if self.settings.supply is None:
            supply = 0.0  # no supply sensor wired: reported as 0 (supply-loss checks off)
        return PressureFrame(t_s=t, pressures_pa=pa[:n].astype(np.float64), supply_pa=supply)

    def _levels(self, channel: int, inflate_open: bool, deflate_open: bool) -> dict[Any, bool]:
        """GPIO line levels of one channel's valves: active opens a normally-closed valve and
        closes a normally-open one (``box.inflate_valves`` / ``deflate_valves``)."""
        w = self.settings.channels[channel - 1]
        s = self.settings
        return {
            (w.gpiochip, w.inflate_line): inflate_open != (s.inflate_valves == "normally_open"),
            (w.gpiochip, w.deflate_line): deflate_open != (s.deflate_valves == "normally_open"),
        }

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        if command is ValveCommand.INFLATE and self._compiled is not None:
            if self._compiled.stats()["venting"][channel - 1]:  # it would re-vent next tick
                from softpad.box._safety import SafetyTrip

                raise SafetyTrip(
                    f"channel {channel} is being vented by the compiled guard (over the trip "
                    "level): inflation refused"
                )
        # close first, then open: never both valves of a channel open at once
        self._lines.set(self._levels(channel, False, False))
        if command is not ValveCommand.CLOSED:
            inflate = command is ValveCommand.INFLATE
            self._lines.set(self._levels(channel, inflate, not inflate))

    def start_guard(self, trip_pa: float, release_pa: float) -> bool:
        """Run the over-pressure guard in compiled code on its own thread, without the
        interpreter lock (:mod:`softpad.box._fastguard`): every period it reads each channel's
        IIO file and vents a channel above ``trip_pa`` (pascals) until it reads below
        ``release_pa``, whatever the Python side is doing. False (nothing started) when the
        extension is not built or the valve lines give no file descriptors (in-memory fakes).
        """
        try:
            from softpad.box._fastguard import Guard
        except ImportError:
            return False
        native = getattr(self._lines, "native", None)
        if native is None or self._compiled is not None:
            return self._compiled is not None
        s = self.settings
        root = Path(s.iio_root)
        wiring = s.channels
        lines = [
            (
                (*native(w.gpiochip, w.inflate_line), int(s.inflate_valves == "normally_open")),
                (*native(w.gpiochip, w.deflate_line), int(s.deflate_valves != "normally_open")),
            )
            for w in wiring
        ]
        self._compiled = Guard(
            [
                str(root / f"iio:device{w.iio_device}" / f"in_voltage{w.iio_channel}_raw")
                for w in wiring
            ],
            [w.offset_pa for w in wiring],
            [w.gain * w.pa_per_count for w in wiring],
            [inflate for inflate, _ in lines],
            [deflate for _, deflate in lines],
            float(trip_pa),
            float(release_pa),
            float(s.sample_rate_hz),
        )
        self._compiled.start()
        return True

    def guard_stats(self) -> dict[str, Any] | None:
        """The compiled guard's ticks, trips, missed ticks, bad reads and venting channels;
        None when it does not run."""
        return None if self._compiled is None else dict(self._compiled.stats())

    def _close(self) -> None:
        if self._compiled is not None:  # before the lines are released
            self._compiled.stop()
        # the base closed every inflation valve; a channel being vented keeps venting: its
        # deflation line is released as it is (issue 49: driving it inactive sealed it)
        try:
            self._lines.release()
        finally:
            self._iio.close()
