"""The analytic world: objects loading modules through their footprints, a kinematic gripper.

Implements :class:`~softpad.sim.World` without a physics engine (see ``_footprint.py`` for the
load model). The gripper is a kinematic parallel jaw (thesis, Section 6.3: 9.5 cm fingers,
opening ranges 10/4, 6/2 and 4/0 cm) whose two rectangular fingertips load the modules under
them once they touch the pad: the force of a fingertip is ``k_tip * penetration``. What a
module senses of any force (objects, fingertips, a probe) is its *equivalent load*, weighted by
the FEM response at the point (:class:`~softpad.sim.PadResponse`): a fingertip near the clamped
edge between two chambers squeezes either little (the thesis's failure mode, Section 6.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import CheckedFields, InputError, Positive, check_finite
from softpad.layout import GripperSpec, PadLayout
from softpad.sim._footprint import (
    GRAVITY_M_S2,
    ObjectFootprint,
    PadSurface,
    fingertip_overlap,
    object_footprint,
    part_outline,
    to_pad_frame,
)
from softpad.sim._objects import ObjectSpec, Placement
from softpad.sim._response import ModuleResponse, PadResponse, operating_pressure
from softpad.sim._tips import TipState, next_tip_state
from softpad.sim._world import GripperState, PadWorld

#: Opening ranges of the thesis's gripper mountings, (max, min) width in metres (Section 6.3).
GRIPPER_MOUNTINGS = thesis.GRIPPER_MOUNTINGS_M


#: The fields :class:`SimGripper` shares with :class:`softpad.layout.GripperSpec`.
_GEOMETRY_FIELDS = (
    "max_width_m",
    "min_width_m",
    "finger_length_m",
    "tip_thickness_m",
    "tip_width_m",
)


@dataclass(frozen=True)
class SimGripper(CheckedFields, what="gripper"):
    """Parallel-jaw gripper of the analytic world: geometry plus contact physics (Section 6.3).

    The geometry matches :class:`softpad.layout.GripperSpec` (see :attr:`geometry` and
    :meth:`from_spec`); the extra fields say how hard the tips press into the pad and grip.
    """

    #: Opening range of the jaws, metres (mountings 10/4, 6/2, 4/0 cm).
    max_width_m: float = 0.10
    #: Opening range of the jaws, metres (mountings 10/4, 6/2, 4/0 cm).
    min_width_m: float = 0.04
    #: Length of the fingers below the palm, metres (9.5 cm).
    finger_length_m: Positive = thesis.FINGER_LENGTH_M
    #: Fingertip size along the closing direction, metres (our choice: 8 mm; the thesis
    #: calls the tips "very small").
    tip_thickness_m: Positive = thesis.FINGERTIP_THICKNESS_M
    #: Fingertip size across the closing direction, metres (our choice: 16 mm).
    tip_width_m: Positive = thesis.FINGERTIP_WIDTH_M
    #: Vertical stiffness of the pad under a fingertip, N/m: force per metre of penetration
    #: (our estimate from the module compliance, docs/box-and-simulator.md).
    tip_stiffness_n_m: Positive = 125.0
    #: Squeezing force of each jaw, newtons.
    grip_force_n: float = 20.0
    #: Friction coefficient between fingertips and objects.
    friction: float = 0.5

    def __post_init__(self) -> None:
        check_finite("gripper min_width_m", self.min_width_m)
        check_finite("gripper max_width_m", self.max_width_m)
        if not (0 <= self.min_width_m < self.max_width_m <= 0.5):
            raise InputError(
                "gripper min_width_m and max_width_m must satisfy 0 <= min < max <= 0.5 m, got "
                f"{self.min_width_m:g}..{self.max_width_m:g} m"
            )
        super().__post_init__()

    @classmethod
    def mounting(cls, name: str, **kwargs: float) -> SimGripper:
        """Gripper of the thesis mounted as ``"10/4"``, ``"6/2"`` or ``"4/0"`` (max/min cm);
        the names of :data:`softpad.layout.GRIPPER_CONFIGS_M` (``wide``, ``medium``,
        ``narrow``) are accepted too."""
        from softpad.layout import GRIPPER_CONFIGS_M

        widths = GRIPPER_MOUNTINGS.get(name) or GRIPPER_CONFIGS_M.get(name)
        if widths is None:
            raise InputError(
                f"unknown gripper mounting {name!r}; use one of {', '.join(GRIPPER_MOUNTINGS)} "
                f"(or {', '.join(GRIPPER_CONFIGS_M)})"
            )
        return cls(max_width_m=widths[0], min_width_m=widths[1], **kwargs)

    @classmethod
    def from_spec(cls, spec: GripperSpec, **kwargs: float) -> SimGripper:
        """The gripper of a :class:`softpad.layout.GripperSpec`, with default contact physics."""
        return cls(**{f: getattr(spec, f) for f in _GEOMETRY_FIELDS}, **kwargs)

    @property
    def geometry(self) -> GripperSpec:
        """The geometry alone, as the planner's :class:`softpad.layout.GripperSpec`."""
        return GripperSpec(**{f: getattr(self, f) for f in _GEOMETRY_FIELDS})


