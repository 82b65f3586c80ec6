"""Robots by URL scheme (``--robot ros1://``): a registry with the entry-point group
``softpad.robots``.

A factory takes the URL's location and options and a :class:`RobotContext` (the box the loop
drives, the pad and the gripper) and returns a :class:`~softpad.control.Robot`. SoftPad's own
robots live in higher layers (the simulated arm in :mod:`softpad.harness`, the ROS 1 arm in
:mod:`softpad.ros`) and are offered lazily by name, so this layer imports neither.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from softpad.box import Box, parse_url
from softpad.control._robot import Robot
from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.registry import Registry


@dataclass(frozen=True)
class RobotContext:
    """What a robot factory is told about the loop it serves.

    Parameters
    ----------
    box
        The box the loop drives (a simulated box's world carries the simulated arm), None
        when not opened yet.
    layout
        The pad.
    gripper
        The gripper's geometry, None when not known.
    """

    box: Box | None = None
    layout: PadLayout = field(default_factory=PadLayout)
    gripper: GripperSpec | None = None


RobotFactory = Callable[[str, dict[str, str], RobotContext], Robot]

#: Robots by URL scheme; entry-point group ``softpad.robots``.
ROBOT_REGISTRY: Registry[RobotFactory] = Registry("robot", "softpad.robots")


def register_robot(scheme: str, factory: RobotFactory, summary: str | None = None) -> None:
    """Make ``make_robot("<scheme>://...")`` call ``factory(location, options, context)``."""
    ROBOT_REGISTRY.register(scheme.lower(), factory, summary)


def available_robots() -> tuple[str, ...]:
    """URL schemes of the robots (built in, registered, and from entry points)."""
    return ROBOT_REGISTRY.names()


def make_robot(url: str, context: RobotContext | None = None, **fields: Any) -> Robot:
    """The robot named by ``url`` (``sim://``, ``ros1://?timeout_s=10``) for ``context`` (its
    fields may be given as keywords). InputError names an unknown scheme and the known ones."""
    scheme, location, options = parse_url(url)
    if scheme not in ROBOT_REGISTRY:
        raise InputError(
            f"unknown robot URL scheme {scheme!r} in {url!r}; available: "
            + ", ".join(f"{s}://" for s in available_robots())
        )
    ctx = RobotContext(**{**(context.__dict__ if context else {}), **fields})
    return ROBOT_REGISTRY.factory(scheme)(location, options, ctx)


ROBOT_REGISTRY.register_lazy(
    "sim", "softpad.harness:open_sim_robot", "the simulated box's own arm and gripper"
)
ROBOT_REGISTRY.register_lazy(
    "ros1", "softpad.ros:open_ros1_robot", "an arm and gripper reached through ROS 1 (docs/ros.md)"
)
