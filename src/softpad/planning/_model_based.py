"""A planner that estimates where the load lies from a model of the pad, then decides.

The module reads top to bottom in the order the planner works:

1. **The pad model** (:class:`PadModel`): how much a load at a point of a module raises its
   chamber's pressure, relative to the same load at the centre: the project's FEM of the pad
   as cast (``softpad/data/cast_pad_response.npz``, written by ``softpad fem cast-response``;
   the simulator's default pad), read as data.
2. **Estimate** (:func:`estimate`): hypotheses of a rectangular footprint (centre, length,
   width, yaw on a coarse grid) carrying the object's weight evenly; each predicts every
   module's increment up to one unknown scale (the weight), fitted in closed form; the Gaussian
   likelihood of the measured increments under the sensor's noise plus a relative model error
   weighs the hypotheses (:class:`Posterior`). Beside them, two-part hypotheses: a dense
   footprint on the heavier modules and a light part of unknown shape on the light ones.
3. **Candidates** (:func:`candidates`): grasp centres at the likely footprints' centres and
   beside them, closing directions along a fixed fan and across each likely footprint.
4. **Score** (:func:`predicted_success`): the chance that a grasp succeeds under the
   posterior: a fingertip lands where the contact detector in use senses it (the response
   map under its sole against the detector's step floor), both jaws come down clear of the
   object, the object is wide enough for the jaws to close on, and the grasp centre lies in
   the middle of the object across the jaws. A footprint may be a box's own, the contact
   strip of a lying cylinder or a round object's contact: all count, with equal weight, since
   the pad cannot tell them apart; a curved object spans at least one of a few diameters
   across its contact (``curved_diameters``).
5. **Choose** (:class:`ModelBasedPlanner`): the candidate with the highest predicted success.
   A landing on the object (the fingers sensed high above the pad) is evidence: the
   posterior keeps the hypotheses under which that grasp would have landed a jaw on the
   object on the side the pad felt pressed, and the choice is made again.

Every number the planner uses is a field of :class:`ModelBasedParams`; nothing in it names an
object. The derivation and its limits are in docs/planner.md ("The model-based planner").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from functools import lru_cache
from importlib import resources
from typing import Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning._detection import NoiseDetectionParams, NoiseObjectDetector
from softpad.planning._pcom import pcom
from softpad.planning._records import GraspPlan
from softpad.sensing import DEFAULT_OUTLINE_THRESHOLD_PA, check_increments, outline_objects

Array = NDArray[np.float64]
_ArrayT = TypeVar("_ArrayT", bound=NDArray[Any])


@dataclass(frozen=True)
class ModelBasedParams:
    """The model-based planner's parameters (SI units; module units where named)."""

    #: Noise of one planning increment (10-read mean minus 10-read reference, with drift),
    #: Pa rms: 5.5 Pa for the box's sensor (softpad.sensing.DEFAULT_OUTLINE_THRESHOLD_PA).
    noise_pa: float = 5.5
    #: How the loop finds this planner's objects: at ``k`` standard deviations of the
    #: increment's noise measured on the box's reference reads, ``k`` from a family-wise
    #: false-alarm probability over the modules (planning._detection); None: the thesis's t_o.
    detection: NoiseDetectionParams | None = field(default_factory=NoiseDetectionParams)
    #: Relative rms error of the even-load model of a module's increment (uneven weight,
    #: the characteristic's curvature, tilt); an assumption, set before any trial ran.
    model_error: float = 0.3
    #: Sub-positions per module side of the hypotheses' centres (4: an 11 mm grid; 6, a
    #: 7.5 mm grid, held fewer development trials in MuJoCo: docs/planner.md).
    centre_steps: int = 4
    #: Footprint sides tried, mm (the length and the width take every pair of them).
    sizes_mm: tuple[float, ...] = (12.0, 24.0, 40.0, 60.0, 90.0, 125.0)
    #: Footprint yaws tried, in [0, pi) (6: 30 degree steps).
    yaw_steps: int = 6
    #: Largest share of a footprint's area off the pad (an object lies on the pad).
    overhang: float = 0.2
    #: Log-likelihood below the best under which a hypothesis is dropped (e^-12: 6e-6).
    log_floor: float = 12.0
    #: Hypotheses drawn from the posterior for the decision (after the evidence).
    kept_hypotheses: int = 32
    #: Closing directions of the fixed fan of candidates in [0, pi) (8: 22.5 degree steps).
    directions: int = 8
    #: Gap left between each open jaw and the object on the way down, m.
    clearance_m: float = 2e-3
    #: Half-width of the band across the jaws, as a share of the object's half-extent, in
    #: which the grasp centre must lie for the object to hang balanced between the jaws.
    centre_band: float = 0.5
    #: The object's extent over its footprint (along the footprint's length, across it) for
    #: each shape the pad cannot tell apart: a box rests on its whole face (1, 1); a lying
    #: cylinder on a strip half its diameter wide (1, 2); a round object (a ball, a fruit) on
    #: a disc half its diameter across (2, 2). The halves are a soft pad's contact, the
    #: simulator's LYING_CYLINDER_CONTACT_FRACTION and SPHERE_CONTACT_FRACTION (0.5 each).
    shape_extents: tuple[tuple[float, float], ...] = ((1.0, 1.0), (1.0, 2.0), (2.0, 2.0))
    #: Prior weight of each shape of ``shape_extents`` (equal: the readings do not tell them
    #: apart; an assumption set before any trial ran).
    shape_weights: tuple[float, ...] = (1.0, 1.0, 1.0)
    #: Diameters a curved object may have, as shares of the jaws' full opening, each as
    #: likely (a shape of ``shape_extents`` with an extent over 1 is curved that way). Its
    #: contact on the soft pad says little of its diameter: an inflated chamber wraps it
    #: until the contact carries the weight at the chamber's pressure (a 68 g fruit at
    #: p0 = 1 kPa: 670 mm^2, a 9 mm strip under a 75 mm fruit), so across a curved shape the
    #: object spans at least each of these. A lab mounts jaws that open wider than the
    #: object (thesis, Section 6.3), so the diameters span the opening evenly (30, 60 and
    #: 90 mm with the 10/4 jaws). Empty: the footprint's multiple only.
    curved_diameters: tuple[float, ...] = (0.3, 0.6, 0.9)
    #: Steps each way of the finer search around the best coarse candidate (2: a 5 x 5 x 5
    #: grid of direction, shift along and shift across the closing direction).
    refine_steps: int = 2
    #: Direction step of the finer search, as a share of the fan's step (0.25: 5.6 degrees,
    #: so that the finer grid reaches half-way to the next direction of the fan).
    refine_turn: float = 0.25
    #: Shift step of the finer search, as a share of the hypotheses' centre step (0.25:
    #: 2.8 mm on the 45 mm pad; the grid reaches half-way to the next centre tried).
    refine_shift: float = 0.25
    #: Room a side between the open jaws (less ``clearance_m``) and the estimated footprint
    #: along the chosen grasp (posterior mean, the nearer jaw's) under which the fit is
    #: tight and the finer search goes on (:func:`tight_search`), m; 0: never.
    tight_room_m: float = 0.0
    #: Best coarse candidates the tight-fit search starts from, in directions more than the
    #: finer search's reach apart (1: the best only).
    tight_starts: int = 1
    #: Rounds of the tight-fit search after the finer search (which runs at twice the
    #: density there): each a 3 x 3 x 3 grid of direction, shift along and across around
    #: the best so far (:func:`polished`).
    tight_rounds: int = 1
    #: Mean response under a fingertip's sole, as a share of the centre's, at which the
    #: thesis's contact detector senses it (scaled by the detector's sensing ratio).
    needed_share: float = 0.5
    #: Chance that a grasp lands a jaw on the object (or on the side not pressed) under a
    #: hypothesis that says it would not: placement drift and model error.
    surprise: float = 0.05
    #: Share of a landing's rise on one side of the jaws' centre line from which the pad
    #: says that side was pressed (else the side is unknown).
    side_share: float = 2.0 / 3.0
    #: A module of an object reading under this share of its largest increment may carry a
    #: light part (a cable, a stem, the light end of an uneven object) beside a dense part on
    #: the others: the two-part hypotheses of :func:`estimate` (0: one part only).
    light_share: float = 0.3
    #: Most modules a light part may lie on (more: the object is read as one part).
    max_light_modules: int = 3
    #: Prior log-odds against a light part, nats per module it lies on: each frees one
    #: load, priced as the Bayesian information criterion prices a free parameter, half the
    #: log of the readings (6 on the 2 x 3 pad: 0.9, rounded to 1).
    part_cost: float = 1.0
    #: Pressure of the modules at which the response map is read, Pa (p0).
    pressure_pa: float = thesis.P0_PA
    #: Increment above which a module next to an object joins its outline, Pa.
    outline_threshold_pa: float = DEFAULT_OUTLINE_THRESHOLD_PA

    def __post_init__(self) -> None:
        positive = ("noise_pa", "clearance_m", "centre_band", "needed_share", "pressure_pa")
        for name in (
            *positive,
            "refine_turn",
            "refine_shift",
            "model_error",
            "surprise",
            "side_share",
            "overhang",
            "outline_threshold_pa",
            "light_share",
            "part_cost",
            "tight_room_m",
        ):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v >= 0):
                raise InputError(f"model-based parameter {name} must be a number >= 0, got {v!r}")
        counts = ("centre_steps", "yaw_steps", "kept_hypotheses", "directions", "tight_starts")
        for name in (*counts, "refine_steps", "max_light_modules", "tight_rounds"):
            v = getattr(self, name)
            if not (isinstance(v, int) and (1 if name in counts else 0) <= v <= 64):
                raise InputError(
                    f"model-based parameter {name} must be an integer 1..64, got {v!r}"
                )
        if not all(0 < s <= 1 for s in self.curved_diameters):
            raise InputError(
                f"curved_diameters must be shares of the opening in (0, 1], "
                f"got {self.curved_diameters!r}"
            )
        if not self.sizes_mm or not all(0 < s <= 500 for s in self.sizes_mm):
            raise InputError(f"sizes_mm must be lengths in (0, 500] mm, got {self.sizes_mm!r}")
        _check_shapes(self.shape_extents, self.shape_weights)


