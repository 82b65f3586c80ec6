"""A planner that knows the gripper: fingertips on sensitive area, opening that spans the object.

:class:`GripperAwarePlanner` starts from the thesis's plan (objects outlined at the noise floor,
:func:`softpad.sensing.outline_objects`) and keeps it when a fingertip is sensed by the contact
detector in use and the jaws span the object's outline; otherwise it takes the best-scoring
grasp shifted along and across the closing direction (and turned, where the outline is wider
than the jaws), the score being the better fingertip's sensed share (:func:`sensed_share`,
the FEM response under its sole) less costs for the shift, the turn and an outline wider than
the jaws, plus a term for the load under the centre. Where the outline is wider than the
jaws, the centre first moves to the load under the jaws' path (:func:`centred_on_load`).
Pairs of one-module objects are grasped across the line joining them (:func:`across_pairs`),
after a tentative grasp between them (:func:`bridge_pairs`); three diagonal-linked modules
are planned along the load's major axis (:func:`along_load_axis`). :meth:`retry` answers a
landing on the object: a quarter turn where the outline allows, else a shift towards the
pressed side, else (after a miss pressed alike on both sides) the same grasp again.

The rules grew from losses on Table 6.1's objects in the simulator; docs/beat-the-thesis.md
("The gripper-aware planner's development history") keeps the record of each one. The
model-based planner (:mod:`softpad.planning._model_based`) replaces them with one model.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning._geometry import theta_perpendicular
from softpad.planning._params import PlannerParams
from softpad.planning._plan import ThesisPlanner
from softpad.planning._records import GraspPlan
from softpad.planning._thesis_rules import diagonal_linked_plan, linked_three
from softpad.sensing import (
    DEFAULT_OBJECT_THRESHOLD_PA,
    DEFAULT_OUTLINE_THRESHOLD_PA,
    check_increments,
    check_threshold,
    outline_objects,
)

#: Width of the bonded, non-sensitive seam between two chambers that the planner assumes, m.
#: A pad specification (measured on the pad, e.g. by ``softpad calibrate``), not a thesis
#: number; the simulated pad's seam is 0 mm nominal, 0-3 mm in its uncertain range
#: (``seam_width_m`` of ``softpad.sim.UNCERTAIN_PARAMETERS``).
DEFAULT_SEAM_WIDTH_M = 5e-3

#: Lever of a landing's rise (module units) under which it counts as pressing both sides.
LANDING_BALANCE = 0.05

#: Share of a landing's rise on one side of the jaws' centre line from which the landing
#: counts as one-sided (:func:`pressed_share`; chosen between development objects'
#: distributions, see docs/beat-the-thesis.md).
ONE_SIDED_SHARE = 0.9

#: Distance of a module's centre from the jaws' centre line, module units, under which it
#: counts on neither side of it.
ON_LINE = 0.25

#: Offsets of the sample points on a fingertip, as fractions of its sides.
_TIP_GRID = np.array([(a, b) for a in (-0.4, 0.0, 0.4) for b in (-0.4, -0.2, 0.0, 0.2, 0.4)])


#: Relative response of a module to a small load at a distance from its centre (Chebyshev
#: distance, m), from the project's FEM of the 45 mm module (issue 10's audit: 0.67 at 13.6 mm,
#: 0.44 at 17.2 mm, 0.18 at 20.2 mm from the centre; nothing on the bonded seam at 22.5 mm).
RESPONSE_DISTANCE_M = (0.0, 0.0136, 0.0172, 0.0202, 0.0225)
RESPONSE_RELATIVE = (1.0, 0.67, 0.44, 0.18, 0.0)


def sensed_share(
    tip_xy_m: tuple[float, float],
    theta: float,
    gripper: GripperSpec,
    layout: PadLayout,
    seam_width_m: float = DEFAULT_SEAM_WIDTH_M,
) -> float:
    """Mean relative response of the modules under a fingertip's sole (0..1).

    Each sample point of the sole counts with the response of the module it lies on at its
    distance from the module's centre (:data:`RESPONSE_RELATIVE`, scaled to the pitch), zero on
    the seam (half its width from a boundary) and off the pad.
    """
    d = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-d[1], d[0]])
    pts = (
        np.asarray(tip_xy_m)
        + np.outer(_TIP_GRID[:, 0] * gripper.tip_thickness_m, d)
        + np.outer(_TIP_GRID[:, 1] * gripper.tip_width_m, n)
    ) / layout.pitch_m
    inside = (pts[:, 0] >= 0) & (pts[:, 0] <= layout.cols) & (pts[:, 1] >= 0)
    inside &= pts[:, 1] <= layout.rows
    off_centre = np.abs(pts - np.floor(pts) - 0.5).max(axis=1)  # module units, 0..0.5
    scale = layout.pitch_m / thesis.MODULE_PITCH_M
    response = np.interp(
        off_centre * layout.pitch_m, np.array(RESPONSE_DISTANCE_M) * scale, RESPONSE_RELATIVE
    )
    on_seam = off_centre > 0.5 - 0.5 * seam_width_m / layout.pitch_m
    return float(np.mean(np.where(inside & ~on_seam, response, 0.0)))


def object_extent_m(modules: tuple[int, ...], theta: float, layout: PadLayout) -> float:
    """Extent of an object's modules along ``theta``, metres (an upper bound of the object's)."""
    d = np.array([math.cos(theta), math.sin(theta)])
    corners = np.array([(-0.5, -0.5), (-0.5, 0.5), (0.5, -0.5), (0.5, 0.5)])
    pts = np.vstack([np.asarray(layout.center(k)) + corners for k in modules])
    proj = pts @ d
    return float(proj.max() - proj.min()) * layout.pitch_m


class GripperAwarePlanner:
    """The thesis's planner, corrected so that the fingers are sensed (a ``Planner``).

    Parameters
    ----------
    gripper
        Jaw geometry: opening range, fingertip size.
    params
        Parameters of the underlying thesis planner.
    seam_width_m
        Width of the non-sensitive seam between modules, metres.
    max_shift
        Largest shift of the centre of grasp tried, module units.
    max_turn_rad
        Largest turn of the closing direction tried, radians.
    good_share
        Sensed share of the better fingertip from which a grasp is kept as it is.
    outline_threshold_pa
        Increment from which a module next to an object counts in its outline, pascals.
    load_cost
        Weight of the load under the centre of grasp in the score.
    sensing_ratio
        The contact detector's step floor over the thesis detector's
        (:func:`softpad.sensing.sensing_ratio`; 1 for the thesis's): ``good_share`` is scaled
        by it.
    """

    def __init__(
        self,
        gripper: GripperSpec | None = None,
        params: PlannerParams | None = None,
        seam_width_m: float = DEFAULT_SEAM_WIDTH_M,
        max_shift: float = 0.3,
        max_turn_rad: float = math.radians(30.0),
        good_share: float = 0.5,
        outline_threshold_pa: float = DEFAULT_OUTLINE_THRESHOLD_PA,
        load_cost: float = 0.1,
        sensing_ratio: float = 1.0,
    ) -> None:
        self.gripper = gripper or GripperSpec()
        self.thesis = ThesisPlanner(params)
        self.seam_width_m = seam_width_m
        self.max_shift, self.max_turn_rad, self.good_share = max_shift, max_turn_rad, good_share
        self.outline_threshold_pa, self.load_cost = outline_threshold_pa, load_cost
        if not (math.isfinite(sensing_ratio) and sensing_ratio > 0):
            raise InputError(f"sensing ratio must be a number > 0, got {sensing_ratio!r}")
        self.sensing_ratio = float(sensing_ratio)

    @property
    def needed_share(self) -> float:
        """Sensed share from which a fingertip counts as sensed by the detector in use."""
        return self.good_share * self.sensing_ratio

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        d = check_increments(increments_pa, layout)
        outlined = _kept_diagonals(
            objects, outline_objects(d, objects, layout, self.outline_threshold_pa), layout
        )
        params = self.thesis.params
        plans = [
            along_load_axis(p, layout, d, params) for p in self.thesis.plan(d, outlined, layout)
        ]
        # turned last: a module's outline, 45 mm square, spans 60.4 mm across the banana's
        # (2, 1) diagonal, and improve() would turn it 15 degrees back to fit the 6 cm jaws
        return bridge_pairs(across_pairs([self.improve(p, layout, d) for p in plans]), d)

    def tip_share(self, cog: tuple[float, float], theta: float, layout: PadLayout) -> float:
        """Sensed share of the better-placed fingertip for a grasp at ``cog`` (module units)."""
        xy = tuple(np.asarray(cog) * layout.pitch_m)
        tips = self.gripper.fingertip_centres((float(xy[0]), float(xy[1])), theta)
        return max(sensed_share(t, theta, self.gripper, layout, self.seam_width_m) for t in tips)

    def improve(
        self, plan: GraspPlan, layout: PadLayout, increments_pa: ArrayLike | None = None
    ) -> GraspPlan:
        """The plan itself when a fingertip is sensed and the jaws span the object, else the
        best-scoring candidate (the plan itself when none is better). Without increments the
        score has no load term."""
        load = None if increments_pa is None else _load_shares(plan, layout, increments_pa)
        fits = not self._too_wide(plan, plan.theta, layout)
        if not fits and increments_pa is not None:
            t_o = self.thesis.params.object_threshold_pa
            plan = centred_on_load(plan, layout, increments_pa, t_o)
        sensed = self.tip_share(plan.cog, plan.theta, layout) >= self.needed_share
        if sensed and (fits or not self._fitting_turns(plan, layout)):
            return plan  # good as it is, or too wide whichever way it turns: nothing to gain
        best, best_score = plan, self._score(plan, layout, plan.cog, plan.theta, load)
        for cog, theta in self._candidates(plan, layout):
            score = self._score(plan, layout, cog, theta, load)
            if score > best_score + 1e-9:
                best, best_score = (
                    replace(plan, cog=cog, theta=theta, rule=plan.rule + "+gripper"),
                    score,
                )
        return best

    def retry(
        self,
        plan: GraspPlan,
        increments_pa: ArrayLike,
        layout: PadLayout,
        landing_rise_pa: ArrayLike,
        closed: bool = True,
    ) -> GraspPlan | None:
        """After ``plan``'s jaws landed on the object and closed on nothing (``closed``), or
        at the landing itself, before closing (not ``closed``: then only when the landing
        pressed one side alone, :func:`pressed_share` at least ``ONE_SIDED_SHARE``).

        Where the object's outline is no wider a quarter turn away, the grasp turned a
        quarter turn, its centre moved along the new closing direction to the object's load
        centroid (PCOM). Otherwise the centre moves along the closing direction towards the
        side the landing pressed (:func:`landing_side`): half a fingertip sole's thickness,
        or on to the middle of the load under the fingertips' path (modules above t_o within
        half a pitch plus half a fingertip's width of the jaws' line) when that lies further
        on the pressed side. After a miss pressed alike on both sides: the same grasp once
        more, except a tentative one; None where nothing applies. Why each answer exists:
        docs/beat-the-thesis.md (development history).
        """
        d = check_increments(increments_pa, layout)
        if not closed and pressed_share(plan, layout, landing_rise_pa) < ONE_SIDED_SHARE:
            return None
        theta = _wrap(plan.theta + math.pi / 2)
        turned_extent = object_extent_m(plan.modules, theta, layout)
        if turned_extent <= object_extent_m(plan.modules, plan.theta, layout) + 1e-9:
            turned = replace(plan, theta=theta, rule=plan.rule + "+turned-after-miss")
            lever = _weighted_lever(turned, layout, d, plan.modules)
            return turned if lever is None else _moved(turned, lever, "+load-centred")
        side = landing_side(plan, layout, landing_rise_pa)
        if side == 0:
            if closed and not plan.tentative:
                return replace(plan, rule=plan.rule + "+again-after-miss")
            return None
        step = 0.5 * self.gripper.tip_thickness_m / layout.pitch_m
        band = 0.5 + 0.5 * self.gripper.tip_width_m / layout.pitch_m
        t_o = self.thesis.params.object_threshold_pa
        lever = _path_lever(plan, layout, d, t_o, band)
        if lever is not None and side * lever > step:
            step = side * lever
        return _moved(plan, side * step, "+shifted-after-miss")

    def _too_wide(self, plan: GraspPlan, theta: float, layout: PadLayout) -> bool:
        extent = object_extent_m(plan.modules, theta, layout)
        return extent > self.gripper.max_width_m

    def _fitting_turns(self, plan: GraspPlan, layout: PadLayout) -> list[float]:
        """Turns of the closing direction (within the limit) in which the outline fits."""
        return [
            float(t)
            for t in np.linspace(-self.max_turn_rad, self.max_turn_rad, 5)
            if t != 0.0 and not self._too_wide(plan, plan.theta + t, layout)
        ]

    def _candidates(
        self, plan: GraspPlan, layout: PadLayout
    ) -> list[tuple[tuple[float, float], float]]:
        out = []
        shifts = np.linspace(-self.max_shift, self.max_shift, 7)
        # the thesis's direction follows the object's shape: turn only to a direction in which
        # the object's outline fits between the jaws
        wide = self._too_wide(plan, plan.theta, layout)
        turns = [0.0] + (self._fitting_turns(plan, layout) if wide else [])
        # an object that may fill the opening leaves no room to shift along the closing direction
        along = [0.0] if wide else shifts
        for turn in turns:
            theta = _wrap(plan.theta + turn)
            d = np.array([math.cos(theta), math.sin(theta)])
            n = np.array([-d[1], d[0]])
            for a in along:
                for b in shifts:
                    # along the closing direction the object's width is unknown: small steps only
                    c = np.asarray(plan.cog) + a / 3 * d + b * n
                    out.append(((round(float(c[0]), 4), round(float(c[1]), 4)), theta))
        return out

    def _score(
        self,
        plan: GraspPlan,
        layout: PadLayout,
        cog: tuple[float, float],
        theta: float,
        load: NDArray[np.float64] | None = None,
    ) -> float:
        """The score of a grasp at ``cog``, ``theta``; ``load`` (from :func:`_load_shares`)
        adds the load term, None leaves it out."""
        module = layout.module_containing(*cog)
        if module not in plan.modules:
            return -math.inf
        # the modules' outline overestimates the object: an outline wider than the jaws is a
        # penalty (a narrower direction is preferred), not a veto
        too_wide = self._too_wide(plan, theta, layout)
        shift = math.dist(cog, plan.cog) / self.max_shift
        turn = abs(_wrap(theta - plan.theta)) / max(self.max_turn_rad, 1e-9)
        score = self.tip_share(cog, theta, layout) - 0.2 * shift - 0.1 * turn - 1.0 * too_wide
        return score if load is None else score + self.load_cost * float(load[module - 1])


def centred_on_load(
    plan: GraspPlan,
    layout: PadLayout,
    increments_pa: ArrayLike,
    threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA,
) -> GraspPlan:
    """The plan with its centre moved along the closing direction to the middle of the load
    under the jaws' path: the increment-weighted mean position, along that direction, of the
    plan's modules above ``threshold_pa`` (t_o) whose centres lie within half a pitch of the
    line the jaws close on.

    The thesis's rules put the centre on module centres and seams; for an object that may fill
    the opening (its outline is wider than the jaws) the load tells better where its middle
    is. Only modules above t_o count: a module of the noise-floor outline tells where a light
    part may reach, not where the object's weight lies (a toy's foot on module 6 at 30 Pa, the
    only outline module on its diagonal plan's path, drew the centre onto itself, beside the
    toy). The plan itself when nothing under the path is loaded above t_o."""
    d = check_increments(increments_pa, layout)
    t = check_threshold(threshold_pa, "object threshold")
    along = _path_lever(plan, layout, d, t, 0.5)
    if along is None or abs(along) < 1e-9:
        return plan
    return _moved(plan, along, "+load-centred")


def _path_lever(
    plan: GraspPlan,
    layout: PadLayout,
    increments_pa: NDArray[np.float64],
    threshold_pa: float,
    half_width: float,
) -> float | None:
    """Offset of the load under the jaws' path from the plan's centre along its closing
    direction, module units: the increment-weighted mean of the plan's modules above
    ``threshold_pa`` whose centres lie within ``half_width`` of the line the jaws close on;
    None when none is loaded."""
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    normal = np.array([-u[1], u[0]])
    cog = np.asarray(plan.cog, dtype=float)
    on_path = [
        m
        for m in plan.modules
        if increments_pa[m - 1] > threshold_pa
        and abs((np.asarray(layout.center(m)) - cog) @ normal) < half_width
    ]
    return _weighted_lever(plan, layout, increments_pa, on_path)


def _moved(plan: GraspPlan, along: float, why: str) -> GraspPlan:
    """The plan with its centre moved ``along`` its closing direction, module units."""
    c = np.asarray(plan.cog) + along * np.array([math.cos(plan.theta), math.sin(plan.theta)])
    return replace(plan, cog=(float(c[0]), float(c[1])), rule=plan.rule + why)


def _weighted_lever(
    plan: GraspPlan,
    layout: PadLayout,
    pressures_pa: ArrayLike,
    modules: list[int] | tuple[int, ...],
) -> float | None:
    """Mean offset of ``modules``' centres from the plan's centre along its closing direction,
    module units, weighted by their pressures clipped at 0; None when they weigh nothing."""
    w = np.clip(check_increments(pressures_pa, layout), 0.0, None)
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    cog = np.asarray(plan.cog, dtype=float)
    weight = sum(float(w[m - 1]) for m in modules)
    if weight <= 0.0:
        return None
    lever = sum(float(w[m - 1]) * float((np.asarray(layout.center(m)) - cog) @ u) for m in modules)
    return lever / weight


def _kept_diagonals(
    objects: list[tuple[int, ...]], outlined: list[tuple[int, ...]], layout: PadLayout
) -> list[tuple[int, ...]]:
    """``outlined`` with every object found as a diagonal pair of modules kept as found where
    the outline only added the corners between its two modules: a bridge lying across the
    corner of a module loads it lightly, and the pair's own rule (closing across the
    diagonal) is the grasp; as an L, the corner rules close along a row onto its ends."""
    out = []
    for group in outlined:
        inside = [obj for obj in objects if set(obj) <= set(group)]
        corners = _corners_between(inside[0], layout) if len(inside) == 1 else None
        kept = corners is not None and set(group) - set(inside[0]) <= corners
        out.append(inside[0] if kept else group)
    return out


def _corners_between(modules: tuple[int, ...], layout: PadLayout) -> set[int] | None:
    """The two modules at the corners between a diagonal pair (two modules that touch only
    at a corner); None for anything else."""
    if len(modules) != 2:
        return None
    (ra, ca), (rb, cb) = (layout.row_col(m) for m in modules)
    if abs(ra - rb) != 1 or abs(ca - cb) != 1:
        return None
    return {layout.module_at(ra, cb), layout.module_at(rb, ca)}


def across_pairs(plans: list[GraspPlan]) -> list[GraspPlan]:
    """Plans of single-module objects turned to close across the line to the nearest other
    object's PCOM; the others as they are.

    A long object resting on its two ends (the banana, whose middle arches over the pad and
    loads nothing) is seen as two single-module objects, which the thesis grasps at their
    module centres in the default direction: along the banana, onto it. It lies along the line
    joining them; an object that fits on one module fits the jaws either way."""
    out = list(plans)
    for i, p in enumerate(plans):
        others = [q for j, q in enumerate(plans) if j != i]
        if len(p.modules) != 1 or not others:
            continue
        near = min(others, key=lambda q: math.dist(q.pcom, p.cog))
        theta = theta_perpendicular(near.pcom[0] - p.cog[0], near.pcom[1] - p.cog[1])
        out[i] = replace(p, theta=theta, rule=p.rule + "+across-pair")
    return out


def load_axis(
    modules: tuple[int, ...], layout: PadLayout, increments_pa: ArrayLike
) -> float | None:
    """Direction of the major axis of the modules' load (their centres' second moments
    weighted by their increments, clipped at 0), radians in (-pi/2, pi/2]; None when they
    weigh nothing or the moments have no major axis."""
    d = check_increments(increments_pa, layout)
    w = np.array([max(float(d[m - 1]), 0.0) for m in modules])
    if w.sum() <= 0.0:
        return None
    c = np.array([layout.center(m) for m in modules], dtype=float)
    r = c - (w[:, None] * c).sum(axis=0) / w.sum()
    sxx, syy, sxy = (
        (w * r[:, 0] ** 2).sum(),
        (w * r[:, 1] ** 2).sum(),
        (w * r[:, 0] * r[:, 1]).sum(),
    )
    if math.hypot(sxx - syy, 2 * sxy) < 1e-9 * w.sum():
        return None
    return _wrap(0.5 * math.atan2(2 * sxy, sxx - syy))


def along_load_axis(
    plan: GraspPlan, layout: PadLayout, increments_pa: ArrayLike, params: PlannerParams
) -> GraspPlan:
    """A plan of three diagonal-linked modules made on the side module whose axis from the
    corner module lies nearest the load's major axis (:func:`load_axis`); the thesis takes the
    side module on the PCOM's side of the bisector through the corner. Other plans, and plans
    whose side is the same either way, as they are.

    The bisector's side is a coin toss when the PCOM lies near it: the banana on modules 2,
    3 and 4 has its centre of mass over the pad's centre, on the bisector through module 2,
    and the thesis's plan flips between closing across the 2-4 diagonal (across the banana)
    and across the 2-3 row (27 degrees off, at its middle's edge). The load's major axis runs
    from end to end of such an object whichever side its PCOM falls."""
    d = check_increments(increments_pa, layout)
    shape = linked_three(layout, plan.modules)
    axis = None if shape is None else load_axis(plan.modules, layout, d)
    if shape is None or axis is None or plan.reduced_modules != plan.modules:
        return plan
    k = layout.center(shape[0])

    def off(side: int) -> float:
        c = layout.center(side)
        return abs(math.remainder(math.atan2(c[1] - k[1], c[0] - k[0]) - axis, math.pi))

    a, b = off(shape[1]), off(shape[2])
    if math.isclose(a, b, abs_tol=1e-9):
        return plan
    best = diagonal_linked_plan(d, plan.modules, layout, params, shape[1] if a < b else shape[2])
    if math.isclose(best.theta, plan.theta, abs_tol=1e-12):
        return plan
    return replace(best, rule=best.rule + "+load-axis")


def bridge_pairs(plans: list[GraspPlan], increments_pa: ArrayLike) -> list[GraspPlan]:
    """The plans with a tentative grasp before each pair of one-module objects that are
    each other's nearest: centred between them at the increment-weighted mean of their PCOMs,
    closing across the line joining them.

    Two one-module objects may be one long object resting on its two ends (a banana whose
    middle arches over the pad and loads nothing). A rigid body on two supports has its
    centre of mass on the segment between them where the supports' forces balance: the
    weighted mean, the pad's increments standing for the forces. Grasped there it hangs
    balanced between the jaws, where a grasp on one end holds it at its tip. If they are two
    objects, the jaws come down on the pad between them and close on nothing; the loop then
    grasps each in turn (:attr:`GraspPlan.tentative`)."""
    d = np.clip(np.asarray(increments_pa, dtype=float), 0.0, None)
    needed = max((m for p in plans for m in p.modules), default=0)
    if d.ndim != 1 or d.size < needed or not np.all(np.isfinite(d)):
        raise InputError(
            f"increments must be {needed} or more finite values (module {needed} is planned), "
            f"got {np.asarray(increments_pa).tolist()!r}"
        )
    out: list[GraspPlan] = []
    paired: list[GraspPlan] = []
    for p in plans:
        q = _end_partner(p, plans)
        if q is not None and all(p is not r for r in paired):
            out.append(_bridge(p, q, d))
            paired += [p, q]
        out.append(p)
    return out


def _end_partner(p: GraspPlan, plans: list[GraspPlan]) -> GraspPlan | None:
    """The one-module plan nearest to one-module ``p`` when ``p`` is also nearest to it."""

    def nearest(a: GraspPlan) -> GraspPlan | None:
        others = [b for b in plans if b is not a]
        return min(others, key=lambda b: math.dist(a.pcom, b.pcom)) if others else None

    q = nearest(p)
    if len(p.modules) != 1 or q is None or len(q.modules) != 1 or nearest(q) is not p:
        return None
    return q


def _bridge(p: GraspPlan, q: GraspPlan, d: NDArray[np.float64]) -> GraspPlan:
    wp, wq = float(d[p.modules[0] - 1]), float(d[q.modules[0] - 1])
    a, b = np.asarray(p.pcom), np.asarray(q.pcom)
    c = (wp * a + wq * b) / (wp + wq) if wp + wq > 0 else (a + b) / 2
    centre = (float(c[0]), float(c[1]))
    modules = tuple(sorted(p.modules + q.modules))
    theta = theta_perpendicular(float(b[0] - a[0]), float(b[1] - a[1]))
    return GraspPlan(modules, centre, centre, theta, "bridge-pair", modules, tentative=True)


def landing_side(plan: GraspPlan, layout: PadLayout, landing_rise_pa: ArrayLike) -> int:
    """Which side of the centre a landing jaw pressed the object into the pad: +1 along the
    closing direction, -1 against it, 0 when the rise is balanced (its rise-weighted lever
    over the plan's modules, module units, is within ``LANDING_BALANCE`` of the centre) or
    absent."""
    lever = _weighted_lever(plan, layout, landing_rise_pa, plan.modules)
    if lever is None or abs(lever) < LANDING_BALANCE:
        return 0
    return 1 if lever > 0 else -1


def pressed_share(plan: GraspPlan, layout: PadLayout, landing_rise_pa: ArrayLike) -> float:
    """Share of a landing's rise (clipped at 0, every module) on the more pressed side of the
    jaws' centre line (the line through the centre across the closing direction); a module
    whose centre lies within ``ON_LINE`` of the line counts on neither side. 0 when nothing
    rose."""
    w = np.clip(check_increments(landing_rise_pa, layout), 0.0, None)
    total = float(w.sum())
    if total <= 0.0:
        return 0.0
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    along = (layout.centers - np.asarray(plan.cog, dtype=float)) @ u
    plus, minus = float(w[along > ON_LINE].sum()), float(w[along < -ON_LINE].sum())
    return max(plus, minus) / total


def _load_shares(
    plan: GraspPlan, layout: PadLayout, increments_pa: ArrayLike
) -> NDArray[np.float64]:
    """dP of every module over the largest dP of the plan's modules, clipped at 0 (all 0 when
    none of them is loaded)."""
    d = np.clip(check_increments(increments_pa, layout), 0.0, None)
    top = max(float(d[m - 1]) for m in plan.modules)
    return d / top if top > 0 else np.zeros_like(d)


def _wrap(theta: float) -> float:
    """Angle in (-pi/2, pi/2] (a parallel-jaw grasp is the same under theta + pi)."""
    t = math.fmod(theta, math.pi)
    if t <= -math.pi / 2:
        t += math.pi
    elif t > math.pi / 2:
        t -= math.pi
    return t
