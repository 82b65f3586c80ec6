"""The ROS adapters' checks that need no ROS master (and most no ROS at all)."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from softpad.errors import InputError
from softpad.ros import ROS_MODULES, NodeConfig, load_config, open_robot
from softpad.ros._rospy_path import DIST_PACKAGES


def test_node_config_file_and_overrides(tmp_path: Path) -> None:
    f = tmp_path / "pad.json"
    f.write_text(json.dumps({"box": "zenoh://127.0.0.1:5757", "pad_x_m": 0.6, "pad_yaw_rad": 1.5}))
    c = load_config(f)
    assert c.box == "zenoh://127.0.0.1:5757" and c.pad.x_m == 0.6 and c.pad.yaw_rad == 1.5
    c2 = c.updated({"pad_x_m": 0.5, "place": "banana,toy", "contact_threshold_pa": 120})
    assert c2.pad.x_m == 0.5 and c2.pad.yaw_rad == 1.5  # one field overridden, others kept
    assert c2.place == ("banana", "toy") and c2.contact_threshold_pa == 120.0
    assert load_config(None) == NodeConfig()


@pytest.mark.parametrize(
    ("values", "words"),
    [
        ({"pad_x": 1.0}, "unknown node setting 'pad_x'"),
        ({"pad_z_m": math.nan}, "pad_z_m must be a finite number"),
        ({"pad_y_m": "1"}, "pad_y_m must be a finite number"),
        ({"settle_s": -1.0}, "settle_s must be >= 0"),
        ({"hold_s": -1.0}, "hold_s must be >= 0"),
        ({"robot": "ur5://"}, "unknown robot 'ur5'; available: "),
        ({"robot": "sim"}, "robot must be a URL such as sim:// or ros1://"),
        ({"gripper": "5/5"}, "gripper mounting must be one of 10/4, 6/2, 4/0"),
    ],
)
def test_node_config_rejects_bad_values(values: dict[str, object], words: str) -> None:
    with pytest.raises(InputError, match=words):
        NodeConfig().updated(values)


def test_node_config_file_errors(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="cannot read node config"):
        load_config(tmp_path / "missing.json")
    (tmp_path / "list.json").write_text("[1]")
    with pytest.raises(InputError, match="must hold a JSON object"):
        load_config(tmp_path / "list.json")


@pytest.mark.parametrize(
    ("url", "words"),
    [
        ("ur5://", "unknown robot URL"),
        ("ros1://robot.example:11311", "takes no host"),
        ("ros1://?speed=2", "unknown ros1:// option 'speed'"),
        ("ros1://?timeout_s=abc", "must be numbers"),
        ("ros1://?stale_s=0", r"must be in \(0, 3600\)"),
    ],
)
def test_robot_urls_are_checked_before_ros_is_touched(url: str, words: str) -> None:
    with pytest.raises(InputError, match=words):
        open_robot(url)


def test_only_ros_modules_come_from_the_system_python() -> None:
    """rospy imports, but the system's other packages stay invisible to the environment."""
    if not os.path.isdir(os.path.join(DIST_PACKAGES, "rospy")):
        pytest.skip(f"no rospy in {DIST_PACKAGES} (make ros-deps installs it)")
    assert not {"numpy", "matplotlib", "scipy", "paramiko", "apt"} & ROS_MODULES
    others = [
        n
        for n in ("paramiko", "apt", "httplib2", "cryptography")
        if os.path.isdir(os.path.join(DIST_PACKAGES, n))
    ]
    code = (
        "import importlib.util, json, sys; from softpad.ros import ensure_rospy; ensure_rospy();"
        "import std_msgs.msg, numpy;"
        "print(json.dumps([numpy.__file__.startswith(sys.prefix),"
        f" [importlib.util.find_spec(n) is None for n in {others!r}]]))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == [True, [True] * len(others)]


def _softpad(*args: str, **env: str) -> subprocess.CompletedProcess[str]:
    exe = str(Path(sys.executable).with_name("softpad"))
    return subprocess.run(
        [exe, *args], capture_output=True, text=True, env={**os.environ, **env}, check=False
    )


def test_without_ros_the_node_says_how_to_install_it() -> None:
    if os.path.isdir(os.path.join(sys.prefix, "lib", "python3.11", "site-packages", "rospy")):
        pytest.skip("rospy is installed inside the environment")
    r = _softpad("ros", "node", "--box", "sim://", SOFTPAD_ROS_DIST_PACKAGES="/nonexistent")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "apt-get install -y ros-core python3-rospy" in r.stderr


def test_run_with_an_unknown_robot_is_one_line() -> None:
    r = _softpad("run", "--robot", "ur5://", "--objects", "banana")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "ur5://" in r.stderr


def test_without_a_master_the_node_says_so_at_once(free_port) -> None:
    from softpad.ros import rospy_available

    if not rospy_available():
        pytest.skip("ROS 1 not installed (make ros-deps)")
    port = free_port()  # a loopback port where no master listens
    r = _softpad(
        "ros", "node", "--box", "sim://", ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_IP="127.0.0.1", ROS_HOSTNAME="localhost",
    )  # fmt: skip
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    assert f"no ROS master answers at http://127.0.0.1:{port}" in r.stderr


def test_run_with_ros_without_a_master_is_one_line(free_port) -> None:
    """``softpad run --ros`` with no master: the node's one-line error, exit 2, no run (stdout
    holds only the first line that names the box, issue 51)."""
    from softpad.ros import rospy_available

    if not rospy_available():
        pytest.skip("ROS 1 not installed (make ros-deps)")
    port = free_port()
    r = _softpad(
        "run", "--ros", "--objects", "object-5", ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_IP="127.0.0.1", ROS_HOSTNAME="localhost",
    )  # fmt: skip
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    assert r.stdout.splitlines() == ["softpad run: object-5 on sim://"]
    assert f"no ROS master answers at http://127.0.0.1:{port}" in r.stderr


def test_the_loop_publisher_translates_the_loops_report() -> None:
    """LoopPublisher (no ROS needed with stand-in topics): every frame passes with the
    contact state, true from the loop's contact until the grasp's release; a plan goes to
    the objects and grasps; the phase is passed on; a fault is the link's error and an
    outcome; finish() publishes the result's dict."""
    import numpy as np

    from softpad.box import PressureFrame
    from softpad.ros import LoopPublisher

    class Topics:
        fault: str | None = None

        def __init__(self) -> None:
            self.calls: list[tuple[str, object]] = []

        def __getattr__(self, name: str):  # type: ignore[no-untyped-def]
            return lambda *a: self.calls.append((name, a[0] if a else None))

    class Result:
        def to_dict(self) -> dict[str, str]:
            return {"outcome": "held"}

    topics = Topics()
    loop = LoopPublisher(topics)  # type: ignore[arg-type]
    frame = PressureFrame(0.0, np.zeros(6), 0.0)
    touching = []
    for kind, data in [
        ("phase", {"phase": "descend"}), ("frame", None), ("contact", {"modules": [5]}),
        ("frame", None), ("phase", {"phase": "hold"}), ("frame", None),
        ("phase", {"phase": "release"}), ("frame", None),
    ]:  # fmt: skip
        if kind == "frame":
            loop.frame(frame, "x")
            touching.append(topics.calls[-1])
        else:
            loop.event(1.0, kind, **(data or {}))
    assert touching == [("contact", False), ("contact", True), ("contact", True),
                        ("contact", False)]  # fmt: skip
    loop.event(2.0, "plan", increments_pa=[], objects=[{"cog_m": [0, 0]}])
    assert topics.calls[-1] == ("plans", [{"cog_m": [0, 0]}])
    loop.event(3.0, "fault", message="arm lost", phase="descend")
    assert topics.fault == "arm lost" and topics.calls[-2] == ("diagnostics", None)
    assert topics.calls[-1] == (
        "outcome", {"outcome": "fault", "t_s": 3.0, "message": "arm lost", "phase": "descend"}
    )  # fmt: skip
    loop.finish(Result())
    assert topics.calls[-1] == ("outcome", {"outcome": "held"})
    loop.error("no object placed on the pad within 30 s")
    assert topics.calls[-1] == (
        "outcome", {"outcome": "error", "message": "no object placed on the pad within 30 s"}
    )  # fmt: skip


def test_a_retry_republishes_the_grasp_under_way() -> None:
    """An ``approach`` to another grasp of a planned object (a retry) republishes
    /softpad/plan/grasps with it (COG in metres from the pad's pitch); the planned grasp's own
    approach publishes nothing more."""
    from softpad.layout import PadLayout
    from softpad.ros import LoopPublisher

    class Topics:
        layout = PadLayout()

        def __init__(self) -> None:
            self.published: list[list[dict[str, object]]] = []
            self.events: list[str] = []

        def phase(self, name: str) -> None:
            pass

        def event(self, t_s: float, kind: str, data: dict[str, object]) -> None:
            self.events.append(kind)

        def plans(self, plans: list[dict[str, object]]) -> None:
            self.published.append([dict(p) for p in plans])

    topics = Topics()
    loop = LoopPublisher(topics)  # type: ignore[arg-type]
    planned = {"modules": [1, 2], "pcom": [1.0, 1.5], "cog": [1.0, 1.5], "theta": 0.0,
               "cog_m": [0.045, 0.0675], "rule": "n2"}  # fmt: skip
    loop.event(1.0, "plan", increments_pa=[], objects=[planned])
    loop.event(1.1, "phase", phase="approach", modules=[1, 2], cog=[1.0, 1.5], theta=0.0)
    assert len(topics.published) == 1
    loop.event(5.0, "phase", phase="approach", modules=[1, 2], cog=[1.2, 1.5], theta=1.0)
    assert len(topics.published) == 2
    (again,) = topics.published[-1]
    assert again["theta"] == 1.0 and again["cog"] == [1.2, 1.5]
    assert again["cog_m"] == pytest.approx([1.2 * 0.045, 1.5 * 0.045], abs=1e-12)
    assert again["pcom"] == [1.0, 1.5]  # the object is where it was
    assert topics.events == ["plan", "phase", "phase"]  # every event on /softpad/events


def test_only_an_in_process_simulator_is_paced() -> None:
    """Frames of an in-process ``sim://`` box (lock-step, faster than real time; also behind
    a BoxWrapper) are paced to the wall clock; a box that sends frames at its own rate is not
    (pacing it would only delay the loop's reads)."""
    from softpad.box import BoxWrapper, open_box
    from softpad.ros import PadPublishers

    pubs = PadPublishers.__new__(PadPublishers)  # the box's setter needs no ROS
    with open_box("sim://") as sim:
        pubs.box = sim
        assert pubs.pace
        pubs.box = BoxWrapper(sim)
        assert pubs.pace
    pubs.box = object()  # a served or hardware box: any other kind
    assert not pubs.pace