def _check_shapes(extents: tuple[tuple[float, float], ...], weights: tuple[float, ...]) -> None:
    """InputError unless every shape has two extents >= 1 and a weight >= 0, some > 0."""
    ok = len(extents) >= 1 and len(weights) == len(extents)
    ok = ok and all(len(e) == 2 and all(math.isfinite(v) and v >= 1 for v in e) for e in extents)
    ok = ok and all(math.isfinite(w) and w >= 0 for w in weights) and sum(weights) > 0
    if not ok:
        raise InputError(
            "shape_extents must be pairs of numbers >= 1 with one weight >= 0 each (some > 0), "
            f"got {extents!r} and {weights!r}"
        )


# --- 1. the pad model --------------------------------------------------------------------------

#: Samples per module side of the response lookup table.
_LOOKUP = 91


@dataclass(frozen=True, eq=False)
class PadModel:
    """Relative response of a module to a load at a point of its top face (1 at the centre,
    0 at the clamped edge), tabulated on a module's square in module units."""

    #: Response on a ``_LOOKUP`` x ``_LOOKUP`` grid over [-0.5, 0.5]^2 module units.
    table: Array

    def response(self, local: Array) -> Array:
        """Relative response at points relative to their module's centre, module units."""
        idx = np.rint((np.clip(local, -0.5, 0.5) + 0.5) * (_LOOKUP - 1)).astype(np.int64)
        return self.table.ravel()[idx[..., 0] * _LOOKUP + idx[..., 1]]

    def on_pad(self, points: Array, layout: PadLayout) -> Array:
        """Relative response at pad-frame points in module units (0 off the pad)."""
        cell = np.floor(points)  # x >= 0 and x < n exactly where floor(x) is (n whole)
        inside = (cell >= 0) & (cell < (layout.cols, layout.rows))
        inside = inside[..., 0] & inside[..., 1]
        return np.where(inside, self.response(points - cell - 0.5), 0.0)


@lru_cache(maxsize=4)
def packaged_pad_model(pressure_pa: float = thesis.P0_PA, pad: str = "cast") -> PadModel:
    """The pad model from the project's packaged FEM response at ``pressure_pa``.

    ``pad="cast"`` (default): the pad as built, one silicone layer cast over every chamber
    (``softpad/data/cast_pad_response.npz``, ``softpad fem cast-response``; the simulator's
    default pad): each chamber's response over its own square, relative to its centre,
    averaged over the chambers (linear between the table's pressures). ``pad="clamped"``:
    the single module clamped at its edge (``module_response.npz``, the first generation's
    model; bilinear, nearest pressure)."""
    if pad == "cast":
        return _cast_pad_model(pressure_pa)
    if pad != "clamped":
        raise InputError(f"pad model must be 'cast' or 'clamped', got {pad!r}")
    z = _read_npz("module_response.npz", ("pressure_pa", "axis_m", "influence_m3_n"))
    p, axis, infl = z["pressure_pa"], z["axis_m"], z["influence_m3_n"]
    s = infl[int(np.argmin(np.abs(p - pressure_pa)))]
    side = 2.0 * float(axis[-1])  # the FEM module's chamber; its seam is 0 (thesis figures)
    grid = np.abs(np.linspace(-0.5, 0.5, _LOOKUP)) * side
    return PadModel(np.clip(_bilinear(axis, axis, s, grid, grid) / s[0, 0], 0.0, None))


def _read_npz(name: str, keys: tuple[str, ...]) -> dict[str, Array]:
    """Arrays ``keys`` of the packaged ``name`` (InputError when unreadable)."""
    path = resources.files("softpad").joinpath("data", name)
    try:
        with path.open("rb") as fh, np.load(fh, allow_pickle=False) as z:
            return {k: np.asarray(z[k], dtype=float) for k in keys}
    except (OSError, KeyError, ValueError) as exc:
        raise InputError(f"cannot read the packaged pad response {name}: {exc}") from None


def _bilinear(ax: Array, ay: Array, values: Array, gx: Array, gy: Array) -> Array:
    """``values`` (on nodes ``ax`` x ``ay``) at the grid ``gx`` x ``gy``: (len gx, len gy)."""
    along_x = np.array([np.interp(gx, ax, values[:, j]) for j in range(ay.size)])  # (Ny, L)
    return np.array([np.interp(gy, ay, along_x[:, i]) for i in range(gx.size)])


