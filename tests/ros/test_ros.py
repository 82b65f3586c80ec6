"""The ROS 1 adapters against a real roscore on loopback (skipped without ROS).

Each test starts its processes with ROS_MASTER_URI on 127.0.0.1, ROS_IP=127.0.0.1 and
ROS_HOSTNAME=localhost, waits for them with bounded timeouts and kills them at the end.
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from softpad.ros import rospy_available

pytestmark = pytest.mark.skipif(
    not (rospy_available() and shutil.which("roscore")),
    reason="ROS 1 not installed (make ros-deps, as root, installs Debian's packages)",
)
SOFTPAD = str(Path(sys.executable).with_name("softpad"))


def _wait(predicate, timeout_s: float, what: str):  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.2)
    raise AssertionError(f"timed out after {timeout_s} s waiting for {what}")


class _Procs:
    """Processes of one test, all killed at its end."""

    def __init__(self, env: dict[str, str], tmp: Path) -> None:
        self.env, self.tmp, self.procs = env, tmp, []  # type: ignore[var-annotated]

    def start(self, name: str, *args: str) -> tuple[subprocess.Popen[bytes], Path]:
        out = self.tmp / f"{name}.log"
        p = subprocess.Popen(args, env=self.env, stdout=out.open("wb"), stderr=subprocess.STDOUT)
        self.procs.append(p)
        return p, out

    def run(self, *args: str, timeout_s: float = 30.0) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            args, env=self.env, capture_output=True, text=True, timeout=timeout_s, check=False
        )

    def spawn(self, *args: str) -> subprocess.Popen[str]:
        """``args`` started with its output captured, for :meth:`finish` (commands that
        probe the node side by side: none changes what another sees)."""
        p = subprocess.Popen(
            args, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        self.procs.append(p)  # type: ignore[arg-type]
        return p

    def finish(
        self, p: subprocess.Popen[str], timeout_s: float = 30.0
    ) -> subprocess.CompletedProcess[str]:
        """What a :meth:`spawn`-ed command printed once it ended (as :meth:`run` returns it);
        one still running after ``timeout_s`` is killed and raises ``TimeoutExpired``."""
        try:
            out, err = p.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            p.kill()
            p.communicate()
            raise
        return subprocess.CompletedProcess(p.args, p.returncode, out, err)

    def close(self) -> None:
        """SIGINT to every process still running, at once (they stop side by side, not one
        after another: issue 50), then 5 s for each before SIGKILL."""
        running = [p for p in reversed(self.procs) if p.poll() is None]
        for p in running:
            p.send_signal(signal.SIGINT)
        for p in running:
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(5)


@pytest.fixture(scope="module")
def master(tmp_path_factory: pytest.TempPathFactory, free_port) -> Iterator[dict[str, str]]:
    port = free_port()
    env = dict(os.environ)
    env.update(
        ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_IP="127.0.0.1",
        ROS_HOSTNAME="localhost",
        ROS_HOME=str(tmp_path_factory.mktemp("ros_home")),
        MPLBACKEND="Agg",
    )
    # softpad ros env: the ROS tools decode SoftPad's own messages (events, the outcome)
    from softpad.ros import generate_messages, ros_packages_dir

    env["PYTHONPATH"] = os.pathsep.join(
        p for p in (str(generate_messages()), env.get("PYTHONPATH", "")) if p
    )
    env["ROS_PACKAGE_PATH"] = str(ros_packages_dir())
    core = subprocess.Popen(
        ["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    try:
        _wait(
            lambda: (
                subprocess.run(
                    ["rosparam", "list"], env=env, capture_output=True, timeout=10
                ).returncode
                == 0
            ),
            30.0,
            "roscore",
        )
        yield env
    finally:
        core.send_signal(signal.SIGINT)
        try:
            core.wait(10)
        except subprocess.TimeoutExpired:
            core.kill()


@pytest.fixture
def procs(master: dict[str, str], tmp_path: Path) -> Iterator[_Procs]:
    p = _Procs(master, tmp_path)
    yield p
    p.close()


def _echo(procs: _Procs, topic: str) -> str:
    """One message of ``topic`` as ``rostopic echo`` prints it; "" when none came in 30 s (a
    topic not advertised yet: callers wait on it with their own deadline)."""
    try:
        r = procs.run("rostopic", "echo", "-n", "1", topic, timeout_s=30)
    except subprocess.TimeoutExpired:
        return ""
    return r.stdout


def _rates(procs: _Procs, topic: str, reports: int = 3) -> tuple[list[float], str]:
    """The average rates ``rostopic hz -w 100`` reports for ``topic`` (Hz), read line by line
    until it has reported ``reports`` times (once a second: the last over a full window of
    100 messages at 100 Hz), then stopped; and what it printed. Was a fixed 8 s under
    ``timeout``: the same estimate, without waiting out the seconds after it (issue 50)."""
    p = subprocess.Popen(
        ["rostopic", "hz", "-w", "100", topic],
        env={**procs.env, "PYTHONUNBUFFERED": "1"},  # each report as it is printed
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )  # fmt: skip
    procs.procs.append(p)
    lines: list[str] = []
    rates: list[float] = []
    bound = threading.Timer(60.0, p.kill)  # a bound on a hang: it ends the read below
    bound.start()
    try:
        assert p.stdout is not None
        for line in p.stdout:
            lines.append(line)
            rates += [float(v) for v in re.findall(r"average rate: ([0-9.]+)", line)]
            if len(rates) >= reports:
                break
    finally:
        bound.cancel()
        p.send_signal(signal.SIGINT)
        p.wait(10)
    return rates, "".join(lines)


def _echoed(procs: _Procs, p: subprocess.Popen[str]) -> str:
    """:func:`_echo` of a ``rostopic echo -n 1`` started by :meth:`_Procs.spawn`."""
    try:
        return procs.finish(p, timeout_s=30).stdout
    except subprocess.TimeoutExpired:
        return ""


def _floats(text: str, key: str) -> list[float]:
    return [float(v) for v in re.findall(rf"^\s*{key}: (\S+)$", text, re.M)]


def test_node_publishes_pressures_diagnostics_and_the_plan(procs: _Procs) -> None:
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--box", "sim://", "--place", "object-5"
    )

    def grasps() -> str:
        assert node.poll() is None, log.read_text()
        text = _echo(procs, "/softpad/plan/grasps")
        return text if "position" in text else ""

    text = _wait(grasps, 60.0, "a grasp on /softpad/plan/grasps")
    assert 'frame_id: "softpad"' in text
    x, y, z = _floats(text, "x")[0], _floats(text, "y")[0], _floats(text, "z")
    yaw = 2.0 * math.atan2(z[1], _floats(text, "w")[0])
    # object 5 along the top row: on the row's axis (y = 1.5 module units), left of its middle
    # (towards its heavier part), the jaws across the row
    assert y == pytest.approx(0.0675, abs=1e-9) and 0.045 < x < 0.0675
    assert yaw == pytest.approx(math.pi / 2, abs=1e-9)

    # the probes side by side, each its own process (none changes what another sees): the
    # rate, diagnostics, a pressure, both services, the contact and /tf_static
    echo = ("rostopic", "echo", "-n", "1")
    probes = [
        procs.spawn(*echo, "/diagnostics"),
        procs.spawn(*echo, "/softpad/module_1/pressure"),
        procs.spawn("rosservice", "call", "/softpad/plan"),
        procs.spawn("rosservice", "call", "/softpad/grasp"),  # a node without a robot
        procs.spawn(*echo, "/softpad/contact"),
        procs.spawn(*echo, "/tf_static"),
    ]
    rates, hz = _rates(procs, "/softpad/module_1/pressure")
    assert rates, hz
    # paced to the box clock: never faster than the box's 100 Hz (5 % for the estimate)
    assert 0 < rates[-1] <= 105.0
    diag = _echoed(procs, probes[0])
    levels = [int(v) for v in re.findall(r"level: (\d+)", diag)]
    names = re.findall(r'name: "([^"]+)"', diag)
    assert "softpad: link" in names and "softpad: channel 6" in names
    assert levels[names.index("softpad: link")] == 0
    assert all(levels[names.index(f"softpad: channel {k}")] == 0 for k in range(1, 7))
    pressure = _echoed(procs, probes[1])
    assert 'frame_id: "softpad_module_1"' in pressure
    # absolute: p0 = 1.1 kPa gauge over the standard atmosphere (101.325 kPa), Pa
    assert 102325.0 < _floats(pressure, "fluid_pressure")[0] < 102625.0
    assert _floats(pressure, "variance")[0] == pytest.approx(73.5, abs=0.1)  # sensor model
    r = procs.finish(probes[2])
    assert "success: True" in r.stdout, r.stdout + r.stderr
    assert "n3-row" in r.stdout
    r = procs.finish(probes[3])  # a node without a robot
    assert "success: False" in r.stdout and "the node has no robot" in r.stdout, r.stdout
    assert "data: False" in _echoed(procs, probes[4])  # nothing touches the pad
    tf = _echoed(procs, probes[5])
    assert 'child_frame_id: "softpad"' in tf and 'child_frame_id: "softpad_module_6"' in tf


def test_node_plans_with_the_registered_parts_by_name(procs: _Procs) -> None:
    """``ros node --planner model-based --detector cusum``: the plan service answers with the
    registered planner's plans (the same part ``softpad run --planner`` makes), and the
    CUSUM sees no contact on an untouched pad."""
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--box", "sim://", "--place", "object-5",
        "--planner", "model-based", "--detector", "cusum",
    )  # fmt: skip

    def settled() -> str:  # the node planned the settled object by itself
        assert node.poll() is None, log.read_text()
        text = _echo(procs, "/softpad/plan/grasps")
        return text if "position" in text else ""

    _wait(settled, 90.0, "object 5 planned on /softpad/plan/grasps")
    plan = procs.spawn("rosservice", "call", "/softpad/plan")  # side by side with the echo
    contact = procs.spawn("rostopic", "echo", "-n", "1", "/softpad/contact")
    r = procs.finish(plan)
    assert "success: True" in r.stdout and "model-based" in r.stdout, r.stdout + r.stderr
    assert "[1, 2, 3]" in r.stdout
    assert "data: False" in _echoed(procs, contact)


def _arm(procs: _Procs, *extra: str) -> tuple[subprocess.Popen[bytes], Path, str]:
    arm, log = procs.start("arm", SOFTPAD, "sim", "arm-node", "--port", "0", *extra)
    url = _wait(
        lambda: (re.findall(r"zenoh://127\.0\.0\.1:\d+", log.read_text()) or [None])[0],
        30.0,
        "the arm node",
    )
    return arm, log, url


def test_run_with_the_arm_in_ros_holds_object_5_with_the_simulated_plan(procs: _Procs) -> None:
    _, _, url = _arm(procs)
    args = ("run", "--objects", "object-5", "--hold-s", "1", "--json")
    alone = procs.spawn(SOFTPAD, *args)  # the simulated run, side by side with the ROS one
    r = procs.run(SOFTPAD, *args, "--robot", "ros1://", "--box", url, timeout_s=90)
    assert r.returncode == 0, r.stderr
    ros = json.loads(r.stdout)
    sim = json.loads(procs.finish(alone, timeout_s=90).stdout)
    assert ros["outcome"] == "held"
    # The arm node's daemon samples on the wall clock, so valve commands land a frame or two
    # apart from the in-process run: the same plan, its PCOM and COG (object 5's COG is its
    # PCOM on the row's axis) within 0.05 module units.
    assert len(ros["objects"]) == len(sim["objects"]) == 1
    (a,), (b,) = ros["objects"], sim["objects"]
    assert (a["modules"], a["theta"], a["rule"]) == (b["modules"], b["theta"], b["rule"])
    for key in ("pcom", "cog"):
        assert abs(a[key][0] - b[key][0]) < 0.05 and abs(a[key][1] - b[key][1]) < 0.05
    assert ros["grasps"][0]["contact_modules"]


def test_arm_lost_mid_approach_ends_the_run_with_the_box_safe(
    procs: _Procs, tmp_path: Path
) -> None:
    from softpad.record import load_recording

    _, _, url = _arm(procs, "--lose-arm-on", "descend")
    mcap = tmp_path / "run.mcap"
    r = procs.run(
        SOFTPAD, "run", "--robot", "ros1://", "--box", url, "--objects", "banana",
        "--record", str(mcap), timeout_s=90,
    )  # fmt: skip
    assert r.returncode == 3, r.stdout + r.stderr  # softpad run's hardware-fault exit code
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert "phase 'descend'" in r.stderr and "arm lost" in r.stderr
    assert "safe state verified" in r.stdout, r.stdout
    rec = load_recording(mcap)
    faults = [(t, d) for t, k, d in rec.events if k == "fault"]
    assert len(faults) == 1 and faults[0][1]["phase"] == "descend"
    t_fault = faults[0][0]
    # made safe after the fault: every inflation valve closed, and frames read, none above the
    # maximum. A channel may be left venting: the lost arm goes on down onto the banana, and
    # the safe state vents a channel that rises with its inflation valve closed (it cannot
    # tell a press from a valve stuck open); such a channel is named in what it did.
    last_t, last_valves = rec.valves[-1]
    assert last_t >= t_fault and "inflate" not in last_valves, rec.valves[-3:]
    (safe,) = [d for _, k, d in rec.events if k == "safe_state"]
    assert safe["verified"], safe
    for ch, command in enumerate(last_valves[:6], start=1):
        named = rf"vented channel (\d+, )*{ch}\b"
        assert command == "closed" or any(re.search(named, s) for s in safe["tried"]), safe
    after = rec.pressures_pa[rec.t_s >= t_fault, :6]
    assert len(after) and np.nanmax(after) <= 3000.0


def test_arm_node_killed_mid_approach_gives_one_clear_error(procs: _Procs) -> None:
    arm, log, url = _arm(procs)
    run, out = procs.start(
        "run", SOFTPAD, "run", "--robot", "ros1://", "--box", url, "--objects", "banana"
    )
    _wait(lambda: "arm: descend" in log.read_text(), 60.0, "the descent")
    arm.kill()
    assert run.wait(30) == 3  # softpad run's hardware-fault exit code
    text = out.read_text()
    assert "Traceback" not in text
    assert re.search(r"run stopped in phase 'descend': (arm lost|no frame from the box)", text), (
        text
    )


def test_node_ends_on_a_sensor_fault_with_one_line(procs: _Procs) -> None:
    """A sensor going NaN after the adjustment: error naming the channel, exit 2, box safe."""
    r = procs.run(
        SOFTPAD, "ros", "node", "--box", "sim://?faults=nan:3@7", timeout_s=60
    )  # fmt: skip
    assert r.returncode == 3, r.stdout + r.stderr  # the hardware-fault exit code
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert "channel 3" in r.stderr and "softpad ros: error" in r.stderr


def _watch(procs: _Procs, *topics: str) -> dict[str, Path]:
    """``rostopic echo`` of each topic into its log, returned once each is up: the master lists
    its subscriber, or (a topic nobody published yet) it waits for the topic to appear."""
    from softpad.ros import ensure_rospy

    ensure_rospy()
    import rosgraph

    logs = {t: procs.start("echo" + t.replace("/", "_"), "rostopic", "echo", t)[1] for t in topics}
    master = rosgraph.Master("/softpad_test", master_uri=procs.env["ROS_MASTER_URI"])

    def subscribed() -> bool:
        subs = dict(master.getSystemState()[1])
        return all(
            any(n.startswith("/rostopic") for n in subs.get(t, []))
            or "does not appear to be published yet" in logs[t].read_text()
            for t in topics
        )

    _wait(subscribed, 30.0, f"rostopic echo of {', '.join(topics)}")
    return logs


def _messages(log: Path) -> list[dict]:  # type: ignore[type-arg]
    """The complete messages ``rostopic echo`` wrote to ``log`` (YAML documents)."""
    import yaml

    text = "\n".join(
        line for line in log.read_text().splitlines() if not line.startswith("WARNING")
    )
    return [yaml.safe_load(c) for c in text.split("\n---")[:-1] if c.strip()]


def _outcome(logs: dict[str, Path]) -> dict:  # type: ignore[type-arg]
    outcomes = _wait(lambda: _messages(logs["/softpad/outcome"]), 30.0, "/softpad/outcome")
    return json.loads(outcomes[-1]["summary_json"])  # type: ignore[no-any-return]


def _check_loop_topics(logs: dict[str, Path], outcome: dict) -> None:  # type: ignore[type-arg]
    """The loop's phases in order on /softpad/phase, contact seen on /softpad/contact while
    it held the fingers on the pad, and its plan on /softpad/plan/grasps."""

    def phases() -> list[str]:
        return [m["data"] for m in _messages(logs["/softpad/phase"])]

    # each topic has its own `rostopic echo`: the last phase may be written after the outcome
    _wait(lambda: "done" in phases(), 30.0, "'done' on /softpad/phase")
    loop = ["plan", "approach", "descend", "close", "lift", "hold", "release", "done"]
    assert [p for p in phases() if p in loop] == loop, phases()
    contact = [m["data"] for m in _messages(logs["/softpad/contact"])]
    assert True in contact and contact[0] is False  # untouched until the fingers land
    (plan,) = outcome["objects"]
    poses = [
        (p["position"]["x"], p["position"]["y"])
        for m in _messages(logs["/softpad/plan/grasps"])
        for p in m["poses"]
    ]
    assert any(
        abs(x - plan["cog_m"][0]) < 1e-9 and abs(y - plan["cog_m"][1]) < 1e-9 for x, y in poses
    ), (poses, plan)


_LOOP_TOPICS = ("/softpad/phase", "/softpad/contact", "/softpad/outcome", "/softpad/plan/grasps")


def test_grasp_service_runs_the_loop_and_publishes_plan_contact_and_outcome(
    procs: _Procs, tmp_path: Path
) -> None:
    """``rosservice call /softpad/grasp`` on ``ros node --robot sim://``: the node runs the
    grasp loop of ``softpad run`` on its box, from its reference, with its registered parts;
    object 5 (placed by the node, planned by its watch) is held, and the topics show the
    loop's phases, the contact, the plan and the outcome the service answers with."""
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--hold-s", "1", "--box", "sim://",
        "--robot", "sim://", "--place", "object-5", "--planner", "model-based",
        "--detector", "cusum",
    )  # fmt: skip
    logs = _watch(procs, *_LOOP_TOPICS)
    _wait(lambda: "watch" in logs["/softpad/phase"].read_text(), 60.0, "the node's watch")
    _wait(lambda: "position" in logs["/softpad/plan/grasps"].read_text(), 60.0, "object 5 planned")
    r = procs.run("rosservice", "call", "/softpad/grasp", timeout_s=180)
    assert node.poll() is None, log.read_text()
    assert "success: True" in r.stdout, r.stdout + r.stderr
    import yaml

    answer = json.loads(yaml.safe_load(r.stdout)["message"])
    assert answer["outcome"] == "held"
    outcome = _outcome(logs)
    assert outcome["outcome"] == "held" and outcome["objects"] == answer["objects"]
    assert outcome["objects"][0]["rule"].startswith("model-based")  # the part by name
    assert outcome["objects"][0]["modules"] == [1, 2, 3]
    assert outcome["grasps"][0]["contact_detected"] is True
    assert outcome["phases"][0]["phase"] == "wait_object"  # the node's own reference
    _check_loop_topics(logs, outcome)
    _wait(lambda: _messages(logs["/softpad/phase"])[-1]["data"] == "watch", 30.0, "watch again")


