"""One trial: the box branch's execution state machine on the simulated box and a MuJoCo world.

``softpad.control.GraspExecution`` runs the loop of Section 6.2 (adjust -> reference -> wait
for the object -> plan -> approach -> descend -> contact at t_g -> close -> lift ->
hold 15 s -> release). This module only sets it up for a trial (the world, the object's placement)
and reads the failure's cause from the world through the loop's recorder hook: which surfaces
the fingertips touched, whether a jaw came down on the object, whether the object was between
the jaws when they closed.

No ground truth reaches the loop: it sees the box's pressures, its plan and the robot's own
state. The jaws open to the mounting's full width (the only opening a real system knows
without a model of the object); the object's true geometry (``truth``) and the world's contacts
are read only to score the trial.
"""

from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass
from typing import Any

from softpad.trials._config import TrialConfig, drawn_placement
from softpad.trials._geometry import distance_to_object_m, half_extent_along_m
from softpad.trials._records import TrialResult

#: A finger pressing the object harder than this counts as touching it, newtons.
_TOUCH_N = 0.2
#: A planned COG farther than this from the object's top-view footprint lies outside it, mm
#: (the thesis's cylinder failure had it about 10 mm outside).
_OUTSIDE_MM = 0.5
#: The world steps for real through the hold's last second (``TrialConfig.coast_settled_hold``),
#: so that the outcome is read from solved contacts and a slip in the last coasting window is
#: still simulated.
_COAST_MARGIN_S = 1.0
#: Phases from which the world coasts while the hand moves clear of everything, until the jaws
#: close or a contact is detected (``TrialConfig.coast_free_hand``): the object is set down and
#: settles, the hand approaches and descends, the jaws release it and the hand withdraws.
_FREE_HAND_PHASES = ("wait_object", "descend", "release")


class _Placed:
    """A placement record (x_m, y_m, yaw_rad)."""

    def __init__(self, x_m: float, y_m: float, yaw_rad: float) -> None:
        self.x_m, self.y_m, self.yaw_rad = x_m, y_m, yaw_rad


class _FixedPlanner:
    """A planner that always answers one given plan (a trial that provokes a failure)."""

    def __init__(self, plan: Any) -> None:
        self.plan_ = plan

    def plan(self, increments_pa: Any, objects: Any, layout: Any) -> list[Any]:
        return [self.plan_]


class _TrialWatcher:
    """The trial's recorder: forwards to the run log and looks at the world (ground truth)
    at the loop's decisive moments (the scorer: the controller never hears it)."""

    def __init__(self, trial: _Trial, log: Any | None) -> None:
        self.t, self.log = trial, log
        self.seen: dict[str, Any] = {}

    def frame(self, frame: Any, phase: str) -> None:
        if self.log is not None:
            self.log.frame(frame, phase)

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if self.log is not None:
            self.log.event(t_s, kind, **data)
        seen, world = self.seen, self.t.world
        phase = data.get("phase") if kind == "phase" else None
        if kind == "plan":
            seen["increments_pa"] = tuple(data.get("increments_pa", ()))
            plans = data.get("objects") or [{}]
            seen["rule"] = plans[0].get("rule")
        elif phase == "approach":
            self._approach(data)
            self._free_hand(True)
        elif phase in _FREE_HAND_PHASES:
            self._free_hand(True)
        elif phase == "close" or kind in ("contact", "no_contact"):
            self._free_hand(False)
        elif phase == "hold" and self.t.config.coast_settled_hold:
            hold_s = self.t.config.execution.hold_s
            world.coast_settled_until(t_s + hold_s - _COAST_MARGIN_S)
        elif phase == "valve_check" and self.t.config.still_valve_check:
            world.rest_while_still(True)  # scored already: see TrialConfig.still_valve_check
        elif phase == "lift":  # the jaws have closed: is the object between them?
            contacts = world.gripper_contacts()
            seen["between"] = min(contacts.finger_on_object_n) > _TOUCH_N
            seen["tip_hit"] = world.tip_hit_object
            s = world.gripper_state()
            seen["closed_at"] = (s.x_m, s.y_m, s.yaw_rad)
        if kind == "no_contact":
            seen["tip_hit"] = world.tip_hit_object
            seen["detected"] = False
        elif kind == "contact":
            seen["detected"] = True
            touch, z = world.first_touch_s, world.first_touch_z_m
            if touch is not None and z is not None:
                seen["delay"] = t_s - touch
                seen["travel"] = 1e3 * (z - world.gripper_state().z_m)
        elif kind == "outcome":  # the end of a hold: is the object carried (truth)?
            world.coast_settled_until(None)
            seen["outcome"] = data.get("outcome")
            if seen["outcome"] == "landed":  # the loop went up without closing: on what?
                seen["tip_hit"] = world.tip_hit_object
            seen["carried"] = seen.get("carried", False) or world.holding()
        elif kind == "retry":
            seen["attempts"] = seen.get("attempts", 1) + 1

    def _free_hand(self, on: bool) -> None:
        """Coast the world while the hand moves clear of everything (TrialConfig.coast_free_hand)."""
        if self.t.config.coast_free_hand:
            world = self.t.world
            world.coast_free_hand(on)
            world.coast_settled_until(math.inf if on else None)

    def _approach(self, data: dict[str, Any]) -> None:
        """Score only: where the plan puts the COG relative to the true object."""
        t, pitch = self.t, self.t.world.layout.pitch_m
        self.seen["plan"] = (tuple(data["modules"]), tuple(data["cog"]), float(data["theta"]))
        cog = (data["cog"][0] * pitch, data["cog"][1] * pitch)
        self.seen["cog_outside_mm"] = 1e3 * distance_to_object_m(cog, t.truth, t.placed)