def _cast_pad_model(pressure_pa: float) -> PadModel:
    """:func:`packaged_pad_model` of the cast pad (see there)."""
    keys = ("pressure_pa", "x_axis_m", "y_axis_m", "influence_m3_n", "centers_m")
    z = _read_npz("cast_pad_response.npz", keys)
    p, infl = z["pressure_pa"], z["influence_m3_n"]
    i = int(np.clip(np.searchsorted(p, pressure_pa) - 1, 0, max(p.size - 2, 0)))
    j = min(i + 1, p.size - 1)
    f = 0.0 if j == i else float(np.clip((pressure_pa - p[i]) / (p[j] - p[i]), 0.0, 1.0))
    s = (1 - f) * infl[i] + f * infl[j]  # (K, Nx, Ny)
    centres = z["centers_m"]
    pitch = float(np.min(np.diff(np.unique(np.round(centres[:, 0], 9)))))
    local = np.linspace(-0.5, 0.5, _LOOKUP) * pitch
    maps = []
    for k, (cx, cy) in enumerate(centres):
        m = _bilinear(z["x_axis_m"], z["y_axis_m"], s[k], cx + local, cy + local)
        maps.append(m / m[_LOOKUP // 2, _LOOKUP // 2])
    return PadModel(np.clip(np.mean(maps, axis=0), 0.0, None))


# --- 2. estimate -------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Templates:
    """Every footprint hypothesis with its centre in one module, as predicted increments of
    the (2r+1)^2 modules around it per unit weight."""

    offsets: Array  # (T, 2) centre from its module's centre, module units
    halves: Array  # (T, 2) half length and half width, module units
    yaws: Array  # (T,) radians in [0, pi)
    #: (2, W, T): response-weighted share of the load on each window module, and its square
    #: (0 on modules the footprint does not touch): the likelihood's sums are two products.
    shares: Array
    starts: NDArray[np.int64]  # (T,) first entry of each template's window modules
    modules: NDArray[np.int64]  # (E,) window module of each entry
    covers: Array  # (E,) share of the footprint's area on it
    window: NDArray[np.int64]  # (W, 2) column and row-from-bottom offsets of the window
    radius: int

    def on_pad(self, pad: Array) -> Array:
        """Share of each template's area on the pad, ``pad`` (W, C) being 1 on it: (T, C)."""
        return np.add.reduceat(self.covers[:, None] * pad[self.modules], self.starts, axis=0)


@lru_cache(maxsize=8)
def _templates(pitch_m: float, params: ModelBasedParams, model: PadModel) -> _Templates:
    """The footprint hypotheses of ``params`` on a pad of ``pitch_m``."""
    k = params.centre_steps
    offs = (np.arange(k) + 0.5) / k - 0.5
    sizes = np.asarray(sorted(params.sizes_mm)) * 1e-3 / pitch_m
    pairs = [(a, b) for i, a in enumerate(sizes) for b in sizes[: i + 1]]
    yaws = np.arange(params.yaw_steps) * math.pi / params.yaw_steps
    radius = math.ceil(0.5 + 0.5 * math.hypot(sizes[-1], sizes[-1]))
    rng = np.arange(-radius, radius + 1)
    window = np.array([(c, r) for r in rng for c in rng], dtype=np.int64)
    rows = [
        (o, (a / 2, b / 2), y, *_pattern(np.array(o), a, b, y, model, radius))
        for a, b in pairs
        for y in yaws
        for o in ((ox, oy) for ox in offs for oy in offs)
    ]
    patterns, covers = np.array([r[3] for r in rows]), np.array([r[4] for r in rows])
    touched = covers > 0  # every footprint covers its centre module
    starts = np.concatenate([[0], np.cumsum(touched.sum(axis=1))[:-1]])
    shares = np.where(touched, patterns, 0.0)
    return _Templates(
        np.array([r[0] for r in rows]),
        np.array([r[1] for r in rows]),
        np.array([r[2] for r in rows]),
        _frozen(np.ascontiguousarray(np.stack([shares.T, shares.T**2]))),
        starts.astype(np.int64),
        np.nonzero(touched)[1].astype(np.int64),
        covers[touched],
        window,
        radius,
    )


def _frozen(a: _ArrayT) -> _ArrayT:
    """``a``, read-only (a cached table)."""
    a.flags.writeable = False
    return a


def _pattern(
    offset: Array, length: float, width: float, yaw: float, model: PadModel, radius: int
) -> tuple[Array, Array]:
    """Share of an evenly spread unit load on each window module, weighted by the response
    at each point, and share of the footprint's area on it (module units; the window's
    module (0, 0) holds the centre)."""
    n = max(2, math.ceil(max(length, width) / 0.05))
    u = (np.arange(n) + 0.5) / n - 0.5
    gx, gy = np.meshgrid(u * length, u * width, indexing="ij")
    c, s = math.cos(yaw), math.sin(yaw)
    pts = np.column_stack([c * gx.ravel() - s * gy.ravel(), s * gx.ravel() + c * gy.ravel()])
    pts += offset + 0.5  # the centre module spans [0, 1)^2
    cell = np.floor(pts).astype(np.int64)
    resp = model.response(pts - cell - 0.5)
    side = 2 * radius + 1
    idx = (cell[:, 1] + radius) * side + (cell[:, 0] + radius)
    ok = (np.abs(cell) <= radius).all(axis=1)
    load = np.bincount(idx[ok], weights=resp[ok], minlength=side * side) / len(pts)
    return load, np.bincount(idx[ok], minlength=side * side) / len(pts)


@dataclass(frozen=True)
class Posterior:
    """The most likely footprints of one object (module units, pad frame)."""

    centres: Array  # (H, 2)
    halves: Array  # (H, 2) half length, half width
    yaws: Array  # (H,)
    probs: Array  # (H,) summing to 1
    #: (H,) parts of each hypothesis: 1 (the footprint carries the whole weight) or 2 (a
    #: dense part, the footprint, and a light part beside it); None: all 1
    parts: Array | None = None

    def mean_centre(self) -> tuple[float, float]:
        """Posterior mean of the footprint's centre, module units."""
        c = self.probs @ self.centres
        return float(c[0]), float(c[1])

    def spread(self) -> float:
        """Posterior rms distance of the centre from its mean, module units."""
        r = self.centres - np.asarray(self.mean_centre())
        return float(math.sqrt(self.probs @ (r**2).sum(axis=1)))

    def sample(self, n: int) -> Posterior:
        """``n`` hypotheses drawn in proportion to their probability (systematic: evenly
        spaced quantiles, deterministic), each distinct one weighted by its count."""
        cum = np.cumsum(self.probs)
        picks = np.searchsorted(cum, (np.arange(n) + 0.5) / n * cum[-1])
        i, count = np.unique(np.minimum(picks, self.probs.size - 1), return_counts=True)
        parts = None if self.parts is None else self.parts[i]
        p = count / count.sum()
        return Posterior(self.centres[i], self.halves[i], self.yaws[i], p, parts)

    def part_share(self) -> float:
        """Posterior chance that the object is a dense part and a light one."""
        return 0.0 if self.parts is None else float(self.probs @ (self.parts > 1))

    def reweighted(self, likelihood: Array) -> Posterior:
        """The posterior times ``likelihood``, normalised (unchanged where it is all 0)."""
        p = self.probs * likelihood
        return self if p.sum() <= 0 else replace(self, probs=p / p.sum())


def estimate(
    increments_pa: Array,
    modules: tuple[int, ...],
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    masked: frozenset[int] = frozenset(),
) -> Posterior:
    """The footprint posterior of the object on ``modules`` (its centre on one of them):
    every hypothesis within ``log_floor`` of the most likely; ``masked`` modules (other
    objects') say nothing about it.

    Beside the footprints that carry the whole weight evenly (one part), the posterior holds
    two-part hypotheses (:func:`light_modules`): a dense part, the footprint, centred on the
    object's heavier modules, and a light part of unknown shape on its light modules, which
    adds a load >= 0 there (a cable, a stem, a light end); each light module costs
    ``part_cost`` nats of prior odds. ``Posterior.parts`` says which is which."""
    g, b, a, const = _sums(increments_pa, tuple(modules), layout, model, params, masked)
    parts = [(g, _gaussian(b, a, const)[1], 0.0)]
    light = light_modules(increments_pa, modules, layout, params)
    if light:
        heavy = tuple(m for m in modules if m not in light)
        groups = (tuple(modules), heavy, light, masked)
        gh, ll = _two_part(increments_pa, groups, (b, a), layout, model, params)
        parts.append((gh, ll - params.part_cost * len(light), 1.0))
    top = max(float(ll.max()) for _, ll, _ in parts)
    kept = [(g, ll, extra, np.flatnonzero(ll > top - params.log_floor)) for g, ll, extra in parts]
    p = np.exp(np.concatenate([ll[k] for _, ll, _, k in kept]) - top)
    return Posterior(
        np.concatenate([g.centres[k] for g, _, _, k in kept]),
        np.concatenate([g.halves[k] for g, _, _, k in kept]),
        np.concatenate([g.yaws[k] for g, _, _, k in kept]),
        p / p.sum(),
        np.concatenate([np.full(k.size, 1.0 + extra) for _, _, extra, k in kept]),
    )


def light_modules(
    increments_pa: Array, modules: tuple[int, ...], layout: PadLayout, params: ModelBasedParams
) -> tuple[int, ...]:
    """The object's modules a light part may lie on: those reading under ``light_share`` of
    its largest increment, when the others (the dense part's) are at least one and those
    light ones at most ``max_light_modules`` (none when ``light_share`` is 0)."""
    d = np.asarray(increments_pa, dtype=float).ravel()
    top = max(float(d[m - 1]) for m in modules)
    light = tuple(m for m in modules if d[m - 1] < params.light_share * top)
    if not light or len(light) >= len(modules) or len(light) > params.max_light_modules:
        return ()
    return light


def _sums(
    increments_pa: Array,
    modules: tuple[int, ...],
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    masked: frozenset[int],
) -> tuple[_Group, Array, Array, Array]:
    """The hypotheses centred on ``modules`` and the likelihood's sums over each one's
    window (V,) each, every module but ``masked`` weighed by 1 / its variance (w): sum w d g,
    sum w g^2 (g the footprint's share of the load, d the increment) and sum w d^2."""
    t = _templates(layout.pitch_m, params, model)
    g = _group(layout, modules, params, model)
    grid, weight = _padded(increments_pa, layout, t.radius, masked, params)
    d, w = grid[g.window], weight[g.window]  # (C, W) each
    wd = w * d
    b = (wd[:, g.used] @ g.shares[0]).ravel()[g.flat]
    a = (w[:, g.used] @ g.shares[1]).ravel()[g.flat]
    return g, b, a, (wd * d).sum(axis=1)[g.module]


def _gaussian(b: Array, a: Array, const: Array) -> tuple[Array, Array]:
    """Each hypothesis's weight fitted in closed form (>= 0) and its log-likelihood, from
    :func:`_sums`."""
    # a = 0 only where every share is 0, so b = 0 too; with s = max(b, 0) / a the Gaussian's
    # -(const - 2 s b + s^2 a) / 2 is (s max(b, 0) - const) / 2
    positive = np.maximum(b, 0.0)
    scale = positive / np.maximum(a, np.finfo(float).tiny)
    return scale, 0.5 * (scale * positive - const)


def _two_part(
    increments_pa: Array,
    groups: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...], frozenset[int]],
    sums: tuple[Array, Array],
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
) -> tuple[_Group, Array]:
    """The two-part hypotheses (centred on the ``heavy`` modules of ``groups``: the object's
    modules, the heavy ones, the light ones, the masked ones of other objects) and their
    log-likelihoods: Gaussian on every module but ``masked`` and ``light`` ones; on a
    light module the reading
    may exceed the footprint's prediction (a light part adds load there, at no cost) but not
    fall short of it. The sums are the one-part hypotheses' (``sums``: sum w d g and
    sum w g^2 over all of ``modules``) less the light modules' terms: no second product."""
    modules, heavy, light, masked = groups
    t, gh = _templates(layout.pitch_m, params, model), _group(layout, heavy, params, model)
    sel = _subset(layout, modules, heavy, params, model)
    shares = _light_shares(layout, heavy, params, model, light)  # (L, V')
    d = np.asarray(increments_pa, dtype=float).ravel()[np.array(light) - 1]
    w = 1.0 / (params.noise_pa**2 + (params.model_error * d) ** 2)
    b, a = sums[0][sel] - (w * d) @ shares, sums[1][sel] - w @ shares**2
    grid, weight = _padded(increments_pa, layout, t.radius, masked | set(light), params)
    dd, ww = grid[gh.window], weight[gh.window]
    scale, loglik = _gaussian(b, a, (ww * dd * dd).sum(axis=1)[gh.module])
    return gh, loglik - _shortfall(increments_pa, scale, layout, heavy, params, model, light)


