"""The thesis's grasp-planning rules (thesis, Section 6.2.1.3 and Fig. 6.5).

Every rule works in module units on the pad frame of DESIGN.md. The rules are written for the
2 x 3 prototype, and generalised to any R x C pad where the thesis suggests how (rectangles
as "big N = 2" objects, reduction of larger objects by dropping extremity modules far from
the PCOM). The interpretation chosen for each ambiguous case is documented in
``docs/planner.md``; the rule names below appear there with a picture.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from softpad.layout import PadLayout
from softpad.planning._geometry import (
    distance_to_line,
    inside_square,
    point_on_segment,
    project_on_line,
    theta_perpendicular,
)
from softpad.planning._params import PlannerParams
from softpad.planning._pcom import pcom as compute_pcom
from softpad.planning._records import GraspPlan, new_plan

Point = tuple[float, float]
#: Increments of every module, pascals (a list on the planner's hot path, or an array).
Increments = list[float] | NDArray[np.float64]


class _Grasp(NamedTuple):
    """What a rule returns before it becomes a GraspPlan (a named tuple: built several times
    per plan, it costs a third of a frozen dataclass)."""

    cog: Point
    theta: float
    rule: str
    kept: tuple[int, ...]
    tie: bool = False


class _Object:
    """One detected object: its modules, their increments and the PCOM, with grid helpers."""

    def __init__(self, delta: Increments, modules: tuple[int, ...], layout: PadLayout):
        self.delta = delta
        self.modules = modules
        self.layout = layout
        self.pcom = compute_pcom(delta, modules, layout)
        self._cells, self._centres = _module_tables(layout, modules)

    def c(self, m: int) -> Point:
        return self._centres[m]

    def adjacent(self, a: int, b: int) -> bool:
        """8-neighbours (edge or corner), from the cached cells."""
        (ca, ra), (cb, rb) = self._cells[a], self._cells[b]
        return a != b and abs(ca - cb) <= 1 and abs(ra - rb) <= 1

    def connected(self, mods: list[int]) -> bool:
        """Whether the modules form one 8-connected group."""
        if not mods:
            return False
        seen, stack = {mods[0]}, [mods[0]]
        while stack:
            m = stack.pop()
            for o in mods:
                if o not in seen and self.adjacent(m, o):
                    seen.add(o)
                    stack.append(o)
        return len(seen) == len(mods)

    def _cell(self, m: int) -> tuple[int, int]:
        r, col = self.layout.row_col(m)
        return col, self.layout.rows - 1 - r

    def cell(self, m: int) -> tuple[int, int]:
        """(column, row counted from the bottom) of a module."""
        return self._cells[m] if m in self._cells else self._cell(m)

    def edge_adjacent(self, a: int, b: int) -> bool:
        (ca, ra), (cb, rb) = self._cells[a], self._cells[b]
        return abs(ca - cb) + abs(ra - rb) == 1

    def bbox(self, mods: tuple[int, ...]) -> tuple[int, int, int, int]:
        """(first column, last column, first row, last row) of the modules, rows from the
        bottom."""
        return _bbox(self.layout, mods)

    def is_rectangle(self, mods: tuple[int, ...]) -> bool:
        c0, c1, r0, r1 = _bbox(self.layout, mods)
        return (c1 - c0 + 1) * (r1 - r0 + 1) == len(mods)


# The shape analysis of a set of modules depends on the layout and the set only, not on the
# increments: computed once per (layout, modules) and reused by every later plan (profiling:
# most of a plan's time went into these loops over adjacency).


@lru_cache(maxsize=64)
def _tables(layout: PadLayout) -> tuple[tuple[tuple[int, int], ...], tuple[Point, ...]]:
    """Cells (column, row from the bottom) and centres of every module of ``layout``."""
    cells = tuple((c, layout.rows - 1 - r) for r, c in (layout.row_col(m) for m in layout.modules))
    return cells, tuple(layout.center(m) for m in layout.modules)


@lru_cache(maxsize=4096)
def _module_tables(
    layout: PadLayout, modules: tuple[int, ...]
) -> tuple[dict[int, tuple[int, int]], dict[int, Point]]:
    """Cells and centres of ``modules`` by module number (shared, read-only)."""
    cells, centres = _tables(layout)
    return {m: cells[m - 1] for m in modules}, {m: centres[m - 1] for m in modules}


@lru_cache(maxsize=16384)
def _bbox(layout: PadLayout, mods: tuple[int, ...]) -> tuple[int, int, int, int]:
    cells = _tables(layout)[0]
    cols = [cells[m - 1][0] for m in mods]
    rows = [cells[m - 1][1] for m in mods]
    return min(cols), max(cols), min(rows), max(rows)


@lru_cache(maxsize=16384)
def _three_shape(layout: PadLayout, mods: tuple[int, ...]) -> tuple[str, int]:
    """The kind of a 3-module object that is not a row (``corner``, ``line`` or ``linked``)
    and its corner module (0 for a diagonal line)."""
    obj = _Object.__new__(_Object)
    obj.layout = layout
    cells = _tables(layout)[0]
    obj._cells = {m: cells[m - 1] for m in mods}
    c0, c1, r0, r1 = _bbox(layout, mods)
    if c1 - c0 == 1 and r1 - r0 == 1:
        # Three modules of a 2 x 2 block: an L ("corner-shaped", Fig. 6.4d-(2)(3)).
        (k,) = [m for m in mods if all(obj.edge_adjacent(m, o) for o in mods if o != m)]
        return "corner", k
    centres = _tables(layout)[1]
    a, b, c = (centres[m - 1] for m in mods)
    if abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) < 1e-12:
        return "line", 0
    (k,) = [m for m in mods if all(obj.adjacent(m, o) for o in mods if o != m)]
    return "linked", k


@lru_cache(maxsize=16384)
def _reduce_candidates(layout: PadLayout, mods: tuple[int, ...]) -> tuple[int, ...]:
    """Extremity modules whose removal leaves the object connected (all extremities if none)."""
    obj = _Object.__new__(_Object)
    obj.layout = layout
    cells = _tables(layout)[0]
    obj._cells = {m: cells[m - 1] for m in mods}
    c0, c1, r0, r1 = _bbox(layout, mods)
    ends: set[int] = set()
    if c1 - c0 >= r1 - r0:
        ends |= {m for m in mods if obj.cell(m)[0] in (c0, c1)}
    if r1 - r0 >= c1 - c0:
        ends |= {m for m in mods if obj.cell(m)[1] in (r0, r1)}
    ordered = sorted(ends)
    return tuple(m for m in ordered if obj.connected([o for o in mods if o != m])) or tuple(ordered)


def plan_with_rules(
    delta: Increments,
    modules: tuple[int, ...],
    layout: PadLayout,
    params: PlannerParams,
) -> GraspPlan:
    """Plan one object with the thesis's rules (dispatch on N and shape)."""
    obj = _Object(delta, modules, layout)
    g = _plan(obj, modules, params.safety_shift, params.default_theta)
    cog = (float(g.cog[0]), float(g.cog[1]))
    return new_plan(modules, obj.pcom, cog, float(g.theta), g.rule, g.kept, g.tie, False)


