"""The grasp-execution state machine on the simulated box (seed, Section 6.2.2)."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import ConnectionLost, SimBox, ValveCommand, open_box, simulator_of
from softpad.control import ExecutionParams, GraspExecution
from softpad.errors import HardwareFault, InputError
from softpad.harness import SimulatedRobot, run_simulated
from softpad.planning import GraspPlan, RetryPlanner
from softpad.record import RunLog
from softpad.sim import AnalyticWorld, SimGripper, get_object

FAST = ExecutionParams(hold_s=1.0)


def test_full_loop_on_object_5() -> None:
    """Object 5 (a Duplo plate along the top row, a brick stack one stud left of its middle):
    seen on the top row, planned on the row's axis left of its middle (towards the heavier
    part, short of the stack at x = 1.14) with the jaws across the row, and held."""
    log = RunLog()
    r = run_simulated(["object-5"], "sim://?seed=11", FAST, log)
    d = r.to_dict()
    assert d["outcome"] == "held" and d["contact_detected"] is True
    assert [o["modules"] for o in d["objects"]] == [[1, 2, 3]]
    x, y = d["objects"][0]["cog"]
    assert 1.14 < x < 1.5 and y == 1.5
    np.testing.assert_allclose(d["objects"][0]["theta"], np.pi / 2, atol=1e-9)
    # delay from first touch to detection, and the travel it implies at 0.05 m/s
    assert 0.0 < d["contact_delay_s"] < 0.3
    np.testing.assert_allclose(d["finger_travel_m"], 0.05 * d["contact_delay_s"], atol=0.51e-3)
    phases = [p for p, _ in r.result.phases]
    assert phases == [
        "adjust",
        "reference",
        "wait_object",
        "plan",
        "approach",
        "descend",
        "close",
        "lift",
        "hold",
        "release",
        "valve_check",
        "done",
    ]
    kinds = [k for _, k, _ in log.events]
    for k in ("adjusted", "reference", "object_seen", "plan", "contact", "outcome"):
        assert k in kinds
    # the detector's reference is the pre-descent pressure: the object's own increment does
    # not trigger it, only the fingers do
    t_contact = log.events_of("contact")[0][0]
    t_descend = next(t for t, k, d in log.events if k == "phase" and d["phase"] == "descend")
    assert t_contact - t_descend > 0.5


def test_two_separate_objects_are_grasped_one_after_the_other() -> None:
    # seed 4: the second object's fingertip touch is marginal on some seeds (seeds 6 and 8 miss it
    # before and after the exact gas integrator, seed 5 after it); this test is about the order.
    # The clamped modules: on the cast pad (issue 45) the 6/2 jaws' tips land near object 4's
    # module borders, where the cast layer's response is 10-20 % lower, and the second touch is
    # missed on 8 of seeds 0-9 (held on 3 and 7): a prediction of the cast pad, not of the order
    r = run_simulated(["object-1", "object-4"], "sim://?seed=4&pad=clamped", FAST, gripper="6/2")
    assert [p.modules for p in r.result.plans] == [(1, 4), (3, 6)]
    assert [g.outcome for g in r.result.grasps] == ["held", "held"]
    assert r.result.grasps[0].detected_at_s < r.result.grasps[1].detected_at_s


def test_fingertips_on_the_lines_are_not_detected() -> None:
    """Tips centred on the 2|5 line and on the pad's border: no module senses them (Sec. 6.3)."""
    g = SimGripper(max_width_m=0.043, min_width_m=0.0, tip_thickness_m=0.002, tip_width_m=0.002)
    world = AnalyticWorld(gripper=g)
    box = SimBox(world, seed=4)
    loop = GraspExecution(
        box,
        SimulatedRobot(world),
        world.layout,
        FAST,
        place_objects=lambda: world.place_object(get_object("object-3")),
    )
    r = loop.run()
    assert r.plans[0].modules == (1, 2, 3)
    assert r.grasps[0].outcome == "contact_not_detected"
    assert not r.contact_detected and r.outcome == "contact_not_detected"


