"""Gripper-contact detection: the :class:`ContactDetector` protocol and the thesis's detector."""

from __future__ import annotations

import copy
from collections.abc import Iterable
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.sensing._filters import DEFAULT_FILTER_LENGTH, RunningAverage
from softpad.sensing._objects import DEFAULT_CONTACT_THRESHOLD_PA, check_threshold


@runtime_checkable
class ContactDetector(Protocol):
    """A streaming detector of the fingers touching the pad.

    The execution calls :meth:`reset` with the pressures read just before the descent (object
    on the pad, fingers above it), then :meth:`update` with every frame of the descent until it
    returns True; :attr:`triggered_modules` then names the modules that showed the contact.
    """

    @property
    def triggered_modules(self) -> tuple[int, ...]:
        """1-based modules that triggered the detection (empty before it)."""
        ...

    def reset(self, reference_pa: ArrayLike) -> None:
        """Start over, taking increments from ``reference_pa`` (one value per module, Pa)."""
        ...

    def update(self, pressures_pa: ArrayLike) -> bool:
        """Feed one frame (Pa per module); True once contact is detected, and from then on."""
        ...


class LatchingContactDetector:
    """Base of the contact detectors that latch on a per-module statistic of the rise.

    Every frame's rise over the reference (Pa per module) goes to :meth:`_exceeds`; the
    first frame where any module's statistic exceeds its threshold names the triggered
    modules, and :meth:`update` returns True from then on until :meth:`reset`. Subclasses
    implement :meth:`_exceeds` and :meth:`_restart`.
    """

    def __init__(self) -> None:
        self.reference_pa: NDArray[np.float64] | None = None
        self._triggered: tuple[int, ...] = ()

    @property
    def triggered_modules(self) -> tuple[int, ...]:
        return self._triggered

    @property
    def floor_key(self) -> tuple[object, ...] | None:
        """A hashable description of the detector's settings (the step floor's cache key);
        None: not stated, and the detector's step floor is not measured."""
        return None

    def floor_probe(self) -> LatchingContactDetector:
        """A copy whose modules decide independently (:func:`softpad.sensing.step_floor_pa`
        feeds it many modules at once)."""
        return copy.deepcopy(self)

    def reset(self, reference_pa: ArrayLike) -> None:
        self.reference_pa = np.asarray(reference_pa, dtype=float).copy()
        self._triggered = ()
        self._restart(self.reference_pa.shape[0])

    def update(self, pressures_pa: ArrayLike) -> bool:
        if self._triggered:
            return True
        if self.reference_pa is None:
            raise RuntimeError(f"{type(self).__name__}.update called before reset")
        rise = np.asarray(pressures_pa, dtype=float) - self.reference_pa
        hits = np.flatnonzero(self._exceeds(rise))
        self._triggered = tuple(int(k) + 1 for k in hits)
        return bool(self._triggered)

    def _restart(self, modules: int) -> None:
        """Clear the statistic's state for a pad of ``modules`` modules."""
        raise NotImplementedError

    def _exceeds(self, rise_pa: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Whether each module's statistic exceeds its threshold after this frame's rise."""
        raise NotImplementedError


class ThesisContactDetector(LatchingContactDetector):
    """The thesis's contact detector (thesis, Section 6.2.2).

    Contact is declared on the first frame where the running average (``window`` samples) of
    any module's increment over its reference exceeds ``threshold_pa`` (t_g). The filter starts
    primed with ``window`` zero increments (the reference itself), so one noise spike at the
    start cannot trigger it before the window has filled.

    Parameters
    ----------
    threshold_pa
        t_g, pascals (:data:`softpad.thesis.CONTACT_THRESHOLD_PA`).
    window
        Running-average length, samples (:data:`softpad.thesis.FILTER_WINDOW`).
    reference_pa
        Optional reference to start with (same as calling :meth:`reset`).
    """

    def __init__(
        self,
        threshold_pa: float = DEFAULT_CONTACT_THRESHOLD_PA,
        window: int = DEFAULT_FILTER_LENGTH,
        reference_pa: ArrayLike | None = None,
    ) -> None:
        super().__init__()
        self.threshold_pa = check_threshold(threshold_pa, "contact threshold")
        self._filter = RunningAverage(window)
        if reference_pa is not None:
            self.reset(reference_pa)

    @property
    def floor_key(self) -> tuple[object, ...]:
        return ("thesis", self.threshold_pa, self._filter.length)

    def _restart(self, modules: int) -> None:
        self._filter.reset()
        for _ in range(self._filter.length):  # primed with zero increments (the reference)
            self._filter.update(np.zeros(modules))

    def _exceeds(self, rise_pa: NDArray[np.float64]) -> NDArray[np.bool_]:
        filtered: NDArray[np.float64] = self._filter.update(rise_pa)
        return filtered > self.threshold_pa


def count_alarms(
    detector: ContactDetector,
    reference_pa: ArrayLike,
    frames: Iterable[ArrayLike],
    rearm_only: bool = False,
) -> int:
    """Contact alarms of ``detector`` over ``frames`` (Pa per module) on which nothing touches
    the pad: every one is false. The detector starts from ``reference_pa`` (goes on from its
    state with ``rearm_only``) and is re-armed with it after every alarm."""
    if not rearm_only:
        detector.reset(reference_pa)
    alarms = 0
    for pressures_pa in frames:
        if detector.update(pressures_pa):
            alarms += 1
            detector.reset(reference_pa)
    return alarms
