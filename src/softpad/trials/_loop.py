"""The closed loop of one trial on the simulated box and the MuJoCo world (Section 6.2).

inflate and adjust -> reference -> object placed -> settle -> increments -> plan -> open and
move over the COG -> descend at 0.05 m/s -> contact (running average of 10 samples above
t_g) -> stop -> close -> lift -> hold 15 s -> outcome. The outcome's cause is read from the
world (which surfaces the fingertips touched, whether the object ended between the jaws,
whether it stayed in them).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from softpad.trials._geometry import distance_to_object_m, half_extent_along_m
from softpad.trials._records import TrialResult
from softpad.trials._runner import APPROACH_CLEARANCE_M, TrialConfig, TrialTrace

#: A finger pressing the object harder than this counts as touching it, newtons.
_TOUCH_N = 0.2


def execute_trial(
    spec: Any,
    placement: tuple[float, float, float],
    seed: int,
    config: TrialConfig,
    plan_override: Any | None = None,
    opening_m: float | None = None,
    mounting: str | None = None,
) -> tuple[TrialResult, TrialTrace | None]:
    """Run one trial; see :func:`softpad.trials.run_trial`."""
    from softpad.box import SimBox
    from softpad.control._inflation import InflationParams, inflate_and_adjust
    from softpad.control._robot import SimulatedRobot, ToolPose
    from softpad.planning import plan_grasps
    from softpad.sensing import ContactDetector
    from softpad.sim import Placement
    from softpad.sim._mujoco_model import GripperParams
    from softpad.sim._mujoco_world import MujocoWorld
    from softpad.sim._sensor import SensorParams

    gripper = GripperParams(mounting=mounting or spec.gripper)
    world = MujocoWorld(gripper=gripper)
    layout = world.layout
    n = layout.n_modules
    box = SimBox(
        world,
        sample_rate_hz=config.sample_rate_hz,
        seed=seed % (2**31),
        sensor=SensorParams() if config.noise else SensorParams.ideal(),
        initial_pressure_pa=1.0e3 if config.inflated_start else 0.0,
    )
    times: list[float] = []
    frames: list[np.ndarray] = []
    phases: list[tuple[float, str]] = []

    def log(frame: Any) -> None:
        if config.record_trace:
            times.append(frame.t_s)
            frames.append(np.asarray(frame.pressures_pa[:n], dtype=float).copy())

    def read() -> np.ndarray:
        f = box.read()
        log(f)
        return np.asarray(f.pressures_pa[:n], dtype=float)

    def mark(label: str) -> None:
        phases.append((box.time_s, label))

    def wait(seconds: float) -> None:
        for _ in range(max(1, round(seconds * config.sample_rate_hz))):
            read()

    def until_stopped(robot: Any, limit_s: float) -> None:
        for _ in range(max(1, round(limit_s * config.sample_rate_hz))):
            read()
            if not robot.is_moving():
                return

    base: dict[str, Any] = dict(
        object=spec.name,
        trial=0,
        seed=seed,
        placement=placement,
        mounting=gripper.mounting,
    )

    def finish(**kw: Any) -> tuple[TrialResult, TrialTrace | None]:
        trace = None
        if config.record_trace and frames:
            trace = TrialTrace(np.asarray(times), np.vstack(frames), tuple(phases))
        return TrialResult(**base, sim_time_s=box.time_s, **kw), trace

    with box:
        # TODO(box): the leak check of the WIP inflation flags sensor drift as a leak for some
        # seeds (also with the analytic world); relaxed here until the box branch settles it
        adj = inflate_and_adjust(box, n, InflationParams(max_drift_pa_s=200.0), on_frame=log)
        mark("reference saved")
        world.place_object(spec, Placement(*placement))
        mark("object placed")
        wait(config.settle_s)
        with_object = np.mean([read() for _ in range(10)], axis=0)
        rest_z = world.object_pose(spec.name).z_m
        delta = with_object - adj.reference_pa
        mark("plan")
        plans = plan_grasps(delta, layout)
        if plan_override is not None:
            plans = [plan_override]
        base["increments_pa"] = tuple(float(v) for v in delta)
        if not plans:
            return finish(success=False, cause="object_not_detected", detail="no module above t_o")
        plan = plans[0]
        cog_m = plan.cog_m(layout)
        off_mm = 1e3 * distance_to_object_m(cog_m, spec, _Pl(*placement))
        # the jaws open to pass the object where the fingers come down (within their width),
        # plus the clearance; fully when nothing of the object lies there
        half = half_extent_along_m(
            spec, _Pl(*placement), cog_m, plan.theta, band_m=gripper.tip_width_m / 2
        )
        wanted = gripper.max_width_m if half is None else 2 * (half + config.clearance_m)
        if opening_m is not None:
            wanted = opening_m
        opening = float(np.clip(wanted, gripper.min_width_m, gripper.max_width_m))
        planned = dict(modules=plan.modules, cog=plan.cog, theta=plan.theta, opening_m=opening)
        robot = SimulatedRobot(world)
        # open the jaws and move over the COG, fingertips clear of the object
        robot.set_gripper(opening, config.jaw_speed_m_s)
        until_stopped(robot, 2.0)
        z_above = float(spec.height_m) + APPROACH_CLEARANCE_M + world.pad.free_height_m
        robot.move_to(ToolPose(cog_m[0], cog_m[1], z_above, plan.theta), config.travel_speed_m_s)
        until_stopped(robot, 5.0)
        pre = np.mean([read() for _ in range(10)], axis=0)
        detector = ContactDetector(pre)
        mark("descend")
        robot.descend(config.approach_speed_m_s, 0.0)
        detected = False
        for _ in range(round((z_above / config.approach_speed_m_s + 1.0) * config.sample_rate_hz)):
            if detector.update(read()):
                robot.stop()
                detected = True
                break
            if not robot.is_moving():
                break
        state = robot.state()
        touch = getattr(world, "first_touch_s", None)
        touch_z = getattr(world, "first_touch_z_m", None)
        timing = dict(
            contact_detected=detected,
            contact_delay_s=None if (touch is None or not detected) else box.time_s - touch,
            finger_travel_mm=None if touch_z is None else 1e3 * (touch_z - state.z_m),
            cog_outside_object_mm=off_mm,
        )
        if not detected:
            mark("no contact")
            return finish(
                success=False,
                cause="contact_not_detected",
                detail="descended to the pad base without the pad sensing the fingers",
                **planned,
                **timing,
            )
        mark("contact")
        robot.set_gripper(gripper.min_width_m, config.jaw_speed_m_s)
        until_stopped(robot, opening / config.jaw_speed_m_s + 0.5)
        wait(0.2)
        mark("closed")
        contacts = world.gripper_contacts()
        between = min(contacts.finger_on_object_n) > _TOUCH_N
        s = robot.state()
        robot.move_to(
            ToolPose(s.x_m, s.y_m, s.z_m + config.lift_m, s.yaw_rad), config.travel_speed_m_s
        )
        until_stopped(robot, config.lift_m / config.travel_speed_m_s + 1.0)
        mark("lifted")
        wait(config.hold_s)
        mark("held")
        pose = world.object_pose(spec.name)
        # carried: the object rose with the gripper and stayed up for the whole hold
        held = pose.z_m > rest_z + 0.5 * config.lift_m
        if held:
            return finish(
                success=True, cause=None, detail="held for the whole hold", **planned, **timing
            )
        hit = getattr(world, "tip_hit_object", None)
        if hit is not None:
            cause, why = "jaws_hit_object", f"a jaw came down on {hit}"
        elif not between:
            s = robot.state()
            inside = half_extent_along_m(
                spec, _Pl(*placement), (s.x_m, s.y_m), s.yaw_rad, band_m=gripper.tip_width_m / 2
            )
            if inside is not None and 2 * inside < gripper.min_width_m:
                cause = "object_too_narrow"
                why = (
                    f"the object between the jaws is {2e3 * inside:.0f} mm wide, under the "
                    f"{gripper.mounting} mounting's {gripper.min_width_m * 1e3:.0f} mm"
                )
            else:
                cause, why = (
                    "object_outside_jaws",
                    "the jaws closed without the object between them",
                )
        else:
            cause, why = (
                "slipped_during_hold",
                f"object left the jaws (at z = {pose.z_m * 1e3:.0f} mm)",
            )
        return finish(success=False, cause=cause, detail=why, **planned, **timing)


class _Pl:
    """A placement record (x_m, y_m, yaw_rad)."""

    def __init__(self, x_m: float, y_m: float, yaw_rad: float) -> None:
        self.x_m, self.y_m, self.yaw_rad = x_m, y_m, yaw_rad
