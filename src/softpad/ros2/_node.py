"""``softpad ros2 node``: the pad as a ROS 2 node (rclpy). Translation only.

The node is the ROS 1 node's loop (:class:`softpad.ros.PadNode`: it owns the box, inflates
and adjusts, keeps the reference, watches and plans with the registered parts, runs the grasp
loop of ``softpad run`` on request) with ROS 2 edges: the topics of the table's ``ros2``
output (:class:`~softpad.ros2.Ros2Publishers`), ROS 2 parameters (every key of
:data:`softpad.ros.CONFIG_KEYS`, declared with the installation's value), ``std_srvs/Trigger``
services ``~/inflate``, ``~/capture_reference`` and ``~/plan``, and the grasp as the action
``/softpad/grasp`` (``softpad_msgs/action/Grasp``): feedback is the loop's phase, the result
its outcome; a cancel stops the loop, which ends in the safe state (the arm stopped, inflation
valves closed, vented channels venting; :class:`softpad.control.GraspExecution`'s fault path).

rclpy runs in its own thread (a multi-threaded executor); the box is used from the node's
loop only: requests are handed to it through a queue, as the ROS 1 node does.
"""

from __future__ import annotations

import json
import threading
from dataclasses import dataclass, field
from typing import Any

from softpad import topics as T
from softpad.errors import HardwareFault, InputError
from softpad.ros import CONFIG_KEYS, LoopPublisher, NodeConfig, PadNode, jsonable
from softpad.ros2._publish import Ros2Publishers


class GraspCanceled(HardwareFault):
    """The grasp action's goal was canceled: the loop stops through its fault path, so it ends
    in the safe state; the node goes on watching."""


@dataclass
class _Request:
    """A service call or action goal handed to the node's loop."""

    name: str
    done: threading.Event = field(default_factory=threading.Event)
    cancel: threading.Event = field(default_factory=threading.Event)
    ok: bool = False
    message: str = ""
    hold_s: float = 0.0
    result: Any = None
    outcome: str = ""


class Ros2LoopPublisher(LoopPublisher):
    """The ROS 1 loop publisher's translation on ROS 2 publishers, every event also on
    ``/softpad/events``; while a grasp goal runs, a cancel raises :class:`GraspCanceled` at the
    next frame (once: the loop's way to the safe state reads frames too)."""

    def __init__(self, publishers: Ros2Publishers) -> None:
        super().__init__(publishers)  # type: ignore[arg-type]  # the same methods
        self.ros2 = publishers
        self.request: _Request | None = None
        self._canceling = False

    def start(self, request: _Request | None) -> None:
        """A new grasp loop, for ``request`` (None: not cancellable)."""
        self.request, self._canceling, self.touching = request, False, False

    def frame(self, frame: Any, phase: str) -> None:
        super().frame(frame, phase)
        r = self.request
        if r is not None and r.cancel.is_set() and not self._canceling:
            self._canceling = True
            raise GraspCanceled("grasp canceled by its action client")

    def event(self, t_s: float, kind: str, **data: Any) -> None:
        if kind == "fault" and self._canceling:  # not a fault of the link: no ERROR
            self.ros2.event(t_s, "canceled", data)
            self.ros2.outcome({"outcome": "canceled", "t_s": t_s, **data})
            return
        super().event(t_s, kind, **data)  # every event also on /softpad/events


class _Running:
    """The stop condition of the node's loop (the ROS 1 node asks ``rospy.is_shutdown``)."""

    def __init__(self) -> None:
        self.stop = threading.Event()

    def is_shutdown(self) -> bool:
        import rclpy

        return self.stop.is_set() or not rclpy.ok()

    def signal_shutdown(self, reason: str) -> None:
        """End the loop (the ROS 1 node's ``rospy.signal_shutdown`` when its run ends)."""
        self.stop.set()


def declare_parameters(node: Any, config: NodeConfig) -> dict[str, Any]:
    """Declare every key of :data:`CONFIG_KEYS` as a ROS 2 parameter with ``config``'s value
    (a launch file or ``--ros-args -p key:=value`` overrides it); returns the values set."""
    defaults = _flat(config)
    out = {}
    for key in CONFIG_KEYS:
        value = node.declare_parameter(key, defaults[key]).value
        if value != defaults[key]:
            out[key] = value
    return out


def _flat(config: NodeConfig) -> dict[str, Any]:
    """``config`` as the flat keys of :data:`CONFIG_KEYS` (floats, strings; ``place`` joined)."""
    out: dict[str, Any] = {}
    for key in CONFIG_KEYS:
        if key.startswith("pad_"):
            out[key] = float(getattr(config.pad, key[4:]))
        elif key == "place":
            out[key] = ",".join(config.place)
        else:
            v = getattr(config, key)
            out[key] = float(v) if isinstance(v, int | float) else str(v)
    return out


