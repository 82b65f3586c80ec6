"""What a pad publishes on ROS 2 (rclpy): the ``ros2`` rows of :data:`softpad.topics.TOPICS`.

:class:`Ros2Publishers` makes one publisher per row of the topic table that names the ROS 2
output, with the row's type and QoS, so the node publishes exactly the table's names and types.
Its messages are those of :class:`softpad.ros.PadPublishers` (one class builds them for both,
``softpad.ros._pad_topics.PadTopics``: ``frame``, ``plans``, ``contact``, ``phase``,
``outcome``, ``diagnostics``, ``static_frames``...), so the one
:class:`softpad.ros.LoopPublisher` and the pad node's loop drive either. Translation only.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from softpad import thesis
from softpad import topics as T
from softpad.layout import PadLayout
from softpad.ros import PadTopics


def message_class(type_name: str) -> Any:
    """The rclpy message class of a ROS 2 type name ``pkg/msg/Name``."""
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def qos_profile(qos: T.Qos) -> Any:
    """rclpy's QoSProfile of a row of the table."""
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    return QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=qos.depth,
        reliability=ReliabilityPolicy.RELIABLE if qos.reliable else ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if qos.latched else DurabilityPolicy.VOLATILE,
    )


class Ros2Publishers(PadTopics):
    """The pad's topics on one rclpy node (module docstring; the messages are
    :class:`~softpad.ros._pad_topics.PadTopics`', shared with ROS 1).

    Parameters
    ----------
    node
        The rclpy node.
    layout, box_url, ambient_pressure_pa
        As :class:`~softpad.ros._pad_topics.PadTopics`'s.
    """

    def __init__(
        self,
        node: Any,
        layout: PadLayout,
        box_url: str,
        ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA,
    ) -> None:
        self.node = node
        super().__init__(layout, box_url, ambient_pressure_pa)
        #: Called with (phase, box time) at every phase (the grasp action's feedback).
        self.on_phase: Callable[[str, float], None] | None = None
        for t in T.TOPICS:
            if "ros2" in t.outputs:
                cls = message_class(t.type)
                for name in t.names(self.n):
                    self.pub[name] = node.create_publisher(cls, name, qos_profile(t.qos))

    def stamp(self) -> Any:
        """The node's clock now, as a message stamp."""
        return self.node.get_clock().now().to_msg()

    def softpad_messages(self) -> Any:
        import softpad_msgs.msg

        return softpad_msgs.msg

    def phase(self, name: str) -> None:
        super().phase(name)
        if self.on_phase is not None:
            self.on_phase(name, self.last_t)