@pytest.mark.parametrize(
    ("fault", "exc", "match"),
    [
        ("nan:2@8.0", HardwareFault, "channel 2.*NaN"),
        ("dropout:5@8.0", HardwareFault, "channel 5.*dropout"),
        ("disconnect@8.0", ConnectionLost, "stopped answering"),
    ],
    ids=["nan", "dropout", "disconnect"],
)
def test_fault_during_the_loop_is_logged_and_leaves_the_box_safe(
    fault: str, exc: type, match: str
) -> None:
    log = RunLog()
    box = open_box(f"sim://?seed=2&faults={fault}")
    with pytest.raises(exc, match=match):
        run_simulated(["banana"], box, FAST, log)
    assert log.events_of("fault")
    assert len(log) > 500 and log.t_s[-1] >= 7.99  # nothing logged before the fault is lost
    if exc is not ConnectionLost:
        assert all(v is not ValveCommand.INFLATE for v in box.valves)
        assert box.true_pressures_pa.max() <= 3000.0


def test_overpressure_from_a_stuck_valve_during_the_run_is_vented() -> None:
    """Inflation valve of channel 1 stuck open mid-run: fault naming it, vented below max."""
    log = RunLog()
    box = open_box("sim://?seed=2&faults=stuck:1:inflate@6.0")
    with pytest.raises(
        HardwareFault,
        match=r"channel 1: rising \d+ Pa/s with its inflation valve closed",
    ):
        run_simulated(["banana"], box, ExecutionParams(hold_s=30.0), log)
    assert box.true_pressures_pa[:6].max() <= 3000.0
    assert box.valves[0] is ValveCommand.DEFLATE  # venting against the stuck valve
    assert all(v is ValveCommand.CLOSED for v in box.valves[1:])


def test_no_object_times_out() -> None:
    from softpad.control import ExecutionError

    world = AnalyticWorld()
    box = SimBox(world, seed=1)
    loop = GraspExecution(
        box, SimulatedRobot(world), world.layout, ExecutionParams(object_wait_s=2.0)
    )
    with pytest.raises(ExecutionError, match="no object"):
        loop.run()


def test_an_object_being_placed_is_a_load_the_monitor_expects() -> None:
    """While the loop waits for an object, a sealed module rising is what it waits for: the
    fault monitor does not call it a stuck inflation valve (a 122 g object settling into the
    pad rose 258 Pa/s for 1.5 s in a simulated trial and was); before, it does."""
    from softpad.control import ExecutionError

    expected: dict[str, set[bool]] = {}

    class Watch:
        def frame(self, frame: object, phase: str) -> None:
            expected.setdefault(phase, set()).add(loop.safety.monitor.loads_expected)

        def event(self, t_s: float, kind: str, **data: object) -> None:
            pass

    world = AnalyticWorld()
    box = SimBox(world, seed=1)
    params = ExecutionParams(object_wait_s=1.0)
    loop = GraspExecution(box, SimulatedRobot(world), world.layout, params, recorder=Watch())
    with pytest.raises(ExecutionError, match="no object"):
        loop.run()
    assert expected["wait_object"] == {True}
    assert expected["adjust"] == {False}


def test_unknown_object_and_bad_params() -> None:
    with pytest.raises(InputError, match="unknown object 'teapot'"):
        run_simulated(["teapot"])
    with pytest.raises(InputError, match="approach_speed_m_s"):
        ExecutionParams(approach_speed_m_s=0.0)


def test_same_seed_same_run() -> None:
    a = run_simulated(["object-2"], "sim://?seed=21", FAST).to_dict()
    b = run_simulated(["object-2"], "sim://?seed=21", FAST).to_dict()
    assert a == b


def test_contact_delay_is_consistent_with_the_frames() -> None:
    """The detection comes a whole number of sample periods after the first touch."""
    r = run_simulated(["object-3"], "sim://?seed=8&rate_hz=200", FAST)
    delay = r.contact_delay_s()
    assert delay is not None and r.touches[0].first_touch_s is not None
    np.testing.assert_allclose(delay * 200, round(delay * 200), atol=1e-6)
    # at least half the running-average window (10 samples) passes before detection
    assert delay >= 4.5 / 200


def test_interrupt_closes_the_valves() -> None:
    """Ctrl-C while inflating: the box is put in its safe state before the interrupt propagates."""
    log = RunLog()
    box = SimBox(seed=1)
    world = box.world

    class Interrupting(RunLog):
        def frame(self, frame, phase):  # type: ignore[no-untyped-def]
            log.frame(frame, phase)
            if frame.t_s > 1.0 and phase == "adjust":
                raise KeyboardInterrupt

    loop = GraspExecution(box, SimulatedRobot(world), world.layout, FAST, recorder=Interrupting())
    with pytest.raises(KeyboardInterrupt):
        loop.run()
    assert set(box.valves) == {ValveCommand.CLOSED}
    assert "safe" in log.phases