class Ros2PadNode(PadNode):
    """The ROS 2 node of one pad (module docstring; docs/ros.md, "ROS 2").

    Parameters
    ----------
    config
        Installation; ROS 2 parameters override it.
    name
        ROS node name.
    ros_args
        Arguments for ``rclpy.init`` after ``--ros-args`` (``-p key:=value``, remappings).
    """

    def __init__(
        self, config: NodeConfig, name: str = "softpad", ros_args: list[str] | None = None
    ) -> None:
        from softpad.layout import parse_layout
        from softpad.ros2._interfaces import apply_loopback_environment, ensure_rclpy

        ensure_rclpy()
        apply_loopback_environment()
        import rclpy
        from rclpy.signals import SignalHandlerOptions

        # Ctrl-C and SIGTERM stop the node as they stop every softpad command (exit 130 / 143,
        # the box left safe), not through rclpy's handler, which invalidates the context first
        rclpy.init(
            args=["softpad", "--ros-args", *(ros_args or [])],
            signal_handler_options=SignalHandlerOptions.NO,
        )
        self.node = rclpy.create_node(name)
        self.running = _Running()
        self.rospy = self.running  # type: ignore[assignment]  # the loop's stop condition
        self.config = config.updated(declare_parameters(self.node, config))
        self.layout = parse_layout(self.config.layout)
        self.n = self.layout.n_modules
        import queue

        self._requests: queue.Queue[Any] = queue.Queue()
        self.ros2 = Ros2Publishers(
            self.node, self.layout, self.config.box, self.config.ambient_pressure_pa
        )
        self.pubs = self.ros2  # type: ignore[assignment]  # the same methods
        self.ros2_loop = Ros2LoopPublisher(self.ros2)
        self.loop_publisher = self.ros2_loop
        self.reference_pa = None
        self.plans = []
        self._busy = threading.Lock()
        self._make_interfaces()
        self._spin()

    def _make_interfaces(self) -> None:
        from rclpy.action import ActionServer, CancelResponse, GoalResponse
        from rclpy.callback_groups import ReentrantCallbackGroup
        from softpad_msgs.action import Grasp
        from std_srvs.srv import Trigger

        group = ReentrantCallbackGroup()
        self.services = [
            self.node.create_service(
                Trigger, f"~/{n}", self._trigger(n), callback_group=group
            )
            for n in ("inflate", "capture_reference", "plan")
        ]  # fmt: skip

        def goal(_request: Any) -> Any:
            return GoalResponse.REJECT if self._busy.locked() else GoalResponse.ACCEPT

        self.action = ActionServer(
            self.node, Grasp, T.GRASP_ACTION, execute_callback=self._execute,
            goal_callback=goal, cancel_callback=lambda _g: CancelResponse.ACCEPT,
            callback_group=group,
        )  # fmt: skip

    def _spin(self) -> None:
        from rclpy.executors import MultiThreadedExecutor

        self.executor = MultiThreadedExecutor(num_threads=4)
        self.executor.add_node(self.node)
        self._spinner = threading.Thread(target=self._spin_until_shutdown, daemon=True)
        self._spinner.start()

    def _spin_until_shutdown(self) -> None:
        from rclpy.executors import ExternalShutdownException

        try:
            self.executor.spin()
        except ExternalShutdownException:
            pass

    def _trigger(self, name: str) -> Any:
        from std_srvs.srv import Trigger

        def call(_req: Any, response: Any) -> Any:
            r = _Request(name)
            self._requests.put(r)
            if not r.done.wait(60.0):
                return Trigger.Response(success=False, message=f"{name}: no answer in 60 s")
            return Trigger.Response(success=r.ok, message=r.message)

        return call

    def _execute(self, goal_handle: Any) -> Any:
        """The grasp action: hand the goal to the node's loop, relay cancels, wait for it."""
        from geometry_msgs.msg import PoseArray
        from softpad_msgs.action import Grasp
        from std_msgs.msg import Header

        with self._busy:
            r = _Request("grasp", hold_s=float(goal_handle.request.hold_s))

            def feedback(phase: str, t_s: float) -> None:
                goal_handle.publish_feedback(Grasp.Feedback(phase=phase, t_s=float(t_s)))

            self.ros2.on_phase = feedback
            self._requests.put(r)
            while not r.done.wait(0.05):
                if goal_handle.is_cancel_requested:
                    r.cancel.set()
            self.ros2.on_phase = None
        result = Grasp.Result(outcome=r.outcome, message=r.message)
        if r.result is not None:
            result.grasps = PoseArray(
                header=Header(stamp=self.ros2.stamp(), frame_id=T.PAD_FRAME),
                poses=_grasp_poses(r.result),
            )
            result.result_json = json.dumps(jsonable(r.result.to_dict()))
        if r.outcome == "canceled":
            goal_handle.canceled()
        elif r.ok:
            goal_handle.succeed()
        else:
            goal_handle.abort()
        return result

    # --- the loop's side ----------------------------------------------------------------
    def _serve(self, r: Any) -> None:
        if r.name != "grasp":
            return super()._serve(r)
        from softpad.control import ExecutionError

        try:
            self.ros2_loop.start(r)
            r.result = self._grasp_once(r.hold_s)
            r.outcome, r.ok = r.result.outcome, True
        except GraspCanceled as exc:
            r.outcome, r.message = "canceled", f"{exc}; the box is in its safe state"
        except (InputError, ExecutionError) as exc:
            r.outcome, r.message = "error", str(exc)
            if isinstance(exc, ExecutionError):
                self.loop_publisher.error(r.message)
        except HardwareFault as exc:
            r.outcome, r.message = "fault", f"hardware fault: {exc}"
            raise  # the node then ends, the box made safe
        finally:
            self.ros2_loop.start(None)
            self.ros2.robot_state = None
            self.pubs.phase("watch")
            r.done.set()

    def _grasp_once(self, hold_s: float) -> Any:
        """:meth:`PadNode._grasp` with the goal's hold time; on an in-process simulated box the
        gripper's measured pose is published (as recordings take it)."""
        from dataclasses import replace

        from softpad.box import simulator_of

        sim = simulator_of(self.box)
        if sim is not None:
            self.ros2.robot_state = sim.world.gripper_state
        config = self.config
        if hold_s > 0:
            self.config = replace(config, hold_s=hold_s)
        try:
            return self._grasp()
        finally:
            self.config = config

    def close(self) -> None:
        """Stop the loop, the executor and rclpy."""
        import rclpy

        self.running.stop.set()
        self.executor.shutdown()
        spinner = getattr(self, "_spinner", None)
        if spinner is not None:  # a C++ wait still running at exit aborts the process
            spinner.join(timeout=10.0)
        self.node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()


