"""Object detection: modules above t_o, grouped into 8-connected objects."""

from __future__ import annotations

import math
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout

#: t_o (:data:`softpad.thesis.OBJECT_THRESHOLD_PA`).
DEFAULT_OBJECT_THRESHOLD_PA = thesis.OBJECT_THRESHOLD_PA
#: t_g (:data:`softpad.thesis.CONTACT_THRESHOLD_PA`).
DEFAULT_CONTACT_THRESHOLD_PA = thesis.CONTACT_THRESHOLD_PA


#: Full scale of the module pressure sensors (gauge), pascals: an increment above it is not
#: a pressure a module can show (pascals given as kPa, or a broken frame).
SENSOR_FULL_SCALE_PA = 10_000.0
#: Below this, a non-zero set of increments is under the converter's resolution (2.4 Pa) and
#: the sensor noise (8 Pa): kPa values given as pascals.
SMALLEST_PLAUSIBLE_INCREMENT_PA = 1.0


def measured_change(delta_pa: ArrayLike) -> NDArray[np.float64]:
    """A change the loop measured (reads minus the reference), as increments for the detectors
    and planners: zeros when every module changed by less than
    :data:`SMALLEST_PLAUSIBLE_INCREMENT_PA`.

    An average of quantised reads minus an averaged reference can land anywhere between the
    converter's steps, so a quiet pad can measure a fraction of a pascal on every module;
    :func:`check_increments` takes such a vector for kPa given as pascals, which is right for
    numbers a user typed and wrong for a measurement. Under a pascal on every module (far under
    the noise and every threshold) is no change."""
    d = np.asarray(delta_pa, dtype=float)
    if d.size and np.all(np.abs(d) < SMALLEST_PLAUSIBLE_INCREMENT_PA):
        return np.zeros_like(d)
    return d


def check_increments(delta_pa: ArrayLike, layout: PadLayout) -> np.ndarray:
    """Validate an increment vector against a layout and return it as floats.

    Raises :class:`InputError` for a wrong length, non-finite values, an increment beyond the
    sensor's full scale (10 kPa: pascals given as kPa?) or a non-zero vector whose largest
    increment is under 1 Pa (kPa given as pascals?).
    """
    if not isinstance(layout, PadLayout):
        raise InputError(
            f"layout must be a PadLayout (parse_layout('2x3') for a name), got {layout!r}"
        )
    try:
        d = np.asarray(delta_pa, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"increments must be numbers in pascals, got {delta_pa!r}") from None
    if d.ndim != 1 or d.size != layout.n_modules:
        raise InputError(
            f"a {layout.name} pad needs {layout.n_modules} increments (modules 1..{layout.n_modules}), "
            f"got {d.size}"
        )
    # the usual case: every value finite (so is their sum), the largest magnitude within the
    # full scale and not a lone sub-pascal vector; a pad's few values are checked faster in
    # Python than by numpy's reductions (the planner's budget is 20 us a plan)
    values = d.tolist()
    top = max(map(abs, values)) if values else 0.0
    if (
        math.isfinite(sum(values))
        and top <= SENSOR_FULL_SCALE_PA
        and not 0.0 < top < SMALLEST_PLAUSIBLE_INCREMENT_PA
    ):
        return d
    top = float(np.abs(d).max()) if d.size else 0.0
    bad = ~np.isfinite(d)
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"increment of module {i + 1} must be finite, got {d[i]!r}")
    big = np.abs(d) > SENSOR_FULL_SCALE_PA
    if big.any():
        i = int(np.argmax(big))
        raise InputError(
            f"increment of module {i + 1} is {d[i]:g} Pa ({d[i] / 1e3:g} kPa), beyond the sensor's "
            f"{SENSOR_FULL_SCALE_PA / 1e3:g} kPa full scale: were pascals given as kPa?"
        )
    if 0.0 < top < SMALLEST_PLAUSIBLE_INCREMENT_PA:
        raise InputError(
            f"every increment is below {SMALLEST_PLAUSIBLE_INCREMENT_PA:g} Pa (largest {top:g} Pa), "
            "under the sensor's resolution: were kPa given as pascals? (increments are in Pa)"
        )
    return d


def increments_list(delta_pa: ArrayLike, layout: PadLayout) -> list[float]:
    """:func:`check_increments` as a list of floats; a list or tuple of numbers that passes
    is checked without numpy (a few microseconds less in every plan), anything else as there."""
    if isinstance(delta_pa, list | tuple) and len(delta_pa) == layout.n_modules:
        try:
            values = [float(v) for v in delta_pa]
        except (TypeError, ValueError):
            values = []
        top = max(map(abs, values)) if values else math.inf
        if (
            math.isfinite(sum(values))
            and top <= SENSOR_FULL_SCALE_PA
            and not 0.0 < top < SMALLEST_PLAUSIBLE_INCREMENT_PA
        ):
            return values
    return check_increments(delta_pa, layout).tolist()  # type: ignore[no-any-return]


