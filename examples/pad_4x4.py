"""A 4 x 4 pad planned and grasped through the same execution.

The layout, the simulated world and the box take the grid; the planner generalises the
thesis's rules to R x C pads (docs/planner.md). Object 5 lies across modules 6, 7 and 8.

Run: .venv/bin/python examples/pad_4x4.py
"""

from __future__ import annotations

import math

from softpad.box import SimBox
from softpad.control import ExecutionParams, GraspExecution
from softpad.harness import SimulatedRobot
from softpad.layout import PadLayout
from softpad.sim import AnalyticWorld, Placement, SimGripper, get_object


def main() -> dict[str, object]:
    layout = PadLayout(rows=4, cols=4)
    obj = get_object("object-5")
    world = AnalyticWorld(layout=layout, gripper=SimGripper.mounting(obj.gripper))
    box = SimBox(world, channels=16, seed=5)
    # the catalogue places it on the 2 x 3 pad; shift it by one module up and right
    p = obj.placement
    where = Placement(p.x_m + layout.pitch_m, p.y_m + layout.pitch_m, p.yaw_rad)
    execution = GraspExecution(
        box,
        SimulatedRobot(world),
        layout,
        ExecutionParams(hold_s=1.0),
        place_objects=lambda: world.place_object(obj, where),
    )
    with box:
        result = execution.run()
    plan = result.plans[0]
    print(f"modules {plan.modules}, COG {plan.cog}, theta {math.degrees(plan.theta):+.0f} deg")
    print(f"outcome: {result.outcome}")
    return {
        "modules": plan.modules,
        "cog": plan.cog,
        "theta": plan.theta,
        "outcome": result.outcome,
    }


if __name__ == "__main__":
    main()