def test_a_held_object_is_put_down_before_the_jaws_open() -> None:
    """After the hold the object goes back down by the lift height at the approach speed, then
    the jaws open (a dropped object hits the pad: a full-scale reading and a disturbed valve
    check after the outcome)."""
    log = RunLog()
    r = run_simulated(["object-5"], "sim://?seed=11", FAST, log)
    assert r.to_dict()["outcome"] == "held"
    events = [(t, k, d) for t, k, d in log.events if k in ("phase", "robot")]
    phase_at = {d["phase"]: i for i, (_, k, d) in enumerate(events) if k == "phase"}
    lift = next(d for _, k, d in events[phase_at["lift"] :] if k == "robot")
    release = [
        d for _, k, d in events[phase_at["release"] : phase_at["valve_check"]] if k == "robot"
    ]
    assert release[0]["command"] == "move_to"
    assert release[0]["z_m"] == pytest.approx(lift["z_m"] - FAST.lift_m, abs=1e-9)
    assert release[0]["speed_m_s"] == FAST.approach_speed_m_s
    assert release[1] == {
        "command": "set_gripper",
        "width_m": 1.0,
        "speed_m_s": FAST.travel_speed_m_s,
    }


class _GripperSaysEmpty(SimulatedRobot):
    """The simulated arm whose gripper always reports nothing held (jaws closed past the
    holding margin on a can held by the fingertips), whatever the world carries."""

    def holding(self) -> bool:
        return False


def _release_commands(log: RunLog) -> list[dict]:  # type: ignore[type-arg]
    events = [(t, k, d) for t, k, d in log.events if k in ("phase", "robot")]
    phase_at = {d["phase"]: i for i, (_, k, d) in enumerate(events) if k == "phase"}
    return [d for _, k, d in events[phase_at["release"] : phase_at["valve_check"]] if k == "robot"]


def test_an_object_the_pad_reads_in_the_air_is_put_down_whatever_the_gripper_says() -> None:
    """The gripper reports nothing held but the world lifted the object: the pad, which read
    the object's modules empty during the hold, has the loop put it down before the jaws open
    (the outcome stays the gripper's). Before, the jaws opened at the lift height and the
    object fell (a can read 4.7-10 kPa)."""
    box = open_box("sim://?seed=11")
    try:
        log = RunLog()
        robot = _GripperSaysEmpty(simulator_of(box).world)
        r = run_simulated(["object-5"], box, FAST, log, robot=robot)
    finally:
        box.close()
    assert r.to_dict()["outcome"] == "missed"
    release = _release_commands(log)
    assert release[0]["command"] == "move_to"
    assert release[0]["speed_m_s"] == FAST.approach_speed_m_s
    assert release[1]["command"] == "set_gripper" and release[1]["width_m"] == 1.0


def test_a_miss_with_the_object_still_on_the_pad_opens_where_it_is() -> None:
    """Jaws closed beside the object: the pad still reads it, so the jaws open where they
    are (nothing to put down)."""
    log = RunLog()
    plan = GraspPlan((1, 2, 3), (1.5, 1.5), (0.5, 0.5), 0.0, "beside the object", (1, 2, 3))
    r = run_simulated(["object-5"], "sim://?seed=11", FAST, log, planner=_FixedPlanner(plan))
    assert r.to_dict()["outcome"] == "missed"
    assert _release_commands(log)[0]["command"] == "set_gripper"


class _FixedPlanner:
    """Plans the one grasp it was given."""

    def __init__(self, plan: GraspPlan) -> None:
        self.fixed = plan

    def plan(self, increments_pa, objects, layout):  # type: ignore[no-untyped-def]
        return [self.fixed]


class _CountingRetryPlanner:
    """A planner with a retry that counts its calls (a RetryPlanner)."""

    def __init__(self) -> None:
        self.calls = 0
        self.closed: list[bool] = []
        self.turned = GraspPlan((1, 2, 4, 5), (1.0, 1.0), (1.0, 1.0), np.pi / 2, "turned", ())

    def plan(self, increments_pa, objects, layout):  # type: ignore[no-untyped-def]
        return []

    def retry(self, plan, increments_pa, layout, landing_rise_pa, closed=True):  # type: ignore[no-untyped-def]
        self.calls += 1
        self.closed.append(closed)
        return self.turned


