"""``softpad ros node``: the pad as a ROS 1 node (rospy). Translation only.

The node owns the box (the one controller): it inflates and adjusts every module
(:func:`softpad.control.inflate_and_adjust`), keeps the reference, reads every frame and
publishes it, and plans on the filtered increments once the objects on the pad have settled
(and on request). Its ``~grasp`` service runs the loop of ``softpad run``
(:func:`softpad.harness.build_loop`) once on that box from that reference with the ``robot`` of its config, and
publishes what the loop does as it runs (:class:`softpad.ros._publish.LoopPublisher`). Its parts
are the registered ones ``softpad run`` uses, by name (``planner``, ``detector``: the object
detector, planner and contact detector of :mod:`softpad.sensing` and :mod:`softpad.planning`'s
registries, made for the box's rate and the pad; :func:`softpad.harness.build_loop` for a
grasp). Topics, services and parameters: docs/ros.md.
"""

from __future__ import annotations

import json
import math
import queue
import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import HardwareFault, InputError
from softpad.layout import PadLayout, PadPose

#: Keys of the installation file and ROS parameters (``~name``) of the node.
CONFIG_KEYS = (
    "box", "layout", "pitch_m", "pad_x_m", "pad_y_m", "pad_z_m", "pad_yaw_rad", "base_frame",
    "object_threshold_pa", "contact_threshold_pa", "settle_s", "place", "place_after_s",
    "ambient_pressure_pa", "planner", "detector", "robot", "gripper", "hold_s",
)  # fmt: skip


@dataclass(frozen=True)
class NodeConfig:
    """Installation of the pad node (JSON file, then ROS parameters override it).

    Parameters
    ----------
    box
        Box URL (``sim://``, ``zenoh://127.0.0.1:PORT``, ...).
    layout
        Pad layout ``RxC``.
    pitch_m
        Module pitch, metres (the installation's ``pad.pitch_mm``; thesis 45 mm).
    pad
        Pose of the pad frame in the robot base frame (static transform ``base_frame`` ->
        ``softpad``).
    base_frame
        Name of the robot's base frame.
    object_threshold_pa, contact_threshold_pa
        t_o and t_g, pascals (thesis: 50 and 90).
    settle_s
        An object is planned after it has lain still this long, seconds (the grasp loop's
        ``object_settle_s``, which the node's grasps use too; default the loop's, 1 s).
    place
        Simulation only: catalogue objects put on a ``sim://`` box ``place_after_s`` after the
        reference (for demonstrations and tests; a person places them on a real pad).
    ambient_pressure_pa
        Added to the gauge readings in ``sensor_msgs/FluidPressure`` (absolute), Pa (default
        the standard atmosphere, 101325 Pa).
    planner, detector
        The planner and contact detector by name (:func:`softpad.planning.available_planners`,
        :func:`softpad.sensing.available_contact_detectors`), as ``softpad run --planner
        --detector``.
    robot
        URL of the arm the ``~grasp`` service drives (:data:`softpad.control.ROBOT_REGISTRY`:
        ``sim://`` on a ``sim://`` box, ``ros1://`` for an arm node); empty: no grasps.
    gripper
        Gripper mounting (``10/4``, ``6/2``, ``4/0``); empty: the first ``place`` object's
        catalogue mounting, else ``10/4``.
    hold_s
        Hold time of a grasp, seconds (thesis: 15).
    """

    box: str = "sim://"
    layout: str = "2x3"
    pitch_m: float = thesis.MODULE_PITCH_M
    pad: PadPose = field(default_factory=PadPose)
    base_frame: str = "base"
    object_threshold_pa: float = thesis.OBJECT_THRESHOLD_PA
    contact_threshold_pa: float = thesis.CONTACT_THRESHOLD_PA
    settle_s: float = 1.0
    place: tuple[str, ...] = ()
    place_after_s: float = 1.0
    ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA
    planner: str = "thesis"
    detector: str = "thesis"
    robot: str = ""
    gripper: str = ""
    hold_s: float = thesis.HOLD_S

    def updated(self, values: dict[str, Any]) -> NodeConfig:
        """This config with ``values`` (keys of :data:`CONFIG_KEYS`) applied, checked."""
        unknown = sorted(set(values) - set(CONFIG_KEYS))
        if unknown:
            raise InputError(
                f"unknown node setting {unknown[0]!r}; known: {', '.join(CONFIG_KEYS)}"
            )
        pad = {k[4:]: _finite(k, values[k]) for k in values if k.startswith("pad_")}
        out = replace(self, pad=replace(self.pad, **pad))
        for k in (
            "object_threshold_pa", "contact_threshold_pa", "settle_s", "place_after_s",
            "ambient_pressure_pa", "hold_s", "pitch_m",
        ):  # fmt: skip
            if k in values:
                v = _finite(k, values[k])
                if v < 0:
                    raise InputError(f"{k} must be >= 0, got {v!r}")
                out = replace(out, **{k: v})  # type: ignore[arg-type]
        for k in ("box", "layout", "base_frame", "planner", "detector", "robot", "gripper"):
            if k in values:
                out = replace(out, **{k: str(values[k])})  # type: ignore[arg-type]
        _check_parts(out)
        if "place" in values:
            names = values["place"]
            names = names.split(",") if isinstance(names, str) else names
            out = replace(out, place=tuple(str(n) for n in names if n))
        return out


