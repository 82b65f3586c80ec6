"""The objects' unknowns fitted to the thesis's plans of them (issue 45: calibration apart).

The seed gives each object of Table 6.1 its mass and the plan the thesis's planner made of
it, but for five objects not the shape or mass distribution that decide the plan: the can's
end weight, the charger's mass split, the limes' arrangement, the toy's shape, the banana's
curve. Each is one uncertain input with a sourced range (:data:`softpad.sim.OBJECT_UNKNOWNS`).
Where the plan is the only evidence, :func:`fit_object_unknowns` chooses the value within the
range whose modal plan over seeded placement draws (the analytic world behind the noisy box,
as ``softpad validate``'s static rows) lies nearest the thesis's plan:

    score = |COG - COG_thesis| / (1 module) + angle(theta, theta_thesis) / (pi / 4)

(one module of COG weighs as one 45-degree step of the thesis's rules), over an even grid of
the range; of values tied at the lowest score, the middle one. Those plan rows are then marked ``calibration`` in
``softpad validate`` and counted apart; no other row is used, so no validation row chooses a
value. ``softpad calibrate --objects`` runs the fit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from softpad.errors import InputError

__all__ = [
    "ObjectFit",
    "fit_object_unknowns",
    "object_fits_table",
    "plan_score",
]

#: Placement draws per grid value, and grid values per range, of the default fit.
FIT_DRAWS = 20
FIT_GRID = 7


def plan_score(
    plans: list[tuple[float, float, float] | None], thesis_plan: tuple[float, float, float]
) -> float:
    """Distance of the modal plan of ``plans`` from ``thesis_plan`` (module units; one 45
    degree step counts as one module); ``inf`` when no plan was made."""
    from softpad.trials._validate import _angle_apart, _modal_plan

    made = [p for p in plans if p is not None]
    if not made:
        return math.inf
    modal, _, _, med, _ = _modal_plan(made)
    cog = float(np.hypot(med[0] - thesis_plan[0], med[1] - thesis_plan[1]))
    return cog + _angle_apart(modal, thesis_plan[2]) / (math.pi / 4)


@dataclass(frozen=True)
class ObjectFit:
    """One object's unknown fitted to its Table 6.1 plan."""

    object: str
    #: The uncertain input (:data:`softpad.sim.UNCERTAIN_PARAMETERS`).
    parameter: str
    #: Its range and the nominal before the fit.
    low: float
    high: float
    nominal: float
    #: The grid and the score of each value (:func:`plan_score`).
    grid: tuple[float, ...]
    scores: tuple[float, ...]
    #: The value of the lowest score (of several tied, the middle one).
    fitted: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {
            "object": self.object,
            "parameter": self.parameter,
            "range": [self.low, self.high],
            "nominal": self.nominal,
            "fitted": float(f"{self.fitted:.6g}"),
            "grid": [float(f"{g:.6g}") for g in self.grid],
            "scores": [round(s, 4) if math.isfinite(s) else None for s in self.scores],
        }


def fit_object_unknowns(
    objects: tuple[str, ...] | None = None,
    draws: int = FIT_DRAWS,
    grid: int = FIT_GRID,
    seed: int = 0,
) -> list[ObjectFit]:
    """Fit each object's unknown (:data:`softpad.sim.OBJECT_UNKNOWNS`) to its Table 6.1 plan.

    Parameters
    ----------
    objects
        Names to fit (default: every object with an unknown).
    draws
        Placement draws per grid value (seeded as the static rows' draws: the trials'
        placement noise).
    grid
        Values evenly spaced over the parameter's range, both ends included.
    seed
        Seed of the draws.
    """
    from softpad.sim import OBJECT_UNKNOWNS, UNCERTAIN_PARAMETERS, LabVariation, get_object
    from softpad.trials._records import THESIS_TABLE_6_1
    from softpad.trials._validate import static_draws

    if not isinstance(draws, int) or not 2 <= draws <= 1000:
        raise InputError(f"draws per value must be an integer from 2 to 1000, got {draws!r}")
    if not isinstance(grid, int) or not 2 <= grid <= 101:
        raise InputError(f"grid values must be an integer from 2 to 101, got {grid!r}")
    names = tuple(OBJECT_UNKNOWNS) if objects is None else objects
    by_name = {p.name: p for p in UNCERTAIN_PARAMETERS}
    out = []
    for name in names:
        if name not in OBJECT_UNKNOWNS:
            raise InputError(
                f"{name!r} has no fitted unknown; use one of {', '.join(OBJECT_UNKNOWNS)}"
            )
        p = by_name[OBJECT_UNKNOWNS[name]]
        values = tuple(float(v) for v in np.linspace(p.low, p.high, grid))
        thesis_plan = THESIS_TABLE_6_1[name][1]
        scores = []
        for v in values:
            spec = LabVariation.of({p.name: v}).object(get_object(name))
            scores.append(
                plan_score([d.plan for d in static_draws(spec, draws, seed)], thesis_plan)
            )
        tied = [v for v, s in zip(values, scores, strict=True) if s <= min(scores) + 1e-9]
        best = tied[len(tied) // 2]
        out.append(ObjectFit(name, p.name, p.low, p.high, p.nominal, values, tuple(scores), best))
    return out


def object_fits_table(fits: Sequence[ObjectFit]) -> str:
    """The fitted unknowns as a Markdown table (range, nominal, fitted, best score).

    Parameters
    ----------
    fits
        The fits (:func:`fit_object_unknowns`).
    """
    lines = [
        "| object | parameter | range | nominal | fitted | best score |",
        "|---|---|---|---|---|---|",
    ]
    for f in fits:
        lines.append(
            f"| {f.object} | {f.parameter} | {f.low:g} .. {f.high:g} | {f.nominal:g} | "
            f"{f.fitted:.4g} | {min(f.scores):.3g} |"
        )
    return "\n".join(lines)
