"""Grasp execution: the closed loop of the seed's Section 6.2.2, as a state machine.

Phases (each logged with its start time through the recorder hook)::

    adjust -> reference -> wait_object -> plan -> for each object:
        approach (over the COG) -> descend (0.05 m/s) -> close -> lift -> hold (15 s) -> release
    -> done

Contact is declared when the running average (10 samples) of any module's increment over the
pressures read just before the descent exceeds t_g = 0.09 kPa; the arm then stops and the jaws
close. Objects planned as separate (not 8-connected) are grasped one after the other, in the
planner's order. The box is the clock: every step reads one frame, so in simulation the world
and the robot advance exactly with the frames.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from softpad.box import Box, PressureFrame
from softpad.control._inflation import (
    AdjustmentResult,
    InflationParams,
    inflate_and_adjust,
)
from softpad.control._robot import Robot, ToolPose
from softpad.control._safety import DetectedFault, RunSafety, SafeStateResult
from softpad.errors import HardwareFault, InputError, SoftPadError
from softpad.layout import PadLayout
from softpad.planning import GraspPlan, PlannerParams, plan_grasps
from softpad.sensing import DEFAULT_CONTACT_THRESHOLD_PA, ContactDetector, RunningAverage

#: Grasp outcomes.
OUTCOMES = ("held", "dropped", "missed", "contact_not_detected")


class ExecutionError(SoftPadError, RuntimeError):
    """The loop cannot go on (no object placed in time, nothing to grasp)."""


class Recorder(Protocol):
    """Hook receiving every frame and event of a run (``softpad.record.RunLog`` implements it)."""

    def frame(self, frame: PressureFrame, phase: str) -> None:
        """One frame read during ``phase``."""
        ...

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        """Something happened at box time ``t_s`` (phase start, contact, plan, fault...)."""
        ...


class _NullRecorder:
    def frame(self, frame: PressureFrame, phase: str) -> None:
        pass

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        pass


@dataclass(frozen=True)
class ExecutionParams:
    """Parameters of the closed loop (thesis values where it gives them, Sections 6.2-6.3).

    Parameters
    ----------
    inflation
        Inflation/adjustment parameters (p0 = 1.1 kPa, t_adj = 0.03 kPa, max 3 kPa).
    planner
        Planner parameters (t_o = 0.05 kPa, c_s = 0.2).
    contact_threshold_pa
        t_g, pascals (0.09 kPa).
    filter_length
        Running-average length of the contact detector and object detector, samples (10).
    approach_speed_m_s
        Descent speed towards the pad, m/s (0.05).
    travel_speed_m_s
        Speed of the other arm motions, m/s.
    gripper_speed_m_s
        Speed of each jaw when closing/opening, m/s.
    approach_height_m
        Height of the fingertips above the pad base when moving over the COG, m.
    min_height_m
        Lowest fingertip height of a descent (the rigid base), m; reaching it without a
        detected contact is the outcome ``contact_not_detected``.
    lift_m
        Lift after closing, m.
    hold_s
        Hold time, seconds (15 s).
    object_wait_s
        Time to wait for an object after the reference, seconds.
    object_settle_s
        Wait between the first sight of an object and the planning reads, seconds.
    planning_reads
        Reads averaged for planning (10, like the reference).
    pre_descent_reads
        Reads averaged into the contact detector's reference, samples.
    motion_timeout_s
        Longest allowed arm or jaw motion, seconds.
    """

    inflation: InflationParams = field(default_factory=InflationParams)
    planner: PlannerParams = field(default_factory=PlannerParams)
    contact_threshold_pa: float = DEFAULT_CONTACT_THRESHOLD_PA
    filter_length: int = 10
    approach_speed_m_s: float = 0.05
    travel_speed_m_s: float = 0.25
    gripper_speed_m_s: float = 0.05
    approach_height_m: float = 0.12
    min_height_m: float = 0.001
    lift_m: float = 0.08
    hold_s: float = 15.0
    object_wait_s: float = 30.0
    object_settle_s: float = 1.0
    planning_reads: int = 10
    pre_descent_reads: int = 10
    motion_timeout_s: float = 20.0

    def __post_init__(self) -> None:
        for n in (
            "contact_threshold_pa",
            "approach_speed_m_s",
            "travel_speed_m_s",
            "gripper_speed_m_s",
            "approach_height_m",
            "lift_m",
            "object_wait_s",
            "motion_timeout_s",
        ):
            v = getattr(self, n)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise InputError(f"execution {n} must be a positive number, got {v!r}")
        for n in ("hold_s", "object_settle_s", "min_height_m"):
            v = getattr(self, n)
            if not (isinstance(v, int | float) and math.isfinite(v) and v >= 0):
                raise InputError(f"execution {n} must be a number >= 0, got {v!r}")
        for n in ("filter_length", "planning_reads", "pre_descent_reads"):
            v = getattr(self, n)
            if not (isinstance(v, int) and v >= 1):
                raise InputError(f"execution {n} must be an integer >= 1, got {v!r}")


@dataclass(frozen=True)
class GraspRecord:
    """What happened to one planned object.

    Attributes
    ----------
    plan
        The grasp plan that was executed.
    outcome
        ``held``, ``dropped`` (held after lifting, lost during the hold), ``missed`` (nothing
        between the closed jaws) or ``contact_not_detected``.
    contact_detected
        Whether the pad sensed the fingers (filtered increment above t_g).
    contact_modules
        Modules whose filtered increment first exceeded t_g.
    detected_at_s
        Box time of the detection, seconds (None when not detected).
    first_touch_s
        Box time of the first fingertip touch (simulation ground truth; None if unknown).
    contact_delay_s
        Detection time minus first-touch time, seconds.
    finger_travel_mm
        Downward travel of the fingertips from first touch to the stop, millimetres.
    """

    plan: GraspPlan
    outcome: str
    contact_detected: bool
    contact_modules: tuple[int, ...] = ()
    detected_at_s: float | None = None
    first_touch_s: float | None = None
    contact_delay_s: float | None = None
    finger_travel_mm: float | None = None

    def to_dict(self, layout: PadLayout) -> dict[str, Any]:
        """JSON-ready dict."""

        def r(v: float | None, n: int) -> float | None:
            return None if v is None else round(v, n)

        return {
            "plan": self.plan.to_dict(layout),
            "outcome": self.outcome,
            "contact_detected": self.contact_detected,
            "contact_modules": list(self.contact_modules),
            "detected_at_s": r(self.detected_at_s, 4),
            "first_touch_s": r(self.first_touch_s, 4),
            "contact_delay_s": r(self.contact_delay_s, 4),
            "finger_travel_mm": r(self.finger_travel_mm, 3),
        }


@dataclass(frozen=True)
class ExecutionResult:
    """Timeline and outcome of one run of the loop.

    Attributes
    ----------
    layout
        Pad geometry.
    adjustment
        Inflation/adjustment result (reference pressures).
    increments_pa
        Increments dP_i used for planning, pascals.
    plans
        Plans of the detected objects, in grasp order.
    grasps
        One record per executed plan.
    phases
        (phase name, start time s) in order.
    faults
        Faults detected (empty on a run that ended normally; a faulted run raises, with its
        faults and safe state attached to the exception).
    safe_state
        Result of the verified safe state when one was reached, else None.
    """

    layout: PadLayout
    adjustment: AdjustmentResult
    object_seen_at_s: float
    increments_pa: NDArray[np.float64]
    plans: tuple[GraspPlan, ...]
    grasps: tuple[GraspRecord, ...]
    phases: tuple[tuple[str, float], ...]
    faults: tuple[DetectedFault, ...] = ()
    safe_state: SafeStateResult | None = None

    @property
    def outcome(self) -> str:
        """``held`` when every object was held, else the first other outcome."""
        for g in self.grasps:
            if g.outcome != "held":
                return g.outcome
        return "held" if self.grasps else "missed"

    @property
    def contact_detected(self) -> bool:
        """True when contact was detected on every grasp."""
        return bool(self.grasps) and all(g.contact_detected for g in self.grasps)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``objects`` as in ``softpad plan --json``, then the first grasp's
        ``contact_detected``, ``contact_delay_s``, ``finger_travel_mm`` and the overall
        ``outcome``; every grasp and the phase timeline in detail."""
        first = self.grasps[0] if self.grasps else None
        return {
            "objects": [p.to_dict(self.layout) for p in self.plans],
            "contact_detected": self.contact_detected,
            "contact_delay_s": None
            if first is None or first.contact_delay_s is None
            else round(first.contact_delay_s, 4),
            "finger_travel_mm": None
            if first is None or first.finger_travel_mm is None
            else round(first.finger_travel_mm, 3),
            "outcome": self.outcome,
            "increments_kpa": [round(float(v) / 1e3, 5) for v in self.increments_pa],
            "adjustment": self.adjustment.to_dict(),
            "object_seen_at_s": round(self.object_seen_at_s, 4),
            "grasps": [g.to_dict(self.layout) for g in self.grasps],
            "phases": [{"phase": n, "t_s": round(t, 4)} for n, t in self.phases],
            "faults": [f.to_dict() for f in self.faults],
            "safe_state": None if self.safe_state is None else self.safe_state.to_dict(),
        }


