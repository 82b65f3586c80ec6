"""``softpad ros node`` and ``softpad sim arm-node``: the ROS 1 adapters (docs/ros.md)."""

from __future__ import annotations

import argparse
import json
from typing import Any

from softpad.cli._args import add_box_option, add_command, add_group, bounded_int

_NETWORK = """\
ROS networking: set ROS_MASTER_URI=http://127.0.0.1:11311, ROS_IP=127.0.0.1 and
ROS_HOSTNAME=localhost (loopback only)."""

_NODE_DESCRIPTION = f"""\
Open the box, inflate and adjust every module, save the reference, then publish every frame
(/softpad/module_K/pressure, /softpad/pressures), the objects and grasps (/softpad/objects,
/softpad/grasps), /softpad/contact, /diagnostics and the static transforms; services
~inflate, ~capture_reference, ~plan and ~grasp (the grasp loop of 'softpad run' once, on this
box, with the --robot; its phase and outcome on /softpad/phase and /softpad/outcome). ROS
parameters (~box, ~pad_x_m, ...) override the config file. {_NETWORK}"""

_ARM_DESCRIPTION = f"""\
Own a simulated box and its world; serve the box on zenoh://127.0.0.1:PORT and the arm on
/softpad_arm/command and /softpad_arm/state, so that 'softpad run --robot ros1:// --box
zenoh://127.0.0.1:PORT' runs the loop with the arm in ROS. {_NETWORK}"""


_ROS_EPILOG = """examples:
  softpad ros node --box sim:// --place object-5                 the pad as a ROS node
  softpad ros node --box sim:// --robot sim:// --place object-5  ... that grasps on request
  rosservice call /softpad/grasp
"""

_SIM_EPILOG = """examples:
  softpad sim arm-node --port 5757        simulated arm on ROS + a served sim box
  softpad run --robot ros1:// --box zenoh://127.0.0.1:5757 --objects object-5
"""


def register(sub: Any) -> None:
    rsub = add_group(
        sub,
        "ros",
        "ROS 1 node of the pad (rospy; docs/ros.md)",
        f"ROS 1 adapters of SoftPad. {_NETWORK}",
        _ROS_EPILOG,
        metavar="COMMAND",
    )
    node = add_command(
        rsub,
        "node",
        "the pad as a ROS node: pressures, objects, grasps, contact, diagnostics",
        _NODE_DESCRIPTION,
        "examples:\n  softpad ros node --box sim:// --place banana\n"
        "  softpad ros node --box sim:// --robot sim:// --place object-5   then:\n"
        "  rosservice call /softpad/grasp",
        json="print the start line as JSON",
    )
    node.add_argument("--config", metavar="FILE.json", help="installation file (docs/ros.md)")
    add_box_option(node, None, "box URL (overrides the config; default sim://)")
    _add_node_parts(node)
    node.add_argument(
        "--robot",
        metavar="URL",
        help="the arm of the ~grasp service: sim:// (on a sim:// box) or ros1:// (an arm "
        "node); overrides the config's 'robot' (default: none, no grasps)",
    )
    node.add_argument(
        "--place",
        metavar="NAMES",
        help="simulation: catalogue objects put on a sim:// box 1 s after the reference",
    )
    node.set_defaults(handler=run_node)

    _register_sim(sub)


def _register_sim(sub: Any) -> None:
    """``softpad sim arm-node``."""
    ssub = add_group(
        sub,
        "sim",
        "simulated devices for ROS (docs/ros.md)",
        "Simulated devices that a ROS 1 system talks to like real ones.",
        _SIM_EPILOG,
        metavar="COMMAND",
    )
    arm = add_command(
        ssub,
        "arm-node",
        "simulated arm on ROS (ros1:// contract) sharing its world with a served sim box",
        _ARM_DESCRIPTION,
        json="print the served box URL as JSON",
    )
    add_box_option(arm, help="sim:// URL (default sim://)")
    arm.add_argument(
        "--port",
        type=bounded_int("--port", 0, 65535),
        default=5757,
        help="port of the served box, zenoh on tcp/127.0.0.1 (0: a free one)",
    )
    arm.add_argument(
        "--lose-arm-on",
        choices=("move_to", "descend", "stop", "gripper"),
        help="fault injection: the arm goes silent on this command (the box stays served)",
    )
    arm.set_defaults(handler=run_arm_node)


def _add_node_parts(node: Any) -> None:
    """``--planner`` and ``--detector`` of the node, from the registries (default: the
    installation file's, else the thesis's)."""
    from softpad.cli._args import add_registry_option
    from softpad.planning import PLANNER_REGISTRY
    from softpad.sensing import CONTACT_DETECTOR_REGISTRY

    add_registry_option(node, "--planner", PLANNER_REGISTRY, "grasp planner", None)
    add_registry_option(node, "--detector", CONTACT_DETECTOR_REGISTRY, "contact detector", None)


def run_node(args: argparse.Namespace) -> int:
    from softpad.ros import PadNode, load_config

    config = load_config(args.config)
    changes: dict[str, Any] = {}
    if args.box:
        changes["box"] = args.box
    if args.place:
        changes["place"] = args.place
    for key in ("planner", "detector", "robot"):
        if getattr(args, key):
            changes[key] = getattr(args, key)
    node = PadNode(config.updated(changes))
    if args.json:
        print(json.dumps({"box": node.config.box, "layout": node.layout.name}), flush=True)
    else:
        print(f"softpad ros node: box {node.config.box}, {node.layout.name} pad", flush=True)
    node.run()
    return 0


def run_arm_node(args: argparse.Namespace) -> int:
    from softpad.ros import SimArmNode

    node = SimArmNode(args.box, args.port, args.lose_arm_on)
    if args.json:
        print(json.dumps({"box": node.url, "arm": "/softpad_arm"}), flush=True)
    else:
        print(f"softpad sim arm-node: box on {node.url}, arm on /softpad_arm", flush=True)
    node.serve()
    return 0


def run_with_robot_url(
    args: argparse.Namespace,
    names: list[str],
    box: Any,
    recorder: Any,
    params: Any,
    **parts: Any,
) -> Any:
    """``softpad run --robot URL``: the loop with a robot made by the robot registry
    (``ros1://``, or a robot an installed package registers)."""
    from softpad.control import make_robot
    from softpad.harness import SimulatedRun, TouchTruth
    from softpad.ros import run_with_robot

    robot = make_robot(args.robot, box=box)
    try:
        result = run_with_robot(names, box, robot, params, recorder, gripper=args.gripper, **parts)
    finally:
        close = getattr(robot, "close", None)
        if close is not None:
            close()
    # no ground truth of the touches through ROS: the report leaves them empty
    return SimulatedRun(result, tuple(TouchTruth(None, None) for _ in result.grasps))
