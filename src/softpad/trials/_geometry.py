"""Top-view geometry of catalogue objects and fingertips (pad frame, metres).

Used to choose the jaws' opening for an object, to tell whether a centre of grasp lies on the
object, and to draw the planned grasps like the thesis's Fig. 6.10.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray


def _rot(yaw: float) -> NDArray[np.float64]:
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s], [s, c]])


def part_outline_m(part: Any, placement: Any, n_arc: int = 24) -> NDArray[np.float64]:
    """Closed top-view outline of one part in the pad frame, shape (n, 2), metres.

    Parameters
    ----------
    part
        A catalogue part (``shape``, ``pos_m``, ``yaw_rad``, ``size_m`` / ``radius_m`` /
        ``length_m`` / ``axis``).
    placement
        Pose of the object frame in the pad frame (``x_m``, ``y_m``, ``yaw_rad``).
    n_arc
        Points on a circle outline.
    """
    if part.shape == "box":
        lx, ly = part.size_m[0] / 2, part.size_m[1] / 2
        local = np.array([[-lx, -ly], [lx, -ly], [lx, ly], [-lx, ly]])
    elif part.shape == "cylinder" and part.axis in ("x", "y"):
        half, r = part.length_m / 2, part.radius_m
        local = np.array([[-half, -r], [half, -r], [half, r], [-half, r]])
        if part.axis == "y":
            local = local[:, ::-1].copy()
    else:  # sphere, standing cylinder: a circle
        t = np.linspace(0, 2 * np.pi, n_arc, endpoint=False)
        local = part.radius_m * np.column_stack([np.cos(t), np.sin(t)])
    in_object = local @ _rot(part.yaw_rad).T + np.asarray(part.pos_m[:2])
    return np.asarray(
        in_object @ _rot(placement.yaw_rad).T + np.array([placement.x_m, placement.y_m]),
        dtype=float,
    )


def object_outlines_m(spec: Any, placement: Any) -> list[NDArray[np.float64]]:
    """Top-view outlines of every part of ``spec`` placed at ``placement``, metres."""
    return [part_outline_m(p, placement) for p in spec.parts]


def point_in_polygon(point: tuple[float, float], poly: NDArray[np.float64]) -> bool:
    """True when ``point`` lies inside the convex polygon ``poly`` (vertices in order)."""
    x, y = point
    n = len(poly)
    sign = 0.0
    for i in range(n):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % n]
        cross = (x2 - x1) * (y - y1) - (y2 - y1) * (x - x1)
        if cross != 0:
            if sign == 0:
                sign = math.copysign(1.0, cross)
            elif math.copysign(1.0, cross) != sign:
                return False
    return True


def distance_to_object_m(point: tuple[float, float], spec: Any, placement: Any) -> float:
    """Distance from ``point`` to the object's top-view footprint, metres (0 inside)."""
    best = math.inf
    p = np.asarray(point, dtype=float)
    for poly in object_outlines_m(spec, placement):
        if point_in_polygon(point, poly):
            return 0.0
        for i in range(len(poly)):
            a, b = poly[i], poly[(i + 1) % len(poly)]
            ab = b - a
            t = float(np.clip(np.dot(p - a, ab) / max(float(np.dot(ab, ab)), 1e-18), 0.0, 1.0))
            best = min(best, float(np.linalg.norm(p - (a + t * ab))))
    return best


def _densify(poly: NDArray[np.float64], step_m: float) -> NDArray[np.float64]:
    pts = []
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        k = max(1, math.ceil(float(np.linalg.norm(b - a)) / step_m))
        t = np.arange(k)[:, None] / k
        pts.append(a + t * (b - a))
    return np.vstack(pts)


def half_extent_along_m(
    spec: Any,
    placement: Any,
    centre_m: tuple[float, float],
    theta_rad: float,
    band_m: float | None = None,
) -> float | None:
    """Largest distance of the object's footprint from ``centre_m`` along the closing
    direction ``theta_rad``, metres: the jaws must open to twice this to pass the object.

    Parameters
    ----------
    band_m
        Only count the footprint within this distance across the closing direction (the
        fingers' half width: what lies beside the fingers does not block them); None counts
        the whole footprint.

    Returns
    -------
    The half extent, or None when no part of the footprint lies in the band.
    """
    u = np.array([math.cos(theta_rad), math.sin(theta_rad)])
    v = np.array([-u[1], u[0]])
    c = np.asarray(centre_m, dtype=float)
    pts = np.vstack([_densify(p, 0.5e-3) for p in object_outlines_m(spec, placement)]) - c
    if band_m is not None:
        pts = pts[np.abs(pts @ v) <= band_m]
        if not len(pts):
            return None
    return float(np.max(np.abs(pts @ u)))