def _plan(obj: _Object, mods: tuple[int, ...], c_s: float, theta0: float) -> _Grasp:
    n = len(mods)
    if n == 1:
        return _Grasp(obj.c(mods[0]), theta0, "n1-module-centre", mods)
    if n == 2:
        return _two(obj, mods)
    if obj.is_rectangle(mods):
        return _rectangle(obj, mods, theta0)
    if n == 3:
        return _three(obj, mods, c_s)
    if n == 5 and obj.layout.rows == 2 and obj.layout.cols == 3:
        return _five_on_2x3(obj, mods, c_s)
    return _reduce(obj, mods, c_s, theta0)


def _two(obj: _Object, mods: tuple[int, ...]) -> _Grasp:
    """N = 2: COG = PCOM (on the axis linking the centres), jaws perpendicular to that axis."""
    a, b = obj.c(mods[0]), obj.c(mods[1])
    dx, dy = b[0] - a[0], b[1] - a[1]
    kind = "horizontal" if dy == 0 else "vertical" if dx == 0 else "diagonal"
    return _Grasp(obj.pcom, theta_perpendicular(dx, dy), f"n2-{kind}", mods)


def _rectangle(obj: _Object, mods: tuple[int, ...], theta0: float) -> _Grasp:
    """A full a x b block of modules: a "big N = 2" object (thesis: N = 3 row, N = 6).

    Square blocks (2 x 2) take their centre and the default direction (thesis, N = 4 square).
    Otherwise the COG is the PCOM projected on the block's major axis and the jaws close
    across it.
    """
    c0, c1, r0, r1 = obj.bbox(mods)
    w, h = c1 - c0 + 1, r1 - r0 + 1
    centre = ((c0 + c1 + 1) / 2, (r0 + r1 + 1) / 2)
    n = len(mods)
    if w == h:
        return _Grasp(centre, theta0, "n4-square-centre" if n == 4 else "square-centre", mods)
    name = {3: "n3-row", 6: "n6-major-axis"}.get(n, "rectangle-major-axis")
    if w > h:
        return _Grasp((obj.pcom[0], centre[1]), math.pi / 2, name, mods)
    return _Grasp((centre[0], obj.pcom[1]), 0.0, name, mods)


