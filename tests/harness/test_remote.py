"""The simulated world and robot served over zenoh (RemoteRobot, simulation_extensions)."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.box import ValveCommand, ZenohBox, open_box, simulator_of
from softpad.control import ExecutionParams, ToolPose
from softpad.errors import InputError
from softpad.harness import RemoteRobot, run_simulated
from softpad.record import RunLog


def test_remote_robot_moves_the_served_gripper(served) -> None:
    with served() as (_daemon, url), open_box(url) as box:
        assert isinstance(box, ZenohBox)
        remote = RemoteRobot(box, gripper="10/4")
        assert (remote.layout.rows, remote.layout.cols) == (2, 3)
        remote.set_gripper(0.08, 0.1)  # closing to 0.08 m on nothing: reached, holds nothing
        while remote.is_moving():
            box.read()
        assert remote.state().width_m == pytest.approx(0.08, abs=1e-6)
        assert remote.holding() is False
        remote.move_to(ToolPose(0.05, 0.04, 0.03, 0.3), 0.5)
        while remote.is_moving():
            box.read()
        s = remote.state()
        np.testing.assert_allclose(
            [s.x_m, s.y_m, s.z_m, s.yaw_rad], [0.05, 0.04, 0.03, 0.3], atol=1e-9
        )
        assert remote.holding() is False and remote.touches() == []


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda r: r.descend(float("nan"), 0.001), "cannot be sent"),
        (
            lambda r: r._call("robot.descend", speed_m_s=None, min_z_m=0.0),
            "speed_m_s must be a finite number, got None",
        ),
        (lambda r: r.set_gripper(0.01, -1.0), "robot speed must be > 0"),
        (lambda r: r.place(["teapot"]), "unknown object 'teapot'"),
        (lambda r: r._call("sim.place", objects="banana"), "objects must be a list of names"),
        (lambda r: r._call("robot.fly"), "unknown service 'robot.fly'"),
        (lambda r: r._call("sim.setup", gripper="12/5"), "12/5"),
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
def test_bad_remote_requests_are_input_errors(call, match: str, served) -> None:
    with served() as (daemon, url), open_box(url) as box:
        assert isinstance(box, ZenohBox)
        robot = RemoteRobot(box)
        with pytest.raises(InputError, match=match):
            call(robot)
        box.read()  # the session goes on
        assert daemon.controller == box.client_id


def test_loop_over_zenoh_holds_object_5_with_the_local_plan_and_closes_valves(served) -> None:
    params = ExecutionParams(hold_s=0.5)
    log = RunLog()
    with served(lockstep_frames=2) as (daemon, url):
        result = run_simulated(["object-5"], url, params, recorder=log)
        local = run_simulated(["object-5"], "sim://?seed=4", params)
        assert result.outcome == local.outcome == "held"
        assert [g.plan.modules for g in result.result.grasps] == [
            g.plan.modules for g in local.result.grasps
        ]
        np.testing.assert_allclose(
            [g.plan.cog for g in result.result.grasps],
            [g.plan.cog for g in local.result.grasps],
            atol=0.05,
        )
        assert len(log) > 100
        box = daemon.box
        assert simulator_of(box) is not None
        assert set(box.valves) == {ValveCommand.CLOSED}
        assert daemon.controller is None


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