def _check_parts(config: NodeConfig) -> None:
    """The planner, detector and robot are registered ones, the gripper a mounting
    (InputError naming the known ones)."""
    from softpad.control import ROBOT_REGISTRY
    from softpad.layout import GripperSpec
    from softpad.planning import PLANNER_REGISTRY
    from softpad.sensing import CONTACT_DETECTOR_REGISTRY

    PLANNER_REGISTRY.factory(config.planner)
    CONTACT_DETECTOR_REGISTRY.factory(config.detector)
    if config.robot:
        scheme, sep, _ = config.robot.partition("://")
        if not sep:
            raise InputError(f"robot must be a URL such as sim:// or ros1://, got {config.robot!r}")
        ROBOT_REGISTRY.summary(scheme.lower())  # InputError naming the registered robots
    if config.gripper:
        GripperSpec.from_mounting(config.gripper)


def _finite(key: str, v: object) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"{key} must be a finite number, got {v!r}")
    return float(v)


def load_config(path: str | Path | None) -> NodeConfig:
    """Read a node installation file (JSON object of :data:`CONFIG_KEYS`); defaults when None."""
    if path is None:
        return NodeConfig()
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as exc:
        raise InputError(f"cannot read node config {str(path)!r}: {exc}") from None
    if not isinstance(data, dict):
        raise InputError(f"node config {str(path)!r} must hold a JSON object")
    return NodeConfig().updated(data)


@dataclass
class _Request:
    """A service call or action goal handed to the node's loop (the box is used from one
    thread only)."""

    name: str
    done: threading.Event = field(default_factory=threading.Event)
    ok: bool = False
    message: str = ""
    #: A grasp's hold time, s (None: the config's ``hold_s``).
    hold_s: float | None = None
    #: A grasp's phases as they come, with their box time (the action's feedback).
    on_phase: Callable[[str, float], None] | None = None
    #: Whether the grasp is to stop (the action's cancel).
    cancel_requested: Callable[[], bool] | None = None
    #: The grasp loop's result (``softpad run --json``'s object) once it ran.
    result: dict[str, Any] | None = None
    cancelled: bool = False