def check_threshold(threshold_pa: float, name: str = "threshold", positive: bool = False) -> float:
    """Validate a detection threshold: finite, >= 0 Pa (> 0 with ``positive``), within the
    sensor's full scale."""
    if isinstance(threshold_pa, str | bytes):  # float("50") would pass: text is a slip
        raise InputError(f"{name} must be a pressure in pascals, got the text {threshold_pa!r}")
    try:
        t = float(threshold_pa)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a pressure in pascals, got {threshold_pa!r}") from None
    if not np.isfinite(t) or t < 0 or (positive and t == 0):
        bound = "> 0" if positive else ">= 0"
        raise InputError(f"{name} must be a finite pressure {bound} kPa, got {t / 1e3:g} kPa")
    if t > SENSOR_FULL_SCALE_PA:
        raise InputError(
            f"{name} is {t:g} Pa, beyond the sensor's {SENSOR_FULL_SCALE_PA / 1e3:g} kPa full "
            "scale: were pascals given as kPa?"
        )
    if 0.0 < t < SMALLEST_PLAUSIBLE_INCREMENT_PA:
        raise InputError(
            f"{name} is {t:g} Pa, under the sensor's resolution: were kPa given as pascals? "
            f"(thresholds are in Pa, e.g. {thesis.OBJECT_THRESHOLD_PA:g} for the thesis's t_o of "
            f"{thesis.OBJECT_THRESHOLD_PA / 1e3:g} kPa)"
        )
    return t


def detect_objects(
    delta_pa: ArrayLike,
    layout: PadLayout,
    threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA,
) -> list[tuple[int, ...]]:
    """Modules touched by objects, grouped into separate objects.

    A module is touched when its increment is strictly above ``threshold_pa`` (t_o). Touched
    modules that are not 8-connected belong to different objects (thesis, Section 6.2.1.3:
    bridge-shaped objects are not handled).

    Returns
    -------
    list of tuple of int
        One sorted tuple of 1-based module numbers per object, ordered by their first module.
    """
    d = check_increments(delta_pa, layout)
    t = check_threshold(threshold_pa)
    touched = [int(k) + 1 for k in np.flatnonzero(d > t)]
    return layout.connected_groups(touched)


#: Threshold on dP of a module counted in an object's outline, pascals. The increment is the
#: mean of 10 reads minus the 10-read reference: the simulated sensor's 8 Pa rms white noise
#: per sample (docs/box-and-simulator.md) gives 8 x sqrt(1/10 + 1/10) = 3.6 Pa rms, and its
#: slow drift (3 Pa rms, 2 s correlation) up to 4.2 Pa between reference and plan: 5.5 Pa rms
#: together. 25 Pa is 4.5 of those, so an unloaded neighbour joins an outline about once in
#: 10^5 plans; a real sensor's noise sets this value on an installation.
DEFAULT_OUTLINE_THRESHOLD_PA = 25.0


def outline_objects(
    delta_pa: ArrayLike,
    objects: list[tuple[int, ...]],
    layout: PadLayout,
    threshold_pa: float = DEFAULT_OUTLINE_THRESHOLD_PA,
) -> list[tuple[int, ...]]:
    """The objects found at t_o, outlined at the noise floor.

    A module next to an object's (8-neighbour) whose increment is above ``threshold_pa``
    carries part of that object too light to pass t_o (the ends of a banana, a can's light
    side); it joins the object, and two objects such a module touches both become one (a
    banana on modules 2, 3 and 4 whose middle on module 2 stays under t_o). Modules not next
    to an object found at t_o are not added: the threshold outlines objects, it finds none.

    Returns
    -------
    list of tuple of int
        One sorted tuple of 1-based modules per object, ordered by their first module.
    """
    d = check_increments(delta_pa, layout)
    t = check_threshold(threshold_pa, "outline threshold")
    found = {m for obj in objects for m in obj}
    near = {n for m in found for n in layout.neighbours(m)}  # checks every module number
    extra = {n for n in near - found if d[n - 1] > t}
    return layout.connected_groups(sorted(found | extra))


@runtime_checkable
class ObjectDetector(Protocol):
    """Finds the objects lying on the pad from (filtered) pressure increments."""

    def objects(self, increments_pa: ArrayLike, layout: PadLayout) -> list[tuple[int, ...]]:
        """One sorted tuple of 1-based modules per object; empty when nothing lies there."""
        ...


class ThesisObjectDetector:
    """The thesis's detector: modules above t_o, 8-connected groups (Section 6.2.1.2).

    Parameters
    ----------
    threshold_pa
        t_o, pascals (:data:`softpad.thesis.OBJECT_THRESHOLD_PA`).
    """

    def __init__(self, threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA) -> None:
        self.threshold_pa = check_threshold(threshold_pa, "object threshold")

    def objects(self, increments_pa: ArrayLike, layout: PadLayout) -> list[tuple[int, ...]]:
        return detect_objects(increments_pa, layout, self.threshold_pa)
