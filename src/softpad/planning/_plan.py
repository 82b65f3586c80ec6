"""Planner entry points: the :class:`Planner` protocol, the thesis's planner, ``plan_grasps``."""

from __future__ import annotations

from functools import lru_cache
from typing import Protocol, runtime_checkable

from numpy.typing import ArrayLike

from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout, parse_layout
from softpad.planning._params import PlannerParams
from softpad.planning._records import GraspPlan
from softpad.planning._thesis_rules import plan_with_rules
from softpad.sensing import check_increments, increments_list


@runtime_checkable
class Planner(Protocol):
    """Turns the increments of the objects found on the pad into grasp plans."""

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        """One plan per object (``objects``: sorted 1-based modules each), in grasp order; a
        planner that reads the increments may join objects it finds to be one (fewer plans)."""
        ...


@runtime_checkable
class RetryPlanner(Planner, Protocol):
    """A planner that has another grasp to try when the jaws came down on the object (the
    fingers sensed high above the pad: the object is wider than the jaws along the plan's
    closing direction, or the centre is off)."""

    def retry(
        self,
        plan: GraspPlan,
        increments_pa: ArrayLike,
        layout: PadLayout,
        landing_rise_pa: ArrayLike,
        closed: bool = True,
    ) -> GraspPlan | None:
        """The grasp to try after ``plan`` landed on its object and missed (``closed``), or
        at the landing before the jaws close (not ``closed``), or None when there is none
        worth trying. ``increments_pa``: the increments it was planned from;
        ``landing_rise_pa``: each module's rise over the pre-descent reference in the frame
        that sensed the fingers (where the landing jaw pressed the object into the pad)."""
        ...


@runtime_checkable
class MountingChooser(Protocol):
    """A planner that predicts how likely a grasp is to succeed with a given gripper: the
    hook with which ``--mounting auto`` chooses among the installed mountings the one with
    the highest predicted success (:func:`softpad.planning.choose_mounting`)."""

    def mounting_success(
        self,
        increments_pa: ArrayLike,
        objects: list[tuple[int, ...]],
        layout: PadLayout,
        gripper: GripperSpec,
    ) -> float:
        """Predicted success, in [0, 1], of this planner's grasp of the most loaded of
        ``objects`` (sorted 1-based modules each) with ``gripper``'s jaws."""
        ...


class ThesisPlanner:
    """The thesis's rules (Section 6.2.1.3), generalised to R x C pads (docs/planner.md).

    Parameters
    ----------
    params
        Planner parameters (t_o, c_s, default theta).
    """

    def __init__(self, params: PlannerParams | None = None) -> None:
        self.params = params or PlannerParams()

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        d = check_increments(increments_pa, layout)
        return [plan_with_rules(d, tuple(sorted(g)), layout, self.params) for g in objects]


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
        Pad geometry (2 x 3, 45 mm by default).
    params
        Planner parameters (thesis defaults).
    """
    if isinstance(layout, str):
        layout = parse_layout(layout)
    elif layout is not None and not isinstance(layout, PadLayout):
        raise InputError(f"layout must be a PadLayout or a string like '2x3', got {layout!r}")
    layout = layout or _DEFAULT_LAYOUT
    params = params or _DEFAULT_PARAMS
    d = increments_list(delta_pa, layout)
    t_o = params.object_threshold_pa
    touched = tuple(k for k, v in enumerate(d, 1) if v > t_o)
    return [plan_with_rules(d, g, layout, params) for g in _objects(layout, touched)]


_DEFAULT_LAYOUT = PadLayout()
_DEFAULT_PARAMS = PlannerParams()


@lru_cache(maxsize=4096)
def _objects(layout: PadLayout, touched: tuple[int, ...]) -> list[tuple[int, ...]]:
    """The objects of a set of touched modules: it depends on the set only (cached)."""
    return layout.connected_groups(touched)
