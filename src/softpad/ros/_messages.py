"""Conversions between SoftPad values and ROS 1 standard messages (no logic of their own).

Imported only after :func:`softpad.ros.ensure_rospy` (the message packages come with ROS).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from softpad import thesis
from softpad.layout import PadLayout, PadPose

#: Frame of the pad (DESIGN.md: origin at the bottom-left corner, z up out of the pad).
PAD_FRAME = "softpad"


def module_frame(k: int) -> str:
    """Frame name of module ``k`` (1-based): ``softpad_module_K``."""
    return f"softpad_module_{k}"


def quaternion_z(yaw_rad: float) -> tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a rotation by ``yaw_rad`` about z."""
    return 0.0, 0.0, math.sin(yaw_rad / 2.0), math.cos(yaw_rad / 2.0)


def yaw_of(q: Any) -> float:
    """Rotation about z of a geometry_msgs/Quaternion (the planner's poses are planar)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose(x_m: float, y_m: float, z_m: float, yaw_rad: float) -> Any:
    """geometry_msgs/Pose at (x, y, z) rotated by ``yaw_rad`` about z."""
    from geometry_msgs.msg import Point, Pose, Quaternion

    return Pose(Point(x_m, y_m, z_m), Quaternion(*quaternion_z(yaw_rad)))


def fluid_pressure(
    stamp: Any,
    k: int,
    gauge_pa: float,
    ambient_pa: float = thesis.AMBIENT_PRESSURE_PA,
    variance_pa2: float = thesis.SENSOR_VARIANCE_PA2,
) -> Any:
    """sensor_msgs/FluidPressure of module ``k``: absolute (the message's definition), the
    gauge reading plus ``ambient_pa``, Pa; ``variance_pa2`` that of the sensor model, Pa^2."""
    from sensor_msgs.msg import FluidPressure

    msg = FluidPressure(fluid_pressure=float(gauge_pa) + ambient_pa, variance=variance_pa2)
    msg.header.stamp, msg.header.frame_id = stamp, module_frame(k)
    return msg


def labelled_array(values: Sequence[float], label: str) -> Any:
    """std_msgs/Float64MultiArray, one dimension named ``label``."""
    from std_msgs.msg import Float64MultiArray, MultiArrayDimension

    msg = Float64MultiArray(data=[float(v) for v in values])
    msg.layout.dim = [MultiArrayDimension(label=label, size=len(msg.data), stride=len(msg.data))]
    return msg


def pose_array(stamp: Any, poses: Sequence[Any]) -> Any:
    """geometry_msgs/PoseArray in the pad frame."""
    from geometry_msgs.msg import PoseArray

    msg = PoseArray(poses=list(poses))
    msg.header.stamp, msg.header.frame_id = stamp, PAD_FRAME
    return msg


def object_poses(plans: Sequence[dict[str, Any]], layout: PadLayout) -> list[Any]:
    """One pose per object at its PCOM on the pad surface (orientation: identity), metres;
    ``plans`` as :meth:`GraspPlan.to_dict <softpad.planning.GraspPlan.to_dict>` gives them
    (the loop's ``plan`` event carries them so)."""
    xy = [layout.to_metres(tuple(p["pcom"])) for p in plans]
    return [pose(float(x), float(y), 0.0, 0.0) for x, y in xy]


def grasp_poses(plans: Sequence[dict[str, Any]]) -> list[Any]:
    """One pose per object at its COG on the pad surface, yaw = closing direction theta;
    ``plans`` as :meth:`GraspPlan.to_dict <softpad.planning.GraspPlan.to_dict>` gives them."""
    return [pose(float(p["cog_m"][0]), float(p["cog_m"][1]), 0.0, float(p["theta"])) for p in plans]


def static_transform(stamp: Any, pad: PadPose, base_frame: str) -> Any:
    """tf2_msgs/TFMessage with the transform base_frame -> softpad (the pad's pose in the base)."""
    from geometry_msgs.msg import Quaternion, TransformStamped, Vector3
    from tf2_msgs.msg import TFMessage

    t = TransformStamped()
    t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, base_frame, PAD_FRAME
    t.transform.translation = Vector3(pad.x_m, pad.y_m, pad.z_m)
    t.transform.rotation = Quaternion(*quaternion_z(pad.yaw_rad))
    return TFMessage(transforms=[t])


def module_transforms(stamp: Any, layout: PadLayout) -> list[Any]:
    """Transforms softpad -> softpad_module_K at each module's centre (pad surface)."""
    from geometry_msgs.msg import Quaternion, TransformStamped, Vector3

    out = []
    for k in range(1, layout.n_modules + 1):
        x, y = layout.center(k)
        t = TransformStamped()
        t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, PAD_FRAME, module_frame(k)
        t.transform.translation = Vector3(x * layout.pitch_m, y * layout.pitch_m, 0.0)
        t.transform.rotation = Quaternion(0.0, 0.0, 0.0, 1.0)
        out.append(t)
    return out


def diagnostic_status(level: int, name: str, message: str, **values: object) -> Any:
    """diagnostic_msgs/DiagnosticStatus (level 0 OK, 1 WARN, 2 ERROR) with key/values."""
    from diagnostic_msgs.msg import DiagnosticStatus, KeyValue

    return DiagnosticStatus(
        level=level,
        name=name,
        message=message,
        hardware_id="softpad",
        values=[KeyValue(key=k, value=str(v)) for k, v in values.items()],
    )