class _Trial:
    """The simulated lab of one trial: MuJoCo world, simulated box and robot.

    ``spec`` is the object placed in the world; ``truth`` the geometry the lab scores with
    (``spec`` unless a test swaps it: the loop's commands must not change).
    """

    def __init__(
        self,
        spec: Any,
        placement: tuple[float, float, float],
        seed: int,
        config: TrialConfig,
        opening_m: float | None,
        mounting: str | None,
        truth: Any | None = None,
        gripper: Any | None = None,
        lab: Any | None = None,
    ) -> None:
        from softpad.harness import SimulatedRobot
        from softpad.layout import GripperSpec
        from softpad.sim import MujocoGripper, MujocoWorld, parse_mounting

        self.spec, self.config, self.opening_m = spec, config, opening_m
        self.truth = spec if truth is None else truth
        self.placement = placement
        self.placed = _Placed(*placement)
        self.geometry = gripper or GripperSpec(*parse_mounting(mounting or spec.gripper))
        #: The drawn uncertain parameters (``config.randomize``), or None.
        self.lab = lab
        world = _lab_world(lab)
        physics = lab.gripper_physics() if lab is not None else {}
        self.gripper = MujocoGripper.from_spec(self.geometry, **physics)
        self.world = MujocoWorld(gripper=self.gripper, timestep_s=config.mujoco_timestep_s, **world)
        self.box = _trial_box(self.world, seed, config, lab)
        # the jaws open to the mounting's width (the loop commands "fully open"); an explicit
        # opening_m is an experimenter's choice that provokes a failure on purpose
        self.robot = SimulatedRobot(
            self.world,
            max_opening_m=self.gripper.max_width_m if opening_m is None else opening_m,
            closed_width_m=self.geometry.min_width_m,
        )

    def planner(self, detector: Any) -> Any:
        """The configured planner, told the trial gripper's geometry (a published spec) and
        the contact detector's sensing ratio."""
        from softpad.planning import planner_for

        return planner_for(
            self.config.planner,
            self.geometry,
            self.config.execution.planner,
            detector,
            self.box.sample_rate_hz,
            self.world.layout,
            catalogue=self.config.catalogue,
        )

    def place(self) -> None:
        from softpad.sim import Placement

        self.world.place_object(self.spec, Placement(*self.placement))


def _lab_world(lab: Any | None) -> dict[str, Any]:
    """The MuJoCo world's pad physics and response drawn by ``lab`` (none: the nominal)."""
    from softpad.layout import PadLayout

    if lab is None:
        return {}
    layout = PadLayout()
    return dict(pad=lab.pad_physics(layout.pitch_m), response=lab.pad_response(layout))


