"""Grasp execution: the closed loop of the thesis's Section 6.2.2, assembled from parts.

:class:`GraspExecution` drives a :class:`~softpad.box.Box` and a :class:`Robot` and takes its
planner, object detector, contact detector and recorder as arguments (the thesis's by default).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.box import Box, BoxWrapper, PressureFrame, ValveCommand
from softpad.control._inflation import (
    AdjustmentResult,
    InflationParams,
    inflate_and_adjust,
)
from softpad.control._phases import LOADING_PHASES, PRESSING_PHASES, Phase, next_phase
from softpad.control._robot import Robot, RobotWrapper, ToolPose
from softpad.control._safety import DetectedFault, RunSafety, SafeStateResult
from softpad.control._watch import ObjectWatch, plan_from_reads
from softpad.errors import (
    KPA_AS_PA,
    MM_AS_M,
    CheckedFields,
    Count,
    HardwareFault,
    InputError,
    NonNegative,
    Positive,
    SoftPadError,
    check_range,
)
from softpad.layout import PadLayout
from softpad.planning import (
    GraspPlan,
    Planner,
    PlannerParams,
    RetryPlanner,
    ThesisPlanner,
    planner_detector,
)
from softpad.sensing import (
    ContactDetector,
    ObjectDetector,
    ThesisContactDetector,
    ThesisObjectDetector,
    measured_change,
)


class ExecutionError(SoftPadError, RuntimeError):
    """The loop cannot go on (no object placed in time, nothing to grasp)."""


class Recorder(Protocol):
    """Receives every frame and event of a run (``softpad.record.RunLog`` implements it).

    Event kinds and their data (SI units): ``phase`` (phase), ``adjusted`` (target_pa),
    ``reference`` (reference_pa), ``object_seen`` (modules), ``plan`` (increments_pa, objects),
    ``contact`` (modules), ``no_contact`` (z_m), ``outcome`` (outcome), ``valve`` (channel,
    command), ``robot`` (command and its arguments), ``fault`` (message, phase),
    ``interrupted`` (phase).
    """

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


#: Fastest arm or jaw motion the loop accepts, m/s (a robot arm near a pad; the thesis's
#: approach is 0.05 m/s): a larger value is a unit mix-up.
MAX_SPEED_M_S = 2.0
#: Longest height or lift the loop accepts, m.
MAX_TRAVEL_M = 2.0


@dataclass(frozen=True)
class ExecutionParams(CheckedFields, what="execution"):
    """Parameters of the closed loop (thesis values where it gives them, Sections 6.2-6.3)."""

    #: Inflation/adjustment parameters (p0, t_adj, maximum pressure).
    inflation: InflationParams = field(default_factory=InflationParams)
    #: Parameters of the default planner and object detector (t_o, c_s).
    planner: PlannerParams = field(default_factory=PlannerParams)
    #: t_g of the default contact detector, pascals.
    contact_threshold_pa: Positive = thesis.CONTACT_THRESHOLD_PA
    #: Running-average length of the default contact detector and of the object watch, samples.
    filter_length: Count = thesis.FILTER_WINDOW
    #: Descent speed towards the pad, m/s.
    approach_speed_m_s: Positive = thesis.APPROACH_SPEED_M_S
    #: Speed of the other arm motions, m/s.
    travel_speed_m_s: Positive = 0.25
    #: Speed of each jaw when closing/opening, m/s.
    gripper_speed_m_s: Positive = thesis.JAW_SPEED_M_S
    #: Height of the fingertips above the pad base when moving over the COG, m.
    approach_height_m: Positive = 0.12
    #: Lowest fingertip height of a descent (the rigid base), m; reaching it without a
    #: detected contact is the outcome ``contact_not_detected``.
    min_height_m: NonNegative = 0.001
    #: Lift after closing, m.
    lift_m: Positive = 0.08
    #: Hold time, seconds.
    hold_s: NonNegative = thesis.HOLD_S
    #: Time to wait for an object after the reference, seconds.
    object_wait_s: Positive = 30.0
    #: Wait between the first sight of an object and the planning reads, seconds.
    object_settle_s: NonNegative = 1.0
    #: Reads averaged for planning (like the reference).
    planning_reads: Count = thesis.REFERENCE_READS
    #: Reads averaged into the contact detector's reference, samples.
    pre_descent_reads: Count = thesis.REFERENCE_READS
    #: Longest allowed arm or jaw motion, seconds.
    motion_timeout_s: Positive = 20.0
    #: Fingertip height above the pad base over which a sensed contact is the jaws landing
    #: on the object, not on the pad, metres: the module height at p0 (about 9 mm, thesis
    #: Section 6.3; 8.3 mm from the project's FEM) plus 8 mm. Fingers sensed on the pad stop
    #: 2.5 to 7.6 mm above the base in simulation; on the lowest catalogue object, a 19.2 mm
    #: Duplo brick resting on the pad, above 25 mm.
    landing_height_m: Positive = 0.017
    #: Grasps tried per object: when the jaws landed on the object and closed on nothing
    #: (the gripper closed fully; or at the landing, see ``retry_before_close``), the loop
    #: tries the planner's next grasp (:class:`~softpad.planning.RetryPlanner`), up to this
    #: many in all. A planner without one (the thesis's) makes one attempt, as the thesis does.
    max_attempts: Count = 2
    #: Ask the planner for its retry at a landing on the object, before closing; it offers
    #: one only where the landing pressed one side of the jaws' centre line alone (a jaw on
    #: a brick's edge, tipping it: closing there shoves the brick 10 to 15 mm across the pad
    #: as the landed jaw slides off it, and the next grasp, planned where it lay, lands on it
    #: again), not where it also pressed the line (a jaw on a toy's arm, its body on the
    #: line: closing still holds it). Development seeds 100-115 (80 trials each,
    #: gripper-aware planner, adaptive detector): charger 79 held against 65; toy, can and
    #: banana trial for trial as without it. Asked on the last attempt too: where the planner
    #: would try again the loop goes up without closing (outcome ``landed``) instead of
    #: closing with a jaw on the object (issue 47: a retry landing on a lying apple, orange or
    #: can wedged it into the pad, chambers at the sensor's 10 kPa full scale, 5 of 50
    #: ycb-dev trials; until 2026-11-28). False: close after every landing, retry only
    #: after closing on nothing (the loop before 2026-11-24).
    retry_before_close: bool = True
    #: After a grasp that held, skip the later planned objects whose modules all unloaded
    #: while it was held (read at the end of the hold, with the object detector): they went
    #: up with it, one object the pad showed as two (a banana arched over its thin middle,
    #: resting on its ends). A loop feature, the same with every planner (issue 33: until
    #: 2026-11-27 only with a :class:`~softpad.planning.RetryPlanner`). False: grasp every
    #: planned object in turn from the one plan, as the thesis does.
    drop_carried: bool = True

    def __post_init__(self) -> None:
        super().__post_init__()
        for name in ("approach_speed_m_s", "travel_speed_m_s", "gripper_speed_m_s"):
            check_range(
                f"execution {name}",
                getattr(self, name),
                1e-4,
                MAX_SPEED_M_S,
                "m/s",
                "millimetres per second given as metres per second?",
            )
        for name in ("approach_height_m", "min_height_m", "lift_m", "landing_height_m"):
            check_range(f"execution {name}", getattr(self, name), 0.0, MAX_TRAVEL_M, "m", MM_AS_M)
        # a contact threshold under 1 Pa (the sensor's noise is 5.5 Pa) is kilopascals given as
        # pascals; a hold over an hour is milliseconds given as seconds
        check_range(
            "execution contact_threshold_pa",
            self.contact_threshold_pa,
            1.0,
            1e4,
            "Pa",
            low_hint=KPA_AS_PA,
        )
        check_range(
            "execution hold_s", self.hold_s, 0.0, 3600.0, "s", "milliseconds given as seconds?"
        )


@dataclass(frozen=True)
class GraspRecord:
    """What happened to one planned object, as the controller saw it."""

    #: The grasp plan that was executed.
    plan: GraspPlan
    #: ``held``, ``dropped`` (held after lifting, lost during the hold), ``missed`` (nothing
    #: between the closed jaws), ``landed`` (a jaw sensed on the object, where the planner
    #: would try again, with no attempt left: the jaws did not close) or
    #: ``contact_not_detected``.
    outcome: str
    #: Whether the contact detector sensed the fingers.
    contact_detected: bool
    #: Modules that triggered the contact detector.
    contact_modules: tuple[int, ...] = ()
    #: Box time of the detection, seconds (None when not detected).
    detected_at_s: float | None = None
    #: Fingertip height where the descent stopped (robot's own state), metres.
    stop_z_m: float | None = None
    #: Grasps tried (more than one after landings on the object); ``plan`` is the last.
    attempts: int = 1
    #: Modules of later planned objects that unloaded while this grasp held its object
    #: (they went up with it and were not grasped again; ``drop_carried``).
    carried_modules: tuple[int, ...] = ()

    def to_dict(self, layout: PadLayout) -> dict[str, Any]:
        """JSON-ready dict (SI units)."""
        return {
            "plan": self.plan.to_dict(layout),
            "outcome": self.outcome,
            "contact_detected": self.contact_detected,
            "contact_modules": list(self.contact_modules),
            "detected_at_s": None if self.detected_at_s is None else round(self.detected_at_s, 4),
            "stop_z_m": None if self.stop_z_m is None else round(self.stop_z_m, 6),
            "attempts": self.attempts,
            "carried_modules": list(self.carried_modules),
        }


@dataclass(frozen=True)
class ExecutionResult:
    """Timeline and outcome of one run of the loop."""

    #: Pad geometry.
    layout: PadLayout
    #: Inflation/adjustment result (reference pressures).
    adjustment: AdjustmentResult
    #: Box time when the object watch first saw an object, seconds.
    object_seen_at_s: float
    #: Increments dP_i used for planning, pascals.
    increments_pa: NDArray[np.float64]
    #: Plans of the detected objects, in grasp order.
    plans: tuple[GraspPlan, ...]
    #: One record per executed plan (a plan dropped because its object went up with an
    #: earlier one has none: see :attr:`GraspRecord.carried_modules`).
    grasps: tuple[GraspRecord, ...]
    #: (phase name, start time s) in order.
    phases: tuple[tuple[str, float], ...]
    #: Faults detected (empty on a run that ended normally; a faulted run raises, with its
    #: faults and safe state attached to the exception).
    faults: tuple[DetectedFault, ...] = ()
    #: Result of the verified safe state when one was reached, else None.
    safe_state: SafeStateResult | None = None

    @property
    def outcome(self) -> str:
        """``held`` when every object was held, else the first other outcome (a tentative
        grasp that did not hold does not count: the grasps after it stand for its objects)."""
        counted = [g for g in self.grasps if g.outcome == "held" or not g.plan.tentative]
        for g in counted:
            if g.outcome != "held":
                return g.outcome
        return "held" if counted else "missed"

    @property
    def contact_detected(self) -> bool:
        """True when contact was detected on every grasp."""
        return bool(self.grasps) and all(g.contact_detected for g in self.grasps)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (SI units): ``objects`` as in ``softpad plan --json``, the overall
        ``outcome``, every grasp and the phase timeline."""
        return {
            "objects": [p.to_dict(self.layout) for p in self.plans],
            "contact_detected": self.contact_detected,
            "outcome": self.outcome,
            "increments_pa": [round(float(v), 2) for v in self.increments_pa],
            "adjustment": self.adjustment.to_dict(),
            "object_seen_at_s": round(self.object_seen_at_s, 4),
            "grasps": [g.to_dict(self.layout) for g in self.grasps],
            "phases": [{"phase": n, "t_s": round(t, 4)} for n, t in self.phases],
            "faults": [f.to_dict() for f in self.faults],
            "safe_state": None if self.safe_state is None else self.safe_state.to_dict(),
        }


