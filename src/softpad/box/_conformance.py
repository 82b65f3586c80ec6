"""Public conformance check that every box back-end must pass (like Gymnasium's env checker)."""

from __future__ import annotations

import math

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
        n = box.channels
        _require(isinstance(n, int) and n >= 1, f"channels must be a positive int, got {n!r}")
        rate = box.sample_rate_hz
        _require(
            isinstance(rate, float | int) and math.isfinite(rate) and rate > 0,
            f"sample_rate_hz must be > 0, got {rate!r}",
        )
        _require(not box.closed, "a freshly opened box must not be closed")
        _require(box.valves == (ValveCommand.CLOSED,) * n, "valves must start closed")
        last_t = -math.inf
        stamps = []
        for _ in range(frames):
            f = box.read()
            _require(
                isinstance(f, PressureFrame),
                f"read() must return a PressureFrame, got {type(f).__name__}",
            )
            p = f.pressures_pa
            _require(
                isinstance(p, np.ndarray) and p.shape == (n,),
                f"pressures_pa must have shape ({n},), got {getattr(p, 'shape', None)}",
            )
            _require(p.dtype == np.float64, f"pressures_pa must be float64, got {p.dtype}")
            _require(not np.isinf(p).any(), "pressures must be finite or NaN, never infinite")
            _require(
                math.isfinite(f.supply_pa), f"supply pressure must be finite, got {f.supply_pa!r}"
            )
            _require(f.t_s > last_t, f"time stamps must increase strictly ({f.t_s} after {last_t})")
            last_t = f.t_s
            stamps.append(f.t_s)
        if len(stamps) > 2:
            period = float(np.median(np.diff(stamps)))
            _require(
                abs(period * rate - 1) < 0.2,
                f"frames must come at sample_rate_hz ({rate} Hz), median period {period} s",
            )
        for bad in (0, n + 1, -1, 1.5, True):
            try:
                box.set_valve(bad, ValveCommand.CLOSED)  # type: ignore[arg-type]
            except InputError:
                pass
            else:
                raise ConformanceError(f"set_valve({bad!r}, ...) must raise InputError")
        try:
            box.set_valve(1, "open-ish")
        except InputError:
            pass
        else:
            raise ConformanceError("an unknown valve command must raise InputError")
        try:
            box.set_valves([ValveCommand.CLOSED] * (n + 1))
        except InputError:
            pass
        else:
            raise ConformanceError("set_valves with the wrong count must raise InputError")
        if exercise_valves:
            for ch in range(1, n + 1):
                box.set_valve(ch, "inflate")
                _require(
                    box.valves[ch - 1] is ValveCommand.INFLATE,
                    "valves must report the last command",
                )
                box.read()
                box.set_valve(ch, ValveCommand.DEFLATE)
                box.read()
                box.set_valve(ch, ValveCommand.CLOSED)
        box.set_valves(["inflate"] * n)
        box.close()
        _require(box.closed, "close() must mark the box closed")
        _require(box.valves == (ValveCommand.CLOSED,) * n, "close() must close every valve")
        box.close()  # idempotent
        try:
            box.read()
        except InputError:
            pass
        else:
            raise ConformanceError("read() after close() must raise InputError")
    finally:
        box.close()