def _trial_box(world: Any, seed: int, config: TrialConfig, lab: Any | None) -> Any:
    """The simulated box over ``world``: the trial's sensor noise and pneumatics (drawn by
    ``lab``), its start pressure and the box-side safety limits."""
    from softpad.box import SafetyLimits, SimBox
    from softpad.sim import SensorParams

    sensor = SensorParams() if lab is None else lab.sensor()
    box = SimBox(
        world,
        sample_rate_hz=config.sample_rate_hz,
        seed=seed % (2**31),
        sensor=sensor if config.noise else SensorParams.ideal(),
        pneumatics=None if lab is None else lab.pneumatics(),
        # between trials of a session the modules stay near p0 (1 kPa, under it)
        initial_pressure_pa=1.0e3 if config.inflated_start else 0.0,
    )
    # the box-side limit follows the trials' fault limit (a gripper pressing an object
    # into the pad reads above the 3 kPa inflation maximum: trial_execution_params)
    max_pa = config.execution.inflation.max_pressure_pa
    box.safety_limits = SafetyLimits(max_pressure_pa=max_pa, release_pa=min(2500.0, max_pa - 500.0))
    return box


@dataclass(frozen=True)
class TrialOverrides:
    """What a study changes in one trial (the arguments of :func:`softpad.trials.run_trial`
    of the same names): a forced plan, opening, mounting, gripper, the geometry that scores it
    and a recorder that also hears the loop."""

    plan: Any | None = None
    opening_m: float | None = None
    mounting: str | None = None
    truth: Any | None = None
    recorder: Any | None = None
    gripper: Any | None = None


def varied_lab(spec: Any, seed: int, config: TrialConfig) -> tuple[Any, TrialConfig, Any | None]:
    """The object, trial configuration and :class:`softpad.sim.LabVariation` of one trial:
    with ``config.randomize`` every uncertain parameter drawn from the trial's seed (the
    placement noise and sample rate into the configuration, the charger's and the can's
    unknowns into the object), else ``spec``, ``config`` and None."""
    if not config.randomize:
        return spec, config, None
    config, lab = drawn_placement(config, seed)
    return lab.object(spec), config, lab


def configured_mounting(
    spec: Any, placement: tuple[float, float, float], seed: int, config: TrialConfig, lab: Any
) -> str | None:
    """The mounting ``config.mounting`` asks for: the one chosen from the pad's reading of the
    placed object (``"auto"``, :func:`softpad.trials._survey.surveyed_mounting`), the one
    named, or None (the object's own)."""
    if config.mounting == "auto":
        from softpad.trials._survey import surveyed_mounting

        return surveyed_mounting(spec, placement, seed, config, lab)
    return config.mounting


def execute_trial(
    spec: Any,
    placement: tuple[float, float, float],
    seed: int,
    config: TrialConfig,
    overrides: TrialOverrides | None = None,
) -> tuple[TrialResult, Any | None]:
    """Run one trial; see :func:`softpad.trials.run_trial`. Returns the result and the run's
    :class:`softpad.record.RunLog` when ``config.record_trace``."""
    from softpad.control import ExecutionError
    from softpad.errors import HardwareFault
    from softpad.harness import build_loop
    from softpad.record import RunLog, Tee
    from softpad.sensing import make_contact_detector

    o = overrides or TrialOverrides()
    spec, config, lab = varied_lab(spec, seed, config)
    mounting = o.mounting or configured_mounting(spec, placement, seed, config, lab)
    t = _Trial(spec, placement, seed, config, o.opening_m, mounting, o.truth, o.gripper, lab)
    log = RunLog({"object": spec.name, "seed": seed}) if config.record_trace else None
    mcap = _trial_recorder(t, seed)
    watcher = _TrialWatcher(t, Tee(log, mcap, o.recorder))
    detector = make_contact_detector(config.detector, t.box.sample_rate_hz, t.world.layout)
    execution = build_loop(
        t.box,
        t.robot,
        params=config.execution,
        layout=t.world.layout,
        planner=_FixedPlanner(o.plan) if o.plan is not None else t.planner(detector),
        contact_detector=detector,
        recorder=watcher,
        place_objects=t.place,
    ).execution
    base: dict[str, Any] = dict(
        object=spec.name,
        trial=0,
        seed=seed,
        placement=placement,
        mounting=t.gripper.mounting,
        parameters=None if lab is None else lab.to_dict(),
    )
    with t.box, mcap if mcap is not None else contextlib.nullcontext():
        try:
            execution.run()
        except ExecutionError as exc:
            return _not_detected(base, watcher.seen, t, exc), log
        except HardwareFault as exc:
            # A fault the loop detected (over-pressure, a leak alarm during the adjustment...):
            # after the outcome the trial stands; before it, the trial is a failure of its own
            # kind, with the plan when there was one.
            if "plan" not in watcher.seen:
                return _box_fault(base, None, t, execution.phase, exc), log
            if "outcome" not in watcher.seen:
                return _box_fault(base, watcher.seen, t, execution.phase, exc), log
        sim_time = t.box.time_s
    return _scored(base, watcher.seen, t, sim_time), log