def test_run_with_ros_publishes_the_loop_it_runs(procs: _Procs) -> None:
    """``softpad run --ros``: the run is the box's one controller and ROS watches it: its
    phases, contact, plan and outcome on the node's topics, the outcome that of its JSON."""
    logs = _watch(procs, *_LOOP_TOPICS)
    r = procs.run(
        SOFTPAD, "run", "--ros", "--objects", "object-5", "--hold-s", "1", "--json",
        timeout_s=120,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    run = json.loads(r.stdout)
    outcome = _outcome(logs)
    assert outcome["outcome"] == run["outcome"] == "held"
    assert outcome["objects"] == run["objects"]
    # the run's report adds the simulator's ground truth (first touches) to each grasp
    pairs = zip(outcome["grasps"], run["grasps"], strict=True)
    assert [{k: g[k] for k in o} for o, g in pairs] == outcome["grasps"]
    _check_loop_topics(logs, outcome)


def test_run_with_ros_stands_the_pad_where_the_installation_says(procs: _Procs, site: Any) -> None:
    """``softpad run --ros --config site.toml``: /tf_static (latched, as ``rostopic echo``
    receives it) carries the installation's ``[pad.pose]`` (issue 48: the pad stood at the
    base's origin), the modules on the pad; the run's node publishes exactly the topic table's
    ``ros1`` names and types."""
    from softpad.ros import ensure_rospy

    ensure_rospy()
    import rosgraph

    from softpad.topics import ros1_type, topics_for

    logs = _watch(procs, "/tf_static")
    run, log = procs.start(
        "run", SOFTPAD, "run", "--ros", "--objects", "object-5", "--hold-s", "0.5",
        "--config", str(site.path), "--json",
    )  # fmt: skip
    (tf,) = _wait(lambda: _messages(logs["/tf_static"]), 120.0, "/tf_static of the run")
    master = rosgraph.Master("/softpad_test", master_uri=procs.env["ROS_MASTER_URI"])
    publishers, _, _ = master.getSystemState()
    types = dict(master.getTopicTypes())
    ours = {
        t: types[t] for t, nodes in publishers
        if any(n.startswith("/softpad_run") for n in nodes) and t != "/rosout"
    }  # fmt: skip
    assert ours == {n: ros1_type(t) for n, t in topics_for("ros1", 6).items()}
    assert run.wait(180) == 0, log.read_text()[-2000:]
    pad, *modules = tf["transforms"]
    t, q = pad["transform"]["translation"], pad["transform"]["rotation"]
    site.check_pad_transform(
        (pad["header"]["frame_id"], pad["child_frame_id"]),
        (t["x"], t["y"], t["z"]),
        (q["x"], q["y"], q["z"], q["w"]),
    )
    assert [m["child_frame_id"] for m in modules] == [f"softpad_module_{k}" for k in range(1, 7)]
    first = modules[0]["transform"]["translation"]  # module 1 at (0.5, 1.5) pitches of 45 mm
    assert (first["x"], first["y"]) == pytest.approx((0.5 * 0.045, 1.5 * 0.045))


# make test-slow (10 CPU s, issue 50): its parts run in make test: the grasp service
# (test_grasp_service_runs_the_loop_...), the arm node over ROS (test_run_with_the_arm_in_ros_...)
@pytest.mark.slow
def test_grasp_service_drives_the_arm_node_through_ros(procs: _Procs, tmp_path: Path) -> None:
    """``ros node --box <the arm node's served simulator> --robot ros1://``: the node is the
    box's controller, places object 5 through the served ``sim.place``, and ``~grasp`` moves
    the simulated arm over ROS (its commands in the arm node's log); held, with the contact
    and the outcome on the topics."""
    arm, arm_log, url = _arm(procs)
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--hold-s", "1", "--box", url,
        "--robot", "ros1://", "--place", "object-5",
    )  # fmt: skip
    logs = _watch(procs, *_LOOP_TOPICS)
    _wait(lambda: "position" in logs["/softpad/plan/grasps"].read_text(), 90.0, "object 5 planned")
    r = procs.run("rosservice", "call", "/softpad/grasp", timeout_s=180)
    assert node.poll() is None and arm.poll() is None, log.read_text() + arm_log.read_text()
    assert "success: True" in r.stdout, r.stdout + r.stderr
    outcome = _outcome(logs)
    assert outcome["outcome"] == "held" and outcome["objects"][0]["modules"] == [1, 2, 3]
    assert "arm: descend" in arm_log.read_text() and "arm: gripper" in arm_log.read_text()
    _check_loop_topics(logs, outcome)