def fingertip_rectangles_m(
    centre_m: tuple[float, float],
    theta_rad: float,
    width_m: float,
    tip_thickness_m: float,
    tip_width_m: float,
) -> list[NDArray[np.float64]]:
    """The two fingertip footprints (4 corners each) for jaws open to ``width_m``, metres.

    The jaws close along ``theta_rad``; ``width_m`` is the gap between the tips' inner faces.
    """
    u = np.array([math.cos(theta_rad), math.sin(theta_rad)])
    v = np.array([-u[1], u[0]])
    c = np.asarray(centre_m, dtype=float)
    rects = []
    for sign in (1.0, -1.0):
        mid = c + sign * (width_m / 2 + tip_thickness_m / 2) * u
        ht, hw = tip_thickness_m / 2, tip_width_m / 2
        rects.append(
            np.array(
                [mid + a * ht * u + b * hw * v for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            )
        )
    return rects


#: Held-out placements keep the footprint's centre at least this far from the pad's centre,
#: metres (issue 45: the development sets lay within 10 mm of it).
ANYWHERE_CLEARANCE_M = 0.010
#: Overhang a held-out placement allows past each pad edge, metres (docs/make_eval_objects.py).
ANYWHERE_OVERHANG_M = 0.005
#: Candidate poses tried before the fallback.
ANYWHERE_TRIES = 500


def footprint_box_m(spec: Any, yaw_rad: float) -> tuple[float, float, float, float]:
    """(x_min, x_max, y_min, y_max) of the top-view outline of ``spec`` turned by ``yaw_rad``
    about its origin, metres."""
    from softpad.sim import Placement

    pts = np.vstack(object_outlines_m(spec, Placement(0.0, 0.0, yaw_rad)))
    return (
        float(pts[:, 0].min()),
        float(pts[:, 0].max()),
        float(pts[:, 1].min()),
        float(pts[:, 1].max()),
    )


def anywhere_placement(
    spec: Any, seed: int, pad_size_m: tuple[float, float]
) -> tuple[float, float, float]:
    """A pose of ``spec`` anywhere on a pad of ``pad_size_m`` that it fits, from ``seed``.

    Yaw uniform on [-pi, pi), then the footprint's bounding box uniform over the positions
    where it stays on the pad (:data:`ANYWHERE_OVERHANG_M` past an edge allowed), redrawn
    until its centre lies at least :data:`ANYWHERE_CLEARANCE_M` from the pad's centre. After
    :data:`ANYWHERE_TRIES` candidates without one, the fitting candidate farthest from the
    centre; an object that fits at no yaw is centred at its catalogue yaw.

    Returns
    -------
    (x_m, y_m, yaw_rad) of the object's frame in the pad frame.
    """
    import zlib

    rng = np.random.default_rng(np.random.SeedSequence([int(seed), zlib.crc32(b"anywhere")]))
    w, h = pad_size_m
    m = ANYWHERE_OVERHANG_M
    best: tuple[float, tuple[float, float, float]] | None = None
    for _ in range(ANYWHERE_TRIES):
        yaw = float(rng.uniform(-math.pi, math.pi))
        x0, x1, y0, y1 = footprint_box_m(spec, yaw)
        if x1 - x0 > w + 2 * m or y1 - y0 > h + 2 * m:
            continue
        cx = float(rng.uniform((x1 - x0) / 2 - m, w - (x1 - x0) / 2 + m))
        cy = float(rng.uniform((y1 - y0) / 2 - m, h - (y1 - y0) / 2 + m))
        pose = (cx - (x0 + x1) / 2, cy - (y0 + y1) / 2, yaw)
        off = math.hypot(cx - w / 2, cy - h / 2)
        if off >= ANYWHERE_CLEARANCE_M:
            return pose
        if best is None or off > best[0]:
            best = (off, pose)
    if best is not None:
        return best[1]
    x0, x1, y0, y1 = footprint_box_m(spec, spec.placement.yaw_rad)
    return w / 2 - (x0 + x1) / 2, h / 2 - (y0 + y1) / 2, spec.placement.yaw_rad