def _not_detected(
    base: dict[str, Any], seen: dict[str, Any], t: _Trial, exc: Exception
) -> TrialResult:
    return TrialResult(
        **base,
        success=False,
        cause="object_not_detected",
        increments_pa=seen.get("increments_pa", ()),
        sim_time_s=t.box.time_s,
        detail=str(exc),
    )


def _box_fault(
    base: dict[str, Any], seen: dict[str, Any] | None, t: _Trial, phase: str, exc: Exception
) -> TrialResult:
    """A box fault's result; ``seen`` None: the fault came before planning."""
    when = "" if seen is not None else ", before planning"
    return TrialResult(
        **base,
        success=False,
        cause="box_fault",
        **(_planned(seen, t) if seen is not None else {}),
        sim_time_s=t.box.time_s,
        detail=f"box fault in phase {phase}{when}: {exc}",
    )


def _planned(seen: dict[str, Any], t: _Trial) -> dict[str, Any]:
    """The fields of a trial result that a planned grasp has, from what the watcher saw."""
    modules, cog, theta = seen["plan"]
    return dict(
        modules=modules,
        increments_pa=seen.get("increments_pa", ()),
        cog=cog,
        theta=theta,
        rule=seen.get("rule"),
        opening_m=t.robot.max_opening_m,
        contact_detected=seen.get("detected", False),
        cog_outside_object_mm=seen.get("cog_outside_mm"),
        attempts=seen.get("attempts", 1),
    )


def _scored(base: dict[str, Any], seen: dict[str, Any], t: _Trial, sim_time: float) -> TrialResult:
    outcome = seen.get("outcome", "contact_not_detected")
    common = dict(
        **_planned(seen, t),
        contact_delay_s=seen.get("delay"),
        finger_travel_mm=seen.get("travel"),
        sim_time_s=sim_time,
    )
    # held when the world carried the object at the end of a hold, whichever grasp did it
    if seen.get("carried", False):
        return TrialResult(**base, success=True, cause=None, detail="held", **common)
    if outcome == "held":  # the gripper reported a grip, the world carried nothing
        why = "the jaws stopped short of closing, the object not carried at the end of the hold"
        return TrialResult(**base, success=False, cause="slipped_during_hold", detail=why, **common)
    cause, why = _cause(outcome, seen, t.truth, t.placed, t.gripper)
    return TrialResult(**base, success=False, cause=cause, detail=why, **common)


def _cause(
    outcome: str, seen: dict[str, Any], spec: Any, placed: Any, gripper: Any
) -> tuple[str, str]:
    """Failure cause from the loop's outcome and what the world showed."""
    if outcome == "contact_not_detected":
        return (
            "contact_not_detected",
            "descended to the pad base without the pad sensing the fingers",
        )
    outside = seen.get("cog_outside_mm")
    if outside is not None and outside > _OUTSIDE_MM:
        hit = "" if seen.get("tip_hit") is None else f"; a jaw came down on {seen['tip_hit']}"
        return "cog_outside_object", f"the planned COG lay {outside:.1f} mm outside the object{hit}"
    if seen.get("tip_hit") is not None:
        return "jaws_hit_object", f"a jaw came down on {seen['tip_hit']}"
    if outcome == "landed":  # sensed on the object with no attempt left: the jaws never closed
        return "jaws_hit_object", "a jaw was sensed on the object; the jaws did not close"
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


def _trial_recorder(t: _Trial, seed: int) -> Any:
    """The trial's MCAP recorder when ``config.record_path`` (gripper pose from the world)."""
    if t.config.record_path is None:
        return None
    from dataclasses import asdict

    from softpad.record import McapRecorder

    meta: dict[str, Any] = {"command": "trials", "objects": [t.spec.name], "seed": seed}
    meta.update(layout=t.world.layout.name, placement=list(t.placement), box="sim (MuJoCo)")
    meta.update(params=asdict(t.config.execution), mounting=t.gripper.mounting)
    meta.update(planner=t.config.planner, contact_detector=t.config.detector)
    return McapRecorder(t.config.record_path, meta, force=True, robot_state=t.world.gripper_state)
