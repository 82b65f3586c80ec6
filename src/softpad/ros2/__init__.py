"""ROS 2 adapters (rclpy): the pad as a ROS 2 node, and a run that ROS 2 watches.

Translation only, over the same loop as ``softpad run`` and the ROS 1 node: the topics are the
``ros2`` rows of the one table (:mod:`softpad.topics`), grasps are the action
``/softpad/grasp`` (``softpad_msgs/action/Grasp``). rclpy and the standard messages come from
the package index's wheels (``pip install 'softpad[ros2]'``); ``tf2_msgs`` and
``softpad_msgs`` are built locally from the table's definitions (:func:`build_interfaces`).
Everything here imports rclpy lazily, so ``import softpad.ros2`` works without ROS 2; every
node keeps to loopback (:func:`loopback_environment`). docs/ros.md, "ROS 2".
"""

from softpad.ros2._interfaces import (
    INSTALL_HINT,
    LOCAL_PACKAGES,
    apply_loopback_environment,
    build_interfaces,
    ensure_rclpy,
    fastdds_profile,
    interfaces_available,
    loopback_environment,
    rclpy_available,
    write_packages,
)
from softpad.ros2._node import (
    GraspCanceled,
    Ros2LoopPublisher,
    Ros2PadNode,
    Ros2RunPublisher,
    declare_parameters,
    watch_loop2,
)
from softpad.ros2._publish import Ros2Publishers, message_class, qos_profile

__all__ = [
    "INSTALL_HINT",
    "LOCAL_PACKAGES",
    "GraspCanceled",
    "Ros2LoopPublisher",
    "Ros2PadNode",
    "Ros2Publishers",
    "Ros2RunPublisher",
    "apply_loopback_environment",
    "build_interfaces",
    "declare_parameters",
    "ensure_rclpy",
    "fastdds_profile",
    "interfaces_available",
    "loopback_environment",
    "message_class",
    "qos_profile",
    "rclpy_available",
    "watch_loop2",
    "write_packages",
]