class GraspExecution:
    """The closed loop on a box and a robot (seed, Section 6.2.2).

    Parameters
    ----------
    box
        An open box; module k of ``layout`` is channel k.
    robot
        The arm and gripper (pad-frame poses).
    layout
        Pad geometry.
    params
        Loop parameters (thesis defaults).
    recorder
        Receives every frame and event (e.g. ``softpad.record.RunLog``).
    place_objects
        Called once when the loop starts waiting for an object (simulation: put the object
        on the pad); None on real hardware, where a person places it.
    """

    def __init__(
        self,
        box: Box,
        robot: Robot,
        layout: PadLayout | None = None,
        params: ExecutionParams | None = None,
        recorder: Recorder | None = None,
        place_objects: Callable[[], None] | None = None,
    ) -> None:
        self.box = box
        self.robot = robot
        self.layout = layout or PadLayout()
        self.params = params or ExecutionParams()
        self.recorder: Recorder = recorder if recorder is not None else _NullRecorder()
        self.place_objects = place_objects
        self.n = self.layout.n_modules
        if self.n > box.channels:
            raise InputError(
                f"a {self.layout.name} pad needs {self.n} channels, the box has {box.channels}"
            )
        self.phase = "idle"
        self._phases: list[tuple[str, float]] = []
        self._last_t = 0.0
        infl = self.params.inflation
        #: Fault monitor of every frame and the safe state of this run.
        self.safety = RunSafety(box, self.n, infl.max_pressure_pa, infl.trip_margin_pa)

    # --- plumbing -------------------------------------------------------------------
    def _enter(self, phase: str, **data: Any) -> None:
        self.phase = phase
        self._phases.append((phase, self._last_t))
        self.recorder.event(self._last_t, "phase", phase=phase, **data)

    def _read(self) -> tuple[PressureFrame, NDArray[np.float64]]:
        frame = self.box.read()
        self._last_t = frame.t_s
        self.recorder.frame(frame, self.phase)
        return frame, self.safety.watch(frame)

    def _wait_motion(self, what: str) -> None:
        t0 = self._last_t
        while self.robot.is_moving():
            self._read()
            if self._last_t - t0 > self.params.motion_timeout_s:
                raise HardwareFault(
                    f"robot: {what} did not finish within {self.params.motion_timeout_s:g} s"
                )

    def _mean_reads(self, n: int) -> NDArray[np.float64]:
        return np.mean([self._read()[1] for _ in range(n)], axis=0)

    # --- the loop -------------------------------------------------------------------
    def run(self) -> ExecutionResult:
        """Run the whole loop once; raises HardwareFault (after making the box safe) on a fault."""
        try:
            return self._run()
        except HardwareFault as exc:
            self._make_safe(exc)
            raise
        except KeyboardInterrupt:  # a user's Ctrl-C must not leave valves open
            self.recorder.event(self._last_t, "interrupted", phase=self.phase)
            self._make_safe(HardwareFault("interrupted"))
            raise

    def _make_safe(self, exc: HardwareFault) -> None:
        """Record the fault, stop the arm (holding what it holds), reach the verified safe state."""
        try:
            self.robot.stop()
        except HardwareFault:
            pass  # a robot behind a lost link cannot be stopped from here
        f = self.safety.fail(exc, self._last_t, lambda fr: self.recorder.frame(fr, "safe"))
        self.recorder.event(
            f.t_s, "fault", message=f.message, phase=self.phase, channel=f.channel, cause=f.cause
        )
        s = self.safety.safe_state
        if s is not None:
            d = s.to_dict()
            del d["t_s"]
            self.recorder.event(s.t_s, "safe_state", **d)

    def _run(self) -> ExecutionResult:
        p = self.params
        self._enter("adjust")
        adj = inflate_and_adjust(
            self.box,
            self.n,
            p.inflation,
            on_frame=self._on_adjust_frame,
            on_adjusted=self._on_adjusted,
            safe_state=False,
        )
        self.recorder.event(
            adj.reference_at_s,
            "reference",
            reference_kpa=[round(v / 1e3, 5) for v in adj.reference_pa],
        )
        self.safety.monitor.set_reference(adj.reference_pa)

        self._enter("wait_object")
        if self.place_objects is not None:
            self.place_objects()
        seen_at = self._wait_for_object(adj.reference_pa)

        self._enter("plan")
        mean = self._mean_reads(p.planning_reads)
        delta = mean - adj.reference_pa
        plans = tuple(plan_grasps(delta, self.layout, p.planner))
        self.recorder.event(
            self._last_t,
            "plan",
            increments_kpa=[round(float(v) / 1e3, 5) for v in delta],
            objects=[pl.to_dict(self.layout) for pl in plans],
        )
        if not plans:
            raise ExecutionError("the object disappeared before planning: no module above t_o")

        grasps = [self._grasp(plan) for plan in plans]
        self._enter("valve_check")
        self.safety.check_valves(self._read)
        self._enter("done")
        return ExecutionResult(
            self.layout,
            adj,
            seen_at,
            delta,
            plans,
            tuple(grasps),
            tuple(self._phases),
            tuple(self.safety.faults),
        )

    def _on_adjust_frame(self, frame: PressureFrame) -> None:
        self._last_t = frame.t_s
        self.recorder.frame(frame, self.phase)
        self.safety.watch(frame)

    def _on_adjusted(self, t_s: float) -> None:
        self.recorder.event(t_s, "adjusted", target_kpa=self.params.inflation.target_pa / 1e3)
        self._enter("reference")

    def _wait_for_object(self, reference: NDArray[np.float64]) -> float:
        p = self.params
        filt = RunningAverage(p.filter_length)
        t0 = self._last_t
        seen_at: float | None = None
        while True:
            _, pr = self._read()
            d = filt.update(pr - reference)
            if seen_at is None:
                if filt.full and (d > p.planner.object_threshold_pa).any():
                    seen_at = self._last_t
                    self.recorder.event(
                        seen_at,
                        "object_seen",
                        modules=[
                            int(k) + 1 for k in np.flatnonzero(d > p.planner.object_threshold_pa)
                        ],
                    )
                elif self._last_t - t0 > p.object_wait_s:
                    raise ExecutionError(
                        f"no object placed on the pad within {p.object_wait_s:g} s"
                    )
            elif self._last_t - seen_at >= p.object_settle_s:
                return seen_at

    def _grasp(self, plan: GraspPlan) -> GraspRecord:
        p = self.params
        x, y = plan.cog_m(self.layout)
        self._enter("approach", modules=list(plan.modules), cog=list(plan.cog), theta=plan.theta)
        self.robot.set_gripper(1.0, p.travel_speed_m_s)  # fully open (clamped to the mounting)
        self._wait_motion("opening the gripper")
        self.robot.move_to(ToolPose(x, y, p.approach_height_m, plan.theta), p.travel_speed_m_s)
        self._wait_motion("moving over the centre of grasp")
        reference = self._mean_reads(p.pre_descent_reads)

        self._enter("descend")
        detector = ContactDetector(reference, p.contact_threshold_pa, p.filter_length)
        self.robot.descend(p.approach_speed_m_s, p.min_height_m)
        detected_at: float | None = None
        t0 = self._last_t
        while True:
            _, pr = self._read()
            if detector.update(pr):
                self.robot.stop()
                detected_at = self._last_t
                self.recorder.event(
                    detected_at, "contact", modules=list(detector.triggered_modules)
                )
                break
            if not self.robot.is_moving():
                self.recorder.event(self._last_t, "no_contact", z_m=self.robot.state().z_m)
                break
            if self._last_t - t0 > p.motion_timeout_s:
                raise HardwareFault(
                    f"robot: descent did not finish within {p.motion_timeout_s:g} s"
                )
        touch = self.robot.first_touch()
        stop_z = self.robot.state().z_m
        first_touch_s = touch[0] if touch else None
        delay = travel = None
        if touch is not None and detected_at is not None:
            delay = detected_at - touch[0]
            travel = (touch[1] - stop_z) * 1e3

        if detected_at is None:
            outcome = "contact_not_detected"
            self.robot.move_to(ToolPose(x, y, p.approach_height_m, plan.theta), p.travel_speed_m_s)
            self._wait_motion("retreating")
        else:
            self._enter("close")
            self.robot.set_gripper(0.0, p.gripper_speed_m_s)
            self._wait_motion("closing the gripper")
            self._enter("lift")
            s = self.robot.state()
            self.robot.move_to(
                ToolPose(s.x_m, s.y_m, s.z_m + p.lift_m, s.yaw_rad), p.travel_speed_m_s
            )
            self._wait_motion("lifting")
            lifted = self.robot.holding()
            self._enter("hold")
            t_hold = self._last_t
            while self._last_t - t_hold < p.hold_s:
                self._read()
            held = self.robot.holding()
            outcome = "held" if held else ("dropped" if lifted else "missed")
            self.recorder.event(self._last_t, "outcome", outcome=outcome)
            self._enter("release")
            self.robot.set_gripper(1.0, p.travel_speed_m_s)
            self._wait_motion("opening the gripper")
            s = self.robot.state()
            self.robot.move_to(
                ToolPose(s.x_m, s.y_m, p.approach_height_m, s.yaw_rad), p.travel_speed_m_s
            )
            self._wait_motion("moving up")
        return GraspRecord(
            plan,
            outcome,
            detected_at is not None,
            tuple(detector.triggered_modules),
            detected_at,
            first_touch_s,
            delay,
            travel,
        )