def test_only_a_miss_after_landing_on_the_object_asks_the_planner_again() -> None:
    """The loop asks for a retry when the fingers were sensed above ``landing_height_m``
    (17 mm: on the object, not on the ~9 mm pad), at the landing (``landed``, the planner
    told the jaws have not closed) and after the jaws closed on nothing (``missed``), while
    attempts are left, and only with a planner that has a retry (not the thesis's)."""
    world = AnalyticWorld()
    planner = _CountingRetryPlanner()
    first = GraspPlan((1, 2, 4, 5), (1.0, 1.0), (1.0, 1.0), 0.0, "square", ())
    loop = GraspExecution(SimBox(world), SimulatedRobot(world), planner=planner)
    assert isinstance(planner, RetryPlanner)
    assert loop.params.landing_height_m == pytest.approx(0.017)
    assert loop._retry(first, np.zeros(6), "missed", 0.049, 1) is planner.turned
    assert loop._retry(first, np.zeros(6), "landed", 0.049, 1) is planner.turned  # not closed
    assert planner.closed == [True, False]
    assert loop._retry(first, np.zeros(6), "missed", 0.0075, 1) is None  # fingers on the pad
    assert loop._retry(first, np.zeros(6), "landed", 0.0075, 1) is None
    assert loop._retry(first, np.zeros(6), "held", 0.049, 1) is None
    assert loop._retry(first, np.zeros(6), "dropped", 0.049, 1) is None
    assert loop._retry(first, np.zeros(6), "missed", 0.049, 2) is None  # max_attempts (2) used
    assert loop._retry(first, np.zeros(6), "landed", 0.049, 2) is None
    assert planner.calls == 2
    # the planner's word at a landing, whatever the attempts left: on the last attempt the
    # loop goes up without closing where it is given (tests/control/test_retry_landing.py)
    assert loop._next_grasp(first, np.zeros(6), "landed", 0.049) is planner.turned
    assert loop._next_grasp(first, np.zeros(6), "landed", 0.0075) is None
    assert planner.calls == 3
    thesis = GraspExecution(SimBox(world), SimulatedRobot(world))
    assert thesis._retry(first, np.zeros(6), "missed", 0.049, 1) is None
    assert thesis._retry(first, np.zeros(6), "landed", 0.049, 1) is None
    # without retry_before_close the planner is asked only after closing on nothing
    late = ExecutionParams(retry_before_close=False)
    after = GraspExecution(SimBox(world), SimulatedRobot(world), params=late, planner=planner)
    assert after._retry(first, np.zeros(6), "landed", 0.049, 1) is None
    assert after._retry(first, np.zeros(6), "missed", 0.049, 1) is planner.turned
    assert planner.calls == 4


def test_a_bad_attempt_count_is_named() -> None:
    with pytest.raises(InputError, match="max_attempts"):
        ExecutionParams(max_attempts=0)


class _SplittingPlanner:
    """The thesis's plans plus a second plan on the first object's last module, as if the
    pad had shown that object as two (a RetryPlanner without retries)."""

    def plan(self, increments_pa, objects, layout):  # type: ignore[no-untyped-def]
        from softpad.planning import ThesisPlanner

        plans = ThesisPlanner().plan(increments_pa, objects, layout)
        k = plans[0].modules[-1]
        centre = tuple(float(v) for v in layout.centers[k - 1])
        ghost = GraspPlan((k,), centre, centre, 0.0, "ghost", (k,))
        return [plans[0], ghost, *plans[1:]]

    def retry(self, plan, increments_pa, layout, landing_rise_pa, closed=True):  # type: ignore[no-untyped-def]
        return None


def _split_run(objects: list[str], params: ExecutionParams, planner: object):  # type: ignore[no-untyped-def]
    log = RunLog()
    # seed 4: see test_two_separate_objects_are_grasped_one_after_the_other
    r = run_simulated(
        objects, "sim://?seed=4&pad=clamped", params, log, gripper="6/2", planner=planner
    )
    return r.result, log


