"""``softpad ros node|env|urdf`` and ``softpad sim arm-node``: the ROS 1 adapters (docs/ros.md)."""

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
(/softpad/module_K/pressure, /softpad/pressures, /softpad/supply/pressure), the objects and
grasps (/softpad/plan/objects, /softpad/plan/grasps), /softpad/contact, /softpad/events,
/diagnostics and the static transforms (the topic table's ros1 rows); services
~inflate, ~capture_reference, ~plan and ~grasp (the grasp loop of 'softpad run' once, on this
box, with the --robot; its phase and outcome on /softpad/phase and /softpad/outcome), and the
grasp action ~grasp (softpad_msgs/GraspAction: the phases as feedback, a cancel ends in the
box's safe state); every event on /softpad/events (softpad_msgs/Event). --config reads the
installation file (TOML, mm and degrees, as every command); options, then ROS parameters
(~box, ~pad_x_m, ..., SI units) override it. {_NETWORK}"""

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
    node.add_argument(
        "--config",
        metavar="FILE.toml",
        help="installation file (TOML: box link, pad and its pose, thresholds, gripper)",
    )
    add_box_option(node, None, "box URL (overrides the config; default sim://)")
    _add_node_parts(node)
    _add_node_grasp_options(node)
    node.set_defaults(handler=run_node)
    _register_tools(rsub)

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


def _add_node_grasp_options(node: Any) -> None:
    """``--robot``, ``--place`` and ``--hold-s`` of the node's grasps."""
    node.add_argument(
        "--robot",
        metavar="URL",
        help="the arm of the ~grasp service and action: sim:// (on a sim:// box) or ros1:// "
        "(an arm node); overrides ~robot (default: none, no grasps)",
    )
    node.add_argument(
        "--place",
        metavar="NAMES",
        help="simulation: catalogue objects put on a sim:// box 1 s after the reference",
    )
    node.add_argument(
        "--hold-s",
        type=float,
        help="hold time of a grasp, seconds (default 15, the thesis's)",
    )


def _add_node_parts(node: Any) -> None:
    """``--planner`` and ``--detector`` of the node, from the registries (default: the
    installation file's, else the thesis's)."""
    from softpad.cli._args import add_registry_option
    from softpad.planning import PLANNER_REGISTRY
    from softpad.sensing import CONTACT_DETECTOR_REGISTRY

    add_registry_option(node, "--planner", PLANNER_REGISTRY, "grasp planner", None)
    add_registry_option(node, "--detector", CONTACT_DETECTOR_REGISTRY, "contact detector", None)


def _register_tools(rsub: Any) -> None:
    """``softpad ros env`` and ``softpad ros urdf``."""
    env = add_command(
        rsub,
        "env",
        "shell lines that let ROS tools decode SoftPad's messages (eval them)",
        "Generate the Python modules of the softpad_msgs package (Event, ValveCommands, the "
        "Grasp action) and print the exports that put them on PYTHONPATH and SoftPad's ROS "
        "packages (softpad_msgs, softpad_ros: launch files, URDF, rviz) on ROS_PACKAGE_PATH.",
        'example:\n  eval "$(softpad ros env)"; rostopic echo /softpad/events',
        json="print the two directories as JSON (PYTHONPATH, ROS_PACKAGE_PATH)",
    )
    env.set_defaults(handler=run_env)
    urdf = add_command(
        rsub,
        "urdf",
        "URDF of the pad: one link per module, the frames of /tf_static",
        "Print (or write with --out) the pad's URDF: link softpad and softpad_module_K on "
        "fixed joints at the module centres (check_urdf reads it).",
        json="print the URDF (or the file written) as JSON",
        force=True,
    )
    urdf.add_argument("--layout", default="2x3", help="pad layout RxC (default %(default)s)")
    urdf.add_argument("--pitch-mm", type=float, default=45.0, help="module pitch, mm")
    urdf.add_argument("--out", metavar="FILE.urdf", help="write the URDF there")
    urdf.set_defaults(handler=run_urdf)


def run_env(args: argparse.Namespace) -> int:
    from softpad.ros import generate_messages, ros_packages_dir, shell_environment

    if args.json:
        dirs = {"PYTHONPATH": str(generate_messages()), "ROS_PACKAGE_PATH": str(ros_packages_dir())}
        print(json.dumps(dirs))
        return 0
    print(shell_environment(), end="")
    return 0


def run_urdf(args: argparse.Namespace) -> int:
    from pathlib import Path

    from softpad.errors import InputError
    from softpad.layout import parse_layout
    from softpad.ros import pad_urdf

    if not 1.0 <= args.pitch_mm <= 1000.0:
        raise InputError(f"--pitch-mm must be within 1 to 1000 mm, got {args.pitch_mm:g}")
    text = pad_urdf(parse_layout(args.layout, args.pitch_mm / 1e3))
    if args.out is None:
        print(json.dumps({"urdf": text}) if args.json else text, end="\n" if args.json else "")
        return 0
    out = Path(args.out)
    if out.exists() and not args.force:
        raise InputError(f"{str(out)!r} exists; refusing to overwrite it (add --force)")
    out.write_text(text)
    print(json.dumps({"file": str(out)}) if args.json else f"softpad ros urdf: {out}")
    return 0


def installation_settings(path: str) -> dict[str, Any]:
    """The node's settings (:data:`softpad.ros.CONFIG_KEYS`, SI) from the installation file
    ``path`` (TOML, mm and degrees), as every other command reads it
    (:func:`softpad.ros.installation_settings`)."""
    from softpad.config import load_installation
    from softpad.errors import InputError
    from softpad.ros import installation_settings as settings

    if path.endswith(".json"):
        raise InputError(
            f"--config {path!r}: the node reads the installation file (TOML, examples/site.toml);"
            " give node settings as options or ROS parameters (docs/ros.md)"
        )
    return settings(load_installation(path))


def run_node(args: argparse.Namespace) -> int:
    from softpad.ros import NodeConfig, PadNode, given_settings

    config = NodeConfig()
    if args.config:
        config = config.updated(installation_settings(args.config))
    names = {key: getattr(args, key) for key in ("box", "place", "planner", "detector", "robot")}
    node = PadNode(config.updated(given_settings(args.hold_s, **names)))
    try:
        if args.json:
            print(json.dumps({"box": node.config.box, "layout": node.layout.name}), flush=True)
        else:
            print(f"softpad ros node: box {node.config.box}, {node.layout.name} pad", flush=True)
        node.run()
    finally:  # a signal before run() too: actionlib's goal thread would keep the process alive
        node.rospy.signal_shutdown("softpad ros node ended")
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
