"""Grasp plan record."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

from softpad.layout import PadLayout


@dataclass(frozen=True)
class GraspPlan:
    """A planned top grasp for one object."""

    #: 1-based numbers of the modules the object touches (dP > t_o).
    modules: tuple[int, ...]
    #: Pressure-based centre of mass (x, y), module units (Eq. 6.1).
    pcom: tuple[float, float]
    #: Centre of grasp (x, y), module units.
    cog: tuple[float, float]
    #: Direction of grasp (the direction the jaws close), radians, in (-pi/2, pi/2].
    theta: float
    #: Name of the planning rule that produced the plan (see docs/planner.md).
    rule: str
    #: Modules the rule kept after dropping some (equal to ``modules`` when none was dropped).
    reduced_modules: tuple[int, ...]
    #: True when the plan hinged on an exact tie (PCOM exactly on a bisector, two axes at the
    #: same distance, two modules equally far) that a documented convention decided.
    tie_break: bool = False
    #: True for a grasp tried on a guess before the plans that follow it (two one-module
    #: objects taken as one long object resting on its ends, :func:`bridge_pairs`): when it
    #: holds, the loop sees the others go up with it; when it misses, they are grasped in
    #: turn and its miss does not count in the run's outcome.
    tentative: bool = False

    def cog_m(self, layout: PadLayout) -> tuple[float, float]:
        """Centre of grasp in metres in the pad frame (COG times the module pitch)."""
        x, y = layout.to_metres(self.cog)
        return float(x), float(y)

    def to_dict(self, layout: PadLayout) -> dict[str, Any]:
        """JSON-ready dict with the keys of ``softpad plan --json``."""
        return {
            "modules": list(self.modules),
            "pcom": [self.pcom[0], self.pcom[1]],
            "cog": [self.cog[0], self.cog[1]],
            "theta": self.theta,
            "rule": self.rule,
            "cog_m": list(self.cog_m(layout)),
            "tentative": self.tentative,
        }


_FIELDS = tuple(f.name for f in fields(GraspPlan))


def new_plan(*values: Any) -> GraspPlan:
    """``GraspPlan(*values)`` with every field given, in field order, built without the frozen
    dataclass's ``object.__setattr__`` per field (a third of a 2 x 3 plan's time; equal to
    the constructor's plan, which a test checks)."""
    if len(values) != len(_FIELDS):
        raise TypeError(f"new_plan takes all {len(_FIELDS)} fields, got {len(values)}")
    plan = object.__new__(GraspPlan)
    plan.__dict__.update(zip(_FIELDS, values, strict=True))
    return plan
