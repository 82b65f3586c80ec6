"""The simulated world and robot served over tcp:// (RemoteRobot, simulation_extensions)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from softpad.box import BoxServer, SimBox, TcpBox, ValveCommand, open_box
from softpad.control import ExecutionParams, ToolPose
from softpad.errors import InputError
from softpad.harness import RemoteRobot, SimulatedRobot, run_simulated, simulation_extensions
from softpad.record import RunLog


@pytest.fixture
def served(serve_box: Callable[..., BoxServer]) -> BoxServer:
    box = open_box("sim://?seed=4")
    assert isinstance(box, SimBox)
    return serve_box(box, extensions=simulation_extensions(box))


def test_remote_robot_moves_the_served_gripper_like_the_local_one(served: BoxServer) -> None:
    local_box = open_box("sim://?seed=4")
    assert isinstance(local_box, SimBox)
    local = SimulatedRobot(local_box.world)
    with open_box(served.url) as box:
        assert isinstance(box, TcpBox)
        remote = RemoteRobot(box, gripper="10/4")
        assert (remote.layout.rows, remote.layout.cols) == (2, 3)
        for robot, b in ((local, local_box), (remote, box)):
            robot.set_gripper(1.0, 0.1)
            robot.move_to(ToolPose(0.05, 0.04, 0.03, 0.3), 0.1)
            b.read_many(200)
        assert remote.state() == local.state()
        assert remote.is_moving() is local.is_moving() is False
        assert remote.holding() is local.holding() is False
        assert remote.touches() == local.touches == []
    local_box.close()


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda r: r.descend(float("nan"), 0.001), "cannot be sent"),
        (
            lambda r: r.box.request("robot.descend", speed_m_s=None, min_z_m=0.0),
            "speed_m_s must be a finite number, got None",
        ),
        (lambda r: r.set_gripper(0.01, -1.0), "robot speed must be > 0"),
        (lambda r: r.place(["teapot"]), "unknown object 'teapot'"),
        (lambda r: r.box.request("sim.place", objects="banana"), "objects must be a list of names"),
        (lambda r: r.box.request("robot.fly"), "does not offer 'robot.fly'"),
        (lambda r: r.box.request("sim.setup", gripper="12/5"), "12/5"),
        (lambda r: r.move_to(ToolPose(1e300, 0.0, 0.1, 0.0), 0.1), "x_m must be within"),
        (lambda r: r.set_gripper(-1.0, 0.1), "width_m must be within"),
    ],
    ids=[
        "nan",
        "missing",
        "negative-speed",
        "object",
        "objects-type",
        "unknown-op",
        "mounting",
        "x-1e300",
        "width-negative",
    ],
)
def test_bad_remote_requests_are_input_errors(served: BoxServer, call, match: str) -> None:
    with open_box(served.url) as box:
        assert isinstance(box, TcpBox)
        robot = RemoteRobot(box)
        with pytest.raises(InputError, match=match):
            call(robot)
        box.read()  # the session goes on


def test_loop_over_tcp_logs_the_same_frames_and_leaves_valves_closed(served: BoxServer) -> None:
    params = ExecutionParams(hold_s=0.5)
    remote_log, local_log = RunLog(), RunLog()
    result = run_simulated(["object-5"], served.url, params, recorder=remote_log)
    local = run_simulated(["object-5"], "sim://?seed=4", params, recorder=local_log)
    assert result.outcome == local.outcome == "held"
    assert result.to_dict() == local.to_dict()  # ground truth included
    np.testing.assert_array_equal(remote_log.t_s, local_log.t_s)
    np.testing.assert_array_equal(remote_log.pressures_pa, local_log.pressures_pa)
    assert remote_log.events == local_log.events
    box = served.box
    assert isinstance(box, SimBox)
    assert set(box.valves) == {ValveCommand.CLOSED}


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda r: r.move_to(ToolPose(1e300, 0.0, 0.1, 0.0), 0.1), "x_m"),
        (lambda r: r.move_to(ToolPose(0.0, 0.0, -5.0, 0.0), 0.1), "z_m"),
        (lambda r: r.set_gripper(-1.0, 0.1), "width_m"),
        (lambda r: r.move_to(ToolPose(0.0, 0.0, 0.1, 0.0), 1e9), "speed"),
    ],
    ids=["x-1e300", "z-below", "width-negative", "speed-huge"],
)
def test_simulated_robot_refuses_targets_outside_workspace(call, match) -> None:
    from softpad.harness import SimulatedRobot
    from softpad.sim import AnalyticWorld

    with pytest.raises(InputError, match=match):
        call(SimulatedRobot(AnalyticWorld()))
