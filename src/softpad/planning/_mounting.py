"""The gripper mounting chosen from the pad's readings (``--mounting auto``; issue 45).

The thesis mounted the Sawyer's fingers in one of three ways per object (Section 6.3: maximum
and minimum width 10/4, 6/2 or 4/0 cm), chosen by the experimenters who saw the object. On
objects nobody measured, a lab chooses from what the pad tells: the object's modules give its
reach along the planned direction of grasp (:func:`reach_m`), and the jaws must open beyond it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout

#: Every mounting of the thesis, the default installed set.
ALL_MOUNTINGS = tuple(thesis.GRIPPER_MOUNTINGS_M)


def choose_mounting(
    delta_pa: ArrayLike,
    layout: PadLayout | None = None,
    installed: Sequence[str] = ALL_MOUNTINGS,
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA,
    planner: Any | None = None,
) -> str:
    """The installed mounting for the most loaded object the pad reads.

    With a ``planner`` that predicts its grasps' success (a
    :class:`~softpad.planning.MountingChooser`, e.g. the model-based planner), the mounting
    is a decision: the installed one under which the planner's grasp of the most loaded
    object has the highest predicted success (the narrowest of equals). Otherwise:

    The thesis's planner plans every object above ``threshold_pa`` (t_o); for the one with
    the largest summed increment, :func:`reach_m` estimates its width along the planned
    direction of grasp. The mounting is the installed one with the narrowest maximum opening
    that exceeds it (finer jaws where they fit, as the thesis mounted 6/2 on most objects);
    when none does, or nothing is seen, the widest.

    Parameters
    ----------
    delta_pa
        Increment of every module over its reference, pascals, module order.
    layout
        Pad geometry (2 x 3, 45 mm by default).
    installed
        Names of the mountings at hand (``"10/4"``, ``"6/2"``, ``"4/0"``).
    threshold_pa
        Object threshold t_o, pascals.
    planner
        The planner that will grasp; used when it is a ``MountingChooser``.

    Returns
    -------
    The mounting's name.
    """
    from softpad.planning._params import PlannerParams
    from softpad.planning._plan import plan_grasps

    names = list(installed)
    unknown = [n for n in names if n not in thesis.GRIPPER_MOUNTINGS_M]
    if not names or unknown:
        raise InputError(
            f"installed mountings must be among {', '.join(ALL_MOUNTINGS)}, got {names!r}"
        )
    layout = layout or PadLayout()
    d = [float(v) for v in np.asarray(delta_pa, dtype=float).ravel()]
    by_width = sorted(names, key=lambda n: thesis.GRIPPER_MOUNTINGS_M[n][0])
    plans = plan_grasps(d, layout, PlannerParams(object_threshold_pa=threshold_pa))
    if not plans:
        return by_width[-1]
    from softpad.planning._plan import MountingChooser

    if isinstance(planner, MountingChooser):
        return _most_successful(planner, d, [p.modules for p in plans], layout, by_width)
    best = max(plans, key=lambda p: sum(d[m - 1] for m in p.modules))
    extent = reach_m(best.modules, best.theta, layout)
    fits = [n for n in by_width if thesis.GRIPPER_MOUNTINGS_M[n][0] > extent]
    return fits[0] if fits else by_width[-1]


def _most_successful(
    planner: Any,
    d: list[float],
    objects: list[tuple[int, ...]],
    layout: PadLayout,
    by_width: list[str],
) -> str:
    """The mounting of ``by_width`` (narrowest first) with the highest predicted success of
    ``planner``'s grasp; the narrowest of equals."""
    from softpad.layout import GripperSpec

    best, best_p = by_width[-1], -1.0
    for name in by_width:
        p = planner.mounting_success(d, objects, layout, GripperSpec.from_mounting(name))
        if p > best_p:
            best, best_p = name, p
    return best


def reach_m(modules: Sequence[int], theta: float, layout: PadLayout) -> float:
    """Estimated width of an object along ``theta`` from the modules it presses, metres: the
    span of their centres along ``theta`` plus one pitch (an object seen on one module is
    taken as wide as the module; the modules' full squares, an upper bound, would reach
    sqrt(2) pitches along a diagonal and send a 32 mm plate to the 10/4 mounting, too wide
    to close on it)."""
    d = np.array([np.cos(theta), np.sin(theta)])
    proj = np.array([np.asarray(layout.center(k)) for k in modules]) @ d
    return float(proj.max() - proj.min() + 1.0) * layout.pitch_m
