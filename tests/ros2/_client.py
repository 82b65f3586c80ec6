"""A ROS 2 client in its own process for tests/ros2: ``python _client.py MODE SECONDS``.

Modes (each prints one JSON object on stdout):

- ``watch``: subscribe to module 1's pressure, the supply, /diagnostics and /tf_static for
  SECONDS after the first pressure message; report the count, the header stamps' span, the
  pressures and the statuses.
- ``grasp``: send one goal to the grasp action (hold 1 s); report the feedback phases, the
  result and the final status.
- ``cancel``: send one goal, cancel it at the first ``descend`` feedback; report the same and
  every /softpad/events kind with the safe state's data.
- ``topics``: every topic name and type seen after SECONDS; with NAMES after SECONDS
  (``topics SECONDS NAME...``), seen once every one of NAMES is and a second more, SECONDS
  at most (issue 50: a node's topics are discovered within a second or two of each other).

The test process never imports rclpy itself (one process speaks ROS 1 or ROS 2).
"""

from __future__ import annotations

import json
import sys
import time
from typing import Any


def _spin_until(node: Any, done: Any, timeout_s: float) -> None:
    import rclpy

    deadline = time.monotonic() + timeout_s
    while not done() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)


def _stamp(msg: Any) -> float:
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def watch(node: Any, seconds: float) -> dict[str, Any]:
    from diagnostic_msgs.msg import DiagnosticArray
    from geometry_msgs.msg import PoseStamped
    from rclpy.qos import DurabilityPolicy, QoSProfile
    from sensor_msgs.msg import FluidPressure
    from tf2_msgs.msg import TFMessage

    pressures: list[Any] = []
    supply: list[Any] = []
    diagnostics: list[Any] = []
    tf: list[Any] = []
    poses: list[Any] = []
    node.create_subscription(PoseStamped, "/softpad/robot/pose", poses.append, 50)
    node.create_subscription(FluidPressure, "/softpad/module_1/pressure", pressures.append, 200)
    node.create_subscription(FluidPressure, "/softpad/supply/pressure", supply.append, 200)
    node.create_subscription(DiagnosticArray, "/diagnostics", diagnostics.append, 10)
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(TFMessage, "/tf_static", tf.append, latched)
    _spin_until(node, lambda: bool(pressures) and bool(tf), 120.0)
    start = len(pressures)
    t_end = time.monotonic() + seconds
    _spin_until(node, lambda: time.monotonic() >= t_end, seconds + 1)
    window = pressures[start:]
    transforms = [
        {
            "parent": t.header.frame_id,
            "child": t.child_frame_id,
            "xyz": [t.transform.translation.x, t.transform.translation.y,
                    t.transform.translation.z],
            "q": [t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                  t.transform.rotation.w],
        }
        for t in (tf[-1].transforms if tf else [])
    ]  # fmt: skip
    return {
        "count": len(window),
        "span_s": _stamp(window[-1]) - _stamp(window[0]) if len(window) > 1 else 0.0,
        "frame_id": window[0].header.frame_id if window else None,
        "pressures_pa": [m.fluid_pressure for m in window[:50]],
        "supply_pa": [m.fluid_pressure for m in supply[-5:]],
        "statuses": sorted({s.name for d in diagnostics for s in d.status}),
        "levels": {s.name: int.from_bytes(s.level, "little") for d in diagnostics[-1:] for s in
                   d.status},
        "transforms": transforms,
        "robot_poses": len(poses),
    }  # fmt: skip


def grasp(node: Any, cancel_at: str | None, timeout_s: float) -> dict[str, Any]:
    from geometry_msgs.msg import PoseArray
    from rclpy.action import ActionClient
    from rclpy.qos import DurabilityPolicy, QoSProfile
    from softpad_msgs.action import Grasp
    from softpad_msgs.msg import Event

    events: list[Any] = []
    node.create_subscription(Event, "/softpad/events", events.append, 100)
    plans: list[Any] = []
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(PoseArray, "/softpad/plan/grasps", plans.append, latched)
    client = ActionClient(node, Grasp, "/softpad/grasp")
    if not client.wait_for_server(timeout_sec=60.0):
        return {"error": "no action server"}
    # the node's watch plans the object once it lies still: its plan before any grasp
    _spin_until(node, lambda: any(p.poses for p in plans), 120.0)
    watched = [[q.position.x, q.position.y] for p in plans if p.poses for q in p.poses][:1]
    phases: list[str] = []
    state: dict[str, Any] = {}

    def feedback(msg: Any) -> None:
        phases.append(msg.feedback.phase)
        if cancel_at is not None and msg.feedback.phase == cancel_at and "cancel" not in state:
            state["cancel"] = state["handle"].cancel_goal_async()

    send = client.send_goal_async(Grasp.Goal(hold_s=1.0), feedback_callback=feedback)
    _spin_until(node, send.done, 30.0)
    state["handle"] = handle = send.result()
    if not handle.accepted:
        return {"error": "goal rejected"}
    result = handle.get_result_async()
    _spin_until(node, result.done, timeout_s)
    if not result.done():
        return {"error": f"no result within {timeout_s} s", "phases": phases}
    _spin_until(node, lambda: False, 1.0)  # the events published with the result
    r = result.result()
    return {
        "status": int(r.status),
        "outcome": r.result.outcome,
        "message": r.result.message,
        "grasps": [[p.position.x, p.position.y] for p in r.result.grasps.poses],
        "grasps_frame": r.result.grasps.header.frame_id,
        "result": json.loads(r.result.result_json) if r.result.result_json else None,
        "phases": phases,
        "watch_plan": watched,
        "events": [[e.kind, json.loads(e.data_json)] for e in events],
    }


def topics(node: Any, seconds: float, names: list[str] | None = None) -> dict[str, Any]:
    if names:  # until every one is seen, then a second more for any other the node makes
        t_end = time.monotonic() + seconds
        _spin_until(node, lambda: set(names) <= set(_names(node)), seconds)
        _spin_until(node, lambda: False, min(1.0, max(0.0, t_end - time.monotonic())))
    else:
        _spin_until(node, lambda: False, seconds)
    return {"topics": {n: t for n, t in node.get_topic_names_and_types()}}


def _names(node: Any) -> list[str]:
    return [n for n, _ in node.get_topic_names_and_types()]


def main() -> None:
    import rclpy

    mode, seconds = sys.argv[1], float(sys.argv[2])
    rclpy.init()
    node = rclpy.create_node(f"softpad_test_{mode}")
    try:
        if mode == "watch":
            out = watch(node, seconds)
        elif mode == "topics":
            out = topics(node, seconds, sys.argv[3:])
        else:
            out = grasp(node, "descend" if mode == "cancel" else None, seconds)
    finally:
        node.destroy_node()
        rclpy.shutdown()
    print(json.dumps(out), flush=True)


if __name__ == "__main__":
    main()
