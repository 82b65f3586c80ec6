"""A rigid-body world on MuJoCo behind the :class:`~softpad.sim.World` interface.

Module loads come from MuJoCo's contact forces on each module top (``mj_contactForce``), so the
simulated box's pressures, the plans made from them and the contact detection all follow from
the physics. :class:`MujocoWorld` composes three parts: the compiled model with its index
tables (:mod:`softpad.sim._mujoco_scene`, built from :mod:`softpad.sim._mujoco_model`), the
kinematic arm (:mod:`softpad.sim._mujoco_arm`) and the contact sensing
(:mod:`softpad.sim._mujoco_contacts`); the world itself steps them in time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import MM_AS_M, InputError, check_finite, check_range
from softpad.layout import PadLayout
from softpad.sim._mujoco_arm import ARM_ACCELERATION_M_S2, KinematicArm
from softpad.sim._mujoco_clearance import HandClearance
from softpad.sim._mujoco_coast import HoldCoast
from softpad.sim._mujoco_contacts import ContactSensing, GripperContacts
from softpad.sim._mujoco_fast import AVAILABLE as FAST_STEPS_BUILT
from softpad.sim._mujoco_fast import FastSteps
from softpad.sim._mujoco_model import MujocoGripper, ObjectModel, PadPhysics, parking_position
from softpad.sim._mujoco_scene import MujocoScene
from softpad.sim._response import ModuleResponse, PadResponse, operating_pressure
from softpad.sim._world import GripperState, PadWorld

__all__ = ["ARM_ACCELERATION_M_S2", "GripperContacts", "MujocoWorld", "ObjectPose"]

#: Time constant of the low-pass on the module rest heights handed over by the box, seconds.
#: Slow next to the contact dynamics (tens of ms), so that the box's height, which itself
#: depends on the load measured here, cannot close a fast feedback loop through MuJoCo.
_HEIGHT_FILTER_S = 0.5

#: Resolution of the jaw-width reading, metres.
_WIDTH_RESOLUTION_M = 1e-5
#: Fraction of the grip force at which closing jaws count as settled on an object (the servo
#: approaches its force limit asymptotically through the joint damping).
_SETTLED_FORCE = 0.95

#: Height above the highest module top at which a placed object appears, metres.
_DROP_M = 0.0

#: A placed object is lowered onto the pad no faster than this for ``_LOWER_S`` seconds, as by
#: a hand laying it down, m/s (dropped from 1 mm, the 187 g limes hit the pad with 2.8 N peaks,
#: which also collapse the box's module model).
_LOWER_M_S = 0.005
_LOWER_S = 1.0
_NO_DOFS = np.zeros(0, dtype=np.int64)


@dataclass(frozen=True)
class ObjectPose:
    """Pose of an object's frame in the pad frame."""

    #: Position of the object frame's origin, metres.
    x_m: float
    #: Position of the object frame's origin, metres.
    y_m: float
    #: Position of the object frame's origin, metres.
    z_m: float
    #: Rotation about z, radians.
    yaw_rad: float
    #: Angle between the object's z axis and the vertical, radians.
    tilt_rad: float

    def __post_init__(self) -> None:
        from softpad.layout import POSE_LIMIT_M

        for name in ("x_m", "y_m", "z_m"):
            lim = POSE_LIMIT_M
            check_range(f"object pose {name}", getattr(self, name), -lim, lim, "m", MM_AS_M)
        for name in ("yaw_rad", "tilt_rad"):
            check_finite(f"object pose {name}", getattr(self, name))