@dataclass
class _Placed:
    spec: ObjectSpec
    placement: Placement
    footprint: ObjectFootprint
    outline_m: NDArray[np.float64]  # pad-frame sample points of every part (stacked ones too)
    loads_n: NDArray[np.float64]  # equivalent loads of the object's weight on each module, N
    lifted: bool = False

    @property
    def load_fraction(self) -> NDArray[np.float64]:
        """Equivalent load per newton pushing on the object, per module."""
        return self.loads_n / (self.spec.mass_kg * GRAVITY_M_S2)


@dataclass
class _Tip:
    state: TipState = TipState.FREE  # softpad.sim._tips: free, on the pad, on an object
    touch_z_m: float | None = None  # surface height where the tip touched (None: free)
    prev_z_m: float = math.inf  # tip height at the previous evaluation
    on_object: _Placed | None = None  # the object the tip landed on (None: the pad)

    def land(self, surface_z_m: float, on_object: _Placed | None) -> None:
        """Touch down on a module's top (``on_object`` None) or an object's."""
        on = TipState.ON_PAD if on_object is None else TipState.ON_OBJECT
        self.state = next_tip_state(self.state, on)
        self.touch_z_m, self.on_object = surface_z_m, on_object

    def leave(self) -> None:
        """Rise above where it touched."""
        self.state = next_tip_state(self.state, TipState.FREE)
        self.touch_z_m, self.on_object = None, None