class _RecordingBox(BoxWrapper):
    """The execution's view of the box: every valve command also becomes a recorder event.
    The caller owns the wrapped box; the view shares its safety guard (its limits, its trips)."""

    def __init__(self, box: Box, recorder: Recorder, clock: Callable[[], float]) -> None:
        super().__init__(box, owns_inner=False)
        self._recorder, self._clock = recorder, clock
        self._limits, self._guard = box.safety_limits, box.safety

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        super()._apply_valve(channel, command)
        self._recorder.event(self._clock(), "valve", channel=channel, command=command.value)


class _RecordingRobot(RobotWrapper):
    """The execution's view of the robot: every command also becomes a recorder event."""

    def __init__(self, robot: Robot, recorder: Recorder, clock: Callable[[], float]) -> None:
        super().__init__(robot)
        self._recorder, self._clock = recorder, clock

    def _log(self, command: str, **data: float) -> None:
        self._recorder.event(self._clock(), "robot", command=command, **data)

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self._log("move_to", **vars(pose), speed_m_s=speed_m_s)
        super().move_to(pose, speed_m_s)

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self._log("descend", speed_m_s=speed_m_s, min_z_m=min_z_m)
        super().descend(speed_m_s, min_z_m)

    def stop(self) -> None:
        self._log("stop")
        super().stop()

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self._log("set_gripper", width_m=width_m, speed_m_s=speed_m_s)
        super().set_gripper(width_m, speed_m_s)