@lru_cache(maxsize=32)
def _subset(
    layout: PadLayout,
    modules: tuple[int, ...],
    heavy: tuple[int, ...],
    params: ModelBasedParams,
    model: PadModel,
) -> NDArray[np.int64]:
    """Where the hypotheses centred on ``heavy`` (a subset of ``modules``) lie among those
    centred on ``modules``, in their order (the test of the pad's edge is per hypothesis)."""
    g = _group(layout, modules, params, model)
    ids = np.asarray(modules)[g.module]
    return _frozen(np.flatnonzero(np.isin(ids, heavy)))


def _shortfall(
    increments_pa: Array,
    scale: Array,
    layout: PadLayout,
    modules: tuple[int, ...],
    params: ModelBasedParams,
    model: PadModel,
    light: tuple[int, ...],
) -> Array:
    """Minus the log-likelihood (V,) of the ``light`` modules' readings where each
    hypothesis centred on ``modules`` (its footprint at its fitted ``scale``) predicts more
    than they read."""
    shares = _light_shares(layout, modules, params, model, light)  # (L, V)
    d = np.asarray(increments_pa, dtype=float).ravel()[np.array(light) - 1][:, None]
    var = params.noise_pa**2 + (params.model_error * d) ** 2
    over = np.clip(scale * shares - d, 0.0, None)
    return np.asarray(0.5 * (over**2 / var).sum(axis=0))


@lru_cache(maxsize=32)
def _light_shares(
    layout: PadLayout,
    modules: tuple[int, ...],
    params: ModelBasedParams,
    model: PadModel,
    light: tuple[int, ...],
) -> Array:
    """Each hypothesis's (centred on ``modules``) share of the load, response-weighted, on
    each ``light`` module (L, V): 0 where its window does not reach the module."""
    g = _group(layout, modules, params, model)
    radius = _templates(layout.pitch_m, params, model).radius
    tn = g.shares.shape[2]
    col = g.flat % tn
    out = []
    for m in light:
        row, c = layout.row_col(m)
        r = layout.rows - 1 - row + radius
        at = (g.window[0][:, g.used] == r) & (g.window[1][:, g.used] == c + radius)  # (C, K)
        k = np.where(at.any(axis=1), at.argmax(axis=1), -1)[g.module]  # (V,)
        out.append(np.where(k >= 0, g.shares[0][np.maximum(k, 0), col], 0.0))
    return _frozen(np.array(out))


@dataclass(frozen=True)
class _Group:
    """What the hypotheses centred on an object's modules (C) need of the pad, whatever the
    increments (read-only arrays)."""

    window: tuple[NDArray[np.int64], ...]  # padded grid's index of each one's window (C, W)
    used: NDArray[np.int64]  # (K,) window modules on the pad for one of the modules at least
    #: (2, K, T'): the templates' shares (and squares) on those window modules, of the
    #: templates at most ``overhang`` off the pad centred on one of the modules at least
    shares: Array
    #: The hypotheses (template, module) at most ``overhang`` off the pad, in the order of
    #: the (T, C) table (V of them): their index in the (C, T') products, their module, and
    #: their footprint (centre in module units in the pad frame, half length and width, yaw)
    flat: NDArray[np.int64]
    module: NDArray[np.int64]
    centres: Array  # (V, 2)
    halves: Array  # (V, 2)
    yaws: Array  # (V,)


