"""The one assembly of the grasp loop (softpad.harness.build_loop) and the one question "is
this box simulated?" (Box.simulated)."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import softpad
from softpad.box import Box, BoxDaemon, BoxWrapper, PressureFrame, ZenohBox, open_box, simulator_of
from softpad.config import Installation, Thresholds
from softpad.control import ExecutionParams, GraspExecution
from softpad.errors import InputError
from softpad.harness import BuiltLoop, SimulatedRobot, build_loop, execution_params, world_access
from softpad.planning import GripperAwarePlanner, ThesisPlanner
from softpad.sensing import ThesisContactDetector

SRC = Path(softpad.__file__).parent


class _RealBox(Box):
    """A box with no simulator behind it (what a real back-end looks like to the loop)."""

    channels = 8
    sample_rate_hz = 100.0

    def __init__(self) -> None:
        super().__init__()
        self.t_s = 0.0

    def _read(self) -> PressureFrame:
        self.t_s += 0.01
        return PressureFrame(self.t_s, np.zeros(8), 50e3)

    def _apply_valve(self, channel, command) -> None:
        pass

    def _close(self) -> None:
        pass


def _constructions(name: str) -> list[str]:
    """``path:line`` of every call ``name(...)`` or ``x.name(...)`` in src/softpad."""
    found = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                f = node.func
                called = f.id if isinstance(f, ast.Name) else getattr(f, "attr", None)
                if called == name:
                    found.append(f"{path.relative_to(SRC)}:{node.lineno}")
    return found


def test_the_loop_is_constructed_in_one_place() -> None:
    assert [c.split(":")[0] for c in _constructions("GraspExecution")] == ["harness/_assembly.py"]


def test_the_construction_finder_sees_calls(tmp_path: Path, monkeypatch) -> None:
    (tmp_path / "m.py").write_text("a = GraspExecution(1)\nb = control.GraspExecution(2)\n")
    monkeypatch.setattr(f"{__name__}.SRC", tmp_path)
    assert _constructions("GraspExecution") == ["m.py:1", "m.py:2"]


def test_simulated_is_asked_of_the_box_and_seen_through_views() -> None:
    with open_box("sim://?seed=1") as box:
        assert box.simulated and isinstance(box, BoxWrapper)  # the sim:// layers
        sim = simulator_of(box)
        assert sim is not None and sim.simulated
        assert BoxWrapper(box, owns_inner=False).simulated


def test_a_box_without_a_simulator_is_not_simulated() -> None:
    box = _RealBox()
    assert box.simulated is False and world_access(box) is None
    assert BoxWrapper(box).simulated is False


def test_a_served_simulator_is_simulated(served) -> None:
    with served() as (_daemon, url), open_box(url) as box:
        assert isinstance(box, ZenohBox) and box.simulated
        access = world_access(box)
        assert access is not None and access.setup("6/2").n_modules == 6


def test_a_box_served_without_the_world_requests_is_not_simulated(free_port) -> None:
    port = free_port()
    with BoxDaemon(open_box("sim://?seed=4"), (f"tcp/127.0.0.1:{port}",)):
        with open_box(f"zenoh://127.0.0.1:{port}?timeout_s=60") as box:
            assert box.info.get("services") == [] and box.simulated is False
            assert world_access(box) is None


def test_build_loop_places_objects_and_holds_object_5() -> None:
    with open_box("sim://?seed=3") as box:
        with build_loop(box, objects=["object-5"]) as loop:
            assert isinstance(loop, BuiltLoop) and isinstance(loop.robot, SimulatedRobot)
            assert isinstance(loop.execution, GraspExecution)
            result = loop.run()
            touches = loop.touches()
    assert result.outcome == "held"
    assert touches is not None and touches[0].first_touch_s is not None


def test_build_loop_makes_named_parts_for_the_pad_and_gripper() -> None:
    with open_box("sim://?seed=3") as box:
        loop = build_loop(box, planner="gripper-aware", contact_detector="thesis", gripper="6/2")
        assert isinstance(loop.execution.planner, GripperAwarePlanner)
        assert isinstance(loop.execution.contact_detector, ThesisContactDetector)
        world = simulator_of(box).world  # type: ignore[union-attr]
        assert world.gripper.max_width_m == pytest.approx(0.06)  # the 6/2 mounting installed
        default = build_loop(box)
        assert isinstance(default.execution.planner, ThesisPlanner)


def test_an_unknown_part_name_is_an_input_error() -> None:
    with open_box("sim://?seed=3") as box, pytest.raises(InputError, match="no-such"):
        build_loop(box, planner="no-such")


def test_the_installation_sets_the_site_limits_and_fills_missing_params() -> None:
    site = Installation(
        thresholds=Thresholds(
            adjust_tolerance_pa=40.0,
            object_threshold_pa=70.0,
            contact_threshold_pa=120.0,
            filter_window=8,
            max_pressure_pa=2500.0,
        )
    )
    own = execution_params(None, site)
    assert (own.contact_threshold_pa, own.planner.object_threshold_pa) == (120.0, 70.0)
    assert (own.filter_length, own.inflation.filter_length) == (8, 8)
    given = execution_params(ExecutionParams(contact_threshold_pa=95.0), site)
    assert given.contact_threshold_pa == 95.0  # the caller's thresholds stay
    assert (given.inflation.tolerance_pa, given.inflation.max_pressure_pa) == (40.0, 2500.0)
    assert execution_params(None, None) == ExecutionParams()


def test_a_box_without_a_simulated_world_needs_a_robot() -> None:
    with pytest.raises(InputError, match="no robot for a _RealBox"):
        build_loop(_RealBox())


def test_a_robot_made_from_a_url_is_closed_with_the_loop(monkeypatch) -> None:
    from softpad.control import ROBOT_REGISTRY

    closed = []

    class Arm(SimulatedRobot):
        def close(self) -> None:
            closed.append(True)

    def factory(location, options, context):
        return Arm(simulator_of(context.box).world)

    ROBOT_REGISTRY.register("testarm", factory, "a test arm")
    try:
        with open_box("sim://?seed=3") as box:
            with build_loop(box, "testarm://") as loop:
                assert loop.owns_robot and isinstance(loop.robot, Arm)
            assert closed == [True]
            given = Arm(simulator_of(box).world)  # type: ignore[union-attr]
            with build_loop(box, given) as loop:
                assert not loop.owns_robot
            assert closed == [True]  # the caller's robot is the caller's to close
    finally:
        ROBOT_REGISTRY.unregister("testarm")
