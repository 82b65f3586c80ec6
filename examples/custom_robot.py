"""A robot adapter that logs its commands, driving the same execution.

Any object with the methods of ``softpad.control.Robot`` drives the loop. This one wraps the
simulated robot (a ``softpad.control.RobotWrapper``, which forwards every call) and keeps a log
of every command, the way an adapter to a real arm would translate and forward them.

Run: .venv/bin/python examples/custom_robot.py
"""

from __future__ import annotations

from softpad.box import SimBox
from softpad.control import ExecutionParams, GraspExecution, Robot, RobotWrapper, ToolPose
from softpad.harness import SimulatedRobot
from softpad.sim import SimGripper, get_object


class LoggingRobot(RobotWrapper):
    """Forwards every command to another robot and remembers it (what is not overridden here,
    the robot's state, motion and holding, ``RobotWrapper`` forwards unchanged)."""

    def __init__(self, inner: Robot) -> None:
        super().__init__(inner)
        self.commands: list[str] = []

    def move_to(self, pose: ToolPose, speed_m_s: float) -> None:
        self.commands.append(f"move_to z={pose.z_m:.3f} m")
        super().move_to(pose, speed_m_s)

    def descend(self, speed_m_s: float, min_z_m: float) -> None:
        self.commands.append(f"descend at {speed_m_s:g} m/s")
        super().descend(speed_m_s, min_z_m)

    def stop(self) -> None:
        self.commands.append("stop")
        super().stop()

    def set_gripper(self, width_m: float, speed_m_s: float) -> None:
        self.commands.append(f"gripper {width_m:.3f} m")
        super().set_gripper(width_m, speed_m_s)


def main() -> dict[str, object]:
    box = SimBox(seed=2)
    world = box.world
    obj = get_object("object-5")
    world.gripper = SimGripper.mounting(obj.gripper)  # the thesis's mounting for it
    robot = LoggingRobot(SimulatedRobot(world))
    execution = GraspExecution(
        box,
        robot,
        world.layout,
        ExecutionParams(hold_s=1.0),
        place_objects=lambda: world.place_object(obj),
    )
    with box:
        result = execution.run()
    for c in robot.commands:
        print(c)
    print(f"outcome: {result.outcome}")
    return {"outcome": result.outcome, "commands": robot.commands}


if __name__ == "__main__":
    main()