@lru_cache(maxsize=32)
def _group(
    layout: PadLayout, modules: tuple[int, ...], params: ModelBasedParams, model: PadModel
) -> _Group:
    """The :class:`_Group` of ``modules``: the hypotheses off the pad are ruled out here,
    once, and never scored (about 0.1 MB a module: 0.7 MB for the 2 x 3 pad's six; the
    templates' shares are copied only where some of them are off the pad, at most 1.6 MB)."""
    t = _templates(layout.pitch_m, params, model)
    cols = np.array([layout.row_col(m)[1] for m in modules])
    rows = np.array([layout.rows - 1 - layout.row_col(m)[0] for m in modules])
    gi = (
        rows[:, None] + t.radius + t.window[None, :, 1],
        cols[:, None] + t.radius + t.window[None, :, 0],
    )
    pad = np.zeros((layout.rows + 2 * t.radius, layout.cols + 2 * t.radius))
    pad[t.radius : t.radius + layout.rows, t.radius : t.radius + layout.cols] = 1.0
    on = ~(t.on_pad(pad[gi].T) < 1.0 - params.overhang)  # (T, C)
    ti, ci = np.nonzero(on)
    used_t, used_w = np.flatnonzero(on.any(axis=1)), np.flatnonzero(pad[gi].any(axis=0))
    shares = t.shares
    if used_t.size < on.shape[0] or used_w.size < len(t.window):
        shares = np.ascontiguousarray(shares[:, used_w][:, :, used_t])
    flat = ci * used_t.size + np.searchsorted(used_t, ti)
    centres = np.column_stack([cols[ci] + 0.5, rows[ci] + 0.5]) + t.offsets[ti]
    hyp = (centres, t.halves[ti], t.yaws[ti])
    for x in (*gi, used_w, shares, flat, ci, *hyp):
        _frozen(x)
    return _Group(gi, used_w, shares, flat, ci, *hyp)


def table_bytes(
    layout: PadLayout, modules: tuple[int, ...], params: ModelBasedParams, model: PadModel
) -> tuple[int, int]:
    """Memory the planner keeps (bytes): the templates of ``layout``'s pitch, and the
    hypotheses of the object on ``modules`` (beyond the templates it shares)."""
    t, g = _templates(layout.pitch_m, params, model), _group(layout, modules, params, model)
    own = [getattr(t, f.name) for f in fields(t) if isinstance(getattr(t, f.name), np.ndarray)]
    mine = [*g.window, *(getattr(g, f.name) for f in fields(g) if f.name != "window")]
    shared = {id(a) for a in own}
    return sum(a.nbytes for a in own), sum(a.nbytes for a in mine if id(a) not in shared)


def _padded(
    increments_pa: Array,
    layout: PadLayout,
    radius: int,
    masked: frozenset[int],
    params: ModelBasedParams,
) -> tuple[Array, Array]:
    """The increments and their likelihood weights (1 / variance; 0 off the pad and on
    ``masked`` modules) on the pad grid (row from the bottom, column) padded by ``radius``
    modules of 0."""
    r, c = layout.rows, layout.cols
    grid = np.zeros((r + 2 * radius, c + 2 * radius))
    weight = np.zeros_like(grid)
    d = increments_pa.reshape(r, c)[::-1]  # row 0 at the bottom
    var = params.noise_pa**2 + (params.model_error * d) ** 2
    w = 1.0 / var
    for m in masked:
        row, col = layout.row_col(m)
        w[r - 1 - row, col] = 0.0
    grid[radius : radius + r, radius : radius + c] = d
    weight[radius : radius + r, radius : radius + c] = w
    return grid, weight


# --- 3. candidates -----------------------------------------------------------------------------


def candidate_grid(post: Posterior, params: ModelBasedParams) -> Grid:
    """:func:`candidates` as a :class:`Grid`."""
    step = 1.0 / params.centre_steps
    fan = np.arange(params.directions) * math.pi / params.directions
    thetas = np.unique(np.concatenate([fan, (post.yaws + math.pi / 2) % math.pi]))
    across = np.array([0.0, 0.5, -0.5, 1.0, -1.0]) * step
    return Grid(np.asarray(post.mean_centre()), thetas, np.zeros(1), across)


def refined_grid(centre: Array, theta: float, params: ModelBasedParams, density: int = 1) -> Grid:
    """:func:`refined` as a :class:`Grid`; ``density`` times as many steps each way, each
    ``density`` times shorter (the same reach)."""
    n = params.refine_steps * density
    k = np.arange(-n, n + 1) / density
    thetas = theta + k * params.refine_turn * math.pi / params.directions
    shift = k * params.refine_shift / params.centre_steps
    return Grid(np.asarray(centre, dtype=float), thetas, shift, shift)


#: A grasp found: its predicted success, centre (2,) in module units and direction, rad.
Found = tuple[float, Array, float]


def tight_search(
    post: Posterior,
    coarse: Grid,
    found: Found,
    gripper: GripperSpec,
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    sensing_ratio: float,
) -> Found:
    """The finer search near a tight fit: from ``found`` (the finer search's best) and from
    the best candidates of ``coarse`` in other directions (``tight_starts`` in all, each
    more than the finer search's reach from the others, searched as it is), a pattern
    search of ``tight_rounds`` rounds on the predicted success (:func:`polished`). The best
    grasp found; ``found`` unless another scores higher."""
    args = (gripper, layout, model, params, sensing_ratio)
    reach = params.refine_steps * params.refine_turn * math.pi / params.directions
    starts, best = [found[2]], polished(post, found, *args)
    for _ in range(params.tight_starts - 1):
        gap = np.remainder(coarse.thetas[:, None] - np.array(starts)[None] + math.pi / 2, math.pi)
        far = (np.abs(gap - math.pi / 2) > reach + 1e-9).all(axis=1)
        if not far.any():
            break
        _, centre, theta = best_on_grid(post, replace(coarse, thetas=coarse.thetas[far]), *args)
        starts.append(theta)
        fine = refined_grid(centre, theta, params, 2)
        other = polished(post, best_on_grid(post, fine, *args), *args)
        if other[0] > best[0]:
            best = other
    return best


def polished(
    post: Posterior,
    found: Found,
    gripper: GripperSpec,
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    sensing_ratio: float,
) -> Found:
    """``tight_rounds`` rounds of a pattern search from ``found`` on the predicted success:
    each a 3 x 3 x 3 grid of direction, shift along and shift across the closing direction
    around the best so far (it included), its steps a quarter of the finer search's at
    first (half those of its tight-fit grid, :func:`refined_grid` at density 2), halved
    after every round whose best stays where it was."""
    args = (gripper, layout, model, params, sensing_ratio)
    turn = params.refine_turn * math.pi / params.directions / 4
    shift = params.refine_shift / params.centre_steps / 4
    k = np.array([-1.0, 0.0, 1.0])
    score, centre, theta = found
    for _ in range(params.tight_rounds):
        grid = Grid(np.asarray(centre, dtype=float), theta + k * turn, k * shift, k * shift)
        s, c, t = best_on_grid(post, grid, *args)
        if s > score:
            score, centre, theta = s, c, t
        else:
            turn, shift = turn / 2, shift / 2
    return score, centre, theta


def candidates(post: Posterior, params: ModelBasedParams) -> tuple[Array, Array]:
    """Grasp centres (G, 2), module units, and closing directions (G,): the fixed fan of
    directions and the directions across the likely footprints, each with its centre on the
    posterior mean of the footprint's centre and shifted from it across the closing
    direction by half and one hypothesis step either way. Along the closing direction the
    centre stays on the mean: the object's extent is known only as its footprint (a ball's
    or a can's is wider), so the centred grasp leaves the most room on both sides."""
    step = 1.0 / params.centre_steps
    fan = np.arange(params.directions) * math.pi / params.directions
    thetas = np.unique(np.concatenate([fan, (post.yaws + math.pi / 2) % math.pi]))
    across = np.array([0.0, 0.5, -0.5, 1.0, -1.0]) * step
    normal = np.column_stack([-np.sin(thetas), np.cos(thetas)])  # (D, 2)
    centres = np.asarray(post.mean_centre()) + across[:, None, None] * normal[None]
    return centres.reshape(-1, 2), np.tile(thetas, across.size)


# --- 4. score ----------------------------------------------------------------------------------

#: Sample points of a fingertip's sole: fractions of its thickness (along the closing
#: direction) and of its width (across it).
_SOLE = np.array([(a, b) for a in (-0.4, 0.0, 0.4) for b in (-0.4, -0.2, 0.0, 0.2, 0.4)])


