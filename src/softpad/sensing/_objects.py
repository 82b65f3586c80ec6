"""Object detection: modules above t_o, grouped into 8-connected objects."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout

#: t_o (:data:`softpad.thesis.OBJECT_THRESHOLD_PA`).
DEFAULT_OBJECT_THRESHOLD_PA = thesis.OBJECT_THRESHOLD_PA
#: t_g (:data:`softpad.thesis.CONTACT_THRESHOLD_PA`).
DEFAULT_CONTACT_THRESHOLD_PA = thesis.CONTACT_THRESHOLD_PA


def check_increments(delta_pa: ArrayLike, layout: PadLayout) -> np.ndarray:
    """Validate an increment vector against a layout and return it as floats."""
    d = np.asarray(delta_pa, dtype=float)
    if d.ndim != 1 or d.size != layout.n_modules:
        raise InputError(
            f"a {layout.name} pad needs {layout.n_modules} increments (modules 1..{layout.n_modules}), "
            f"got {d.size}"
        )
    bad = ~np.isfinite(d)
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"increment of module {i + 1} must be finite, got {d[i]!r}")
    return d


def check_threshold(threshold_pa: float, name: str = "threshold") -> float:
    """Validate a detection threshold (finite, >= 0 Pa)."""
    t = float(threshold_pa)
    if not np.isfinite(t) or t < 0:
        raise InputError(f"{name} must be a finite pressure >= 0 kPa, got {t / 1e3:g} kPa")
    return t


def detect_objects(
    delta_pa: ArrayLike,
    layout: PadLayout,
    threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA,
) -> list[tuple[int, ...]]:
    """Modules touched by objects, grouped into separate objects.

    A module is touched when its increment is strictly above ``threshold_pa`` (t_o). Touched
    modules that are not 8-connected belong to different objects (seed, Section 6.2.1.3:
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