def test_an_object_that_went_up_with_a_held_one_is_not_grasped_again() -> None:
    """Object 1 planned as two objects (its own plan and one on module 6): the first grasp
    holds it, module 6 unloads during the hold, so the second plan is dropped (one grasp,
    a ``carried`` event). The loop before (``drop_carried`` off) grasps both; a second real
    object (object 4, on modules 1 and 4, grasped first) still loaded during the hold of
    the first is grasped, its ghost too (module 4 loaded), object 1 after them."""
    r, log = _split_run(["object-1"], FAST, _SplittingPlanner())
    assert [p.modules for p in r.plans] == [(3, 6), (6,)]
    assert [g.outcome for g in r.grasps] == ["held"]
    assert r.grasps[0].carried_modules == (6,)
    assert [d["modules"] for _, d in log.events_of("carried")] == [[6]]
    assert r.to_dict()["grasps"][0]["carried_modules"] == [6]
    r, log = _split_run(
        ["object-1"], ExecutionParams(hold_s=1.0, drop_carried=False), _SplittingPlanner()
    )
    assert len(r.grasps) == 2 and r.grasps[0].carried_modules == ()
    assert log.events_of("carried") == []
    r, log = _split_run(["object-1", "object-4"], FAST, _SplittingPlanner())
    assert [p.modules for p in r.plans] == [(1, 4), (4,), (3, 6)]
    assert [g.plan.modules for g in r.grasps] == [(1, 4), (3, 6)]
    assert [g.outcome for g in r.grasps] == ["held", "held"]


def test_carried_objects_are_dropped_for_every_planner() -> None:
    """A loop feature, the same for a planner without a retry (the thesis's kind): the carried
    ghost plan is not grasped (before issue 33 it was, so the thesis pair could hold a banana
    on its first grasp and lose the run on its second); ``drop_carried=False`` grasps every
    planned object, as the thesis does."""

    class Plain(_SplittingPlanner):
        retry = None  # type: ignore[assignment]

    assert not isinstance(Plain(), RetryPlanner)
    r, _ = _split_run(["object-1"], FAST, Plain())
    assert [g.outcome for g in r.grasps] == ["held"] and r.grasps[0].carried_modules == (6,)
    r, _ = _split_run(["object-1"], ExecutionParams(hold_s=1.0, drop_carried=False), Plain())
    assert len(r.grasps) == 2


def test_a_tentative_grasp_that_missed_does_not_count_in_the_outcome() -> None:
    """A tentative grasp (two ends taken as one object) that missed, then both ends held: the
    run held. A tentative grasp that held counts; a plain miss still fails the run."""
    from softpad.control import GraspRecord
    from softpad.control._execution import ExecutionResult

    bridge = GraspPlan((3, 4), (1.5, 1.0), (1.5, 1.0), 0.0, "bridge-pair", (3, 4), tentative=True)
    end = GraspPlan((3,), (2.5, 1.5), (2.5, 1.5), 0.0, "n1", (3,))

    def run(*grasps: GraspRecord) -> str:
        plans = tuple(g.plan for g in grasps)
        return ExecutionResult(None, None, 0.0, np.zeros(6), plans, grasps, ()).outcome  # type: ignore[arg-type]

    def rec(plan: GraspPlan, outcome: str) -> GraspRecord:
        return GraspRecord(plan, outcome, True)

    assert run(rec(bridge, "missed"), rec(end, "held"), rec(end, "held")) == "held"
    assert run(rec(bridge, "held")) == "held"
    assert run(rec(bridge, "missed"), rec(end, "held"), rec(end, "dropped")) == "dropped"
    assert run(rec(end, "missed"), rec(end, "held")) == "missed"