def _three(obj: _Object, mods: tuple[int, ...], c_s: float) -> _Grasp:
    """N = 3 that is not a straight row: corner-shaped, diagonal-linked, or a diagonal line."""
    kind, k = _three_shape(obj.layout, mods)
    if kind == "corner":
        return _corner_shaped(obj, mods, k, c_s)
    if kind == "line":
        # Three modules on one diagonal (only on pads larger than 2 x 3).
        a, c = obj.c(mods[0]), obj.c(mods[2])
        q, _ = project_on_line(obj.pcom, a, c)
        return _Grasp(q, theta_perpendicular(c[0] - a[0], c[1] - a[1]), "n3-diagonal-line", mods)
    return _diagonal_linked(obj, mods, k, c_s)


def _corner_shaped(obj: _Object, mods: tuple[int, ...], corner: int, c_s: float) -> _Grasp:
    """L-shaped object (thesis, Fig. 6.4d-(2)(3)).

    PCOM strictly inside a side module: project it on that side module's axis (the line
    through the side and corner centres). Otherwise (corner module, a boundary, or outside the
    kept modules after a reduction): project it on the closest axis of the corner module and
    shift the COG by c_s along that axis towards its side module.
    """
    p = obj.pcom
    k = obj.c(corner)
    sides = [m for m in mods if m != corner]
    for s in sides:
        if inside_square(p, obj.c(s), strict=True):
            q, _ = project_on_line(p, k, obj.c(s))
            axis = (obj.c(s)[0] - k[0], obj.c(s)[1] - k[1])
            return _Grasp(q, theta_perpendicular(*axis), "n3-corner-side", mods)
    d = [distance_to_line(p, k, obj.c(s)) for s in sides]
    tie = math.isclose(d[0], d[1], abs_tol=1e-12)
    if tie:
        # Equal distances: take the axis towards the side module with the larger increment.
        i = int(obj.delta[sides[1] - 1] > obj.delta[sides[0] - 1])
    else:
        i = int(d[1] < d[0])
    s = sides[i]
    q, _ = project_on_line(p, k, obj.c(s))
    ux, uy = obj.c(s)[0] - k[0], obj.c(s)[1] - k[1]
    cog = (q[0] + c_s * ux, q[1] + c_s * uy)
    return _Grasp(cog, theta_perpendicular(ux, uy), "n3-corner-shift", mods, tie)


def linked_three(layout: PadLayout, modules: tuple[int, ...]) -> tuple[int, int, int] | None:
    """(corner, side, side) of three modules with a diagonal link (the corner module touches
    both sides, one of them only at a corner), None for any other set of modules."""
    if len(modules) != 3 or len(layout.connected_groups(list(modules))) != 1:
        return None
    kind, k = _three_shape(layout, tuple(sorted(modules)))
    if kind != "linked":
        return None
    a, b = (m for m in sorted(modules) if m != k)
    return k, a, b


def diagonal_linked_plan(
    delta: NDArray[np.float64],
    modules: tuple[int, ...],
    layout: PadLayout,
    params: PlannerParams,
    side: int,
) -> GraspPlan:
    """The thesis's rule for three diagonal-linked modules with the side module given, where
    the thesis takes the one on the PCOM's side of the bisector (:func:`linked_three`)."""
    mods = tuple(sorted(modules))
    shape = linked_three(layout, mods)
    if shape is None or side not in shape[1:]:
        raise ValueError(f"modules {mods} are not diagonal-linked with side module {side}")
    obj = _Object(delta, mods, layout)
    g = _diagonal_linked(obj, mods, shape[0], params.safety_shift, side)
    return GraspPlan(
        mods, obj.pcom, (float(g.cog[0]), float(g.cog[1])), float(g.theta), g.rule, mods
    )


