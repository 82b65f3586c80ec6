"""Parameters of the thesis's grasp planner."""

from __future__ import annotations

import math
from dataclasses import dataclass

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.sensing import DEFAULT_OBJECT_THRESHOLD_PA, check_threshold

#: c_s in the thesis: safety shift for corner-shaped objects, module units (Section 6.2.1.3).
DEFAULT_SAFETY_SHIFT = thesis.SAFETY_SHIFT


@dataclass(frozen=True)
class PlannerParams:
    """Parameters of the grasp planner."""

    #: t_o: a module is touched when dP > t_o, pascals (:data:`softpad.thesis.OBJECT_THRESHOLD_PA`).
    object_threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA
    #: c_s: shift away from the corner of corner-shaped objects, module units, 0.2 in the thesis.
    safety_shift: float = DEFAULT_SAFETY_SHIFT
    #: Direction used when the shape gives none (N = 1, 2x2 square), radians.
    default_theta: float = 0.0

    def __post_init__(self) -> None:
        check_threshold(self.object_threshold_pa, "object threshold")
        check_finite("planner safety_shift", self.safety_shift)
        check_finite("planner default_theta", self.default_theta)
        if not (0.0 <= self.safety_shift < 0.5):
            raise InputError(
                f"safety shift must be in [0, 0.5) module units, got {self.safety_shift!r}"
            )
        if not math.isfinite(self.default_theta):
            raise InputError(
                f"default theta must be a finite angle in rad, got {self.default_theta!r}"
            )