def test_a_quiet_pad_measured_under_a_pascal_is_no_change() -> None:
    """Averages of reads minus an averaged reference can land under a pascal on every module
    on a quiet pad (the compared seeds hit it once in 2200 trials). The loop takes that for
    no change; before, the object detector took it for kPa given as pascals and the run
    stopped with an input error. Here every read after the reference is 0.4 Pa high (an
    ideal sensor): waiting for the object, the empty pad reads 0.4 Pa everywhere, and so does
    the pad during the hold with the object in the air; the run holds object 5, its ghost
    plan dropped as carried."""
    from dataclasses import replace as dc_replace

    from softpad.box import BoxWrapper, PressureFrame
    from softpad.control import GraspExecution as Loop
    from softpad.harness import SimulatedRobot as Robot

    class Offset(BoxWrapper):
        offset_pa = 0.0

        def _read(self) -> PressureFrame:
            f = self.inner.read()
            return dc_replace(f, pressures_pa=f.pressures_pa + self.offset_pa)

    class Shift(RunLog):
        def event(self, t_s: float, kind: str, **data: object) -> None:
            super().event(t_s, kind, **data)
            if kind == "phase" and data.get("phase") == "wait_object":
                box.offset_pa = 0.4

    inner = open_box("sim://?seed=5&noise=0")
    box = Offset(inner)
    assert simulator_of(inner) is not None
    world = inner.world
    assert isinstance(world, AnalyticWorld)
    world.gripper = SimGripper.mounting(get_object("object-5").gripper)
    log = Shift()
    loop = Loop(
        box,
        Robot(world),
        world.layout,
        FAST,
        recorder=log,
        place_objects=lambda: world.place_object(get_object("object-5")),
        planner=_SplittingPlanner(),
    )
    try:
        r = loop.run()
    finally:
        box.close()
    assert [p.modules for p in r.plans] == [(1, 2, 3), (3,)]
    assert [g.outcome for g in r.grasps] == ["held"]
    assert r.grasps[0].carried_modules == (3,)


def test_a_given_adjustment_grasps_the_object_already_on_the_pad() -> None:
    """``adjusted``: the box's owner (the ROS node) adjusted the empty pad before the object
    was put down; the loop takes that reference, starts at ``wait_object`` and grasps object 5
    with the plan of the full loop. Adjusting again instead takes the object into the
    reference: no object is ever seen."""
    from softpad.control import inflate_and_adjust

    full = run_simulated(["object-5"], "sim://?seed=11", FAST).result
    world = AnalyticWorld(gripper=SimGripper.mounting(get_object("object-5").gripper))
    box = SimBox(world, seed=11)
    adj = inflate_and_adjust(box, world.layout.n_modules)
    world.place_object(get_object("object-5"))
    log = RunLog()
    loop = GraspExecution(
        box, SimulatedRobot(world), world.layout, FAST, recorder=log, adjusted=adj
    )
    r = loop.run()
    assert r.outcome == "held" and r.adjustment is adj
    assert [p for p, _ in r.phases][:3] == ["wait_object", "plan", "approach"]
    assert r.phases[0][1] > adj.reference_at_s  # phases on the box clock, after the reference
    assert [(p.modules, p.rule) for p in r.plans] == [(p.modules, p.rule) for p in full.plans]
    np.testing.assert_allclose(r.plans[0].cog, full.plans[0].cog, atol=0.05)
    assert "adjusted" not in [k for _, k, _ in log.events]
    again = GraspExecution(box, SimulatedRobot(world), world.layout, ExecutionParams(
        hold_s=1.0, object_wait_s=2.0))  # fmt: skip
    from softpad.control import ExecutionError

    with pytest.raises(ExecutionError, match="no object"):
        again.run()


def test_robot_wrapper_forwards_every_call_of_the_protocol() -> None:
    """Each method of :class:`softpad.control.Robot` reaches the wrapped robot with its
    arguments, and its answer comes back unchanged."""
    import inspect

    from softpad.control import Robot, RobotState, RobotWrapper, ToolPose

    state = RobotState(0.01, 0.02, 0.03, 0.4, 0.05)
    answers = {"is_moving": True, "state": state, "holding": False}
    calls: list[tuple[str, tuple[object, ...]]] = []

    class _Inner:
        def __getattr__(self, name: str):
            def call(*args: object) -> object:
                calls.append((name, args))
                return answers.get(name)

            return call

    wrapper = RobotWrapper(_Inner())  # type: ignore[arg-type]
    assert isinstance(wrapper, Robot)
    pose = ToolPose(0.1, 0.2, 0.3, 0.5)
    args = {"move_to": (pose, 0.2), "descend": (0.05, 0.01), "set_gripper": (0.06, 0.1)}
    names = [n for n, _ in inspect.getmembers(Robot, inspect.isfunction) if not n.startswith("_")]
    assert sorted(names) == sorted([*args, "stop", *answers])
    for name in names:
        assert getattr(wrapper, name)(*args.get(name, ())) == answers.get(name)
        assert calls[-1] == (name, args.get(name, ()))
    assert len(calls) == len(names)
