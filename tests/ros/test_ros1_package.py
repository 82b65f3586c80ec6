"""SoftPad as a ROS 1 package against a real roscore on loopback (skipped without ROS): the
grasp action (actionlib, a client in Debian's Python), events that ``rostopic echo`` decodes
live, the installation file's pad pose in ``/tf_static``, and the launch file.

The roscore and process fixtures are test_ros's (imported: pytest uses them by their names,
which the tests' parameters therefore repeat).
"""
# ruff: noqa: F811

from __future__ import annotations

import json
import math
import os
import shutil
import signal
import subprocess
from pathlib import Path

import pytest
from test_ros import SOFTPAD, _echo, _messages, _Procs, _wait, _watch, master, procs  # noqa: F401

from softpad.ros import rospy_available

pytestmark = [
    pytest.mark.skipif(
        not (rospy_available() and shutil.which("roscore") and shutil.which("roslaunch")),
        reason="ROS 1 not installed (make ros-deps, as root, installs Debian's packages)",
    ),
    pytest.mark.slow,
]
ROOT = Path(__file__).resolve().parents[2]

#: An actionlib client of the grasp action in Debian's Python (another process, another
#: interpreter: only the generated softpad_msgs on its PYTHONPATH). argv: cancel-at phase or
#: "-", hold_s. Prints the feedback's phases, the goal's final state and the result as JSON.
_CLIENT = """
import json, sys, threading
import actionlib, rospy
import softpad_msgs.msg as m

cancel_at, hold_s = sys.argv[1], float(sys.argv[2])
rospy.init_node("grasp_client", anonymous=True)
client = actionlib.SimpleActionClient("/softpad/grasp", m.GraspAction)
assert client.wait_for_server(rospy.Duration(60)), "no grasp action server"
phases, reached = [], threading.Event()
def feedback(f):
    phases.append(f.phase)
    if f.phase == cancel_at:
        reached.set()
client.send_goal(m.GraspGoal(hold_s=hold_s), feedback_cb=feedback)
if cancel_at != "-":
    assert reached.wait(120), phases
    client.cancel_goal()
assert client.wait_for_result(rospy.Duration(240)), phases
r = client.get_result()
print(json.dumps({
    "phases": phases, "state": client.get_state(), "outcome": r.outcome,
    "message": r.message, "grasps": [[p.position.x, p.position.y] for p in r.grasps.poses],
    "result": json.loads(r.result_json) if r.result_json else None,
}))
"""


def _ros_env(procs: _Procs) -> dict[str, str]:
    """The test's ROS environment plus ``softpad ros env``'s exports (the generated messages
    on PYTHONPATH, SoftPad's ROS packages on ROS_PACKAGE_PATH)."""
    r = procs.run(SOFTPAD, "ros", "env")
    assert r.returncode == 0, r.stderr
    env = dict(procs.env)
    for line in r.stdout.splitlines():
        name, value = line.removeprefix("export ").split("=", 1)
        value = value.strip('"').split("${")[0]
        env[name] = value + (":" + env[name] if env.get(name) else "")
    return env


def _client(procs: _Procs, env: dict[str, str], cancel_at: str, hold_s: float) -> dict:  # type: ignore[type-arg]
    r = subprocess.run(
        ["/usr/bin/python3", "-c", _CLIENT, cancel_at, str(hold_s)],
        env=env, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert r.returncode == 0, r.stdout + r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


def _site(tmp_path: Path) -> Path:
    """The example installation with the pad turned by 30 degrees (pose 400, -100, 20 mm)."""
    text = (ROOT / "examples" / "site.toml").read_text().replace("yaw_deg = 0.0", "yaw_deg = 30.0")
    assert "yaw_deg = 30.0" in text
    site = tmp_path / "site.toml"
    site.write_text(text)
    return site


def test_grasp_action_holds_object_5_with_phase_feedback_and_events_echo_live(
    procs: _Procs, tmp_path: Path
) -> None:
    """``ros node --config site.toml``: the installation's pad pose (mm, degrees) in
    ``/tf_static`` in metres and a quaternion; a goal of the grasp action ends SUCCEEDED with
    object 5 held, its phases as feedback in the loop's order, the planned grasp
    in the result; ``rostopic echo /softpad/events`` (Debian's, with ``softpad ros env``)
    decodes the loop's events live as they are published."""
    env = _ros_env(procs)
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--config", str(_site(tmp_path)), "--box", "sim://",
        "--robot", "sim://", "--place", "object-5",
    )  # fmt: skip
    procs.env = env  # rostopic echo below decodes softpad_msgs/Event with the generated modules
    logs = _watch(procs, "/softpad/events", "/tf_static")
    _wait(lambda: "position" in _echo(procs, "/softpad/plan/grasps"), 90.0, "object 5 planned")
    out = _client(procs, env, "-", 1.0)
    assert node.poll() is None, log.read_text()
    assert out["state"] == 3 and out["outcome"] == "held", out  # actionlib SUCCEEDED
    loop = ["wait_object", "plan", "approach", "descend", "close", "lift", "hold", "release"]
    assert [p for p in out["phases"] if p in loop] == loop, out["phases"]
    (plan,) = out["result"]["objects"]
    assert plan["modules"] == [1, 2, 3]
    assert out["grasps"] == [pytest.approx(plan["cog_m"], abs=1e-9)]
    events = _wait(
        lambda: [m for m in _messages(logs["/softpad/events"]) if m["kind"] == "outcome"]
        or None, 30.0, "the outcome event echoed",
    )  # fmt: skip
    kinds = [m["kind"] for m in _messages(logs["/softpad/events"])]
    assert {"phase", "plan", "contact", "outcome"} <= set(kinds), kinds
    assert json.loads(events[-1]["data_json"])["outcome"] == "held"
    (tf,) = _messages(logs["/tf_static"])[:1]
    pad = next(t for t in tf["transforms"] if t["child_frame_id"] == "softpad")
    assert pad["header"]["frame_id"] == "base"
    assert pad["transform"]["translation"] == pytest.approx({"x": 0.4, "y": -0.1, "z": 0.02})
    q = pad["transform"]["rotation"]
    assert 2.0 * math.atan2(q["z"], q["w"]) == pytest.approx(math.radians(30.0), abs=1e-9)