class MujocoWorld(PadWorld):
    """Pad, gripper and objects simulated by MuJoCo; implements :class:`~softpad.sim.World`.

    Parameters
    ----------
    layout, response
        As in :class:`~softpad.sim._world.PadWorld`.
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

    def __init__(
        self,
        layout: PadLayout | None = None,
        objects: tuple[ObjectModel, ...] | list[ObjectModel] = (),
        pad: PadPhysics | None = None,
        gripper: MujocoGripper | None = None,
        timestep_s: float = 2e-3,
        response: ModuleResponse | PadResponse | None = None,
    ) -> None:
        import mujoco

        self._mj = mujoco
        super().__init__(layout, response)
        self.pad = pad or PadPhysics()
        self.gripper = gripper or MujocoGripper()
        self._timestep_s = timestep_s
        names = [o.name for o in objects]
        if len(set(names)) != len(names):
            raise InputError(f"object names must be unique, got {names}")
        n = self._layout.n_modules
        self._pending_s = 0.0
        self._heights = np.full(n, self.pad.free_height_m)
        #: Where ``_heights`` lies (written in place: the compiled steps read it there).
        self._heights_address = int(self._heights.ctypes.data)
        self._heights_given = False
        self._spring_step = np.zeros(n)
        self._lowering: dict[str, float] = {}
        open_w = self.gripper.max_width_m
        cx = self._layout.cols * self._layout.pitch_m / 2
        cy = self._layout.rows * self._layout.pitch_m / 2
        # gripper high above the pad centre, fully open
        hand = np.array([cx, cy, 0.15 + self.gripper.finger_length_m, 0.0])
        self._arm = KinematicArm(hand, open_w)
        self._sensing = ContactSensing(n, open_w, self.response)
        self._loads = np.zeros(n)
        self._scene: MujocoScene | None = None
        self._coast: HoldCoast | None = None
        self._resting = False
        self._free_hand: HandClearance | None = None
        self._fast: FastSteps | None = None
        self._fast_on = FAST_STEPS_BUILT
        #: MuJoCo steps held still so far (:meth:`rest_while_still`; diagnostics).
        self.rested_steps = 0
        self._build(tuple(objects))

    def _build(self, objects: tuple[ObjectModel, ...]) -> None:
        """(Re)build the MuJoCo model with ``objects``, keeping the state of what existed."""
        scene = MujocoScene(self._layout, self.pad, self.gripper, objects, self._timestep_s)
        if self._scene is None:
            scene.rest(self.pad.free_height_m, self.gripper.max_width_m / 2)
        else:
            scene.carry_over(self._scene)
        scene.data.qpos[scene.hand_qpos] = self._arm.hand
        scene.data.ctrl[:] = self._arm.servo_ctrl()
        scene.forward()
        self._scene = scene
        self._step_s = float(scene.model.opt.timestep)
        until = self._coast.until_s if self._coast is not None else None
        self._coast = HoldCoast(
            np.setdiff1d(np.arange(scene.model.nv), scene.hand_dof), self._step_s
        )
        self._coast.allow(until)
        if self._free_hand is not None:
            self._free_hand = HandClearance(scene.model, scene.hand_body)
        self._fast = None
        if self._fast_on and scene.model.opt.cone == self._mj.mjtCone.mjCONE_ELLIPTIC:
            self._fast = FastSteps(scene, self._coast, self.gripper.finger_length_m)

    def compiled_steps(self, on: bool) -> None:
        """Run the world's real MuJoCo steps in compiled code where it is built (``on``, the
        default when :mod:`softpad.sim._fastworld` is built; False: in Python only). Both give
        the same world, bit for bit (:mod:`softpad.sim._mujoco_fast`)."""
        if on and not FAST_STEPS_BUILT:
            raise InputError("the compiled world steps are not built (make ext)")
        self._fast_on = bool(on)
        s = self.scene
        self._fast = None
        if on and s.model.opt.cone == self._mj.mjtCone.mjCONE_ELLIPTIC:
            self._fast = FastSteps(s, self.coast, self.gripper.finger_length_m)

    @property
    def scene(self) -> MujocoScene:
        """The compiled model, its data and its index tables."""
        assert self._scene is not None
        return self._scene

    @property
    def objects(self) -> dict[str, ObjectModel]:
        """The objects in the model, by name."""
        return self.scene.objects

    # --- ground truth of a descent (World protocol) ---------------------------------------
    @property
    def first_touch_s(self) -> float | None:
        """Simulated time of the first touch of a fingertip on a module top or of a finger on
        an object since the last :meth:`reset_touch`, seconds, or None."""
        return self._sensing.first_touch_s

    @property
    def first_touch_z_m(self) -> float | None:
        """Height of the fingertips' lower faces at the first touch, metres, or None."""
        return self._sensing.first_touch_z_m

    @property
    def tip_hit_object(self) -> str | None:
        """Name of the object a finger came down on from above (jaws still open), or None."""
        return self._sensing.tip_hit_object

    def reset_touch(self) -> None:
        """Forget the first-touch record (call before a new descent)."""
        self._sensing.reset_touch(self._arm.width_setpoint)

    # --- World protocol -------------------------------------------------------------------
    @property
    def timestep_s(self) -> float:
        """MuJoCo's step, seconds."""
        return float(self.scene.model.opt.timestep)

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
            self._take_heights(module_heights_m)
        ts = self._step_s
        # the hand moves continuously (the robot sees it move on every sample, whatever the
        # sample period); MuJoCo steps each time a whole time step has elapsed
        remaining = dt
        arm, coast = self._arm, self.coast
        fast, python_next = self._fast, False
        while self._pending_s + remaining >= ts * (1 - 1e-9):
            clamp = None if fast is None or python_next else self._lowered_dofs()
            if fast is not None and clamp is not None:
                # the steps ahead in compiled code, up to where Python must take over
                alpha = ts / (_HEIGHT_FILTER_S + ts)
                remaining, python_next = fast.run(
                    self, arm, self._sensing, coast, ts, remaining, alpha, clamp
                )
                continue
            python_next = False
            chunk = max(ts - self._pending_s, 0.0)
            arm_still = arm.move(chunk)  # whether the arm stands, asked once a step
            remaining -= chunk
            self._pending_s = 0.0
            if coast.armed and coast.coasts(self._time_s, self._coastable(arm_still)):
                self._coast_step(ts)
            elif self._resting and arm_still and not self._lowering:
                self._rest_step(ts)
            else:
                self._mj_step(ts, arm_still)
        # the chamber feels the impulse of the step's contacts, not the peak of one solver
        # step: the loads of the steps in this period, averaged (see module_loads_n)
        mean = self._sensing.mean_loads()
        if mean is not None:
            self._loads = mean
        if remaining > 0:
            self._arm.move(remaining)
            self._pending_s += remaining
        self._time_s += dt

    def _take_heights(self, module_heights_m: ArrayLike) -> None:
        """The box's module heights for the springs to follow (:meth:`step`)."""
        h = np.asarray(module_heights_m, dtype=float)
        if h.shape != (self._layout.n_modules,) or not np.isfinite(h).all():
            raise InputError(
                f"module heights must be {self._layout.n_modules} finite values, got {h!r}"
            )
        # np.clip's values without its Python wrapper (h is finite here), in place
        np.minimum(np.maximum(h, 0.0), 0.03, out=self._heights)
        self._heights_given = True

    def module_loads_n(self) -> NDArray[np.float64]:
        """Equivalent load on each module, N (>= 0), module order 1..N: every contact's normal
        force on a module top weighted by the FEM response at its point (friction, which
        shears the membrane, is left out), averaged over the MuJoCo steps of the last
        :meth:`step` (the box's sample period), plus a probe block (:meth:`press`).

        The average, not the last step's force: a rigid contact's solver step can carry a
        force of many times an object's weight for 2 ms when jaws close on it (its impulse is
        what moves the membrane and the gas; a sample of that peak read up to the sensor's
        10 kPa full scale on simulated trials and tripped the box)."""
        return self._loads + self._probe_loads

    def module_forces_n(self) -> NDArray[np.float64]:
        """Plain normal contact force on each module top after the last MuJoCo step, N
        (diagnostics: what the response weights, step by step, into :meth:`module_loads_n`)."""
        return self._sensing.forces.copy()

    @property
    def operating_pressure_pa(self) -> float:
        """Chamber pressure at which the response is evaluated, Pa."""
        return self._sensing.pressure_pa

    def set_operating_pressure(self, pressure_pa: float) -> None:
        """Evaluate the response at the chambers' pressure (rounded to 50 Pa, clamped to its
        range); the simulated box calls this as the pressures change."""
        self._sensing.pressure_pa = operating_pressure(pressure_pa, self.response.response)

    def _update_probe(self) -> None:
        """The probe block's loads at the current operating pressure (the block loads the
        chambers only: it does not collide with objects)."""
        self._probe_loads = self._probe_loads_at(self.operating_pressure_pa)

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
            Linear speed of the hand and of the opening's setpoint (each jaw's at half), m/s
            (> 0).
        """
        x, y, z, yaw, w = (
            check_finite(n, getattr(target, n)) for n in ("x_m", "y_m", "z_m", "yaw_rad", "width_m")
        )
        speed = check_finite("gripper speed", speed_m_s)
        if not 0 <= speed <= 2.0:
            raise InputError(f"gripper speed must be in [0, 2] m/s, got {speed!r}")
        if speed == 0.0:
            self._arm.stop()
            return
        measured = self.gripper_state().width_m
        self._arm.command((x, y, z, yaw), w, measured, speed, self.gripper)

    def set_gripper_target(self, target: GripperState) -> None:
        """Put the hand at ``target`` at the next MuJoCo step (for robots that stream
        setpoints at their own rate); the jaw setpoint jumps to ``target.width_m``."""
        self.command_gripper(target, 2.0)
        self._arm.speed_m_s = math.inf

    def gripper_state(self) -> GripperState:
        """Current hand pose and measured jaw opening."""
        s = self.scene
        q, v = s.data.qpos, s.data.qvel
        hand = self._arm.hand
        return GripperState(
            x_m=float(hand[0]),
            y_m=float(hand[1]),
            z_m=float(hand[2] - self.gripper.finger_length_m),
            yaw_rad=float(hand[3]),
            # the gripper's position sensor resolves 10 um: a jaw stalled on an object reads
            # a constant width (how a robot tells that the jaws have stopped)
            width_m=_WIDTH_RESOLUTION_M
            * round(
                (
                    q[s.jaw_qpos[0]]
                    + q[s.jaw_qpos[1]]
                    + self._pending_s * (v[s.jaw_dof[0]] + v[s.jaw_dof[1]])
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
        s = self.scene
        z = float(np.max(s.data.qpos[s.module_qpos])) + _DROP_M
        c, sn = math.cos(yaw), math.sin(yaw)
        for _, qa, da, (ox, oy, oz) in s.obj_bodies[model.name]:
            s.data.qpos[qa : qa + 7] = [
                x + c * ox - sn * oy,
                y + sn * ox + c * oy,
                z + oz,
                math.cos(yaw / 2),
                0.0,
                0.0,
                math.sin(yaw / 2),
            ]
            s.data.qvel[da : da + 6] = 0.0
        self._lowering[model.name] = self._time_s + _LOWER_S
        s.forward()

    def remove_objects(self) -> None:
        """Take every object off the pad and out of the gripper (back to its parking place)."""
        s = self.scene
        for i, name in enumerate(self.objects):
            px, py, pz = parking_position(i)
            for _, qa, da, (ox, oy, oz) in s.obj_bodies[name]:
                s.data.qpos[qa : qa + 7] = [px + ox, py + oy, pz + oz, 1, 0, 0, 0]
                s.data.qvel[da : da + 6] = 0.0
        s.forward()

    def jaws_settled(self) -> bool:
        """False while the jaws close fully, their setpoint is still moving and either jaw's
        servo is below 95 % of the grip force (a blocked jaw's force is still growing)."""
        a = self._arm
        if not a.closing or a.width_setpoint <= a.goal[4] + 1e-9:
            return True
        force = np.abs(self.scene.data.actuator_force)
        return bool(np.min(force) >= _SETTLED_FORCE * self.gripper.grip_force_n)

    def holding(self) -> bool:
        """True when an object (any of its parts) touches both fingers and none of its parts
        touches the pad: it is carried."""
        return self._sensing.holding(self.scene)

    def object_pose(self, name: str) -> ObjectPose:
        """Current pose of object ``name``."""
        if name not in self.objects:
            raise InputError(f"unknown object {name!r}")
        b = self.scene.obj_body[name]
        pos = self.scene.data.xpos[b]
        rot = self.scene.data.xmat[b].reshape(3, 3)
        return ObjectPose(
            x_m=float(pos[0]),
            y_m=float(pos[1]),
            z_m=float(pos[2]),
            yaw_rad=float(math.atan2(rot[1, 0], rot[0, 0])),
            tilt_rad=float(math.acos(max(-1.0, min(1.0, rot[2, 2])))),
        )

    def object_speed_m_s(self, name: str) -> float:
        """Linear speed of an object, m/s (to tell when it has settled)."""
        da = self.scene.obj_dof[name]
        return float(np.linalg.norm(self.scene.data.qvel[da : da + 3]))

    def module_top_heights_m(self) -> NDArray[np.float64]:
        """Current height of every module top in MuJoCo, metres."""
        return np.asarray(self.scene.data.qpos[self.scene.module_qpos], dtype=float).copy()

    # --- diagnostics ----------------------------------------------------------------------
    def gripper_contacts(self) -> GripperContacts:
        """Where the gripper touches the pad and the objects now."""
        return self._sensing.gripper_contacts(self.scene)

    def gripper_vertical_force_n(self) -> float:
        """Upward contact force on the gripper (soles on anything, fingers and palm on objects),
        N: what a force-limited robot would feel while descending."""
        return self._sensing.gripper_vertical_force_n(self.scene)

    def save_xml(self, path: str) -> None:
        """Write the generated MJCF to ``path`` (to look at it in MuJoCo's viewer)."""
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(self.scene.xml)

    def info(self) -> dict[str, Any]:
        """Model size and settings, for reports."""
        return {
            "timestep_s": self.timestep_s,
            "nbody": int(self.scene.model.nbody),
            "ngeom": int(self.scene.model.ngeom),
            "integrator": "implicitfast",
            "cone": "elliptic",
        }

    # --- coasting through a settled hold --------------------------------------------------
    @property
    def coast(self) -> HoldCoast:
        """When the world coasts (:mod:`softpad.sim._mujoco_coast`); its ``coasted_steps``."""
        assert self._coast is not None
        return self._coast

    def coast_settled_until(self, until_s: float | None) -> None:
        """Allow the world to coast before simulated time ``until_s`` (None: never): while the
        hand and the jaw setpoint stand still and every velocity has been steady over a
        verification window, positions advance at those velocities without solving MuJoCo's
        constraints, the module loads held (:mod:`softpad.sim._mujoco_coast`). A trial allows
        it for its hold, where the object has settled in the jaws or on the pad."""
        self.coast.allow(until_s)

    def rest_while_still(self, on: bool) -> None:
        """Hold the world still while nothing it is told to do moves (``on``; False: step it
        again): no MuJoCo step is solved, positions and velocities stay as they are, the module
        loads stay those of the last stepped sample period, the time runs on. For a phase
        whose physics no longer decides anything a caller reads from the world: a trial's
        valve check, after the grasp has been scored (the box's gas physics still runs on the
        held loads)."""
        self._resting = bool(on)

    def _rest_step(self, ts: float) -> None:
        """One step of ``ts`` seconds held still: the module springs follow the box's heights
        (as in every step), nothing else moves."""
        self._follow_heights(ts)
        self.scene.data.time += ts
        self.rested_steps += 1

    def coast_free_hand(self, on: bool) -> None:
        """Let the world coast (:meth:`coast_settled_until`) also while the hand moves, as long
        as it stays clear of every other geom (``on``; False: only while the arm stands still).

        While the hand moves through free air towards a settled object, no contact is made or
        broken: the world coasts at its steady velocities while the hand's geoms stay farther
        than :data:`~softpad.sim._mujoco_clearance.CLEARANCE_MARGIN_M` from every other geom
        (a lower bound from their boxes, less the hand's travel since the last real step) and
        the jaw setpoint stands still. A trial allows it for the approach and the descent."""
        s = self.scene
        self._free_hand = HandClearance(s.model, s.hand_body) if on else None

    def _coastable(self, arm_still: bool) -> bool:
        """True when the world may coast: nothing it is told to do moves, or only the hand
        moves, clear of everything (:meth:`coast_free_hand`); ``arm_still``: the arm stands at
        rest (:meth:`KinematicArm.at_rest`)."""
        if arm_still and not self._lowering:
            return True
        if not self._hand_only_moves():
            return False
        free = self._free_hand
        assert free is not None
        if free.stale:  # the geoms' poses of the real step just taken (hand at its qpos then)
            s = self.scene
            free.update(s.data, s.qpos[s.hand_q])
        return free.clear(self._arm.hand)

    def _hand_only_moves(self) -> bool:
        """True when coasting with a moving hand is allowed and nothing but the hand moves."""
        return self._free_hand is not None and not self._lowering and self._arm.jaws_at_rest()

    #: How fast a placed object may sink while it is lowered, m/s (for the compiled steps).
    _LOWER_M_S = _LOWER_M_S

    def _lowered_dofs(self) -> NDArray[np.int64] | None:
        """The vertical velocities clamped in this frame's steps (objects being lowered), or
        None when a lowering ends in this frame (the Python steps end it)."""
        if not self._lowering:
            return _NO_DOFS
        if any(self._time_s > until for until in self._lowering.values()):
            return None
        s = self.scene
        dofs = [da + 2 for name in self._lowering for _, _, da, _ in s.obj_bodies[name]]
        return np.array(dofs, dtype=np.int64)

    def _coast_step(self, ts: float) -> None:
        """One coasted step of ``ts`` seconds: module springs, positions at constant velocity."""
        s = self.scene
        self._follow_heights(ts)
        qvel = self.coast.qvel
        assert qvel is not None
        self._mj.mj_integratePos(s.model, s.data.qpos, qvel, ts)
        s.qpos[s.hand_q] = self._arm.hand  # the hand moves as commanded (coast_free_hand)
        s.data.time += ts

    # --- stepping -------------------------------------------------------------------------
    def _follow_heights(self, ts: float) -> None:
        """Module rest lengths follow the box's heights, low-passed (see step())."""
        if self._heights_given:
            spring, buf = self.scene.module_spring, self._spring_step
            # spring += alpha (heights - spring), in place: the same operations, no temporaries
            np.subtract(self._heights, spring, out=buf)
            buf *= ts / (_HEIGHT_FILTER_S + ts)
            spring += buf

    def _mj_step(self, ts: float, arm_still: bool) -> None:
        """One MuJoCo step of ``ts`` seconds: module springs, hand, jaws, lowering, loads
        (``arm_still``: the arm stands at rest, :meth:`KinematicArm.at_rest`)."""
        s = self._scene
        assert s is not None
        m, d = s.model, s.data
        self._follow_heights(ts)
        hand, hq, qpos, qvel = self._arm.hand, s.hand_q, s.qpos, s.qvel
        qvel[s.hand_v] = (hand - qpos[hq]) / ts
        qpos[hq] = hand
        s.ctrl[:] = self._arm.servo_ctrl()
        self._mj.mj_step(m, d)
        # the hand moved as commanded whatever pushed on it (the robot is position-controlled)
        qpos[hq] = hand
        if self._lowering:
            for name, until in list(self._lowering.items()):
                if self._time_s > until:
                    del self._lowering[name]
                else:
                    for _, _, da, _ in s.obj_bodies[name]:
                        qvel[da + 2] = max(qvel[da + 2], -_LOWER_M_S)
        tip_z = float(hand[2] - self.gripper.finger_length_m)
        self._sensing.update(s, self._time_s + self._pending_s, tip_z, self._arm.width_setpoint)
        coast = self._coast
        if coast is not None and coast.until_s is not None:
            free = self._free_hand
            if free is not None:
                free.stale = True
            still = arm_still and not self._lowering
            coast.observe(qvel, self._time_s, still or self._hand_only_moves())
