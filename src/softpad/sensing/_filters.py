"""Running-average filter, reference capture and pressure increments."""

from __future__ import annotations

from collections import deque

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError

#: Length of the running-average filter of the thesis (thesis, Section 6.3).
DEFAULT_FILTER_LENGTH = thesis.FILTER_WINDOW
#: Number of reads averaged into the reference (thesis, Fig. 6.8 caption).
DEFAULT_REFERENCE_READS = thesis.REFERENCE_READS


#: Largest gauge pressure, Pa, below which a whole vector of pressures and its reference are
#: taken for kilopascals given as pascals: a module adjusted to p0 reads 500 to 2800 Pa
#: (thesis Section 6.2), so no real reading pair lies entirely under 10 Pa but a quiet, deflated
#: pad, which reads 0.
PLAUSIBLE_PRESSURE_PA = 10.0


def _as_pressures(values: ArrayLike, name: str) -> NDArray[np.float64]:
    a = np.asarray(values, dtype=float)
    if a.ndim != 1:
        raise InputError(f"{name} must be a 1-D vector of pressures, got shape {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"{name}[module {i + 1}] must be finite, got {a[i]!r}")
    return a


class RunningAverage:
    """Running (moving) average over the last ``length`` frames, per channel.

    Until ``length`` frames have arrived the mean of those seen so far is returned.

    Parameters
    ----------
    length
        Number of samples averaged (10 in the thesis).
    """

    def __init__(self, length: int = DEFAULT_FILTER_LENGTH) -> None:
        if not isinstance(length, int) or length < 1:
            raise InputError(f"filter length must be an integer >= 1, got {length!r}")
        self.length = length
        self._buf: deque[NDArray[np.float64]] = deque(maxlen=length)
        self._sum: NDArray[np.float64] | None = None

    def reset(self) -> None:
        """Forget every sample."""
        self._buf.clear()
        self._sum = None

    @property
    def full(self) -> bool:
        """True once ``length`` samples have been seen."""
        return len(self._buf) == self.length

    def update(self, frame: ArrayLike) -> NDArray[np.float64]:
        """Add one frame (one value per channel) and return the current average."""
        x = np.asarray(frame, dtype=float).copy()
        if self._sum is None:
            self._sum = np.zeros_like(x)
        elif x.shape != self._sum.shape:
            raise InputError(
                f"frame has {x.size} channels, filter was started with {self._sum.size}"
            )
        if len(self._buf) == self.length:
            self._sum -= self._buf[0]
        self._buf.append(x)
        self._sum += x
        return self._sum / len(self._buf)


def capture_reference(reads: ArrayLike) -> NDArray[np.float64]:
    """Reference pressures: the mean of repeated reads, one row per read (Section 6.2.1.1).

    Parameters
    ----------
    reads
        Array of shape (n_reads, n_channels), pascals.
    """
    a = np.asarray(reads, dtype=float)
    if a.ndim != 2 or a.shape[0] < 1:
        raise InputError(f"reads must have shape (n_reads >= 1, n_channels), got {a.shape}")
    if not np.isfinite(a).all():
        raise InputError("reads for the reference contain NaN or infinite values")
    return a.mean(axis=0)


def increments(pressures: ArrayLike, reference: ArrayLike) -> NDArray[np.float64]:
    """Pressure increments dP_i = p_i - p_ref,i (pascals), checked for size and finiteness."""
    p = _as_pressures(pressures, "pressures")
    r = _as_pressures(reference, "reference")
    if p.shape != r.shape:
        raise InputError(f"got {p.size} pressures but {r.size} reference values")
    top = max(float(np.abs(p).max(initial=0.0)), float(np.abs(r).max(initial=0.0)))
    if 0.0 < top < PLAUSIBLE_PRESSURE_PA:
        raise InputError(
            f"pressures and reference are all under {PLAUSIBLE_PRESSURE_PA:g} Pa (largest "
            f"{top:g}): give pascals, not kPa (a module at p0 reads 500 to 2800 Pa)"
        )
    return p - r