class PadNode:
    """The ROS 1 node of one pad (see the module docstring and docs/ros.md).

    Parameters
    ----------
    config
        Installation; ROS parameters of the node's private namespace override it.
    name
        ROS node name.
    """

    #: True after a cancelled grasp: the box stays in its safe state, the watch paused, until
    #: ``~inflate`` adjusts the pad again.
    safe_hold = False

    def __init__(self, config: NodeConfig, name: str = "softpad") -> None:
        from softpad.ros._publish import LoopPublisher, PadPublishers
        from softpad.ros._rospy_path import require_master

        self.rospy = require_master()
        self.rospy.init_node(name, disable_signals=True)
        params = {
            k: self.rospy.get_param("~" + k) for k in CONFIG_KEYS if self.rospy.has_param("~" + k)
        }
        self.config = config.updated(params)
        from softpad.layout import parse_layout

        self.layout: PadLayout = parse_layout(self.config.layout, self.config.pitch_m)
        self.n = self.layout.n_modules
        self._requests: queue.Queue[_Request] = queue.Queue()
        self.pubs = PadPublishers(
            self.rospy, self.layout, self.config.box, self.config.ambient_pressure_pa
        )
        #: Publishes the grasp loops the ``~grasp`` service runs.
        self.loop_publisher = LoopPublisher(self.pubs)
        self._make_services()
        self._make_action()
        self.safe_hold = False
        self.reference_pa: NDArray[np.float64] | None = None
        self.plans: list[Any] = []

    def _make_services(self) -> None:
        from std_srvs.srv import Trigger, TriggerResponse

        def handler(name: str, timeout_s: float) -> Callable[[Any], Any]:
            def call(_req: Any) -> Any:
                r = _Request(name)
                self._requests.put(r)
                if not r.done.wait(timeout_s):
                    return TriggerResponse(
                        False, f"{name}: the node did not answer in {timeout_s:g} s"
                    )
                return TriggerResponse(r.ok, r.message)

            return call

        # a grasp waits for an object (30 s), moves, holds (hold_s): its own bound
        grasp_s = 600.0 + self.config.hold_s
        self.services = [
            self.rospy.Service("~" + n, Trigger, handler(n, grasp_s if n == "grasp" else 60.0))
            for n in ("inflate", "capture_reference", "plan", "grasp")
        ]

    def _make_action(self) -> None:
        """The grasp action ``~grasp`` (``softpad_msgs/GraspAction``, actionlib): the loop of
        the ``~grasp`` service with its phases as feedback, its outcome and plans as the
        result, and a cancel that ends in the box's safe state."""
        import actionlib

        from softpad.ros._msgs import ensure_messages

        self.msgs = ensure_messages()
        self.action = actionlib.SimpleActionServer(
            "~grasp", self.msgs.GraspAction, execute_cb=self._execute_goal, auto_start=False
        )
        self.action.start()

    def _execute_goal(self, goal: Any) -> None:
        """Run one goal of the grasp action through the node's loop (actionlib's thread)."""
        from softpad.ros import _messages as m

        action, msgs = self.action, self.msgs
        r = _Request(
            "grasp", hold_s=goal.hold_s if goal.hold_s > 0 else None,
            on_phase=lambda phase, t: action.publish_feedback(msgs.GraspFeedback(phase, t)),
            cancel_requested=action.is_preempt_requested,
        )  # fmt: skip
        self._requests.put(r)
        while not r.done.wait(0.5):
            if self.rospy.is_shutdown():
                action.set_aborted(text="the node shut down")
                return
        result = msgs.GraspResult(message="" if r.ok and not r.cancelled else r.message)
        if r.result is not None:
            result.outcome = str(r.result["outcome"])
            result.grasps = m.pose_array(self.rospy.Time.now(), m.grasp_poses(r.result["objects"]))
            result.result_json = json.dumps(r.result)
        if r.cancelled:
            result.outcome = "canceled"
            action.set_preempted(result, r.message)
        elif r.ok:
            action.set_succeeded(result, result.outcome)
        else:
            result.outcome = result.outcome or "error"
            action.set_aborted(result, r.message)

    # --- the loop -------------------------------------------------------------------------
    def run(self, max_frames: int | None = None) -> None:
        """Open the box, adjust, then publish every frame until ROS shuts down.

        On a hardware fault the diagnostics say ERROR, the box is made safe and the fault
        propagates (the command exits non-zero). However it ends, ROS is shut down in this
        process (actionlib's goal thread is not a daemon: it would keep the process alive).
        """
        from softpad.box import open_box
        from softpad.control import DEFAULT_MAX_PRESSURE_PA, make_safe

        self.pubs.static_frames(self.config.pad, self.config.base_frame)
        try:
            with open_box(self.config.box) as box:
                self.box = self.pubs.box = box
                try:
                    self._make_parts()
                    self._adjust()
                    self._place_later()
                    self._loop(max_frames)
                except HardwareFault as exc:
                    self.pubs.fault = str(exc)
                    self.pubs.diagnostics()
                    make_safe(box, self.n, DEFAULT_MAX_PRESSURE_PA)
                    raise
        finally:
            self.rospy.signal_shutdown("softpad ros node ended")

    def _make_parts(self) -> None:
        """The loop's parts, made as the grasp loop makes them for this node's settings: the
        registered planner and contact detector for the box's rate, the pad and the gripper
        (:func:`softpad.control.loop_parts`), and the loop's object detector (the thesis's t_o
        on the filtered increments): the watch plans what a grasp would."""
        from softpad.control import loop_parts
        from softpad.layout import GripperSpec
        from softpad.sensing import ThesisObjectDetector

        c, rate = self.config, float(self.box.sample_rate_hz)
        self.params = self._execution_params()
        spec = GripperSpec.from_mounting(self._mounting())
        parts = loop_parts(c.planner, c.detector, rate, self.layout, spec, self.params)
        self.planner, self.contact_detector = parts["planner"], parts["contact_detector"]
        self.object_detector = ThesisObjectDetector(self.params.planner.object_threshold_pa)

    def _adjust(self) -> None:
        from softpad.control import inflate_and_adjust

        self.pubs.reset_pace()
        self.adjustment = inflate_and_adjust(self.box, self.n, on_frame=self.pubs.frame)
        self._set_reference(self.adjustment.reference_pa)

    def _set_reference(self, reference_pa: NDArray[np.float64]) -> None:
        self.reference_pa = np.asarray(reference_pa, dtype=float)
        self.contact_ref: NDArray[np.float64] | None = None
        self._recent: deque[NDArray[np.float64]] = deque(maxlen=self.params.planning_reads)
        self._arm_watch()
        self._publish_plans([])

    def _arm_watch(self) -> None:
        """Watch for objects afresh, as the loop's ``wait_object`` does."""
        from softpad.control import ObjectWatch

        assert self.reference_pa is not None
        p = self.params
        self.watch = ObjectWatch(
            self.reference_pa, self.object_detector, self.layout, p.filter_length,
            p.object_settle_s,
        )  # fmt: skip
        self._plan_reads: list[NDArray[np.float64]] | None = None
        self._planned: list[tuple[int, ...]] | None = None

    def _place_later(self) -> None:
        self.place_at = None
        if self.config.place:
            if not self.box.simulated:
                raise InputError(
                    "place= puts catalogue objects on a simulated box only (sim://, or a "
                    "served simulator such as softpad sim arm-node's)"
                )
            self.place_at = self.pubs.last_t + self.config.place_after_s

    def _loop(self, max_frames: int | None) -> None:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA, check_frame

        self._phase("watch")
        while not self.rospy.is_shutdown() and (
            max_frames is None or self.pubs.frames < max_frames
        ):
            frame = self.box.read()
            self.pubs.frame(frame)
            # NaN, dropout or over the maximum: HardwareFault (diagnostics ERROR, box made safe)
            checked = check_frame(frame, self.n, DEFAULT_MAX_PRESSURE_PA)
            if not self.safe_hold:  # a vented pad after a cancel: nothing to watch
                self._track(checked)
            if self.place_at is not None and frame.t_s >= self.place_at:
                self._place()
            while not self._requests.empty():
                self._serve(self._requests.get())

    def _place(self) -> None:
        from softpad.harness import world_access

        world = world_access(self.box)
        assert world is not None
        world.setup(self._mounting())
        world.place(list(self.config.place))
        self.place_at = None

    def _mounting(self) -> str:
        """The gripper mounting: ``gripper``, else the first placed object's, else 10/4."""
        if self.config.gripper:
            return self.config.gripper
        if self.config.place:
            from softpad.harness import resolve_objects

            return str(resolve_objects(self.config.place[:1])[0].gripper)
        return "10/4"

    # --- per frame ------------------------------------------------------------------------
    def _track(self, p: NDArray[np.float64]) -> None:
        """The loop's object watch on every frame (:class:`softpad.control.ObjectWatch`):
        once an object has settled, the loop's planning reads and planning step
        (:func:`softpad.control.plan_from_reads`); after a plan, a changed set of objects
        arms the watch again; and the contact detector."""
        p = np.nan_to_num(p)
        self._recent.append(p)
        if self._plan_reads is not None:  # settled: the reads the loop plans from
            self._plan_reads.append(p)
            if len(self._plan_reads) == self.params.planning_reads:
                self._plan(self._plan_reads)
        else:
            state = self.watch.update(p, self.pubs.last_t)
            if self._planned is None and state == "settled":
                self._plan_reads = []
            elif self._planned is not None and self._objects_now() != self._planned:
                self._arm_watch()  # objects came, went or moved: watch and plan again
                if not self._objects_now():
                    self._publish_plans([])
        contact = False
        if self.contact_ref is not None:
            contact = bool(self.contact_detector.update(p))
        self.pubs.contact(contact)

    def _objects_now(self) -> list[tuple[int, ...]]:
        """Objects in the watch's filtered increments now, sorted."""
        return sorted(tuple(o) for o in self.object_detector.objects(self.watch.filtered(),
                                                                     self.layout))  # fmt: skip

    def _plan(self, reads: Any = None) -> list[Any]:
        """Plan from ``reads`` (default: the last frames, as many as the loop's planning
        reads) with the loop's planning step, publish, and re-arm the contact detector."""
        from softpad.control import plan_from_reads

        assert self.reference_pa is not None
        reads = list(self._recent if reads is None else reads)
        delta, plans = plan_from_reads(
            reads, self.reference_pa, self.object_detector, self.planner, self.layout
        )
        self._plan_reads = None
        self._planned = sorted(tuple(pl.modules) for pl in plans)
        self.contact_ref = self.reference_pa + delta  # the pad with the objects on it
        self.contact_detector.reset(self.contact_ref)
        self._publish_plans(list(plans))
        return list(plans)

    def _publish_plans(self, plans: list[Any]) -> None:
        self.plans = plans
        objects = [p.to_dict(self.layout) for p in plans]
        self.pubs.plans(objects)
        self.pubs.event(self.pubs.last_t, "plan", {"objects": objects, "source": "watch"})

    def _phase(self, name: str) -> None:
        """The node's own phase (``watch``, ``safe``) on the phase topic and as an event."""
        self.pubs.phase(name)
        self.pubs.event(self.pubs.last_t, "phase", {"phase": name})

    # --- services -------------------------------------------------------------------------
    def _serve(self, r: _Request) -> None:
        from softpad.control import ExecutionError

        try:
            if r.name == "inflate":
                self._adjust()
                self.safe_hold = False
                self._phase("watch")
                assert self.reference_pa is not None
                r.message = "adjusted; reference (Pa): " + _pa(self.reference_pa)
            elif r.name == "capture_reference":
                self._capture_reference()
                r.message = "reference (Pa): " + _pa(self.reference_pa)
            elif r.name == "grasp":
                self._serve_grasp(r)
            else:
                plans = self._plan()
                r.message = json.dumps([p.to_dict(self.layout) for p in plans])
            r.ok = True
        except (InputError, ExecutionError) as exc:
            r.message = str(exc)
            if isinstance(exc, ExecutionError):  # the loop ran and could not go on
                self.loop_publisher.error(r.message)
        except HardwareFault as exc:
            r.message = f"hardware fault: {exc}"  # the node then ends, the box made safe
            raise
        finally:
            r.done.set()

    def _serve_grasp(self, r: _Request) -> None:
        """One grasp for the service or the action; a cancel leaves the box safe and the watch
        paused (:attr:`safe_hold`)."""
        from softpad.box import simulator_of
        from softpad.ros._publish import GraspCancelled

        lp = self.loop_publisher
        lp.on_phase, lp.cancel_requested = r.on_phase, r.cancel_requested
        sim = simulator_of(self.box)
        if sim is not None:  # the simulated arm's measured pose, as recordings take it
            self.pubs.robot_state = sim.world.gripper_state
        try:
            r.result = _jsonable_result(self._grasp(r.hold_s).to_dict())
            r.message = json.dumps(_summary(r.result))
        except GraspCancelled as exc:
            r.cancelled, r.message = True, f"{exc}; the box is in its safe state (~inflate resumes)"
            lp.cancelled(r.message)
            self.safe_hold = True
        finally:
            lp.on_phase = lp.cancel_requested = None
            self.pubs.robot_state = None
            self._phase("safe" if self.safe_hold else "watch")

    def _capture_reference(self) -> None:
        """Reference := mean of 10 reads now (pad empty); grasps start from it too."""
        from softpad.sensing import capture_reference

        reads = []
        for _ in range(thesis.REFERENCE_READS):
            frame = self.box.read()
            self.pubs.frame(frame)
            reads.append(frame.pressures_pa[: self.n])
        self._set_reference(capture_reference(reads))
        assert self.reference_pa is not None
        self.adjustment = replace(
            self.adjustment, reference_pa=self.reference_pa, reference_at_s=self.pubs.last_t
        )

    def _grasp(self, hold_s: float | None = None) -> Any:
        """Run the loop (:func:`softpad.harness.build_loop`) once on the node's box, from its
        reference, with the registered parts and the ``robot``; published as it runs."""
        from softpad.harness import build_loop

        c = self.config
        if not c.robot:
            raise InputError(
                "grasp: the node has no robot; set 'robot' (a robot URL: sim:// on a sim:// "
                "box, ros1:// with an arm node) in its config, ~robot or --robot"
            )
        # objects configured but not yet down: the loop puts them there when it waits
        place = self._place if self.place_at is not None else None
        with build_loop(
            self.box, c.robot, params=self._execution_params(hold_s), planner=c.planner,
            contact_detector=c.detector, gripper=self._mounting(), layout=self.layout,
            recorder=self.loop_publisher, place_objects=place, adjusted=self.adjustment,
        ) as loop:  # fmt: skip
            result = loop.run()
        self.loop_publisher.finish(result)
        return result

    def _execution_params(self, hold_s: float | None = None) -> Any:
        from softpad.control import ExecutionParams
        from softpad.planning import PlannerParams

        c = self.config
        return ExecutionParams(
            planner=PlannerParams(object_threshold_pa=c.object_threshold_pa),
            contact_threshold_pa=c.contact_threshold_pa,
            hold_s=c.hold_s if hold_s is None else hold_s,
            object_settle_s=c.settle_s,
        )


def _jsonable_result(result: dict[str, Any]) -> dict[str, Any]:
    """``result`` with non-finite numbers as None (JSON has none)."""
    from softpad.ros._messages import jsonable

    return jsonable(result)  # type: ignore[no-any-return]


def _summary(result: dict[str, Any]) -> dict[str, Any]:
    """The ``~grasp`` answer: outcome, objects and grasps of the loop's result."""
    return {k: result[k] for k in ("outcome", "objects", "grasps")}


def _pa(values: Any) -> str:
    return " ".join(f"{float(v):.1f}" for v in values)