class GraspExecution:
    """The closed loop of the thesis's Section 6.2.2, assembled from parts.

    Phases (:class:`~softpad.control.Phase`, each logged with its start time through the
    recorder; the transitions allowed are :data:`~softpad.control.TRANSITIONS`)::

        adjust -> reference -> wait_object -> plan -> for each object:
            approach (over the COG) -> descend -> close -> lift -> hold -> release
        -> valve_check -> done

    When the jaws closed on nothing after the fingers were sensed above ``landing_height_m``
    (they landed on the object), a planner with a retry (:class:`~softpad.planning.RetryPlanner`)
    is asked for another grasp, tried from ``approach`` again (``max_attempts`` in all); with
    ``retry_before_close`` (default) it is asked at the landing first, and where it offers
    one there the jaws do not close.

    The box is the clock: every step reads one frame, so in simulation the world and the
    robot advance exactly with the frames. The execution sees only what a real system sees:
    the box's frames, the plans, and the robot's own state.

    Parameters
    ----------
    box
        An open box; module k of ``layout`` is channel k.
    robot
        The arm and gripper (pad-frame poses).
    layout
        Pad geometry (2 x 3, 45 mm by default).
    params
        Loop parameters (thesis defaults).
    planner
        Turns objects into grasps; :class:`~softpad.planning.ThesisPlanner` by default.
    object_detector
        Finds objects in the filtered increments; by default the planner's own
        (:func:`~softpad.planning.planner_detector`: the model-based planner's threshold at
        the noise, calibrated on the reference reads), else the thesis's t_o detector.
    contact_detector
        Senses the fingers during the descent; the thesis's t_g detector by default.
    recorder
        Receives every frame and event (frames, phases, plans, valve and robot commands).
    place_objects
        Called once when the loop starts waiting for an object (in simulation: put the object
        on the pad); None on real hardware, where a person places it.
    adjusted
        The adjustment the box's owner already made, with the pad empty (a ROS node that keeps
        the pad inflated between grasps): the loop starts at ``wait_object`` with its reference
        instead of inflating again (which would take an object already lying on the pad into
        the reference). None: the loop adjusts first.
    """

    def __init__(
        self,
        box: Box,
        robot: Robot,
        layout: PadLayout | None = None,
        params: ExecutionParams | None = None,
        *,
        planner: Planner | None = None,
        object_detector: ObjectDetector | None = None,
        contact_detector: ContactDetector | None = None,
        recorder: Recorder | None = None,
        place_objects: Callable[[], None] | None = None,
        adjusted: AdjustmentResult | None = None,
    ) -> None:
        self.adjusted = adjusted
        self.layout = layout or PadLayout()
        self.params = p = params or ExecutionParams()
        self.recorder: Recorder = recorder if recorder is not None else _NullRecorder()
        self.planner: Planner = planner or ThesisPlanner(p.planner)
        self.object_detector: ObjectDetector = (
            object_detector
            or planner_detector(self.planner)
            or ThesisObjectDetector(p.planner.object_threshold_pa)
        )
        self.contact_detector: ContactDetector = contact_detector or ThesisContactDetector(
            p.contact_threshold_pa, p.filter_length
        )
        self.place_objects = place_objects
        self.n = self.layout.n_modules
        if self.n > box.channels:
            raise InputError(
                f"a {self.layout.name} pad needs {self.n} channels, the box has {box.channels}"
            )
        self.box = _RecordingBox(box, self.recorder, lambda: self._last_t)
        self.robot = _RecordingRobot(robot, self.recorder, lambda: self._last_t)
        #: The phase the loop is in (:class:`~softpad.control.Phase`, a transition of
        #: :data:`~softpad.control.TRANSITIONS` at a time).
        self.phase = Phase.IDLE
        self._phases: list[tuple[str, float]] = []
        self._last_t = 0.0
        self._landing_rise = np.zeros(self.n)
        self._reference = np.zeros(self.n)
        self._hold_rise: NDArray[np.float64] | None = None
        infl = p.inflation
        #: Fault monitor of every frame and the safe state of this run.
        self.safety = RunSafety(self.box, self.n, infl.max_pressure_pa, infl.trip_margin_pa)

    # --- plumbing -------------------------------------------------------------------
    def _enter(self, phase: Phase, **data: Any) -> None:
        """Go on to ``phase`` (PhaseError for a transition the table does not hold)."""
        self.phase = phase = next_phase(self.phase, phase)
        self.safety.monitor.loads_expected = phase in LOADING_PHASES
        self.safety.monitor.robot_pressing = phase in PRESSING_PHASES
        self._phases.append((phase.value, self._last_t))
        self.recorder.event(self._last_t, "phase", phase=phase.value, **data)

    def _read(self) -> NDArray[np.float64]:
        frame = self.box.read()
        self._last_t = frame.t_s
        self.recorder.frame(frame, self.phase.value)
        return self.safety.watch(frame)

    def _wait_motion(self, what: str) -> None:
        t0 = self._last_t
        while self.robot.is_moving():
            self._read()
            if self._last_t - t0 > self.params.motion_timeout_s:
                raise HardwareFault(
                    f"robot: {what} did not finish within {self.params.motion_timeout_s:g} s"
                )

    def _move(self, pose: ToolPose, speed_m_s: float, what: str) -> None:
        self.robot.move_to(pose, speed_m_s)
        self._wait_motion(what)

    def _gripper(self, width_m: float, speed_m_s: float, what: str) -> None:
        self.robot.set_gripper(width_m, speed_m_s)
        self._wait_motion(what)

    def _mean_reads(self, n: int) -> NDArray[np.float64]:
        return np.mean([self._read() for _ in range(n)], axis=0)

    # --- the loop -------------------------------------------------------------------
    def run(self) -> ExecutionResult:
        """Run the whole loop once; raises HardwareFault (after making the box safe) on a fault."""
        try:
            return self._run()
        except HardwareFault as exc:
            self._make_safe(exc)
            raise
        except KeyboardInterrupt:  # a user's Ctrl-C must not leave valves open
            self.recorder.event(self._last_t, "interrupted", phase=self.phase.value)
            self._make_safe(HardwareFault("interrupted"))
            raise

    def _safe_frame(self, frame: PressureFrame) -> None:
        """Record a frame read on the way to the safe state; valve commands sent then carry
        its time."""
        self._last_t = frame.t_s
        self.recorder.frame(frame, "safe")

    def _make_safe(self, exc: HardwareFault) -> None:
        """Stop the arm (holding what it holds), record the fault, reach the verified safe state."""
        try:
            self.robot.stop()
        except HardwareFault:
            pass  # a robot behind a lost link cannot be stopped from here
        f = self.safety.fail(exc, self._last_t, self._safe_frame)
        self.recorder.event(
            f.t_s,
            "fault",
            message=f.message,
            phase=self.phase.value,
            channel=f.channel,
            cause=f.cause,
        )
        s = self.safety.safe_state
        if s is not None:
            d = s.to_dict()
            del d["t_s"]
            self.recorder.event(s.t_s, "safe_state", **d)

    def _run(self) -> ExecutionResult:
        p = self.params
        adj = self._adjust()
        calibrate = getattr(self.object_detector, "calibrate", None)
        if calibrate is not None and adj.reference_reads_pa is not None:
            calibrate(adj.reference_reads_pa)  # the empty pad's noise sets its threshold
        self.safety.monitor.set_reference(adj.reference_pa)
        self._reference = adj.reference_pa
        if self.adjusted is not None:
            self._read()  # box time now: the phases start from it
        self._enter(Phase.WAIT_OBJECT)
        if self.place_objects is not None:
            self.place_objects()
        seen_at = self._wait_for_object(adj.reference_pa)

        self._enter(Phase.PLAN)
        reads = [self._read() for _ in range(p.planning_reads)]
        delta, plans = plan_from_reads(
            reads, adj.reference_pa, self.object_detector, self.planner, self.layout
        )
        self.recorder.event(
            self._last_t,
            "plan",
            increments_pa=[float(v) for v in delta],
            objects=[pl.to_dict(self.layout) for pl in plans],
        )
        if not plans:
            raise ExecutionError("the object disappeared before planning: no module above t_o")
        grasps = self._grasp_all(plans, delta)
        self._enter(Phase.VALVE_CHECK)
        self.safety.check_valves(self._read)
        self._enter(Phase.DONE)
        faults = tuple(self.safety.faults)
        return ExecutionResult(
            self.layout, adj, seen_at, delta, plans, grasps, tuple(self._phases), faults
        )

    def _adjust(self) -> AdjustmentResult:
        """Inflate and adjust, save the reference; or take the owner's (``adjusted``)."""
        if self.adjusted is not None:
            return self.adjusted
        self._enter(Phase.ADJUST)
        adj = inflate_and_adjust(
            self.box,
            self.n,
            self.params.inflation,
            on_frame=self._on_adjust_frame,
            on_adjusted=self._on_adjusted,
            safe_state=False,
        )
        self.recorder.event(
            adj.reference_at_s, "reference", reference_pa=[float(v) for v in adj.reference_pa]
        )
        return adj

    def _on_adjust_frame(self, frame: PressureFrame) -> None:
        self._last_t = frame.t_s
        self.recorder.frame(frame, self.phase.value)
        self.safety.watch(frame)

    def _on_adjusted(self, t_s: float) -> None:
        self.recorder.event(t_s, "adjusted", target_pa=self.params.inflation.target_pa)
        self._enter(Phase.REFERENCE)

    def _wait_for_object(self, reference: NDArray[np.float64]) -> float:
        """Watch the filtered increments until an object has lain still for the settle time
        (:class:`~softpad.control.ObjectWatch`, which a watching node uses too)."""
        p = self.params
        watch = ObjectWatch(
            reference, self.object_detector, self.layout, p.filter_length, p.object_settle_s
        )
        t0 = self._last_t
        while True:
            state = watch.update(self._read(), self._last_t)
            if state == "settled":
                assert watch.seen_at is not None
                return watch.seen_at
            if state == "seen":
                modules = sorted(k for obj in watch.objects for k in obj)
                self.recorder.event(self._last_t, "object_seen", modules=modules)
            elif watch.seen_at is None and self._last_t - t0 > p.object_wait_s:
                raise ExecutionError(f"no object placed on the pad within {p.object_wait_s:g} s")

    def _grasp_all(
        self, plans: tuple[GraspPlan, ...], delta: NDArray[np.float64]
    ) -> tuple[GraspRecord, ...]:
        """Grasp the planned objects in order, dropping those that went up with a held one
        (``drop_carried``)."""
        drop = self.params.drop_carried
        records: list[GraspRecord] = []
        todo = list(plans)
        while todo:
            record = self._grasp(todo.pop(0), delta)
            if drop and record.outcome == "held" and self._hold_rise is not None:
                loaded = self._loaded_modules(self._hold_rise)
                carried = [pl for pl in todo if not loaded.intersection(pl.modules)]
                todo = [pl for pl in todo if loaded.intersection(pl.modules)]
                if carried:
                    modules = tuple(sorted(k for pl in carried for k in pl.modules))
                    self.recorder.event(self._last_t, "carried", modules=list(modules))
                    record = replace(record, carried_modules=modules)
            records.append(record)
        return tuple(records)

    def _went_up(self, modules: tuple[int, ...]) -> bool:
        """Whether the pad read the object planned on ``modules`` off it during the hold,
        whatever the gripper reports: none of those modules, nor their neighbours (where
        closing jaws may have pushed it), in an object then. A can hanging by the fingertips
        with the jaws closed past the holding margin is put down before the jaws open, not
        dropped from the lift height."""
        if self._hold_rise is None or not modules:
            return False
        near = set(modules).union(*(self.layout.neighbours(m) for m in modules))
        return not self._loaded_modules(self._hold_rise).intersection(near)

    def _loaded_modules(self, increments: NDArray[np.float64]) -> set[int]:
        """Modules of every object the object detector finds in ``increments``."""
        return {k for obj in self.object_detector.objects(increments, self.layout) for k in obj}

    def _grasp(self, plan: GraspPlan, delta: NDArray[np.float64]) -> GraspRecord:
        """Grasp one object (``delta``: the increments it was planned from), retrying after
        a miss on it while the planner has another grasp and attempts are left."""
        p = self.params
        attempt = 1
        while True:
            x, y = plan.cog_m(self.layout)
            above = ToolPose(x, y, p.approach_height_m, plan.theta)
            self._enter(
                Phase.APPROACH, modules=list(plan.modules), cog=list(plan.cog), theta=plan.theta
            )
            self._gripper(1.0, p.travel_speed_m_s, "opening the gripper")  # clamped to the mounting
            self._move(above, p.travel_speed_m_s, "moving over the centre of grasp")
            detected_at = self._descend()
            stop_z = self.robot.state().z_m
            if detected_at is None:
                self._move(above, p.travel_speed_m_s, "retreating")
                outcome = "contact_not_detected"
                break
            landed = self._next_grasp(plan, delta, "landed", stop_z)
            if landed is None:
                outcome = self._close_lift_hold(plan.modules)
                retry = self._retry(plan, delta, outcome, stop_z, attempt)
            else:  # a jaw is on the object: closing would push it (a round one into the pad)
                outcome, retry = "landed", landed if attempt < p.max_attempts else None
                if retry is None:  # no attempt left: up without closing, the grasp failed
                    self.recorder.event(self._last_t, "outcome", outcome=outcome)
                self._move_up()
            if retry is None:
                break
            self.recorder.event(
                self._last_t,
                "retry",
                z_m=stop_z,
                attempt=attempt,
                closed=outcome != "landed",
                cog=list(retry.cog),
                theta=retry.theta,
                rule=retry.rule,
            )
            plan, attempt = retry, attempt + 1
        return GraspRecord(
            plan,
            outcome,
            detected_at is not None,
            self.contact_detector.triggered_modules if detected_at is not None else (),
            detected_at,
            stop_z,
            attempt,
        )

    def _retry(
        self,
        plan: GraspPlan,
        delta: NDArray[np.float64],
        outcome: str,
        stop_z: float,
        attempt: int,
    ) -> GraspPlan | None:
        """The next grasp when the jaws landed on the object (contact sensed above
        ``landing_height_m``) and attempts are left: after closing on nothing (``outcome``
        ``missed``) or, with ``retry_before_close``, before closing (``landed``); None
        otherwise."""
        if attempt >= self.params.max_attempts:
            return None
        return self._next_grasp(plan, delta, outcome, stop_z)

    def _next_grasp(
        self, plan: GraspPlan, delta: NDArray[np.float64], outcome: str, stop_z: float
    ) -> GraspPlan | None:
        """The planner's next grasp after ``outcome`` at a landing on the object, whatever
        the attempts left (:meth:`_retry`'s conditions but the count). At the landing
        (``landed``) a grasp is also the planner's word that a jaw is on the object and
        closing there would push it: on the last attempt the loop then goes up without
        closing (a round object wedged into the pad by a closing jaw drives its chambers to
        the sensor's full scale)."""
        p = self.params
        wanted = ("landed", "missed") if p.retry_before_close else ("missed",)
        if outcome not in wanted or stop_z <= p.landing_height_m:
            return None
        if not isinstance(self.planner, RetryPlanner):
            return None
        closed = outcome != "landed"
        return self.planner.retry(plan, delta, self.layout, self._landing_rise, closed=closed)

    def _descend(self) -> float | None:
        """Lower the fingers until contact is sensed (box time) or the descent ends (None)."""
        p = self.params
        reference = self._mean_reads(p.pre_descent_reads)
        self.contact_detector.reset(reference)
        self._enter(Phase.DESCEND)
        self.robot.descend(p.approach_speed_m_s, p.min_height_m)
        t0 = self._last_t
        while True:
            frame = self._read()
            if self.contact_detector.update(frame):
                self.robot.stop()
                self._landing_rise = measured_change(frame - reference)
                modules = list(self.contact_detector.triggered_modules)
                z = self.robot.state().z_m
                self.recorder.event(self._last_t, "contact", modules=modules, z_m=z)
                return self._last_t
            if not self.robot.is_moving():
                self.recorder.event(self._last_t, "no_contact", z_m=self.robot.state().z_m)
                return None
            if self._last_t - t0 > p.motion_timeout_s:
                raise HardwareFault(
                    f"robot: descent did not finish within {p.motion_timeout_s:g} s"
                )

    def _close_lift_hold(self, modules: tuple[int, ...]) -> str:
        """Close on the object (planned on ``modules``), lift it, hold it, put it down; the
        grasp's outcome."""
        p = self.params
        self._enter(Phase.CLOSE)
        self._gripper(0.0, p.gripper_speed_m_s, "closing the gripper")
        self._enter(Phase.LIFT)
        s = self.robot.state()
        self._move(replace(s.pose, z_m=s.z_m + p.lift_m), p.travel_speed_m_s, "lifting")
        lifted = self.robot.holding()
        self._enter(Phase.HOLD)
        t_hold = self._last_t
        last: deque[NDArray[np.float64]] = deque(maxlen=p.planning_reads)
        while self._last_t - t_hold < p.hold_s:
            last.append(self._read())
        # the pad with the object in the air: which planned objects went up with it
        self._hold_rise = measured_change(np.mean(last, axis=0) - self._reference) if last else None
        held = self.robot.holding()
        outcome = "held" if held else ("dropped" if lifted else "missed")
        self.recorder.event(self._last_t, "outcome", outcome=outcome)
        self._enter(Phase.RELEASE)
        if held or self._went_up(modules):  # put it back where it was grasped, then open
            s = self.robot.state()
            down = replace(s.pose, z_m=s.z_m - p.lift_m)
            self._move(down, p.approach_speed_m_s, "putting the object down")
        self._gripper(1.0, p.travel_speed_m_s, "opening the gripper")
        self._move_up()
        return outcome

    def _move_up(self) -> None:
        """Straight up to the approach height, where the arm is."""
        p, s = self.params, self.robot.state()
        self._move(replace(s.pose, z_m=p.approach_height_m), p.travel_speed_m_s, "moving up")
