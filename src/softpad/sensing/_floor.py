"""How small a rise a contact detector catches: its step floor on a noisy idle module.

A planner that moves fingertips onto sensitive area needs to know how much of a fingertip's
rise the detector in use needs. :func:`step_floor_pa` measures it on the detector itself: many
idle modules with the box sensor's white noise, each stepping by one amplitude of a grid after
``settle_s`` (long enough for a CUSUM's starting allowance to fade); the floor is the smallest
step caught within ``window_s`` by at least half of the modules, none of which fired before the
step. Each module of the probe decides on its own (the detectors' per-module statistics), so
all amplitudes and repeats run as the columns of one stream. :func:`sensing_ratio` is the floor
over the thesis detector's at the same sample rate and noise: the share of a fingertip's rise
the detector needs compared with the thesis's.
"""

from __future__ import annotations

import math

import numpy as np

from softpad.errors import InputError
from softpad.sensing._contact import (
    ContactDetector,
    LatchingContactDetector,
    ThesisContactDetector,
)

#: White noise of one sample of the box's pressure sensor, pascals (the simulated sensor's
#: default, softpad.sim.SensorParams.noise_std_pa).
DEFAULT_FLOOR_NOISE_PA = 8.0
#: Step amplitudes tried, pascals (2 Pa steps up to 300 Pa: above the thesis's t_g of 90 Pa).
_AMPLITUDES_PA = np.arange(2.0, 302.0, 2.0)
#: Repeats per amplitude (the floor's 50 % point has a binomial spread of 1/sqrt(4 x 32)).
_REPEATS = 32
#: Floors measured in this process, by settings.
_FLOORS: dict[tuple[object, ...], float] = {}


def step_floor_pa(
    detector: ContactDetector,
    sample_rate_hz: float,
    noise_std_pa: float = DEFAULT_FLOOR_NOISE_PA,
    settle_s: float = 1.5,
    window_s: float = 0.2,
) -> float:
    """Smallest step of one module's pressure the detector catches in half of the trials,
    pascals (inf: none up to 300 Pa). Deterministic (fixed noise seed); cached per settings."""
    for name, value in (("sample rate", sample_rate_hz), ("window", window_s)):
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"{name} must be a number > 0, got {value!r}")
    if not (math.isfinite(noise_std_pa) and noise_std_pa >= 0):
        raise InputError(f"sensor noise must be a number of Pa >= 0, got {noise_std_pa!r}")
    if not (math.isfinite(settle_s) and settle_s >= 0):
        raise InputError(f"settling time must be a number of s >= 0, got {settle_s!r}")
    if not isinstance(detector, LatchingContactDetector):
        raise InputError(
            f"{type(detector).__name__} is not a LatchingContactDetector: its modules cannot "
            "be probed apart, its floor is unknown"
        )
    if detector.floor_key is None:
        raise InputError(f"{type(detector).__name__} states no floor_key: its floor is unknown")
    key = (detector.floor_key, sample_rate_hz, noise_std_pa, settle_s, window_s)
    if key not in _FLOORS:
        probe = detector.floor_probe()
        _FLOORS[key] = _measure(probe, sample_rate_hz, noise_std_pa, settle_s, window_s)
    return _FLOORS[key]


def _measure(
    probe: LatchingContactDetector, rate: float, noise: float, settle_s: float, window_s: float
) -> float:
    amplitude = np.repeat(_AMPLITUDES_PA, _REPEATS)
    rng = np.random.default_rng(20261124)
    probe.reset(np.zeros(amplitude.size))
    k_step = round(settle_s * rate)
    early = np.zeros(amplitude.size, dtype=bool)
    caught = np.zeros(amplitude.size, dtype=bool)
    for k in range(k_step + max(1, round(window_s * rate))):
        rise = rng.normal(0.0, noise, amplitude.size) + (amplitude if k >= k_step else 0.0)
        fired = probe._exceeds(rise)
        if k < k_step:
            early |= fired
        else:
            caught |= fired
    share = (caught & ~early).reshape(_AMPLITUDES_PA.size, _REPEATS).mean(axis=1)
    above = np.flatnonzero(share >= 0.5)
    return float(_AMPLITUDES_PA[above[0]]) if above.size else math.inf


def sensing_ratio(
    detector: ContactDetector,
    sample_rate_hz: float,
    noise_std_pa: float = DEFAULT_FLOOR_NOISE_PA,
) -> float | None:
    """The detector's step floor over the thesis detector's at the same rate and noise (the
    share of a fingertip's rise it needs, the thesis's being 1); None for a detector whose
    modules cannot be probed apart (not a :class:`LatchingContactDetector`, or one that
    states no ``floor_key``)."""
    if not isinstance(detector, LatchingContactDetector) or detector.floor_key is None:
        return None
    reference = step_floor_pa(ThesisContactDetector(), sample_rate_hz, noise_std_pa)
    return step_floor_pa(detector, sample_rate_hz, noise_std_pa) / reference
