"""Planner entry points: objects from increments, one plan per object."""

from __future__ import annotations

import math
from dataclasses import dataclass

from numpy.typing import ArrayLike

from softpad.errors import InputError, check_finite
from softpad.layout import PadLayout, parse_layout
from softpad.planning._records import GraspPlan
from softpad.sensing._objects import (
    DEFAULT_OBJECT_THRESHOLD_PA,
    check_increments,
    check_threshold,
)

#: c_s in the thesis: safety shift for corner-shaped objects, module units (Section 6.2.1.3).
DEFAULT_SAFETY_SHIFT = 0.2


@dataclass(frozen=True)
class PlannerParams:
    """Parameters of the grasp planner.

    Parameters
    ----------
    object_threshold_pa
        t_o: a module is touched when dP > t_o (pascals), 50 Pa in the thesis.
    safety_shift
        c_s: shift away from the corner of corner-shaped objects, module units, 0.2 in the thesis.
    default_theta
        Direction used when the shape gives none (N = 1, 2x2 square), radians.
    """

    object_threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA
    safety_shift: float = DEFAULT_SAFETY_SHIFT
    default_theta: float = 0.0

    def __post_init__(self) -> None:
        check_threshold(self.object_threshold_pa, "object threshold")
        if not (0.0 <= self.safety_shift < 0.5):
            raise InputError(
                f"safety shift must be in [0, 0.5) module units, got {self.safety_shift!r}"
            )
        theta = check_finite("default_theta (radians)", self.default_theta)
        if abs(theta) > 2 * math.pi:
            raise InputError(
                f"default_theta must be within -2 pi..2 pi radians, got {theta!r}: degrees?"
            )


def plan_object(
    delta_pa: ArrayLike,
    modules: tuple[int, ...],
    layout: PadLayout,
    params: PlannerParams | None = None,
) -> GraspPlan:
    """Plan the grasp of one object that touches ``modules``."""
    from softpad.planning._thesis_rules import plan_with_rules

    d = check_increments(delta_pa, layout)
    return plan_with_rules(d, tuple(sorted(modules)), layout, params or PlannerParams())


def plan_grasps(
    delta_pa: ArrayLike,
    layout: PadLayout | str | None = None,
    params: PlannerParams | None = None,
) -> list[GraspPlan]:
    """Detect the objects on the pad and plan a grasp for each, in module order.

    Parameters
    ----------
    delta_pa
        Increment dP_i of every module over its reference, pascals, module order 1..N.
    layout
        Pad geometry (2 x 3, 45 mm by default), or a layout string such as ``"2x3"``.
    params
        Planner parameters (thesis defaults).
    """
    from softpad.planning._thesis_rules import plan_with_rules

    if isinstance(layout, str):
        layout = parse_layout(layout)
    elif layout is not None and not isinstance(layout, PadLayout):
        raise InputError(f"layout must be a PadLayout or a string like '2x3', got {layout!r}")
    layout = layout or PadLayout()
    params = params or PlannerParams()
    d = check_increments(delta_pa, layout)
    touched = [k + 1 for k, v in enumerate(d.tolist()) if v > params.object_threshold_pa]
    return [plan_with_rules(d, g, layout, params) for g in layout.connected_groups(touched)]
