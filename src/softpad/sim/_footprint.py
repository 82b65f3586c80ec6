"""Footprints of objects and fingertips on the pad, and how their weight reaches the modules.

Model (documented in docs/box-and-simulator.md):

* The pad surface is a grid of square modules of side ``pitch_m``; between modules (and along
  the pad's border) runs a non-sensitive line of width ``line_width_m``, the bonded seam between
  chambers (0 by default: the thesis's 45 mm chambers at a 45 mm pitch). The square of a module is
  the module square shrunk by half a line on every side. How much a load on it squeezes the
  chamber is the FEM response (``_response.py``), applied by the worlds.
* A rigid object rests on the pad, which acts as a uniform elastic (Winkler) foundation under
  the object's contact footprint (the union of the projections of the parts that touch the
  resting plane). The contact pressure of a rigid body on a Winkler bed is linear in x and y,
  ``q = a + b (x - x_c) + c (y - y_c)``, with ``a, b, c`` fixed by force and moment balance
  about the centre of mass (x_c, y_c); where q would be negative the object lifts off and the
  points are dropped (a few active-set iterations). Heavier parts thus load their modules more.
* Only the modules' sensitive squares support the object: between inflated modules the
  non-sensitive lines are valleys about a module height deep, which an object bridging them
  does not touch. The force on a module is the integral of q over the footprint on its square.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sim._objects import ObjectSpec, PartSpec, Placement
from softpad.sim._response import PadResponse

#: Standard gravity, m/s^2.
GRAVITY_M_S2 = 9.80665
#: Width of the non-sensitive line between modules, metres: the bonded seam between chambers
#: (:data:`softpad.thesis.SEAM_WIDTH_M`, 0 mm within the thesis's figures).
DEFAULT_LINE_WIDTH_M = thesis.SEAM_WIDTH_M
#: Sampling step of footprints, metres.
DEFAULT_SAMPLE_STEP_M = 0.5e-3
#: Fraction of a lying cylinder's diameter that rests on the soft pad (the pad wraps it).
LYING_CYLINDER_CONTACT_FRACTION = 0.5
#: Fraction of a sphere's radius that is the radius of its contact disc on the soft pad.
SPHERE_CONTACT_FRACTION = 0.5


@dataclass(frozen=True)
class PadSurface:
    """Where the pad is sensitive."""

    #: Pad geometry (module pitch, rows, columns).
    layout: PadLayout = field(default_factory=PadLayout)
    #: Width of the non-sensitive line between neighbouring modules, metres (the seam,
    #: :data:`DEFAULT_LINE_WIDTH_M`; half of it also runs along the pad's outer border).
    line_width_m: float = DEFAULT_LINE_WIDTH_M

    def __post_init__(self) -> None:
        if not (0.0 <= self.line_width_m < self.layout.pitch_m):
            raise InputError(
                f"line width must be in [0, {self.layout.pitch_m * 1e3:g}) mm, got "
                f"{self.line_width_m * 1e3:g} mm"
            )

    @property
    def sensitive_side_m(self) -> float:
        """Side of a module's sensitive square, metres."""
        return self.layout.pitch_m - self.line_width_m

    @property
    def sensitive_area_m2(self) -> float:
        """Area of a module's sensitive square, square metres."""
        return self.sensitive_side_m**2

    @property
    def size_m(self) -> tuple[float, float]:
        """Pad extent (x, y), metres."""
        return self.layout.cols * self.layout.pitch_m, self.layout.rows * self.layout.pitch_m

    def module_index(self, points_m: NDArray[np.float64]) -> NDArray[np.int64]:
        """0-based module index of each point on a sensitive square, -1 on a line or off the pad.

        Parameters
        ----------
        points_m
            Pad-frame points (x, y), shape (n, 2), metres.
        """
        pitch = self.layout.pitch_m
        u = points_m[:, 0] / pitch
        v = points_m[:, 1] / pitch
        col = np.floor(u).astype(np.int64)
        row_from_bottom = np.floor(v).astype(np.int64)
        half = 0.5 * self.line_width_m / pitch
        fu = u - col
        fv = v - row_from_bottom
        ok = (
            (col >= 0)
            & (col < self.layout.cols)
            & (row_from_bottom >= 0)
            & (row_from_bottom < self.layout.rows)
            & (fu > half)
            & (fu < 1 - half)
            & (fv > half)
            & (fv < 1 - half)
        )
        row = self.layout.rows - 1 - row_from_bottom
        idx = row * self.layout.cols + col
        return np.where(ok, idx, -1)

    def module_coverage(
        self, points_m: NDArray[np.float64], cell_m: float
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Module of each sample cell and the fraction of the cell on its sensitive square.

        Each point stands for an axis-aligned square cell of side ``cell_m`` (smaller than the
        line width, so a cell never reaches two sensitive squares); the fraction is exact for
        such cells and makes loads vary smoothly with an object's position.

        Returns
        -------
        index, fraction
            0-based module (-1 off the pad) and covered fraction in [0, 1] per point.
        """
        pitch, half_line, h = self.layout.pitch_m, 0.5 * self.line_width_m, 0.5 * cell_m
        col = np.floor(points_m[:, 0] / pitch).astype(np.int64)
        rb = np.floor(points_m[:, 1] / pitch).astype(np.int64)
        ok = (col >= 0) & (col < self.layout.cols) & (rb >= 0) & (rb < self.layout.rows)

        def cover(x: NDArray[np.float64], k: NDArray[np.int64]) -> NDArray[np.float64]:
            lo, hi = k * pitch + half_line, (k + 1) * pitch - half_line
            return np.clip(np.minimum(x + h, hi) - np.maximum(x - h, lo), 0.0, None) / cell_m

        frac = np.where(ok, cover(points_m[:, 0], col) * cover(points_m[:, 1], rb), 0.0)
        idx = np.where(ok, (self.layout.rows - 1 - rb) * self.layout.cols + col, -1)
        return idx, frac

    def on_pad(self, points_m: NDArray[np.float64]) -> NDArray[np.bool_]:
        """True for points over the pad (lines included)."""
        w, h = self.size_m
        return (
            (points_m[:, 0] >= 0)
            & (points_m[:, 0] <= w)
            & (points_m[:, 1] >= 0)
            & (points_m[:, 1] <= h)
        )


def _rect_points(lx: float, ly: float, step: float) -> NDArray[np.float64]:
    nx = max(1, math.ceil(lx / step))
    ny = max(1, math.ceil(ly / step))
    xs = (np.arange(nx) + 0.5) * (lx / nx) - lx / 2
    ys = (np.arange(ny) + 0.5) * (ly / ny) - ly / 2
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    return np.column_stack([gx.ravel(), gy.ravel()])


def _disc_points(r: float, step: float) -> NDArray[np.float64]:
    pts = _rect_points(2 * r, 2 * r, step)
    return pts[np.hypot(pts[:, 0], pts[:, 1]) <= r]


def part_footprint(
    part: PartSpec, step_m: float = DEFAULT_SAMPLE_STEP_M
) -> tuple[NDArray[np.float64], float]:
    """Contact footprint of a part in the object frame, sampled on a grid.

    A box rests on its bottom face; an upright cylinder on its disc; a lying cylinder on a strip
    ``LYING_CYLINDER_CONTACT_FRACTION`` of its diameter wide; a sphere on a disc
    ``SPHERE_CONTACT_FRACTION`` of its radius.

    Returns
    -------
    points, area
        Points (n, 2) in the object frame (metres) and the area each represents (m^2).
    """
    if part.shape == "box":
        assert part.size_m is not None
        local = _rect_points(part.size_m[0], part.size_m[1], step_m)
        area = part.size_m[0] * part.size_m[1] / len(local)
    elif part.shape == "cylinder":
        assert part.radius_m is not None and part.length_m is not None
        if part.axis == "z":
            local = _disc_points(part.radius_m, step_m)
            area = math.pi * part.radius_m**2 / len(local)
        else:
            width = 2 * part.radius_m * LYING_CYLINDER_CONTACT_FRACTION
            lx, ly = (part.length_m, width) if part.axis == "x" else (width, part.length_m)
            local = _rect_points(lx, ly, step_m)
            area = lx * ly / len(local)
    else:
        assert part.radius_m is not None
        r = part.radius_m * SPHERE_CONTACT_FRACTION
        local = _disc_points(r, step_m)
        area = math.pi * r**2 / len(local)
    c, s = math.cos(part.yaw_rad), math.sin(part.yaw_rad)
    rot = np.array([[c, -s], [s, c]])
    return local @ rot.T + np.array(part.pos_m[:2]), area


def part_outline(part: PartSpec, step_m: float = 2e-3) -> NDArray[np.float64]:
    """Points covering the part's full projection on the pad plane, object frame, metres.

    Unlike :func:`part_footprint` (what touches the pad), this is what the jaws meet: a box's
    rectangle, a lying cylinder's length x diameter, a sphere's or an upright cylinder's disc.
    """
    if part.shape == "box":
        assert part.size_m is not None
        local = _rect_points(part.size_m[0], part.size_m[1], step_m)
    elif part.shape == "cylinder" and part.axis != "z":
        assert part.radius_m is not None and part.length_m is not None
        d = 2 * part.radius_m
        lx, ly = (part.length_m, d) if part.axis == "x" else (d, part.length_m)
        local = _rect_points(lx, ly, step_m)
    else:
        assert part.radius_m is not None
        local = _disc_points(part.radius_m, step_m)
    c, s = math.cos(part.yaw_rad), math.sin(part.yaw_rad)
    return local @ np.array([[c, -s], [s, c]]).T + np.array(part.pos_m[:2])


def to_pad_frame(points_obj: NDArray[np.float64], placement: Placement) -> NDArray[np.float64]:
    """Object-frame points (n, 2) -> pad-frame points, metres."""
    c, s = math.cos(placement.yaw_rad), math.sin(placement.yaw_rad)
    rot = np.array([[c, -s], [s, c]])
    return points_obj @ rot.T + np.array([placement.x_m, placement.y_m])


@dataclass(frozen=True)
class ObjectFootprint:
    """An object's contact footprint on the pad and the modules its weight loads."""

    #: Pad-frame contact points that carry load, (n, 2), metres.
    points_m: NDArray[np.float64]
    #: Contact pressure q at each point, pascals (>= 0).
    pressure_pa: NDArray[np.float64]
    #: Area each point represents, square metres.
    area_m2: NDArray[np.float64]
    #: 0-based module of each point, -1 on a line.
    module_index: NDArray[np.int64]
    #: Fraction of the object's weight each module senses, shape (n_modules,); the rest is
    #: carried by the lines.
    weight_fraction: NDArray[np.float64]


def object_footprint(
    spec: ObjectSpec,
    surface: PadSurface,
    placement: Placement | None = None,
    step_m: float = DEFAULT_SAMPLE_STEP_M,
) -> ObjectFootprint:
    """Distribute an object's weight over the modules (rigid body on a Winkler bed).

    Parameters
    ----------
    spec
        The object.
    surface
        Pad geometry and line width.
    placement
        Pose on the pad; ``spec.placement`` by default.
    step_m
        Footprint sampling step, metres.

    Raises
    ------
    InputError
        When the object's centre of mass is not over its support on the pad (it would tip over
        or fall off the pad).
    """
    placement = placement or spec.placement
    pts_list, area_list = [], []
    for part in spec.parts:
        if part.bottom_m > 1e-3:
            continue  # stacked part: its weight reaches the pad through the parts below
        p, a = part_footprint(part, step_m)
        pts_list.append(p)
        area_list.append(np.full(len(p), a))
    pts = to_pad_frame(np.vstack(pts_list), placement)
    areas = np.concatenate(area_list)
    # only the modules' sensitive squares support the object: the lines between inflated
    # modules are valleys an object bridges without touching (and the pad's border is a wall
    # at the base level, below the inflated modules)
    idx_all, cover = surface.module_coverage(pts, step_m)
    keep = cover > 0
    pts, areas, idx = pts[keep], areas[keep] * cover[keep], idx_all[keep]
    com = to_pad_frame(np.array([spec.com_m[:2]]), placement)[0]
    weight = spec.mass_kg * GRAVITY_M_S2
    q = _winkler_pressures(pts, areas, com, weight)
    q = np.clip(q, 0.0, None)
    total = float((q * areas).sum())
    if len(pts) < 3 or total <= 0 or abs(total - weight) > 1e-3 * weight:
        raise InputError(
            f"object {spec.name!r} at ({placement.x_m * 1e3:.1f}, {placement.y_m * 1e3:.1f}) mm is not "
            "supported by the pad (its centre of mass is outside its footprint on the pad)"
        )
    frac = np.zeros(surface.layout.n_modules)
    np.add.at(frac, idx, q * areas)
    return ObjectFootprint(pts, q, areas, idx, frac / weight)


def _winkler_pressures(
    pts: NDArray[np.float64], areas: NDArray[np.float64], com: NDArray[np.float64], weight: float
) -> NDArray[np.float64]:
    """Contact pressure at every sample point of a rigid body of ``weight`` (N) on a Winkler
    bed: linear in x and y about ``com``, in equilibrium, with points that would pull lifted
    off (an active-set iteration); not yet clipped at zero."""
    active = np.ones(len(pts), dtype=bool)
    q = np.zeros(len(pts))
    for _ in range(30):
        if active.sum() < 3:
            break
        d = pts[active] - com
        act_area = areas[active]
        basis = np.column_stack([np.ones(len(d)), d[:, 0], d[:, 1]])
        mat = basis.T @ (basis * act_area[:, None])
        rhs = np.array([weight, 0.0, 0.0])
        try:
            coef = np.linalg.solve(mat, rhs)
        except np.linalg.LinAlgError:
            break
        qa = basis @ coef
        q[:] = 0.0
        q[active] = qa
        if (qa >= -1e-9 * abs(coef[0])).all():
            break
        # lift-off: drop the most negative points only, so the active set shrinks gently
        drop = np.flatnonzero(active)[qa < 0]
        active[drop] = False
    else:  # pragma: no cover - 30 iterations always suffice on sampled footprints
        pass
    return q


def fingertip_overlap(
    center_m: tuple[float, float],
    yaw_rad: float,
    tip_size_m: tuple[float, float],
    surface: PadSurface,
    step_m: float = 0.5e-3,
    response: PadResponse | None = None,
    pressure_pa: float = thesis.P0_PA,
) -> NDArray[np.float64]:
    """Share of a rectangular fingertip's force that each module senses.

    With ``response`` None: the fraction of the tip's area over each module's square (seams
    excluded). Otherwise the tip's *equivalent load* per newton on each module: the mean over
    the tip of the FEM response ``s(x) / s_ref`` (:class:`~softpad.sim.PadResponse`) at
    ``pressure_pa``: large near a module's centre, small near its clamped edge.

    Parameters
    ----------
    center_m
        Fingertip centre, pad frame, metres.
    yaw_rad
        Closing direction of the jaws (theta), radians; the tip's thickness lies along it.
    tip_size_m
        (thickness along the closing direction, width across it), metres.
    surface
        Pad geometry.

    Returns
    -------
    ndarray, shape (n_modules,)
        Per-newton shares of the tip's force (area fractions without a response).
    """
    local = _rect_points(tip_size_m[0], tip_size_m[1], step_m)
    pts = to_pad_frame(local, Placement(center_m[0], center_m[1], yaw_rad))
    if response is None:
        idx, cover = surface.module_coverage(pts, step_m)
    else:
        idx, cover = response.weights(pts, pressure_pa)
    on = idx >= 0
    frac = np.bincount(idx[on], weights=cover[on], minlength=surface.layout.n_modules)
    return frac / len(local)