def tip_response(
    centres: Array, thetas: Array, gripper: GripperSpec, layout: PadLayout, model: PadModel
) -> Array:
    """Mean relative response under the better-placed of the two open fingertips of each
    grasp (G,): what the contact detector has to sense."""
    cos, sin = np.cos(thetas), np.sin(thetas)
    reach = (gripper.max_width_m + gripper.tip_thickness_m) / 2 / layout.pitch_m
    a = _SOLE[:, 0, None] * gripper.tip_thickness_m  # (S, 1) along the closing direction
    b = _SOLE[:, 1, None] * gripper.tip_width_m  # across it
    ends = np.array([1.0, -1.0])[:, None, None] * reach  # the two fingertips (2, 1, 1)
    # the sole's points (2, S, G) per coordinate, in the order PadModel.on_pad reads them
    x = (centres[:, 0] + ends * cos) + (a * cos + b * -sin) / layout.pitch_m
    y = (centres[:, 1] + ends * sin) + (a * sin + b * cos) / layout.pitch_m
    fx, fy = np.floor(x), np.floor(y)
    inside = (fx >= 0) & (fx < layout.cols) & (fy >= 0) & (fy < layout.rows)
    # PadModel.response of the point's offset from its module's centre, in [-0.5, 0.5)
    ix = np.rint((x - fx - 0.5 + 0.5) * (_LOOKUP - 1)).astype(np.int64)
    iy = np.rint((y - fy - 0.5 + 0.5) * (_LOOKUP - 1)).astype(np.int64)
    mean = np.where(inside, model.table.ravel()[ix * _LOOKUP + iy], 0.0).mean(axis=1)
    return np.maximum(np.maximum(0.0, mean[0]), mean[1])


def _offsets(
    post: Posterior, centres: Array, thetas: Array, distinct: int | None = None
) -> tuple[Array, ...]:
    """Offsets of each footprint's centre from each grasp centre along and across the
    closing direction, and |cos|, |sin| of the footprint's yaw from it: (G, H) each
    (``centres`` may be one centre for all, (1, 2); ``distinct``: the directions are all
    different, G of them)."""
    ux, uy = np.cos(thetas)[:, None], np.sin(thetas)[:, None]
    dx = post.centres[None, :, 0] - centres[:, None, 0]
    dy = post.centres[None, :, 1] - centres[:, None, 1]
    if distinct is not None:
        phi = post.yaws[None, :] - thetas[:, None]
        c, s = np.abs(np.cos(phi)), np.abs(np.sin(phi))
    else:  # a few, each at several centres
        directions, row = np.unique(thetas, return_inverse=True)
        phi = post.yaws[None, :] - directions[:, None]
        c, s = np.abs(np.cos(phi))[row], np.abs(np.sin(phi))[row]
    return dx * ux + dy * uy, dy * ux - dx * uy, c, s


def _half_extents(post: Posterior, c: Array, s: Array, shapes: _Shapes) -> tuple[Array, Array]:
    """Half extents of the object along and across the closing direction for each shape
    (:class:`_Shapes`: the object's extent over its footprint along the footprint's length
    and across it, and the least it spans): (S, G, H) each."""
    ext, least = shapes.extents, shapes.least / 2
    hl = np.maximum(ext[:, 0, None, None] * post.halves[None, None, :, 0], least[:, 0, None, None])
    hw = np.maximum(ext[:, 1, None, None] * post.halves[None, None, :, 1], least[:, 1, None, None])
    return hl * c + hw * s, hl * s + hw * c


@dataclass(frozen=True)
class _Shapes:
    """The shapes the pad cannot tell apart (S of them): the object's extent over its
    footprint along the footprint's length and across it (S, 2), the least extent it spans
    each way (S, 2), module units, and the prior weights (S,) summing to 1."""

    extents: Array
    least: Array
    weights: Array


@lru_cache(maxsize=16)
def _shapes(params: ModelBasedParams, pitch_m: float, opening_m: float) -> _Shapes:
    """:class:`_Shapes` of ``params`` on a pad of ``pitch_m`` for jaws opening ``opening_m``:
    each curved shape (an extent over 1) once per diameter of ``curved_diameters``, spanning
    at least that diameter where it is curved, its weight shared evenly among them."""
    w = np.asarray(params.shape_weights, dtype=float)
    extents, least, weights = [], [], []
    diameters = [d * opening_m / pitch_m for d in params.curved_diameters]
    for e, wi in zip(params.shape_extents, w / w.sum(), strict=True):
        curved = [v > 1.0 for v in e]
        spans = diameters if any(curved) and diameters else [0.0]
        for dia in spans:
            extents.append(e)
            least.append([dia if k else 0.0 for k in curved])
            weights.append(wi / len(spans))
    return _Shapes(*(_frozen(np.asarray(a, dtype=float)) for a in (extents, least, weights)))


def edge_scale(params: ModelBasedParams) -> float:
    """Scale of the logistic error of where the object's edge lies beyond a hypothesis's,
    module units: its rms is the rms of the hypotheses' centre grid's rounding (a uniform
    error over one step, step / sqrt(12); 3.2 mm on the 45 mm pad at 4 steps a module)."""
    rms = 1.0 / (params.centre_steps * math.sqrt(12.0))
    return rms * math.sqrt(3.0) / math.pi  # a logistic of scale b has rms b pi / sqrt(3)


def _clear(margin: Array, scale: float) -> Array:
    """Chance that an edge lies inside a jaw's path by less than ``margin`` (logistic)."""
    return 0.5 + 0.5 * np.tanh(margin * (0.5 / scale))  # the logistic, without overflow


def _landing_terms(
    post: Posterior,
    centres: Array,
    thetas: Array,
    gripper: GripperSpec,
    layout: PadLayout,
    params: ModelBasedParams,
) -> tuple[Array, NDArray[np.bool_]]:
    """Per shape and hypothesis (S, G, H): the chance that both open jaws come down clear of
    the object (the landing term), and whether it then closes on it and hangs balanced."""
    half_open = (gripper.max_width_m / 2 - params.clearance_m) / layout.pitch_m
    narrow = gripper.min_width_m / layout.pitch_m
    m_u, m_n, c, s = _offsets(post, centres, thetas)
    e_u, e_n = _half_extents(post, c, s, _shapes(params, layout.pitch_m, gripper.max_width_m))
    b = edge_scale(params)
    clear = _clear(half_open - m_u - e_u, b) * _clear(half_open + m_u - e_u, b)
    hold = (2 * e_u > narrow) & (np.abs(m_n) < params.centre_band * e_n)
    return clear, hold


def footprint_room(
    post: Posterior,
    centre: Array,
    theta: float,
    gripper: GripperSpec,
    layout: PadLayout,
    params: ModelBasedParams,
) -> float:
    """Posterior mean room between the nearer open jaw (less ``clearance_m``) and the
    estimated footprint itself (not the shapes it may belong to) for the grasp at ``centre``
    (2,), module units, closing along ``theta``, m: under 0 the footprint reaches the jaw."""
    half_open = gripper.max_width_m / 2 - params.clearance_m
    m_u, _, c, s = _offsets(post, np.asarray(centre, dtype=float)[None], np.array([theta]), 1)
    e_u = post.halves[:, 0] * c[0] + post.halves[:, 1] * s[0]
    return float(post.probs @ (half_open - (np.abs(m_u[0]) + e_u) * layout.pitch_m))


def landing_chance(
    post: Posterior,
    centres: Array,
    thetas: Array,
    gripper: GripperSpec,
    layout: PadLayout,
    params: ModelBasedParams,
) -> Array:
    """Posterior chance (G,) that a jaw of each grasp comes down on the object: from the
    estimated footprints (the posterior), the shapes they may be of, and the uncertainty of
    where the object's edge lies (:func:`edge_scale`)."""
    clear, _ = _landing_terms(post, centres, thetas, gripper, layout, params)
    weights = _shapes(params, layout.pitch_m, gripper.max_width_m).weights
    return 1.0 - np.einsum("s,sgh,h->g", weights, clear, post.probs)