class AnalyticWorld(PadWorld):
    """World of rigid objects on a Winkler pad and a kinematic parallel-jaw gripper.

    Parameters
    ----------
    layout
        Pad geometry (2 x 3, 45 mm by default).
    gripper
        Gripper geometry; mounting 10/4 by default.
    start_height_m
        Initial height of the fingertips above the pad base, metres.
    response
        As in :class:`~softpad.sim._world.PadWorld`.
    """

    def __init__(
        self,
        layout: PadLayout | None = None,
        gripper: SimGripper | None = None,
        start_height_m: float = 0.15,
        response: ModuleResponse | PadResponse | None = None,
    ) -> None:
        super().__init__(layout, response)
        self.surface = PadSurface(self._layout, self.response.seam_width_m)
        #: Chamber pressure at which the response is evaluated, Pa (see set_operating_pressure).
        self.operating_pressure_pa = operating_pressure(thesis.P0_PA, self.response.response)
        self._gripper = gripper or SimGripper()
        w, h = self.surface.size_m
        self._state = GripperState(w / 2, h / 2, start_height_m, 0.0, self._gripper.max_width_m)
        self._target = self._state
        self._speed = 0.0
        self._objects: list[_Placed] = []
        self._tips = [_Tip(), _Tip()]
        self._tip_loads = np.zeros(self._layout.n_modules)
        self._object_loads = np.zeros(self._layout.n_modules)
        self._loads = np.zeros(self._layout.n_modules)
        self._grasped: _Placed | None = None
        self._grasp_z: float = 0.0
        self._heights = np.zeros(self._layout.n_modules)
        #: Object touched first by a fingertip during the last descent (None: pad or nothing).
        self.tip_hit_object: str | None = None
        #: Time of the first fingertip touch of the last descent, seconds.
        self.first_touch_s: float | None = None
        #: Fingertip height at that first touch, metres.
        self.first_touch_z_m: float | None = None
        self._dirty = True
        self._grasp_width = 0.0
        self._overlap_cache: dict[
            tuple[int, int, float, int], tuple[NDArray[np.float64], _Placed | None]
        ] = {}
        self._objects_version = 0

    @property
    def gripper(self) -> SimGripper:
        """Gripper geometry; setting it (a new mounting) opens the jaws to the new maximum."""
        return self._gripper

    @gripper.setter
    def gripper(self, spec: SimGripper) -> None:
        self._gripper = spec
        self._overlap_cache.clear()  # tip sizes may differ
        self._state = replace(self._state, width_m=spec.max_width_m)
        self._target = self._state

    # --- World protocol -------------------------------------------------------------------
    def module_loads_n(self) -> NDArray[np.float64]:
        return self._loads

    def gripper_state(self) -> GripperState:
        return self._state

    def command_gripper(self, target: GripperState, speed_m_s: float) -> None:
        if not (math.isfinite(speed_m_s) and speed_m_s >= 0):
            raise InputError(f"gripper speed must be a finite number >= 0 m/s, got {speed_m_s!r}")
        width = min(max(target.width_m, self.gripper.min_width_m), self.gripper.max_width_m)
        self._target = replace(target, width_m=width, z_m=max(target.z_m, 0.0))
        self._speed = speed_m_s

    def holding(self) -> bool:
        return self._grasped is not None and self._grasped.lifted

    def place_object(self, spec: ObjectSpec, placement: Placement | None = None) -> None:
        placement = placement or spec.placement
        fp = object_footprint(spec, self.surface, placement)
        pts = [to_pad_frame(part_outline(p, 2e-3), placement) for p in spec.parts]
        placed = _Placed(spec, placement, fp, np.vstack(pts), self._equivalent(fp))
        self._objects.append(placed)
        self._update_object_loads()

    def _equivalent(self, fp: ObjectFootprint) -> NDArray[np.float64]:
        """Equivalent loads of a footprint's contact forces at the operating pressure, N."""
        forces = fp.pressure_pa * fp.area_m2
        return self.response.equivalent_loads(fp.points_m, forces, self.operating_pressure_pa)

    def set_operating_pressure(self, pressure_pa: float) -> None:
        """Evaluate the response at the chambers' pressure (rounded to 50 Pa, clamped to the
        response's range); the simulated box calls this as the pressures change."""
        p = operating_pressure(pressure_pa, self.response.response)
        if p == self.operating_pressure_pa:
            return
        self.operating_pressure_pa = p
        for o in self._objects:
            o.loads_n = self._equivalent(o.footprint)
        self._overlap_cache.clear()
        self._update_probe()

    def _update_probe(self) -> None:
        """The probe block's loads at the operating pressure, and the modules' loads with it
        (again at each change of the operating pressure)."""
        self._probe_loads = self._probe_loads_at(self.operating_pressure_pa)
        self._update_object_loads()

    def remove_objects(self) -> None:
        self._objects.clear()
        self._grasped = None
        self._update_object_loads()

    def step(self, dt_s: float, module_heights_m: NDArray[np.float64]) -> None:
        self._time_s += dt_s
        self._heights = module_heights_m
        moved = self._move(dt_s)
        if moved or (self._tips[0].touch_z_m is not None or self._tips[1].touch_z_m is not None):
            self._update_tips(module_heights_m)
        if self._grasped is not None and not self._grasped.lifted:
            if self._state.z_m > self._grasp_z + 2e-3:
                self._grasped.lifted = True
                self._update_object_loads()
        if moved or self._dirty:
            np.add(self._object_loads, self._tip_loads, out=self._loads)
            self._dirty = False

    # --- helpers --------------------------------------------------------------------------

    @property
    def objects(self) -> tuple[ObjectSpec, ...]:
        """Objects on the pad (or in the gripper)."""
        return tuple(o.spec for o in self._objects)

    def object_loads_n(self) -> NDArray[np.float64]:
        """Equivalent loads of the objects (and of a probe block) without the fingertips, per
        module, newtons."""
        return self._object_loads.copy()

    def _update_object_loads(self) -> None:
        self._objects_version += 1  # objects placed, lifted or removed: tip caches are stale
        self._object_loads = self._probe_loads.copy()
        for o in self._objects:
            if not o.lifted:
                self._object_loads += o.loads_n
        self._dirty = True

    def _move(self, dt_s: float) -> bool:
        s, t = self._state, self._target
        if s is t:  # the idle hot path: no dataclass comparison
            return False
        if s == t or self._speed <= 0:
            if s == t:
                self._state = t  # equal values; from now on the identity test suffices
            return False
        step = self._speed * dt_s
        d = np.array([t.x_m - s.x_m, t.y_m - s.y_m, t.z_m - s.z_m, t.width_m - s.width_m])
        dist = float(np.abs(d).max())
        closing = t.width_m < s.width_m
        if dist <= step:
            new = t
        else:
            f = step / dist
            new = GripperState(
                s.x_m + f * d[0],
                s.y_m + f * d[1],
                s.z_m + f * d[2],
                t.yaw_rad,
                s.width_m + f * d[3],
            )
        new = replace(new, yaw_rad=t.yaw_rad)
        if closing:
            new = self._close_on_object(new)
        self._state = new
        if new.width_m > s.width_m + 1e-12 and self._grasped is not None:
            self._release()
        return True

    def _release(self) -> None:
        """Opening the jaws lets the object go: a lifted object is put away off the pad."""
        o = self._grasped
        self._grasped = None
        if o is not None and o.lifted:
            self._objects.remove(o)
            self._update_object_loads()

    def _jaw_axes(self, st: GripperState) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        d = np.array([math.cos(st.yaw_rad), math.sin(st.yaw_rad)])
        return d, np.array([-d[1], d[0]])

    def _extent_between_jaws(self, st: GripperState, o: _Placed) -> tuple[float, float] | None:
        d, n = self._jaw_axes(st)
        rel = o.outline_m - np.array([st.x_m, st.y_m])
        u, v = rel @ d, rel @ n
        in_band = np.abs(v) <= self.gripper.tip_width_m / 2
        band = in_band & (np.abs(u) <= st.width_m / 2)
        if not band.any():
            return None
        if (
            not o.spec.extra.get("loose_parts", False)
            and (in_band & (np.abs(u) > st.width_m / 2)).any()
        ):
            # a rigid object reaching under a jaw: the jaw lands on it, nothing is caught
            # (parts loosely tied together, like limes in a net, are pushed aside instead)
            return None
        return float(u[band].min()), float(u[band].max())

    def _close_on_object(self, new: GripperState) -> GripperState:
        """Stop the jaws on the object between them and latch the grasp."""
        if self._grasped is not None:
            return replace(new, width_m=max(new.width_m, self._grasp_width))
        for o in self._objects:
            if o.lifted or self._state.z_m >= self._object_top_m(o):
                continue  # fingers above the object: nothing between the jaws
            ext = self._extent_between_jaws(self._state, o)
            if ext is None:
                continue
            umin, umax = ext
            needed = 2 * max(abs(umin), abs(umax))  # jaws close symmetrically about the centre
            width = max(umax - umin, self.gripper.min_width_m)
            if new.width_m <= needed:
                # the first jaw to touch pushes the object (it slides on the soft pad) until
                # the second jaw touches too: the final width is the object's extent
                if umax - umin >= self.gripper.min_width_m and self._can_hold(o):
                    self._grasped = o
                    self._grasp_width = width
                    self._grasp_z = new.z_m
                    return replace(new, width_m=max(new.width_m, width))
        return new

    def _object_top_m(self, o: _Placed) -> float:
        """Height of an object's top above the pad base, metres."""
        return float(self._heights.max()) + o.spec.height_m

    def _can_hold(self, o: _Placed) -> bool:
        g = self.gripper
        return 2 * g.grip_force_n * g.friction >= o.spec.mass_kg * GRAVITY_M_S2

    def tip_centres_m(
        self, st: GripperState | None = None
    ) -> tuple[tuple[float, float], tuple[float, float]]:
        """Pad-frame centres of the two fingertips, metres."""
        st = st or self._state
        d, _ = self._jaw_axes(st)
        off = (st.width_m + self.gripper.tip_thickness_m) / 2
        c = np.array([st.x_m, st.y_m])
        a, b = c - off * d, c + off * d
        return (float(a[0]), float(a[1])), (float(b[0]), float(b[1]))

    def _object_under(self, centre: tuple[float, float], st: GripperState) -> _Placed | None:
        d, n = self._jaw_axes(st)
        g = self.gripper
        for o in self._objects:
            if o.lifted:
                continue
            rel = o.outline_m - np.array(centre)
            if (
                (np.abs(rel @ d) <= g.tip_thickness_m / 2) & (np.abs(rel @ n) <= g.tip_width_m / 2)
            ).any():
                return o
        return None

    def _tip_contact(
        self, centre: tuple[float, float], st: GripperState
    ) -> tuple[NDArray[np.float64], _Placed | None]:
        """Sensed share of a tip's force per module, and the object under the tip (cached).

        Tip positions are keyed on a 0.25 mm grid (the overlap is sampled at 0.5 mm anyway).
        """
        key = (
            round(centre[0] * 4e3),
            round(centre[1] * 4e3),
            round(st.yaw_rad, 4),
            self._objects_version,
        )
        hit = self._overlap_cache.get(key)
        if hit is None:
            g = self.gripper
            frac = fingertip_overlap(
                centre,
                st.yaw_rad,
                (g.tip_thickness_m, g.tip_width_m),
                self.surface,
                response=self.response,
                pressure_pa=self.operating_pressure_pa,
            )
            if len(self._overlap_cache) > 256:
                self._overlap_cache.clear()
            hit = (frac, self._object_under(centre, st))
            self._overlap_cache[key] = hit
        return hit

    def _update_tips(self, heights: NDArray[np.float64]) -> None:
        st = self._state
        g = self.gripper
        if all(t.touch_z_m is None for t in self._tips):
            top = float(heights.max()) + max(
                (o.spec.height_m for o in self._objects if not o.lifted), default=0.0
            )
            if st.z_m > top:  # nothing within reach of the fingertips
                if self._tip_loads.any():
                    self._tip_loads = np.zeros(self._layout.n_modules)
                    self._dirty = True
                return
        loads = np.zeros(self._layout.n_modules)
        for tip, centre in zip(self._tips, self.tip_centres_m(st), strict=True):
            frac, obj = self._tip_contact(centre, st)
            if obj is not None:
                surface_z = float(heights.max()) + obj.spec.height_m
            elif frac.any():
                surface_z = float(heights[frac > 0].max())
            else:
                surface_z = 0.0  # a line: the tip meets the rigid wall/base, no module senses it
            if tip.touch_z_m is None:
                # a touch is a crossing from above: jaws closing onto an object's side, or a
                # module swelling under a resting tip, are not a fingertip landing on it
                crossed = tip.prev_z_m > surface_z >= st.z_m
                tip.prev_z_m = st.z_m
                if crossed and (obj is not None or frac.any()):
                    tip.land(surface_z, obj)
                    if self.first_touch_s is None:
                        self.first_touch_s = self._time_s
                        self.first_touch_z_m = st.z_m
                        self.tip_hit_object = obj.spec.name if obj is not None else None
                continue
            pen = tip.touch_z_m - st.z_m
            if pen <= 0:
                tip.leave()
                continue
            force = g.tip_stiffness_n_m * pen
            # what the tip landed on carries its force while it slides (closing jaws)
            if tip.on_object is not None and not tip.on_object.lifted:
                loads += force * tip.on_object.load_fraction
            elif tip.on_object is None:
                loads += force * frac
        self._tip_loads = loads
        self._dirty = True

    @property
    def tip_states(self) -> tuple[TipState, ...]:
        """Contact state of each fingertip (:class:`~softpad.sim.TipState`; ground truth)."""
        return tuple(t.state for t in self._tips)

    def reset_touch(self) -> None:
        """Forget the first-touch record (call before a new descent)."""
        self.first_touch_s = None
        self.first_touch_z_m = None
        self.tip_hit_object = None
