"""Conversions between SoftPad values and ROS standard messages (no logic of their own), for
ROS 1 and ROS 2 alike: both name their message modules the same (``geometry_msgs.msg``, ...)
and take keyword arguments; numbers are given as Python floats (rclpy checks the types).

The message classes are imported when called: after :func:`softpad.ros.ensure_rospy` in a
ROS 1 process, with rclpy's wheels in a ROS 2 one (a process speaks one ROS).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from softpad import thesis
from softpad.layout import PadLayout

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


def header(stamp: Any, frame_id: str) -> Any:
    """std_msgs/Header (ROS 1's ``seq`` left to rospy)."""
    from std_msgs.msg import Header

    return Header(stamp=stamp, frame_id=frame_id)


def _quaternion(yaw_rad: float) -> Any:
    from geometry_msgs.msg import Quaternion

    qx, qy, qz, qw = quaternion_z(float(yaw_rad))
    return Quaternion(x=qx, y=qy, z=qz, w=qw)


def pose(x_m: float, y_m: float, z_m: float, yaw_rad: float) -> Any:
    """geometry_msgs/Pose at (x, y, z), metres, rotated by ``yaw_rad`` about z."""
    from geometry_msgs.msg import Point, Pose

    position = Point(x=float(x_m), y=float(y_m), z=float(z_m))
    return Pose(position=position, orientation=_quaternion(yaw_rad))


def fluid_pressure(
    stamp: Any,
    frame_id: str,
    gauge_pa: float,
    ambient_pa: float = thesis.AMBIENT_PRESSURE_PA,
    variance_pa2: float = thesis.SENSOR_VARIANCE_PA2,
) -> Any:
    """sensor_msgs/FluidPressure in ``frame_id``: absolute (the message's definition), the
    gauge reading plus ``ambient_pa``, Pa; ``variance_pa2`` that of the sensor model, Pa^2."""
    from sensor_msgs.msg import FluidPressure

    return FluidPressure(
        header=header(stamp, frame_id),
        fluid_pressure=float(gauge_pa) + float(ambient_pa),
        variance=float(variance_pa2),
    )


def labelled_array(values: Sequence[float], label: str) -> Any:
    """std_msgs/Float64MultiArray, one dimension named ``label``."""
    from std_msgs.msg import Float64MultiArray, MultiArrayDimension

    msg = Float64MultiArray(data=[float(v) for v in values])
    msg.layout.dim = [MultiArrayDimension(label=label, size=len(msg.data), stride=len(msg.data))]
    return msg


def pose_array(stamp: Any, poses: Sequence[Any]) -> Any:
    """geometry_msgs/PoseArray in the pad frame."""
    from geometry_msgs.msg import PoseArray

    return PoseArray(header=header(stamp, PAD_FRAME), poses=list(poses))


def object_poses(plans: Sequence[dict[str, Any]], layout: PadLayout) -> list[Any]:
    """One pose per object at its PCOM on the pad surface (orientation: identity), metres;
    ``plans`` as :meth:`GraspPlan.to_dict <softpad.planning.GraspPlan.to_dict>` gives them
    (the loop's ``plan`` event carries them so)."""
    xy = [layout.to_metres(tuple(p["pcom"])) for p in plans]
    return [pose(float(x), float(y), 0.0, 0.0) for x, y in xy]


def grasp_poses(plans: Sequence[dict[str, Any]]) -> list[Any]:
    """One geometry_msgs/Pose per object at its COG on the pad surface, metres, yaw = closing
    direction theta (ROS 1 or ROS 2: whichever this process speaks).

    Parameters
    ----------
    plans
        As :meth:`GraspPlan.to_dict <softpad.planning.GraspPlan.to_dict>` gives them.
    """
    return [pose(float(p["cog_m"][0]), float(p["cog_m"][1]), 0.0, float(p["theta"])) for p in plans]


def static_transforms(
    stamp: Any, frames: Sequence[tuple[str, str, tuple[float, float, float, float]]]
) -> Any:
    """tf2_msgs/TFMessage of ``frames``: ``(parent, child, (x, y, z, yaw))``, metres and
    radians, as :func:`softpad.topics.static_frames` gives them."""
    from geometry_msgs.msg import Transform, TransformStamped, Vector3
    from tf2_msgs.msg import TFMessage

    out = []
    for parent, child, (x, y, z, yaw) in frames:
        shift = Vector3(x=float(x), y=float(y), z=float(z))
        out.append(
            TransformStamped(
                header=header(stamp, parent),
                child_frame_id=child,
                transform=Transform(translation=shift, rotation=_quaternion(yaw)),
            )
        )
    return TFMessage(transforms=out)


def diagnostic_status(level: int, name: str, message: str, **values: object) -> Any:
    """diagnostic_msgs/DiagnosticStatus (level 0 OK, 1 WARN, 2 ERROR) with key/values: the
    level an int on ROS 1, one byte on ROS 2 (its ``byte`` type)."""
    from diagnostic_msgs.msg import DiagnosticStatus, KeyValue

    ros2 = hasattr(DiagnosticStatus, "get_fields_and_field_types")  # rosidl's classes
    return DiagnosticStatus(
        level=bytes([level]) if ros2 else level,
        name=name,
        message=message,
        hardware_id="softpad",
        values=[KeyValue(key=k, value=str(v)) for k, v in values.items()],
    )


def jsonable(value: Any) -> Any:
    """``value`` ready for ``json.dumps``: NaN and infinities as None (JSON has no such
    numbers), NumPy values as Python ones, Enum members as their values.

    Parameters
    ----------
    value
        Any nesting of dicts, lists and tuples of numbers, strings, arrays and Enum members.
    """
    if isinstance(value, float | np.floating):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if hasattr(value, "value") and hasattr(value, "name"):  # an Enum member
        return value.value
    return value
