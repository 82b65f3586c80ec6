"""Public conformance check that every box back-end must pass (like Gymnasium's env checker)."""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from softpad.box._base import Box, PressureFrame, ValveCommand
from softpad.errors import InputError


class ConformanceError(AssertionError):
    """A back-end breaks the box contract; the message says which rule."""


def _require(cond: bool, rule: str) -> None:
    if not cond:
        raise ConformanceError(rule)


def check_conformance(box: Box, frames: int = 20, exercise_valves: bool = True) -> None:
    """Check that ``box`` honours the :class:`~softpad.box.Box` contract; raise otherwise.

    Checked: channel count and sample rate are sane; frames are :class:`PressureFrame` with
    one finite-or-NaN float per channel, a finite supply pressure and strictly increasing
    time stamps spaced about one sample period apart; valve commands by member and by name
    are accepted and reported by :attr:`Box.valves`; bad channels and commands raise
    :class:`~softpad.errors.InputError`; :meth:`Box.close` closes every valve, is idempotent,
    and reads afterwards raise. The box is closed on return.

    Parameters
    ----------
    box
        An open box. Valves are only pulsed for one frame each when ``exercise_valves``.
    frames
        Frames to read.
    exercise_valves
        Also command every channel to inflate/deflate briefly (harmless on a real pad).
    """
    try:
        n, rate = _check_identity(box)
        _check_frames(box, n, rate, frames)
        _check_refusals(box, n)
        if exercise_valves:
            _exercise_valves(box, n)
        _check_close(box, n)
    finally:
        box.close()


def _check_identity(box: Box) -> tuple[int, float]:
    """Channel count and sample rate sane; a fresh box open with every valve closed."""
    n = box.channels
    _require(isinstance(n, int) and n >= 1, f"channels must be a positive int, got {n!r}")
    rate = box.sample_rate_hz
    _require(
        isinstance(rate, float | int) and math.isfinite(rate) and rate > 0,
        f"sample_rate_hz must be > 0, got {rate!r}",
    )
    _require(not box.closed, "a freshly opened box must not be closed")
    _require(box.valves == (ValveCommand.CLOSED,) * n, "valves must start closed")
    return n, float(rate)


def _check_frame(f: object, n: int, last_t: float) -> float:
    """One frame's type, shape, values and stamp; returns its stamp."""
    _require(
        isinstance(f, PressureFrame),
        f"read() must return a PressureFrame, got {type(f).__name__}",
    )
    assert isinstance(f, PressureFrame)
    p = f.pressures_pa
    _require(
        isinstance(p, np.ndarray) and p.shape == (n,),
        f"pressures_pa must have shape ({n},), got {getattr(p, 'shape', None)}",
    )
    _require(p.dtype == np.float64, f"pressures_pa must be float64, got {p.dtype}")
    _require(not np.isinf(p).any(), "pressures must be finite or NaN, never infinite")
    _require(math.isfinite(f.supply_pa), f"supply pressure must be finite, got {f.supply_pa!r}")
    _require(f.t_s > last_t, f"time stamps must increase strictly ({f.t_s} after {last_t})")
    return float(f.t_s)


def _check_frames(box: Box, n: int, rate: float, frames: int) -> None:
    """``frames`` frames, stamps about one sample period apart."""
    stamps = [-math.inf]
    for _ in range(frames):
        stamps.append(_check_frame(box.read(), n, stamps[-1]))
    if len(stamps) > 3:
        period = float(np.median(np.diff(stamps[1:])))
        _require(
            abs(period * rate - 1) < 0.2,
            f"frames must come at sample_rate_hz ({rate} Hz), median period {period} s",
        )


def _refused(call: Callable[[], object], message: str) -> None:
    """``call`` must raise InputError, else ConformanceError(message)."""
    try:
        call()
    except InputError:
        return
    raise ConformanceError(message)


def _check_refusals(box: Box, n: int) -> None:
    """Bad channels, commands and counts raise InputError."""
    bad_channels: tuple[Any, ...] = (0, n + 1, -1, 1.5, True)
    for bad in bad_channels:
        _refused(
            functools.partial(box.set_valve, bad, ValveCommand.CLOSED),
            f"set_valve({bad!r}, ...) must raise InputError",
        )
    _refused(lambda: box.set_valve(1, "open-ish"), "an unknown valve command must raise InputError")
    _refused(
        lambda: box.set_valves([ValveCommand.CLOSED] * (n + 1)),
        "set_valves with the wrong count must raise InputError",
    )


def _exercise_valves(box: Box, n: int) -> None:
    """Every channel inflates and deflates for one frame each; valves report the command."""
    for ch in range(1, n + 1):
        box.set_valve(ch, "inflate")
        _require(box.valves[ch - 1] is ValveCommand.INFLATE, "valves must report the last command")
        box.read()
        box.set_valve(ch, ValveCommand.DEFLATE)
        box.read()
        box.set_valve(ch, ValveCommand.CLOSED)


def _check_close(box: Box, n: int) -> None:
    """close() closes every valve, is idempotent, and reads afterwards raise."""
    box.set_valves(["inflate"] * n)
    box.close()
    _require(box.closed, "close() must mark the box closed")
    _require(box.valves == (ValveCommand.CLOSED,) * n, "close() must close every valve")
    box.close()  # idempotent
    _refused(box.read, "read() after close() must raise InputError")
