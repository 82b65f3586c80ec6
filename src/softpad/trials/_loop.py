"""One trial: the box branch's execution state machine on the simulated box and a MuJoCo world.

``softpad.control.GraspExecution`` runs the loop of Section 6.2 (adjust -> reference -> wait
for the object -> plan -> approach -> descend at 0.05 m/s -> contact at t_g -> close -> lift ->
hold 15 s -> release). This module only sets it up for a trial (the world, the object's placement,
the jaw opening) and reads the failure's cause from the world through the loop's recorder hook:
which surfaces the fingertips touched, whether a jaw came down on the object, whether the object
was between the jaws when they closed.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from softpad.trials._geometry import distance_to_object_m, half_extent_along_m
from softpad.trials._records import TrialResult
from softpad.trials._runner import TrialConfig

#: A finger pressing the object harder than this counts as touching it, newtons.
_TOUCH_N = 0.2


class _Placed:
    """A placement record (x_m, y_m, yaw_rad)."""

    def __init__(self, x_m: float, y_m: float, yaw_rad: float) -> None:
        self.x_m, self.y_m, self.yaw_rad = x_m, y_m, yaw_rad


def execute_trial(
    spec: Any,
    placement: tuple[float, float, float],
    seed: int,
    config: TrialConfig,
    plan_override: Any | None = None,
    opening_m: float | None = None,
    mounting: str | None = None,
) -> tuple[TrialResult, Any | None]:
    """Run one trial; see :func:`softpad.trials.run_trial`. Returns the result and the run's
    :class:`softpad.record.RunLog` when ``config.record_trace``."""
    from softpad.box import SafetyLimits, SimBox
    from softpad.control import (
        ExecutionError,
        ExecutionParams,
        GraspExecution,
        InflationParams,
        SimulatedRobot,
    )
    from softpad.errors import HardwareFault
    from softpad.planning import GraspPlan
    from softpad.record import RunLog
    from softpad.sim import Placement
    from softpad.sim._mujoco_model import MujocoGripper
    from softpad.sim._mujoco_world import MujocoWorld
    from softpad.sim._sensor import SensorParams

    gripper = MujocoGripper(mounting=mounting or spec.gripper)
    world = MujocoWorld(gripper=gripper)
    layout = world.layout
    placed = _Placed(*placement)
    box = SimBox(
        world,
        sample_rate_hz=config.sample_rate_hz,
        seed=seed % (2**31),
        sensor=SensorParams() if config.noise else SensorParams.ideal(),
        initial_pressure_pa=1.0e3 if config.inflated_start else 0.0,
    )
    # the box-side limit follows the trials' (a jaw pressing an object into the pad reads more
    # than the 3 kPa inflation limit; only near the sensor's full scale is it a fault here)
    box.safety_limits = SafetyLimits(
        max_pressure_pa=config.max_pressure_pa,
        release_pa=min(2500.0, config.max_pressure_pa - 500.0),
    )

    class TrialRobot(SimulatedRobot):
        """The simulated robot with the jaw opening chosen for the object: the execution
        opens the jaws "fully"; the trial's gripper opens to ``max_opening_m``."""

        max_opening_m = gripper.max_width_m

        def set_gripper(self, width_m: float, speed_m_s: float) -> None:
            super().set_gripper(min(width_m, self.max_opening_m), speed_m_s)

    robot = TrialRobot(world)
    log = RunLog({"object": spec.name, "seed": seed}) if config.record_trace else None
    seen: dict[str, Any] = {}

    class Recorder:
        """Forwards to the run log; looks at the world at the loop's decisive moments."""

        def frame(self, frame: Any, phase: str) -> None:
            if log is not None:
                log.frame(frame, phase)

        def event(self, t_s: float, kind: str, **data: Any) -> None:
            if log is not None:
                log.event(t_s, kind, **data)
            phase = data.get("phase") if kind == "phase" else None
            if kind == "plan":
                seen["increments_pa"] = tuple(1e3 * v for v in data.get("increments_kpa", ()))
            elif phase == "approach":
                seen["plan"] = (tuple(data["modules"]), tuple(data["cog"]), float(data["theta"]))
                cog = (data["cog"][0] * layout.pitch_m, data["cog"][1] * layout.pitch_m)
                theta = float(data["theta"])
                # open to pass the object where the fingers come down (their width), plus the
                # clearance; fully when nothing of the object lies there
                half = half_extent_along_m(spec, placed, cog, theta, band_m=gripper.tip_width_m / 2)
                wanted = gripper.max_width_m if half is None else 2 * (half + config.clearance_m)
                if opening_m is not None:
                    wanted = opening_m
                robot.max_opening_m = float(
                    np.clip(wanted, gripper.min_width_m, gripper.max_width_m)
                )
                seen["cog_outside_mm"] = 1e3 * distance_to_object_m(cog, spec, placed)
            elif phase == "lift":
                # the jaws have closed: is the object between them?
                contacts = world.gripper_contacts()
                seen["between"] = min(contacts.finger_on_object_n) > _TOUCH_N
                seen["tip_hit"] = world.tip_hit_object
                s = world.gripper_state()
                seen["closed_at"] = (s.x_m, s.y_m, s.yaw_rad)
            elif kind == "no_contact":
                seen["tip_hit"] = world.tip_hit_object
                seen["detected"] = False
            elif kind == "contact":
                seen["detected"] = True
                touch, z = world.first_touch_s, world.first_touch_z_m
                if touch is not None and z is not None:
                    seen["delay"] = t_s - touch
                    seen["travel"] = 1e3 * (z - world.gripper_state().z_m)
            elif kind == "outcome":
                seen["outcome"] = data.get("outcome")

    params = ExecutionParams(
        # A gripper pressing an object into the pad, or a jaw dragging over a dome, reads
        # above the 3 kPa inflation limit that the loop otherwise takes for a stuck valve;
        # in these trials only the sensor's full scale (10 kPa) counts as a fault.
        inflation=InflationParams(max_pressure_pa=config.max_pressure_pa),
        approach_speed_m_s=config.approach_speed_m_s,
        travel_speed_m_s=config.travel_speed_m_s,
        gripper_speed_m_s=config.jaw_speed_m_s,
        lift_m=config.lift_m,
        hold_s=config.hold_s,
        object_settle_s=config.settle_s,
    )

    class TrialExecution(GraspExecution):
        """The loop, with a forced plan when the trial provokes a failure on purpose."""

        def _grasp(self, plan: GraspPlan) -> Any:
            return super()._grasp(plan_override if plan_override is not None else plan)

    def place() -> None:
        world.place_object(spec, Placement(*placement))

    base: dict[str, Any] = dict(
        object=spec.name, trial=0, seed=seed, placement=placement, mounting=gripper.mounting
    )
    execution = TrialExecution(box, robot, layout, params, Recorder(), place)
    with box:
        try:
            execution.run()
        except ExecutionError as exc:
            return (
                TrialResult(
                    **base,
                    success=False,
                    cause="object_not_detected",
                    increments_pa=seen.get("increments_pa", ()),
                    sim_time_s=box.time_s,
                    detail=str(exc),
                ),
                log,
            )
        except HardwareFault as exc:
            # A module read above the box's 3 kPa limit: the box's module model collapses
            # under more than about 1.5 N (a fingertip wedged on a dome's rim, or the object
            # dropped on release after the hold). After the outcome the trial stands;
            # before it, the trial is a failure of its own kind. Faults before the object
            # was placed are real and propagate.
            if "plan" not in seen:
                raise
            if "outcome" not in seen:
                modules, cog, theta = seen["plan"]
                return (
                    TrialResult(
                        **base,
                        success=False,
                        cause="box_fault",
                        modules=modules,
                        increments_pa=seen.get("increments_pa", ()),
                        cog=cog,
                        theta=theta,
                        opening_m=robot.max_opening_m,
                        contact_detected=seen.get("detected", False),
                        cog_outside_object_mm=seen.get("cog_outside_mm"),
                        sim_time_s=box.time_s,
                        detail=f"box fault in phase {execution.phase}: {exc}",
                    ),
                    log,
                )
        sim_time = box.time_s
    modules, cog, theta = seen["plan"]
    outcome = seen.get("outcome", "contact_not_detected")
    common = dict(
        modules=modules,
        increments_pa=seen.get("increments_pa", ()),
        cog=cog,
        theta=theta,
        opening_m=robot.max_opening_m,
        contact_detected=seen.get("detected", False),
        contact_delay_s=seen.get("delay"),
        finger_travel_mm=seen.get("travel"),
        cog_outside_object_mm=seen.get("cog_outside_mm"),
        sim_time_s=sim_time,
    )
    if outcome == "held":
        return TrialResult(**base, success=True, cause=None, detail="held", **common), log
    cause, why = _cause(outcome, seen, spec, placed, gripper)
    return TrialResult(**base, success=False, cause=cause, detail=why, **common), log


def _cause(
    outcome: str, seen: dict[str, Any], spec: Any, placed: Any, gripper: Any
) -> tuple[str, str]:
    """Failure cause from the loop's outcome and what the world showed."""
    if outcome == "contact_not_detected":
        return (
            "contact_not_detected",
            "descended to the pad base without the pad sensing the fingers",
        )
    if seen.get("tip_hit") is not None:
        return "jaws_hit_object", f"a jaw came down on {seen['tip_hit']}"
    if not seen.get("between", False):
        x, y, yaw = seen.get("closed_at", (0.0, 0.0, 0.0))
        inside = half_extent_along_m(spec, placed, (x, y), yaw, band_m=gripper.tip_width_m / 2)
        if inside is not None and 2 * inside < gripper.min_width_m:
            return "object_too_narrow", (
                f"the object between the jaws is {2e3 * inside:.0f} mm wide, under the "
                f"{gripper.mounting} mounting's {gripper.min_width_m * 1e3:.0f} mm"
            )
        return "object_outside_jaws", "the jaws closed without the object between them"
    return "slipped_during_hold", f"squeezed, then lost ({outcome})"