def test_cancelled_grasp_goal_ends_in_the_safe_state(procs: _Procs) -> None:
    """A goal cancelled during the descent: PREEMPTED, outcome ``canceled``; the loop's safe
    state verified (its ``safe_state`` event), every inflation valve closed on /diagnostics,
    the node in phase ``safe`` until ``~inflate`` resumes the watch."""
    env = _ros_env(procs)
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--box", "sim://", "--robot", "sim://",
        "--place", "object-5",
    )  # fmt: skip
    procs.env = env
    logs = _watch(procs, "/softpad/events", "/diagnostics")
    out = _client(procs, env, "descend", 1.0)
    assert out["state"] == 2 and out["outcome"] == "canceled", out  # actionlib PREEMPTED
    assert "safe state" in out["message"]
    assert node.poll() is None, log.read_text()
    events = _wait(
        lambda: [m for m in _messages(logs["/softpad/events"]) if m["kind"] == "safe_state"]
        or None, 30.0, "the safe state event",
    )  # fmt: skip
    assert json.loads(events[-1]["data_json"])["verified"] is True
    diag = _wait(lambda: _messages(logs["/diagnostics"])[-3:], 30.0, "diagnostics after")[-1]
    valves = [v["value"] for s in diag["status"] for v in s["values"] if v["key"] == "valve"]
    assert len(valves) == 6 and "inflate" not in valves, valves
    phase = procs.run("rostopic", "echo", "-n", "1", "/softpad/phase").stdout
    assert 'data: "safe"' in phase
    r = procs.run("rosservice", "call", "/softpad/inflate", timeout_s=60)
    assert "success: True" in r.stdout, r.stdout + r.stderr
    assert 'data: "watch"' in procs.run("rostopic", "echo", "-n", "1", "/softpad/phase").stdout


def test_launch_file_starts_the_node_with_the_installation(procs: _Procs, tmp_path: Path) -> None:
    """``roslaunch softpad_ros pad.launch config:=site.toml``: the node comes up under its
    launch name with the installation's pad pose in /tf_static and its parameters set."""
    env = _ros_env(procs)
    procs.env = env
    launch, log = procs.start(
        "launch", "roslaunch", "softpad_ros", "pad.launch", f"config:={_site(tmp_path)}",
        f"softpad:={SOFTPAD}", "hold_s:=2.5",
    )  # fmt: skip

    def up() -> str:
        assert launch.poll() is None, log.read_text()
        text = procs.run("rostopic", "echo", "-n", "1", "/tf_static", timeout_s=20).stdout
        return text if "softpad_module_6" in text else ""

    tf = _wait(up, 90.0, "the launched node's /tf_static")
    assert "x: 0.4" in tf and "y: -0.1" in tf
    assert procs.run("rosparam", "get", "/softpad/hold_s").stdout.strip() == "2.5"
    nodes = procs.run("rosnode", "list").stdout.split()
    assert "/softpad" in nodes, nodes
    # exactly the table's ros1 topics, with their types (the action's own aside)
    import rosgraph

    from softpad.topics import ros1_type, topics_for

    master = rosgraph.Master("/softpad_test", master_uri=procs.env["ROS_MASTER_URI"])
    publishers, _, _ = master.getSystemState()
    types = dict(master.getTopicTypes())
    ours = {
        t: types[t] for t, nodes in publishers
        if "/softpad" in nodes and not t.startswith(("/softpad/grasp/", "/rosout"))
    }  # fmt: skip
    assert ours == {n: ros1_type(t) for n, t in topics_for("ros1", 6).items()}
    # interrupted, roslaunch stops the node before it ends itself (none left behind: the
    # fixture's 5 s before SIGKILL once orphaned a node still shutting down)
    launch.send_signal(signal.SIGINT)
    assert launch.wait(60) is not None
    assert "/softpad" not in procs.run("rosnode", "list").stdout.split()


def test_ros_env_generates_messages_other_interpreters_import(procs: _Procs) -> None:
    """``softpad ros env``: Debian's Python imports the generated package and finds the ROS
    packages; the event's MD5 is the same in both interpreters."""
    env = _ros_env(procs)
    code = (
        "import rospkg, softpad_msgs.msg as m; "
        "print(m.Event._md5sum, m.GraspAction._type, rospkg.RosPack().get_path('softpad_ros'))"
    )
    r = subprocess.run(
        ["/usr/bin/python3", "-c", code], env=env, capture_output=True, text=True, check=False
    )
    assert r.returncode == 0, r.stderr
    md5, action, path = r.stdout.split()
    from softpad.ros._msgs import ensure_messages

    assert md5 == ensure_messages().Event._md5sum and action == "softpad_msgs/GraspAction"
    assert os.path.isfile(os.path.join(path, "launch", "pad.launch"))
