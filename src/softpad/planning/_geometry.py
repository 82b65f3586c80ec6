"""Small plane-geometry helpers of the planner (module units)."""

from __future__ import annotations

import math


def theta_perpendicular(dx: float, dy: float) -> float:
    """Direction of grasp perpendicular to an object axis (dx, dy), in (-pi/2, pi/2].

    The jaws close perpendicular to the object's major axis (thesis, Section 6.2.1.3, N = 2).
    Axes along the grid and its diagonals return the exact constants 0, pi/2 and +-pi/4.
    """
    if dx < 0 or (dx == 0 and dy < 0):
        dx, dy = -dx, -dy
    if dy == 0:
        return math.pi / 2
    if dx == 0:
        return 0.0
    if math.isclose(dx, dy):
        return -math.pi / 4
    if math.isclose(dx, -dy):
        return math.pi / 4
    t = math.atan2(dy, dx) + math.pi / 2
    return t - math.pi if t > math.pi / 2 else t


def project_on_line(
    p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]
) -> tuple[tuple[float, float], float]:
    """Orthogonal projection of p on the line through a and b.

    Returns the projected point and its parameter t (0 at a, 1 at b).
    """
    dx, dy = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)
    return (a[0] + t * dx, a[1] + t * dy), t


def point_on_segment(
    a: tuple[float, float], b: tuple[float, float], t: float
) -> tuple[float, float]:
    """The point a + t (b - a)."""
    return a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])


def distance_to_line(
    p: tuple[float, float], a: tuple[float, float], b: tuple[float, float]
) -> float:
    """Distance from p to the line through a and b."""
    q, _ = project_on_line(p, a, b)
    return math.hypot(p[0] - q[0], p[1] - q[1])


def inside_square(p: tuple[float, float], center: tuple[float, float], strict: bool) -> bool:
    """Whether p lies in the unit square centred at ``center`` (strictly inside, or closed)."""
    dx, dy = abs(p[0] - center[0]), abs(p[1] - center[1])
    if strict:
        return dx < 0.5 - 1e-12 and dy < 0.5 - 1e-12
    return dx <= 0.5 + 1e-12 and dy <= 0.5 + 1e-12