def _grasp_poses(result: Any) -> list[Any]:
    """The grasps the loop tried: COG on the pad surface, yaw = theta (frame softpad)."""
    from softpad.ros import grasp_poses

    return grasp_poses([g.plan.to_dict(result.layout) for g in result.grasps])


class Ros2RunPublisher(Ros2LoopPublisher):
    """The publisher of ``softpad run --ros2``: :class:`Ros2LoopPublisher` on a node of its own;
    the end of the run (:meth:`finish`, :meth:`error`) waits until the subscribers have
    acknowledged the outcome (at most :attr:`ACK_S`), so a run that exits does not lose it."""

    #: Longest wait for the outcome's acknowledgements, seconds.
    ACK_S = 2.0

    def _flush(self) -> None:
        from rclpy.duration import Duration

        self.ros2.pub[T.OUTCOME_TOPIC].wait_for_all_acked(Duration(seconds=self.ACK_S))

    def finish(self, result: Any) -> None:
        super().finish(result)
        self._flush()

    def error(self, message: str) -> None:
        super().error(message)
        self._flush()


def watch_loop2(
    layout: Any, box: Any, box_url: str, pad: Any = None, base_frame: str = T.BASE_FRAME,
    node_name: str = "softpad_run",
) -> Ros2RunPublisher:  # fmt: skip
    """A :class:`Ros2RunPublisher` for a grasp loop run by this process (``softpad run
    --ros2``): rclpy is started on loopback (:func:`~softpad.ros2.apply_loopback_environment`)
    and this process publishes the table's ``ros2`` topics, with ``/tf_static`` placing the pad
    at ``pad`` (a :class:`~softpad.layout.PadPose`, the installation's ``[pad.pose]``; None:
    the origin) in ``base_frame``."""
    from softpad.ros2._interfaces import apply_loopback_environment, ensure_rclpy

    ensure_rclpy()
    apply_loopback_environment()
    import rclpy

    if not rclpy.ok():
        from rclpy.signals import SignalHandlerOptions

        rclpy.init(args=["softpad"], signal_handler_options=SignalHandlerOptions.NO)
    node = rclpy.create_node(node_name)
    pubs = Ros2Publishers(node, layout, box_url)
    pubs.watch_run(box, pad, base_frame)
    return Ros2RunPublisher(pubs)