def _diagonal_linked(
    obj: _Object, mods: tuple[int, ...], corner: int, c_s: float, side: int | None = None
) -> _Grasp:
    """Three modules with a diagonal link (thesis, Fig. 6.4d-(4)(5)).

    The bisector through the corner module is taken perpendicular to the pad's long side of
    the object's bounding box ("vertical" on the 2 x 3 pad). The PCOM is projected on the axis
    linking the corner module to the side module on the PCOM's side of the bisector. If the
    projection falls in the corner module, the COG moves to the nearest corner of the side
    module (diagonal link) or, for a straight link, by c_s towards the side module as in the
    corner-shaped case. The jaws close perpendicular to the axis. ``side`` overrides the
    side module.
    """
    p = obj.pcom
    k = obj.c(corner)
    c0, c1, r0, r1 = obj.bbox(mods)
    long_x = (c1 - c0) >= (r1 - r0)
    sides = sorted((m for m in mods if m != corner), key=lambda m: obj.c(m)[0 if long_x else 1])
    offset = (p[0] - k[0]) if long_x else (p[1] - k[1])
    tie = side is None and abs(offset) < 1e-12
    if side is not None:
        s = side
    elif tie:
        # PCOM on the bisector: the side with the larger increment, else the lower/left one.
        s = sides[1] if obj.delta[sides[1] - 1] > obj.delta[sides[0] - 1] else sides[0]
    else:
        s = sides[1] if offset > 0 else sides[0]
    sc = obj.c(s)
    q, t = project_on_line(p, k, sc)
    t = min(max(t, 0.0), 1.0)
    q = point_on_segment(k, sc, t)
    theta = theta_perpendicular(sc[0] - k[0], sc[1] - k[1])
    if not inside_square(q, k, strict=True):
        return _Grasp(q, theta, "n3-diagonal-side", mods, tie)
    if sc[0] != k[0] and sc[1] != k[1]:
        return _Grasp(point_on_segment(k, sc, 0.5), theta, "n3-diagonal-corner", mods, tie)
    cog = (q[0] + c_s * (sc[0] - k[0]), q[1] + c_s * (sc[1] - k[1]))
    return _Grasp(cog, theta, "n3-diagonal-shift", mods, tie)


def _five_on_2x3(obj: _Object, mods: tuple[int, ...], c_s: float) -> _Grasp:
    """N = 5 on the 2 x 3 pad (thesis, Fig. 6.4f): a horseshoe, or a 2 x 2 square plus one."""
    layout = obj.layout
    (missing,) = [m for m in layout.modules if m not in mods]
    p = obj.pcom
    mc, _ = obj.cell(missing)
    if mc == 1:
        # Horseshoe: the missing module is central (2 or 5).
        (covered,) = [m for m in mods if obj.cell(m)[0] == 1]
        cc = obj.c(covered)
        if 1.0 <= p[0] <= 2.0:
            # PCOM in the central column: grasp across the horseshoe's covered central module.
            return _Grasp((p[0], cc[1]), math.pi / 2, "n5-horseshoe-central", mods)
        drop_col = 2 if p[0] < 1.5 else 0
        kept = tuple(m for m in mods if obj.cell(m)[0] != drop_col)
        g = _three(obj, kept, c_s)
        return _Grasp(g.cog, g.theta, f"n5-horseshoe-reduce > {g.rule}", kept, g.tie)
    # A 2 x 2 square plus a single module in the missing module's column.
    (single,) = [m for m in mods if obj.cell(m)[0] == mc]
    square = tuple(m for m in mods if m != single)
    xs = [obj.c(m)[0] for m in square]
    if min(xs) - 0.5 <= p[0] <= max(xs) + 0.5:
        return _Grasp((p[0], 1.0), math.pi / 2, "n5-square-plus-one/in-square", mods)
    sc = obj.c(single)
    return _Grasp((p[0], sc[1]), math.pi / 2, "n5-square-plus-one/single", (single,))


def _reduce(obj: _Object, mods: tuple[int, ...], c_s: float, theta0: float) -> _Grasp:
    """Drop the extremity module farthest from the PCOM until a simpler case remains.

    Thesis, N = 4: "the module which is not taken into account is the one whose center is the
    farthest from the PCOM ... central modules (2 and 5) are never removed". Extremity modules
    are those on the two ends of the object's bounding box along its longer side (both
    directions for a square box); on the 2 x 3 pad these are the modules of columns 1 and 3.
    The PCOM keeps the weights of every module (it is the best estimate of the centre of
    mass); the dropped module only changes the shape the rules see.
    """
    p = obj.pcom
    candidates = _reduce_candidates(obj.layout, mods)

    def far(m: int) -> float:
        c = obj.c(m)
        return math.hypot(c[0] - p[0], c[1] - p[1])

    dmax = max(far(m) for m in candidates)
    farthest = [m for m in candidates if math.isclose(far(m), dmax, abs_tol=1e-12)]
    tie = len(farthest) > 1
    # Ties: drop the module with the smallest increment, then the highest number.
    drop = min(farthest, key=lambda m: (obj.delta[m - 1], -m))
    kept = tuple(m for m in mods if m != drop)
    g = _plan(obj, kept, c_s, theta0)
    prefix = f"n{len(mods)}-drop-farthest"
    return _Grasp(g.cog, g.theta, f"{prefix} > {g.rule}", g.kept, g.tie or tie)