def fit_chance(
    post: Posterior,
    centres: Array,
    thetas: Array,
    gripper: GripperSpec,
    layout: PadLayout,
    params: ModelBasedParams,
) -> Array:
    """Posterior chance (G,) that each grasp's jaws come down clear of the object (the
    landing term, :func:`landing_chance`), close on it and hold it balanced, every shape of
    ``params.shape_extents`` counting with its weight."""
    clear, hold = _landing_terms(post, centres, thetas, gripper, layout, params)
    weights = _shapes(params, layout.pitch_m, gripper.max_width_m).weights
    return np.einsum("s,sgh,h->g", weights, clear * hold, post.probs)


def predicted_success(
    post: Posterior,
    centres: Array,
    thetas: Array,
    gripper: GripperSpec,
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    sensing_ratio: float,
) -> Array:
    """Predicted success of each grasp (G,): the chance a fingertip is sensed (its sole's
    response over the share the detector needs, at most 1) times :func:`fit_chance`."""
    need = params.needed_share * sensing_ratio
    sensed = np.clip(tip_response(centres, thetas, gripper, layout, model) / need, 0.0, 1.0)
    return sensed * fit_chance(post, centres, thetas, gripper, layout, params)


@dataclass(frozen=True)
class Grid:
    """Grasps on a grid: every direction of ``thetas`` (D,) with its centre at ``base``
    (2,) shifted by each of ``along`` (A,) along the closing direction and each of
    ``across`` (B,) across it (module units). Scored as a grid, the landing term depends on
    the shift along only and the balance on the shift across only: (A + B) D H terms and one
    product instead of A B D H of each."""

    base: Array
    thetas: Array
    along: Array
    across: Array

    def grasps(self) -> tuple[Array, Array]:
        """Centres (A, B, D, 2) and directions (A, B, D) of the grid's grasps."""
        cos, sin = np.cos(self.thetas), np.sin(self.thetas)
        u, n = np.stack([cos, sin], axis=1), np.stack([-sin, cos], axis=1)  # (D, 2) each
        centres = (
            self.base
            + self.along[:, None, None, None] * u[None, None]
            + self.across[None, :, None, None] * n[None, None]
        )
        shape = (self.along.size, self.across.size, self.thetas.size)
        return centres, np.broadcast_to(self.thetas, shape)

    def grasp(self, flat: NDArray[np.int64]) -> tuple[Array, Array]:
        """Centres (G, 2) and directions (G,) of the grasps at indices ``flat`` of the
        raveled grid (the same figures as :meth:`grasps`)."""
        rest, d = np.divmod(flat, self.thetas.size)
        a, b = np.divmod(rest, self.across.size)
        t = self.thetas[d]
        cos, sin = np.cos(t), np.sin(t)
        u, n = np.stack([cos, sin], axis=1), np.stack([-sin, cos], axis=1)
        return self.base + self.along[a, None] * u + self.across[b, None] * n, t


def grid_fit(
    post: Posterior, grid: Grid, gripper: GripperSpec, layout: PadLayout, params: ModelBasedParams
) -> Array:
    """:func:`fit_chance` of every grasp of ``grid``, (A, B, D) (:meth:`Grid.grasps`)."""
    half_open = (gripper.max_width_m / 2 - params.clearance_m) / layout.pitch_m
    narrow = gripper.min_width_m / layout.pitch_m
    m_u, m_n, c, s = _offsets(post, grid.base[None], grid.thetas, grid.thetas.size)  # (D, H)
    shapes = _shapes(params, layout.pitch_m, gripper.max_width_m)
    weights = shapes.weights
    e_u, e_n = _half_extents(post, c, s, shapes)  # (S, D, H)
    m_u = m_u[None] - grid.along[:, None, None]  # (A, D, H)
    b = edge_scale(params)
    e_u4 = e_u[:, None]
    clear = _clear(half_open - m_u - e_u4, b) * _clear(half_open + m_u - e_u4, b)  # (S,A,D,H)
    m_n = np.abs(m_n[None] - grid.across[:, None, None])  # (B, D, H)
    hold = (2 * e_u > narrow)[:, None] & (m_n < params.centre_band * e_n[:, None])  # (S,B,D,H)
    # sum over shapes and hypotheses of w_s p_h clear[s,a,d,h] hold[s,b,d,h], as (S, D) matrix
    # products (a 4-operand einsum is several times slower)
    lhs = (clear * (weights[:, None, None, None] * post.probs)).transpose(0, 2, 1, 3)
    return (lhs @ hold.astype(float).transpose(0, 2, 3, 1)).sum(axis=0).transpose(1, 2, 0)


def grid_success(
    post: Posterior,
    grid: Grid,
    gripper: GripperSpec,
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    sensing_ratio: float,
) -> tuple[Array, Array, Array]:
    """:func:`predicted_success` of every grasp of ``grid``, (A, B, D), with the grasps
    (:meth:`Grid.grasps`)."""
    fit = grid_fit(post, grid, gripper, layout, params)
    centres, thetas = grid.grasps()
    tip = tip_response(centres.reshape(-1, 2), thetas.ravel(), gripper, layout, model)
    need = params.needed_share * sensing_ratio
    return np.clip(tip.reshape(fit.shape) / need, 0.0, 1.0) * fit, centres, thetas


def best_on_grid(
    post: Posterior,
    grid: Grid,
    gripper: GripperSpec,
    layout: PadLayout,
    model: PadModel,
    params: ModelBasedParams,
    sensing_ratio: float,
) -> tuple[float, Array, float]:
    """The grasp of ``grid`` with the highest :func:`predicted_success` (the first of
    equals, as ``argmax`` of :func:`grid_success` finds it): its success, centre (2,) and
    direction. The fingertips are looked up only where they may decide: the sensed share is
    at most 1, so a grasp whose fit is below the best success found cannot beat it; the
    grasps are scored in batches of falling fit until the next fit is below that."""
    fit = grid_fit(post, grid, gripper, layout, params)
    flat, order = fit.ravel(), np.argsort(-fit.ravel(), kind="stable")
    need = params.needed_share * sensing_ratio
    best, best_i, done, batch = -1.0, 0, 0, _FIRST_BATCH
    centre, theta = np.zeros(2), 0.0
    while done < flat.size and flat[order[done]] >= best:
        idx = np.sort(order[done : done + batch])
        points, directions = grid.grasp(idx)
        tip = tip_response(points, directions, gripper, layout, model)
        score = np.clip(tip / need, 0.0, 1.0) * flat[idx]
        k = int(np.argmax(score))
        if score[k] > best or (score[k] == best and idx[k] < best_i):
            best, best_i = float(score[k]), int(idx[k])
            centre, theta = points[k], float(directions[k])
        done, batch = done + batch, 2 * batch
    return best, centre, theta


#: Grasps whose fingertips are looked up in :func:`best_on_grid`'s first batch (doubling).
_FIRST_BATCH = 32


def refined(centre: Array, theta: float, params: ModelBasedParams) -> tuple[Array, Array]:
    """The finer search around a grasp: centres (G, 2), module units, and directions (G,):
    every direction ``refine_steps`` steps of ``refine_turn`` fan steps either way, with the
    centre shifted along and across it by ``refine_steps`` steps of ``refine_shift``
    hypothesis steps either way (the grasp itself included)."""
    k = np.arange(-params.refine_steps, params.refine_steps + 1)
    thetas = theta + k * params.refine_turn * math.pi / params.directions
    shift = k * params.refine_shift / params.centre_steps
    u = np.column_stack([np.cos(thetas), np.sin(thetas)])  # (D, 2)
    n = np.column_stack([-u[:, 1], u[:, 0]])
    along, across = np.meshgrid(shift, shift, indexing="ij")
    offs = along.ravel()[:, None, None] * u[None] + across.ravel()[:, None, None] * n[None]
    centres = np.asarray(centre) + offs  # (A, D, 2)
    return centres.reshape(-1, 2), np.tile(thetas, along.size)


