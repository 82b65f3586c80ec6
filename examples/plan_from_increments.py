"""Plan the grasp of the thesis's banana from the increments of its three modules.

Run: .venv/bin/python examples/plan_from_increments.py
"""

from __future__ import annotations

import math

from softpad.layout import PadLayout, PadPose
from softpad.planning import plan_grasps


def main() -> dict[str, float]:
    layout = PadLayout(rows=2, cols=3, pitch_m=0.045)
    # Pressure increments over the saved reference, pascals, modules 1..6.
    delta_pa = [0.0, 124.0, 78.0, 109.0, 0.0, 0.0]
    (plan,) = plan_grasps(delta_pa, layout)
    # The pad lies 40 cm in front of the robot, rotated by 90 degrees.
    pose = PadPose(x_m=0.40, y_m=-0.10, z_m=0.02, yaw_rad=math.pi / 2)
    target = pose.to_base(plan.cog_m(layout))
    yaw = pose.yaw_to_base(plan.theta)
    print(f"modules {plan.modules}, rule {plan.rule}")
    print(f"COG {plan.cog} module units, theta {math.degrees(plan.theta):+.0f} deg")
    print(
        f"robot target ({target[0]:.3f}, {target[1]:.3f}, {target[2]:.3f}) m, yaw {math.degrees(yaw):+.0f} deg"
    )
    return {"x": float(target[0]), "y": float(target[1]), "yaw": yaw}


if __name__ == "__main__":
    main()
