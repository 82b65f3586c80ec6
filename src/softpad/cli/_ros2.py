"""``softpad ros2 node`` and ``softpad ros2 build-interfaces``: the ROS 2 adapters
(docs/ros.md, "ROS 2")."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from softpad.cli._args import add_box_option, add_command, add_group

_NETWORK = """\
ROS 2 networking stays on this computer: ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a Fast DDS
profile with loopback unicast and shared memory only, no multicast (set unless already set)."""

_NODE_DESCRIPTION = f"""\
The pad as a ROS 2 node: open the box, inflate and adjust every module, save the reference,
publish every frame and what the grasp loop does on the topics of the one table (python -m
softpad.topics), /diagnostics and /tf_static (the installation's [pad.pose]); services
~/inflate, ~/capture_reference, ~/plan (std_srvs/Trigger); the grasp loop of 'softpad run' as
the action /softpad/grasp (softpad_msgs/action/Grasp: feedback the phase, result the outcome;
a cancel ends in the safe state). ROS 2 parameters (--ros-args -p pad_x_m:=0.4 ...) override
the configuration. {_NETWORK}"""


def register(sub: Any) -> None:
    rsub = add_group(
        sub,
        "ros2",
        "ROS 2 node of the pad (rclpy wheels; docs/ros.md)",
        f"ROS 2 adapters of SoftPad. {_NETWORK}",
        "examples:\n  softpad ros2 build-interfaces                                   once\n"
        "  softpad ros2 node --box sim:// --robot sim:// --place object-3  grasps on request\n",
        metavar="COMMAND",
    )
    node = add_command(
        rsub,
        "node",
        "the pad as a ROS 2 node: pressures, plans, contact, diagnostics, grasp action",
        _NODE_DESCRIPTION,
        "examples:\n  softpad ros2 node --box sim:// --robot sim:// --place object-3   then:\n"
        "  ros2 action send_goal --feedback /softpad/grasp softpad_msgs/action/Grasp {}",
        json="print the start line as JSON",
    )
    node.add_argument(
        "--config",
        metavar="FILE",
        help="installation file (TOML: box link, [pad] layout and pose, thresholds, gripper, "
        "ambient pressure) or the ROS node's JSON settings (docs/ros.md)",
    )
    add_box_option(node, None, "box URL (overrides the config; default sim://)")
    from softpad.cli._ros import _add_node_parts

    _add_node_parts(node)
    node.add_argument("--robot", metavar="URL", help="the arm of the grasp action (sim://, ...)")
    node.add_argument("--place", metavar="NAMES", help="simulation: objects put on a sim:// box")
    node.add_argument(
        "--ros-args",
        dest="ros_args",
        nargs=argparse.REMAINDER,
        default=[],
        help="the rest goes to rclpy (-p KEY:=VALUE parameters, remappings)",
    )
    node.set_defaults(handler=run_node)
    build = add_command(
        rsub,
        "build-interfaces",
        "build tf2_msgs and softpad_msgs for rclpy (CMake, C++ compiler)",
        "Generate and build the interface packages no wheel provides (tf2_msgs/TFMessage from "
        "its upstream definition; softpad_msgs from softpad.topics) with the wheels' rosidl "
        "generators, into this environment's prefix.",
        json="print the prefix as JSON",
    )
    build.add_argument("--prefix", metavar="DIR", help="install prefix (default: this venv)")
    build.set_defaults(handler=run_build)


def node_config(path: str | None) -> Any:
    """The node's settings from ``path``: an installation file (``.toml``: its box link,
    layout, pad pose, thresholds, gripper and ambient pressure) or the ROS node's JSON."""
    from softpad.ros import NodeConfig, load_config

    if path is None or Path(path).suffix != ".toml":
        return load_config(path)
    from softpad.config import load_installation
    from softpad.ros import installation_settings

    return NodeConfig().updated(installation_settings(load_installation(path), pitch=False))


def run_node(args: argparse.Namespace) -> int:
    from softpad.ros import given_settings
    from softpad.ros2 import Ros2PadNode

    names = {key: getattr(args, key) for key in ("box", "place", "planner", "detector", "robot")}
    changes = given_settings(**names)
    node = Ros2PadNode(node_config(args.config).updated(changes), ros_args=args.ros_args)
    try:
        start = {"box": node.config.box, "layout": node.layout.name, "node": "/softpad"}
        if args.json:
            print(json.dumps(start), flush=True)
        else:
            print(f"softpad ros2 node: box {node.config.box}, {node.layout.name} pad", flush=True)
        node.run()
    finally:
        node.close()
    return 0


def run_build(args: argparse.Namespace) -> int:
    from softpad.cli._output import say
    from softpad.ros2 import build_interfaces

    prefix = build_interfaces(args.prefix)
    if args.json:
        print(json.dumps({"prefix": str(prefix)}))
    else:
        say(f"built tf2_msgs and softpad_msgs into {prefix}", False)
    return 0