def landing_likelihood(
    post: Posterior,
    plan: GraspPlan,
    side: int,
    gripper: GripperSpec,
    layout: PadLayout,
    params: ModelBasedParams,
) -> Array:
    """Likelihood (H,) of a landing of ``plan``'s jaws on the object, on the ``side`` of the
    centre the pad felt pressed (+1 along the closing direction, -1 against, 0 unknown):
    1 where the footprint (any shape, by its weight) puts a jaw there, ``surprise``
    elsewhere."""
    centre, theta = np.array([plan.cog]), np.array([plan.theta])
    half_open = gripper.max_width_m / 2 / layout.pitch_m
    tip_half = gripper.tip_width_m / 2 / layout.pitch_m
    m_u, m_n, c, s = _offsets(post, centre, theta)  # (1, H) each
    shapes = _shapes(params, layout.pitch_m, gripper.max_width_m)
    weights = shapes.weights
    e_u, e_n = (a[:, 0] for a in _half_extents(post, c, s, shapes))  # (S, H)
    under = np.abs(m_n) < e_n + tip_half
    plus, minus = under & (m_u + e_u > half_open), under & (m_u - e_u < -half_open)
    hit = {1: plus, -1: minus}.get(side, plus | minus)
    return np.asarray(weights @ np.where(hit, 1.0, params.surprise), dtype=float)


# --- 5. choose ---------------------------------------------------------------------------------


@dataclass
class ModelBasedPlanner:
    """Estimate the footprint from the pad model, then the grasp most likely to succeed
    (a ``RetryPlanner``; see the module's docstring).

    Parameters
    ----------
    gripper
        Jaw geometry: opening range, fingertip size.
    params
        The planner's parameters.
    sensing_ratio
        The contact detector's step floor over the thesis detector's
        (:func:`softpad.sensing.sensing_ratio`; 1 for the thesis's).
    model
        The pad model (:func:`packaged_pad_model` at ``params.pressure_pa`` by default: the
        cast pad's FEM response).
    """

    gripper: GripperSpec = field(default_factory=GripperSpec)
    params: ModelBasedParams = field(default_factory=ModelBasedParams)
    sensing_ratio: float = 1.0
    model: PadModel | None = None
    _evidence: dict[tuple[object, ...], list[tuple[GraspPlan, int]]] = field(
        default_factory=dict, repr=False
    )

    def __post_init__(self) -> None:
        if not (math.isfinite(self.sensing_ratio) and self.sensing_ratio > 0):
            raise InputError(f"sensing ratio must be a number > 0, got {self.sensing_ratio!r}")
        if self.model is None:
            self.model = packaged_pad_model(self.params.pressure_pa)

    def object_detector(self) -> NoiseObjectDetector | None:
        """A fresh detector for a run of the loop, which finds this planner's objects with it
        (``params.detection``; None: the loop's t_o detector)."""
        d = self.params.detection
        return None if d is None else NoiseObjectDetector(d)

    def plan(
        self, increments_pa: ArrayLike, objects: list[tuple[int, ...]], layout: PadLayout
    ) -> list[GraspPlan]:
        d = check_increments(increments_pa, layout)
        groups = outline_objects(d, objects, layout, self.params.outline_threshold_pa)
        self._evidence.clear()
        return [self._choose(d, g, groups, layout, [])[0] for g in groups]

    def mounting_success(
        self,
        increments_pa: ArrayLike,
        objects: list[tuple[int, ...]],
        layout: PadLayout,
        gripper: GripperSpec,
    ) -> float:
        """Predicted success of the grasp this planner would choose for the most loaded of
        ``objects`` with ``gripper``'s jaws (the ``--mounting auto`` hook)."""
        d = check_increments(increments_pa, layout)
        groups = outline_objects(d, objects, layout, self.params.outline_threshold_pa)
        if not groups:
            return 0.0
        target = max(groups, key=lambda g: float(sum(d[m - 1] for m in g)))
        other = replace(self, gripper=gripper, _evidence={})
        return other._choose(d, target, groups, layout, [])[1]

    def retry(
        self,
        plan: GraspPlan,
        increments_pa: ArrayLike,
        layout: PadLayout,
        landing_rise_pa: ArrayLike,
        closed: bool = True,
    ) -> GraspPlan | None:
        """The grasp chosen again once ``plan``'s landing on the object (and the side it
        pressed) is evidence; before closing (not ``closed``) only when it differs from
        ``plan``, after a miss whatever it is."""
        d = check_increments(increments_pa, layout)
        rise = check_increments(landing_rise_pa, layout)
        side = _pressed_side(plan, layout, rise, self.params.side_share)
        key = (plan.modules, d.round(3).tobytes())
        seen = self._evidence.setdefault(key, [])
        if (plan, side) not in seen:  # asked at the landing, then after the miss: one landing
            seen.append((plan, side))
        groups = outline_objects(d, [plan.modules], layout, self.params.outline_threshold_pa)
        best = self._choose(d, plan.modules, groups, layout, seen)[0]
        moved = math.dist(best.cog, plan.cog) * layout.pitch_m > 2e-3
        turned = abs(math.remainder(best.theta - plan.theta, math.pi)) > math.radians(5)
        if not closed and not (moved or turned):
            return None
        return replace(best, rule=best.rule + "+after-landing")

    def _choose(
        self,
        d: Array,
        modules: tuple[int, ...],
        groups: list[tuple[int, ...]],
        layout: PadLayout,
        evidence: list[tuple[GraspPlan, int]],
    ) -> tuple[GraspPlan, float]:
        """The grasp of the object on ``modules`` with the highest predicted success, and
        that success."""
        assert self.model is not None
        others = frozenset(m for g in groups if g != modules for m in g)
        post = estimate(d, modules, layout, self.model, self.params, others)
        for tried, side in evidence:
            post = post.reweighted(
                landing_likelihood(post, tried, side, self.gripper, layout, self.params)
            )
        post = post.sample(self.params.kept_hypotheses)
        args = (self.gripper, layout, self.model, self.params, self.sensing_ratio)
        coarse = candidate_grid(post, self.params)
        found = best_on_grid(post, coarse, *args)
        tight = self._tight(post, found, layout)
        if self.params.refine_steps:
            # the coarse best is the grid's centre: never worse; twice as fine where tight
            fine = refined_grid(found[1], found[2], self.params, 2 if tight else 1)
            found = best_on_grid(post, fine, *args)
        if tight:
            found = tight_search(post, coarse, found, *args)
        score, best, t = found
        centre = (float(best[0]), float(best[1]))
        t %= math.pi
        theta = t - (math.pi if t > math.pi / 2 + 1e-12 else 0.0)
        rule = f"model-based p={score:.2f}"
        plan = GraspPlan(modules, pcom(d, modules, layout), centre, theta, rule, modules)
        return plan, score

    def _tight(self, post: Posterior, found: Found, layout: PadLayout) -> bool:
        """Whether ``found`` leaves the estimated footprint less than ``tight_room_m`` a side
        (:func:`footprint_room`)."""
        if self.params.tight_room_m <= 0:
            return False
        room = footprint_room(post, found[1], found[2], self.gripper, layout, self.params)
        return room < self.params.tight_room_m


def _pressed_side(plan: GraspPlan, layout: PadLayout, rise: Array, share: float) -> int:
    """+1 or -1: the side of the plan's centre along its closing direction where the
    landing's rise (clipped at 0) weighs at least ``share`` of the total; 0 otherwise."""
    w = np.clip(rise, 0.0, None)
    if w.sum() <= 0:
        return 0
    u = np.array([math.cos(plan.theta), math.sin(plan.theta)])
    along = (layout.centers - np.asarray(plan.cog)) @ u
    plus, minus = float(w[along > 0].sum()), float(w[along < 0].sum())
    if max(plus, minus) < share * float(w.sum()):
        return 0
    return 1 if plus > minus else -1