# make test-slow (10 CPU s, issue 50): an arm lost mid-approach runs in make test
# (test_arm_lost_mid_approach_ends_the_run_with_the_box_safe), as does the grasp service
@pytest.mark.slow
def test_arm_lost_during_a_grasp_from_ros_publishes_the_fault(
    procs: _Procs, tmp_path: Path
) -> None:
    """The arm goes silent at the descent of a ``~grasp``: the loop makes the box safe,
    ``/softpad/outcome`` says fault in phase ``descend``, the link's diagnostics ERROR, and the
    node ends with one line and the hardware-fault exit code."""
    _, _, url = _arm(procs, "--lose-arm-on", "descend")
    node, log = procs.start(
        "node", SOFTPAD, "ros", "node", "--box", url, "--robot", "ros1://", "--place", "banana"
    )
    logs = _watch(procs, *_LOOP_TOPICS, "/diagnostics")
    _wait(
        lambda: "position" in logs["/softpad/plan/grasps"].read_text(), 90.0, "the banana planned"
    )
    procs.run("rosservice", "call", "/softpad/grasp", timeout_s=180)  # may end with the node
    outcome = _outcome(logs)
    assert outcome["outcome"] == "fault" and outcome["phase"] == "descend", outcome
    assert "arm lost" in outcome["message"]
    assert node.wait(30) == 3, log.read_text()  # the hardware-fault exit code
    lines = [s for s in log.read_text().splitlines() if "error" in s]
    assert len(lines) == 1 and "arm lost" in lines[0] and "Traceback" not in log.read_text()
    diag = logs["/diagnostics"].read_text()
    assert re.search(r'level: 2\n\s*name: "softpad: link"\n\s*message: "[^"]*arm lost', diag), diag[
        -800:
    ]
