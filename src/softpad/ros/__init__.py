"""ROS 1 adapters: the pad as a rospy node, and a :class:`~softpad.control.Robot` reached
through ROS topics (``ros1://``); the ``softpad_msgs`` message package (events, the grasp action)
and the pad's URDF. Translation only: sensing, planning and control stay
ROS-free. rospy comes from Debian's packages (:func:`ensure_rospy`); everything here imports
it lazily, so ``import softpad.ros`` works without ROS. docs/ros.md has the topics, services,
the arm contract and the frames.
"""

from typing import TYPE_CHECKING, Any

from softpad.ros._arm import (
    ARM_COMMAND_TOPIC,
    ARM_STATE_TOPIC,
    Ros1Robot,
    open_robot,
    open_ros1_robot,
)
from softpad.ros._installation import given_settings, installation_settings
from softpad.ros._messages import grasp_poses, jsonable
from softpad.ros._msgs import (
    ensure_messages,
    generate_messages,
    message_definitions,
    ros_packages_dir,
    shell_environment,
)
from softpad.ros._node import CONFIG_KEYS, NodeConfig, PadNode, load_config
from softpad.ros._pad_topics import PadTopics
from softpad.ros._publish import (
    EVENT_TOPIC,
    OUTCOME_TOPIC,
    PHASE_TOPIC,
    GraspCancelled,
    LoopPublisher,
    PadPublishers,
    watch_loop,
)
from softpad.ros._rospy_path import INSTALL_HINT, ROS_MODULES, ensure_rospy, rospy_available
from softpad.ros._run import run_with_robot
from softpad.ros._urdf import pad_urdf

if TYPE_CHECKING:
    from softpad.ros._sim_arm import SimArmNode


def __getattr__(name: str) -> Any:
    """:class:`SimArmNode` is imported on first use (it needs the simulated box)."""
    if name == "SimArmNode":
        from softpad.ros._sim_arm import SimArmNode

        return SimArmNode
    raise AttributeError(f"module 'softpad.ros' has no attribute {name!r}")


__all__ = [
    "ARM_COMMAND_TOPIC",
    "ARM_STATE_TOPIC",
    "CONFIG_KEYS",
    "EVENT_TOPIC",
    "INSTALL_HINT",
    "OUTCOME_TOPIC",
    "PHASE_TOPIC",
    "ROS_MODULES",
    "GraspCancelled",
    "LoopPublisher",
    "NodeConfig",
    "PadNode",
    "PadPublishers",
    "PadTopics",
    "Ros1Robot",
    "SimArmNode",
    "ensure_messages",
    "ensure_rospy",
    "generate_messages",
    "given_settings",
    "grasp_poses",
    "installation_settings",
    "jsonable",
    "load_config",
    "message_definitions",
    "open_robot",
    "open_ros1_robot",
    "pad_urdf",
    "ros_packages_dir",
    "rospy_available",
    "run_with_robot",
    "shell_environment",
    "watch_loop",
]
