"""A rigid-body world on MuJoCo behind the :class:`~softpad.sim.World` interface.

Module loads come from MuJoCo's contact forces on each module top (``mj_contactForce``), so the
simulated box's pressures, the plans made from them and the contact detection all follow from
the physics. The model itself is described in :mod:`softpad.sim._mujoco_model`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.layout import PadLayout
from softpad.sim._mujoco_model import (
    MujocoGripper,
    ObjectModel,
    PadPhysics,
    body_name,
    build_mjcf,
    loose_body_name,
    parking_position,
)
from softpad.sim._world import GripperState

#: Time constant of the low-pass on the module rest heights handed over by the box, seconds.
#: Slow next to the contact dynamics (tens of ms), so that the box's height, which itself
#: depends on the load measured here, cannot close a fast feedback loop through MuJoCo.
_HEIGHT_FILTER_S = 0.5

#: Resolution of the jaw-width reading, metres.
_WIDTH_RESOLUTION_M = 1e-5

#: A commanded width this close to the measured one means "leave the jaws as they are", metres.
_SAME_WIDTH_M = 0.5e-3

#: Acceleration and braking of the kinematic arm, m/s^2 (a collaborative arm such as the
#: Sawyer reaches 0.2 m/s in about 0.1 s).
ARM_ACCELERATION_M_S2 = 2.0

#: Height above the highest module top at which a placed object appears, metres.
_DROP_M = 0.0

#: A placed object is lowered onto the pad no faster than this for ``_LOWER_S`` seconds, as by
#: a hand laying it down, m/s (dropped from 1 mm, the 187 g limes hit the pad with 2.8 N peaks,
#: which also collapse the box's module model).
_LOWER_M_S = 0.005
_LOWER_S = 1.0


@dataclass(frozen=True)
class GripperContacts:
    """Where the gripper touches things at one instant (diagnostics of a trial).

    Attributes
    ----------
    sole_on_modules
        Per finger (right, left): module numbers the tip's sole presses, empty when none.
    sole_on_lines_n
        Per finger: vertical force of the sole on non-sensitive surfaces (lines, rim, table), N.
    finger_on_object_n
        Per finger: total contact force between the finger and any object, N.
    finger_on_object_from_above
        Per finger: True when the finger touches an object with a mostly vertical contact normal
        (the jaw came down on the object instead of beside it).
    palm_on_object_n
        Contact force between the palm and any object, N.
    """

    sole_on_modules: tuple[tuple[int, ...], tuple[int, ...]]
    sole_on_lines_n: tuple[float, float]
    finger_on_object_n: tuple[float, float]
    finger_on_object_from_above: tuple[bool, bool]
    palm_on_object_n: float


@dataclass(frozen=True)
class ObjectPose:
    """Pose of an object's frame in the pad frame.

    Attributes
    ----------
    x_m, y_m, z_m
        Position of the object frame's origin, metres.
    yaw_rad
        Rotation about z, radians.
    tilt_rad
        Angle between the object's z axis and the vertical, radians.
    """

    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    tilt_rad: float


class MujocoWorld:
    """Pad, gripper and objects simulated by MuJoCo; implements :class:`~softpad.sim.World`.

    Parameters
    ----------
    layout
        Pad geometry (2 x 3, 45 mm by default).
    objects
        Objects that can be placed on the pad (each starts parked far away).
    pad
        Pad physics (heights, stiffnesses, friction).
    gripper
        Gripper geometry (mounting 10/4, 6/2 or 4/0), servo and friction.
    timestep_s
        MuJoCo step, seconds. :meth:`step` is called at the box's sample rate and advances MuJoCo
        only when a whole MuJoCo step has elapsed, so the box may sample at 1 kHz while MuJoCo
        steps every 2 ms (loads are held in between).
    """

    model: Any
    data: Any
    xml: str
    _module_qpos: NDArray[np.int64]
    _jaw_qpos: NDArray[np.int64]
    _obj_qpos: dict[str, int]
    _obj_dof: dict[str, int]

    def __init__(
        self,
        layout: PadLayout | None = None,
        objects: tuple[ObjectModel, ...] | list[ObjectModel] = (),
        pad: PadPhysics | None = None,
        gripper: MujocoGripper | None = None,
        timestep_s: float = 2e-3,
    ) -> None:
        import mujoco

        self._mj = mujoco
        self._layout = layout or PadLayout()
        self.pad = pad or PadPhysics()
        self.gripper = gripper or MujocoGripper()
        self._timestep_s = timestep_s
        names = [o.name for o in objects]
        if len(set(names)) != len(names):
            raise InputError(f"object names must be unique, got {names}")
        self.objects: dict[str, ObjectModel] = {}
        self._force = np.zeros(6)
        n = self._layout.n_modules
        self._loads = np.zeros(n)
        self._pending_s = 0.0
        self._time_s = 0.0
        self._heights = np.full(n, self.pad.free_height_m)
        self._heights_given = False
        #: Simulated time of the first touch of a fingertip on a module top or of a finger on
        #: an object since the last :meth:`reset_touch`, seconds, or None.
        self.first_touch_s: float | None = None
        #: Height of the fingertips' lower faces at the first touch, metres, or None.
        self.first_touch_z_m: float | None = None
        #: Name of the object a finger came down on from above (jaws still open), or None.
        self.tip_hit_object: str | None = None
        open_w = self.gripper.max_width_m
        self._open_width = open_w
        cx = self._layout.cols * self._layout.pitch_m / 2
        cy = self._layout.rows * self._layout.pitch_m / 2
        # gripper high above the pad centre, fully open
        self._hand = np.array([cx, cy, 0.15 + self.gripper.finger_length_m, 0.0])
        self._goal = np.append(self._hand.copy(), open_w)
        self._speed_m_s = 0.0
        self._width_setpoint = open_w
        self._closing = False
        self._hand_speed = 0.0
        self._lowering: dict[str, float] = {}
        self._build(tuple(objects))

    def _build(self, objects: tuple[ObjectModel, ...]) -> None:
        """(Re)build the MuJoCo model with ``objects``, keeping the state of what existed."""
        mujoco = self._mj
        old = getattr(self, "data", None)
        old_idx = None
        if old is not None:
            old_idx = (self._module_qpos, self._jaw_qpos, dict(self._obj_qpos), dict(self._obj_dof))
            old_springs = self.model.qpos_spring[self._module_qpos].copy()
            old_qvel = old.qvel.copy()
            old_qpos = old.qpos.copy()
        self.objects = {o.name: o for o in objects}
        self.xml = build_mjcf(self._layout, self.pad, self.gripper, objects, self._timestep_s)
        self.model = mujoco.MjModel.from_xml_string(self.xml)
        self.data = mujoco.MjData(self.model)
        m = self.model
        n = self._layout.n_modules
        name2id = mujoco.mj_name2id
        gt, bt, jt = mujoco.mjtObj.mjOBJ_GEOM, mujoco.mjtObj.mjOBJ_BODY, mujoco.mjtObj.mjOBJ_JOINT
        top_geom = np.array([name2id(m, gt, f"module{k}_top") for k in self._layout.modules])
        self._geom_module = np.full(m.ngeom, -1, dtype=int)
        self._geom_module[top_geom] = np.arange(n)
        self._module_qpos = np.array(
            [m.jnt_qposadr[name2id(m, jt, f"module{k}_z")] for k in self._layout.modules]
        )
        self._pad_static = {name2id(m, gt, "base"), name2id(m, gt, "table")}
        self._pad_geoms = self._pad_static | {int(g) for g in top_geom}
        self._sole = (name2id(m, gt, "sole_right"), name2id(m, gt, "sole_left"))
        self._finger = (name2id(m, gt, "finger_right"), name2id(m, gt, "finger_left"))
        self._palm = name2id(m, gt, "palm")
        hand_j = [name2id(m, jt, f"hand_{a}") for a in ("x", "y", "z", "yaw")]
        self._hand_qpos = np.array([m.jnt_qposadr[j] for j in hand_j])
        self._hand_dof = np.array([m.jnt_dofadr[j] for j in hand_j])
        self._jaw_qpos = np.array(
            [m.jnt_qposadr[name2id(m, jt, f"jaw_{s}")] for s in ("right", "left")]
        )
        self._jaw_dof = np.array(
            [m.jnt_dofadr[name2id(m, jt, f"jaw_{s}")] for s in ("right", "left")]
        )
        self._obj_body = {o.name: name2id(m, bt, body_name(o)) for o in objects}
        self._obj_qpos = {o.name: int(m.jnt_qposadr[name2id(m, jt, body_name(o))]) for o in objects}
        self._obj_dof = {o.name: int(m.jnt_dofadr[name2id(m, jt, body_name(o))]) for o in objects}
        # every body of every object (a loose object has one per part), with its qpos/qvel
        # addresses and its offset in the object frame
        self._obj_bodies: dict[str, list[tuple[int, int, int, tuple[float, float, float]]]] = {}
        for o in objects:
            bodies = [
                (self._obj_body[o.name], self._obj_qpos[o.name], self._obj_dof[o.name], (0.0,) * 3)
            ]
            if o.loose:
                for j, part in enumerate(o.parts[1:], start=1):
                    jid = name2id(m, jt, loose_body_name(o, j))
                    px, py, pz = (float(v) for v in part.pos_m)
                    bodies.append(
                        (
                            name2id(m, bt, loose_body_name(o, j)),
                            int(m.jnt_qposadr[jid]),
                            int(m.jnt_dofadr[jid]),
                            (px, py, pz),
                        )
                    )
            self._obj_bodies[o.name] = bodies
        self._body_object = {b[0]: name for name, bs in self._obj_bodies.items() for b in bs}
        d = self.data
        if old is None or old_idx is None:
            d.qpos[self._module_qpos] = self.pad.free_height_m
            d.qpos[self._jaw_qpos] = self.gripper.max_width_m / 2
        else:
            mq, jq, oq, od = old_idx
            m.qpos_spring[self._module_qpos] = old_springs
            d.qpos[self._module_qpos] = old_qpos[mq]
            d.qpos[self._jaw_qpos] = old_qpos[jq]
            for name in oq:
                if name in self._obj_qpos:
                    d.qpos[self._obj_qpos[name] : self._obj_qpos[name] + 7] = old_qpos[
                        oq[name] : oq[name] + 7
                    ]
                    d.qvel[self._obj_dof[name] : self._obj_dof[name] + 6] = old_qvel[
                        od[name] : od[name] + 6
                    ]
            d.time = old.time
        d.qpos[self._hand_qpos] = self._hand
        d.ctrl[:] = self._servo_ctrl()
        mujoco.mj_forward(m, d)

    # --- World protocol -------------------------------------------------------------------
    @property
    def layout(self) -> PadLayout:
        """Geometry of the pad."""
        return self._layout

    @property
    def time_s(self) -> float:
        """Simulated time, seconds."""
        return self._time_s

    @property
    def timestep_s(self) -> float:
        """MuJoCo's step, seconds."""
        return float(self.model.opt.timestep)

    def step(self, dt_s: float, module_heights_m: ArrayLike | None = None) -> None:
        """Advance by ``dt_s`` seconds; MuJoCo steps once per elapsed ``timestep_s``.

        Parameters
        ----------
        dt_s
            Time to advance, seconds (the box's sample period).
        module_heights_m
            Top height of every module from the box's characteristic at its current pressure
            and load, metres; None keeps the last (before any is given, the tops rest at
            ``pad.free_height_m``). That height is the chamber's volume over its area, which a
            sealed chamber keeps under a load (the gas hardly compresses); the top's spring
            rests there (low-passed over 0.5 s) and sinks by ``F / k`` under a load ``F``,
            which is the membrane's local indentation under the object.
        """
        dt = check_finite("world time step", dt_s)
        if dt < 0:
            raise InputError(f"world time step must be >= 0 s, got {dt!r}")
        if module_heights_m is not None:
            h = np.asarray(module_heights_m, dtype=float)
            if h.shape != (self._layout.n_modules,) or not np.all(np.isfinite(h)):
                raise InputError(
                    f"module heights must be {self._layout.n_modules} finite values, got {h!r}"
                )
            self._heights = np.clip(h, 0.0, 0.03)
            self._heights_given = True
        ts = self.timestep_s
        # the hand moves continuously (the robot sees it move on every sample, whatever the
        # sample period); MuJoCo steps each time a whole time step has elapsed
        remaining = dt
        while self._pending_s + remaining >= ts * (1 - 1e-9):
            chunk = max(ts - self._pending_s, 0.0)
            self._move(chunk)
            remaining -= chunk
            self._pending_s = 0.0
            self._mj_step(ts)
        if remaining > 0:
            self._move(remaining)
            self._pending_s += remaining
        self._time_s += dt

    def module_loads_n(self) -> NDArray[np.float64]:
        """Normal contact force on each module top, N (>= 0), module order 1..N (vertical for
        an object resting on the domes; friction, which shears the membrane, is left out)."""
        return self._loads.copy()

    def command_gripper(self, target: GripperState, speed_m_s: float) -> None:
        """Move the hand towards ``target`` in a straight line at ``speed_m_s``; the jaw
        servos' setpoint moves towards ``target.width_m`` at the same speed.

        The yaw turns at ``speed_m_s / 0.05 m`` rad/s (1 rad/s at the thesis's 0.05 m/s). A new
        command replaces the previous one; commanding the current state stops the hand. The
        jaws are servoed with the grip-force limit, so they stop on an object and squeeze it.

        Parameters
        ----------
        target
            Goal pose and opening, pad frame, metres and radians; an opening beyond the
            mounting's range is clamped to it (0 closes fully, 1 m opens fully).
        speed_m_s
            Linear speed of the hand and of each jaw's setpoint, m/s (> 0).
        """
        vals = [
            check_finite(n, getattr(target, n)) for n in ("x_m", "y_m", "z_m", "yaw_rad", "width_m")
        ]
        speed = check_finite("gripper speed", speed_m_s)
        if not 0 <= speed <= 2.0:
            raise InputError(f"gripper speed must be in [0, 2] m/s, got {speed!r}")
        g = self.gripper
        w = vals[4]
        if speed == 0.0:
            # stop: the hand stays where it is and the jaws keep their setpoint (and grip)
            self._goal = np.append(self._hand.copy(), self._width_setpoint)
            self._speed_m_s = 0.0
            self._hand_speed = 0.0
            return
        if abs(w - self.gripper_state().width_m) < _SAME_WIDTH_M:
            # "keep the jaws as they are" (e.g. moving with an object in the grip): the servo
            # keeps its goal, so a squeezed object stays squeezed
            w = float(self._goal[4])
        else:
            # widths beyond the mounting's range mean "fully open" / "fully closed" (the
            # execution asks for 1 m and 0 m)
            w = min(max(w, g.min_width_m), g.max_width_m)
            # closing all the way is force-limited (see _servo_ctrl); other widths are held
            self._closing = w <= g.min_width_m + _SAME_WIDTH_M
        self._goal = np.array(
            [vals[0], vals[1], vals[2] + g.finger_length_m, _unwrap(vals[3], self._hand[3]), w]
        )
        self._speed_m_s = speed

    def set_gripper_target(self, target: GripperState) -> None:
        """Put the hand at ``target`` at the next MuJoCo step (for robots that stream
        setpoints at their own rate); the jaw setpoint jumps to ``target.width_m``."""
        self.command_gripper(target, 2.0)
        self._speed_m_s = math.inf

    def gripper_state(self) -> GripperState:
        """Current hand pose and measured jaw opening."""
        q, v = self.data.qpos, self.data.qvel
        return GripperState(
            x_m=float(self._hand[0]),
            y_m=float(self._hand[1]),
            z_m=float(self._hand[2] - self.gripper.finger_length_m),
            yaw_rad=float(self._hand[3]),
            # the gripper's position sensor resolves 10 um: a jaw stalled on an object reads
            # a constant width (how a robot tells that the jaws have stopped)
            width_m=_WIDTH_RESOLUTION_M
            * round(
                (
                    q[self._jaw_qpos[0]]
                    + q[self._jaw_qpos[1]]
                    + self._pending_s * (v[self._jaw_dof[0]] + v[self._jaw_dof[1]])
                )
                / _WIDTH_RESOLUTION_M
            ),
        )

    # --- objects --------------------------------------------------------------------------
    def place_object(self, spec: Any, placement: Any | None = None) -> None:
        """Put an object on the pad, at rest, 0.2 mm above the highest module top; it settles
        under gravity in the next steps.

        Parameters
        ----------
        spec
            A catalogue object (:class:`ObjectModel`, or anything with ``name`` and ``parts``
            in the ``softpad-objects/1`` schema, e.g. ``softpad.sim.ObjectSpec``).
        placement
            Pose of the object frame in the pad frame (``x_m``, ``y_m``, ``yaw_rad``);
            ``spec.placement`` by default.
        """
        model = spec if isinstance(spec, ObjectModel) else ObjectModel.from_spec(spec)
        placement = placement if placement is not None else getattr(spec, "placement", None)
        if placement is None:
            raise InputError(f"object {model.name!r} has no placement")
        x = check_finite("object x", placement.x_m)
        y = check_finite("object y", placement.y_m)
        yaw = check_finite("object yaw", placement.yaw_rad)
        if model.name not in self.objects or self.objects[model.name] != model:
            objs = dict(self.objects)
            objs[model.name] = model
            self._build(tuple(objs.values()))
        z = float(np.max(self.data.qpos[self._module_qpos])) + _DROP_M
        c, sn = math.cos(yaw), math.sin(yaw)
        for _, qa, da, (ox, oy, oz) in self._obj_bodies[model.name]:
            self.data.qpos[qa : qa + 7] = [
                x + c * ox - sn * oy,
                y + sn * ox + c * oy,
                z + oz,
                math.cos(yaw / 2),
                0.0,
                0.0,
                math.sin(yaw / 2),
            ]
            self.data.qvel[da : da + 6] = 0.0
        self._lowering[model.name] = self._time_s + _LOWER_S
        self._mj.mj_forward(self.model, self.data)

    def remove_objects(self) -> None:
        """Take every object off the pad and out of the gripper (back to its parking place)."""
        for i, name in enumerate(self.objects):
            px, py, pz = parking_position(i)
            for _, qa, da, (ox, oy, oz) in self._obj_bodies[name]:
                self.data.qpos[qa : qa + 7] = [px + ox, py + oy, pz + oz, 1, 0, 0, 0]
                self.data.qvel[da : da + 6] = 0.0
        self._mj.mj_forward(self.model, self.data)

    def holding(self) -> bool:
        """True when an object (any of its parts) touches both fingers and none of its parts
        touches the pad: it is carried."""
        d, m = self.data, self.model
        touch: dict[str, set[int]] = {}
        on_pad: set[str] = set()
        fingers = {self._finger[0]: 0, self._finger[1]: 1}
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            for g, other in ((g1, g2), (g2, g1)):
                name = self._body_object.get(int(m.geom_bodyid[g]))
                if name is not None:
                    if other in fingers:
                        touch.setdefault(name, set()).add(fingers[other])
                    elif other in self._pad_geoms:
                        on_pad.add(name)
        return any(len(s) == 2 and name not in on_pad for name, s in touch.items())

    def object_pose(self, name: str) -> ObjectPose:
        """Current pose of object ``name``."""
        if name not in self.objects:
            raise InputError(f"unknown object {name!r}")
        b = self._obj_body[name]
        pos = self.data.xpos[b]
        rot = self.data.xmat[b].reshape(3, 3)
        return ObjectPose(
            x_m=float(pos[0]),
            y_m=float(pos[1]),
            z_m=float(pos[2]),
            yaw_rad=float(math.atan2(rot[1, 0], rot[0, 0])),
            tilt_rad=float(math.acos(max(-1.0, min(1.0, rot[2, 2])))),
        )

    def object_speed_m_s(self, name: str) -> float:
        """Linear speed of an object, m/s (to tell when it has settled)."""
        da = self._obj_dof[name]
        return float(np.linalg.norm(self.data.qvel[da : da + 3]))

    def module_top_heights_m(self) -> NDArray[np.float64]:
        """Current height of every module top in MuJoCo, metres."""
        return np.asarray(self.data.qpos[self._module_qpos], dtype=float).copy()

    # --- diagnostics ----------------------------------------------------------------------
    def gripper_contacts(self) -> GripperContacts:
        """Where the gripper touches the pad and the objects now."""
        m, d = self.model, self.data
        on_mod: list[set[int]] = [set(), set()]
        on_line = [0.0, 0.0]
        on_obj = [0.0, 0.0]
        above = [False, False]
        palm = 0.0
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            f = self._contact_world_force(i)
            for side in (0, 1):
                sole, finger = self._sole[side], self._finger[side]
                if sole in (g1, g2):
                    other = g2 if g1 == sole else g1
                    if self._geom_module[other] >= 0:
                        on_mod[side].add(int(self._geom_module[other]) + 1)
                    elif other in self._pad_static:
                        on_line[side] += abs(f[2])
                if finger in (g1, g2):
                    other = g2 if g1 == finger else g1
                    if int(m.geom_bodyid[other]) in self._body_object:
                        on_obj[side] += float(np.linalg.norm(f))
                        if abs(c.frame[2]) > 0.7 and abs(f[2]) > 1e-3:
                            above[side] = True
            if self._palm in (g1, g2):
                other = g2 if g1 == self._palm else g1
                if int(m.geom_bodyid[other]) in self._body_object:
                    palm += float(np.linalg.norm(f))
        return GripperContacts(
            sole_on_modules=(tuple(sorted(on_mod[0])), tuple(sorted(on_mod[1]))),
            sole_on_lines_n=(on_line[0], on_line[1]),
            finger_on_object_n=(on_obj[0], on_obj[1]),
            finger_on_object_from_above=(above[0], above[1]),
            palm_on_object_n=palm,
        )

    def gripper_vertical_force_n(self) -> float:
        """Upward contact force on the gripper (soles on anything, fingers and palm on objects),
        N: what a force-limited robot would feel while descending."""
        d = self.data
        total = 0.0
        gripper_geoms = {*self._sole, *self._finger, self._palm}
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            if g1 in gripper_geoms or g2 in gripper_geoms:
                f = self._contact_world_force(i)
                # force on geom2 is +f (normal from geom1 to geom2); upward on the gripper
                total += f[2] if g2 in gripper_geoms else -f[2]
        return total

    def save_xml(self, path: str) -> None:
        """Write the generated MJCF to ``path`` (to look at it in MuJoCo's viewer)."""
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(self.xml)

    # --- internals ------------------------------------------------------------------------
    def _contact_world_force(self, i: int) -> NDArray[np.float64]:
        """Force of contact ``i`` in world coordinates, acting on geom2 (from geom1), N."""
        self._mj.mj_contactForce(self.model, self.data, i, self._force)
        frame = self.data.contact[i].frame.reshape(3, 3)
        return np.asarray(frame.T @ self._force[:3], dtype=float)

    def _servo_ctrl(self) -> float:
        """Setpoint of each jaw's servo, metres from the centre.

        Closing fully is force-limited, like the Sawyer gripper closing on an object: the
        setpoint leads the commanded width by twice the grip force over the servo gain, so a
        jaw blocked by an object squeezes it with the full grip force instead of the small
        force of a nearly reached setpoint (an unblocked jaw stops at its joint limit).
        Opening to, or holding, a width is plain position control.
        """
        g = self.gripper
        if self._closing:
            return self._width_setpoint / 2 - 2 * g.grip_force_n / g.servo_stiffness_n_m
        return self._width_setpoint / 2

    def _move(self, dt: float) -> None:
        """Kinematic hand: straight line towards the goal at the commanded speed."""
        delta = self._goal[:3] - self._hand[:3]
        dist = float(np.linalg.norm(delta))
        # the arm accelerates and brakes at ARM_ACCELERATION_M_S2 (a kinematic jump to the
        # lift speed would ask friction for 100 m/s^2 on the object)
        a = ARM_ACCELERATION_M_S2
        if math.isinf(self._speed_m_s):  # streamed setpoints (set_gripper_target): no profile
            v = math.inf
        else:
            v = min(self._speed_m_s, self._hand_speed + a * dt, math.sqrt(2 * a * dist))
        self._hand_speed = v
        step = v * dt if math.isfinite(v) else math.inf
        if dist <= step or dist < 1e-9:
            self._hand[:3] = self._goal[:3]
            if dist < 1e-9:
                self._hand_speed = 0.0
        else:
            self._hand[:3] = self._hand[:3] + delta * (step / dist)
        step = self._speed_m_s * dt
        dyaw = self._goal[3] - self._hand[3]
        ystep = self._speed_m_s / thesis.APPROACH_SPEED_M_S * dt
        self._hand[3] = (
            self._goal[3] if abs(dyaw) <= ystep else self._hand[3] + math.copysign(ystep, dyaw)
        )
        dw = self._goal[4] - self._width_setpoint
        self._width_setpoint = (
            self._goal[4] if abs(dw) <= step else self._width_setpoint + math.copysign(step, dw)
        )

    def _mj_step(self, ts: float) -> None:
        m, d = self.model, self.data
        # module rest lengths follow the box's heights (see step())
        alpha = ts / (_HEIGHT_FILTER_S + ts)
        if self._heights_given:
            ref = self._heights
            spring = m.qpos_spring
            spring[self._module_qpos] += alpha * (ref - spring[self._module_qpos])
        d.qvel[self._hand_dof] = (self._hand - d.qpos[self._hand_qpos]) / ts
        d.qpos[self._hand_qpos] = self._hand
        d.ctrl[:] = self._servo_ctrl()
        self._mj.mj_step(m, d)
        # the hand moved as commanded whatever pushed on it (the robot is position-controlled)
        d.qpos[self._hand_qpos] = self._hand
        for name, until in list(self._lowering.items()):
            if self._time_s > until:
                del self._lowering[name]
            else:
                for _, _, da, _ in self._obj_bodies[name]:
                    d.qvel[da + 2] = max(d.qvel[da + 2], -_LOWER_M_S)
        self._loads = self._compute_loads()

    def _compute_loads(self) -> NDArray[np.float64]:
        """Vertical contact force on every module top; also records the first touch."""
        d, m = self.data, self.model
        loads = np.zeros(self._layout.n_modules)
        gm = self._geom_module
        soles, fingers = self._sole, self._finger
        watch = self.first_touch_s is None or self.tip_hit_object is None
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            k = gm[g1] if gm[g1] >= 0 else gm[g2]
            if k >= 0:
                # the normal force indents the membrane and compresses the chamber; friction
                # shears it along its surface and hardly changes the volume
                self._mj.mj_contactForce(self.model, d, i, self._force)
                loads[k] += abs(self._force[0])
            if not watch:
                continue
            if g1 in soles or g2 in soles:
                if k >= 0 and self.first_touch_s is None:
                    self._touched()
            elif g1 in fingers or g2 in fingers:
                other = g2 if g1 in fingers else g1
                b = int(m.geom_bodyid[other])
                if b in self._body_object and abs(c.frame[2]) > 0.7:
                    if self.first_touch_s is None:
                        self._touched()
                    if self.tip_hit_object is None and self._width_setpoint >= self._open_width:
                        self.tip_hit_object = self._body_object[b]
        return loads

    def _touched(self) -> None:
        self.first_touch_s = self._time_s + self._pending_s
        self.first_touch_z_m = float(self._hand[2] - self.gripper.finger_length_m)

    def reset_touch(self) -> None:
        """Forget the first-touch record (call before a new descent)."""
        self.first_touch_s = None
        self.first_touch_z_m = None
        self.tip_hit_object = None
        self._open_width = self._width_setpoint

    def info(self) -> dict[str, Any]:
        """Model size and settings, for reports."""
        return {
            "timestep_s": self.timestep_s,
            "nbody": int(self.model.nbody),
            "ngeom": int(self.model.ngeom),
            "integrator": "implicitfast",
            "cone": "elliptic",
        }


def _unwrap(angle: float, reference: float) -> float:
    """``angle`` plus a multiple of 2 pi, closest to ``reference`` (no jumps in the yaw joint)."""
    return reference + math.remainder(angle - reference, 2 * math.pi)
