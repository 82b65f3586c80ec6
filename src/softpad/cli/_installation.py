"""``--config FILE.toml`` on every command: the installation file's values become the defaults.

Options given on the command line still win: the file only replaces the built-in defaults
(the thesis's values) of the options it has a value for. The box daemon (``box serve``) reads
the file itself (wiring, link), and the ROS commands take their own JSON configuration.
"""

from __future__ import annotations

import argparse
from collections.abc import Iterator, Sequence
from typing import Any

#: Parsers that read ``--config`` themselves (another meaning or another format).
OWN_CONFIG = (
    "softpad box serve",
    "softpad ros node",
    "softpad ros2 node",
    "softpad sim arm-node",
)


def leaf_parsers(parser: argparse.ArgumentParser) -> Iterator[argparse.ArgumentParser]:
    """Every parser under ``parser`` that has no sub-commands of its own."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield parser
    for action in subs:
        for child in dict.fromkeys(action.choices.values()):
            yield from leaf_parsers(child)


#: Options whose defaults an installation file sets (destinations; see :func:`_defaults`).
SET_BY_FILE = (
    "box", "p0_kpa", "object_threshold_kpa", "threshold_kpa", "contact_threshold_kpa", "window",
    "layout", "pitch_mm", "gripper",
)  # fmt: skip


def add_config_options(parser: argparse.ArgumentParser) -> None:
    """Give every command without one a ``--config FILE.toml`` option, whose help names the
    command's options the file sets (or says that it sets none of them)."""
    for p in leaf_parsers(parser):
        if p.prog != "softpad" and "--config" not in p._option_string_actions:
            p.add_argument("--config", metavar="FILE.toml", help=config_help(p))


def config_help(p: argparse.ArgumentParser) -> str:
    """The help of ``--config`` on the command ``p``."""
    flags = [a.option_strings[-1] for a in p._actions if a.dest in SET_BY_FILE and a.option_strings]
    if not flags:
        return (
            "installation file (TOML): accepted by every command; this one takes nothing "
            "from it (none of its options has an installation default)"
        )
    return f"installation file (TOML): its values become the defaults of {', '.join(flags)}"


def config_path(argv: Sequence[str]) -> str | None:
    """The value of the last ``--config`` in ``argv`` (None without one)."""
    path = None
    for i, word in enumerate(argv):
        if word == "--config" and i + 1 < len(argv):
            path = argv[i + 1]
        elif word.startswith("--config="):
            path = word.split("=", 1)[1]
    return path


def _defaults(inst: Any) -> dict[str, Any]:
    """Option destinations and the installation's values for them (CLI units)."""
    th, pad = inst.thresholds, inst.pad
    out: dict[str, Any] = {
        "p0_kpa": th.p0_pa / 1e3,
        "object_threshold_kpa": th.object_threshold_pa / 1e3,
        "contact_threshold_kpa": th.contact_threshold_pa / 1e3,
        "window": th.filter_window,
        "layout": f"{pad.rows}x{pad.cols}",
        "pitch_mm": pad.pitch_m * 1e3,
    }
    if inst.gripper_mounting is not None:
        out["gripper"] = inst.gripper_mounting
    if inst.box_url is not None:
        out["box"] = inst.box_url
    return out


def installed_pad_pose(path: str | None) -> Any:
    """The installation file's ``[pad.pose]`` as a :class:`~softpad.layout.PadPose` (the
    origin without a file): where the pad stands in the robot's base frame."""
    from softpad.layout import PadPose

    if path is None:
        return PadPose()
    from softpad.config import load_installation

    pad = load_installation(path).pad
    return PadPose(pad.x_m, pad.y_m, pad.z_m, pad.yaw_rad)


def apply_installation(parser: argparse.ArgumentParser, argv: Sequence[str]) -> None:
    """Make the installation file named by ``--config`` in ``argv`` the defaults of every
    command that does not read it itself (see the module docstring)."""
    path = config_path(argv)
    if path is None:
        return
    words = [w for w in argv if not w.startswith("-")]
    if any(" ".join(["softpad", *words[:2]]).startswith(p) for p in OWN_CONFIG):
        return
    from softpad.config import load_installation

    values = _defaults(load_installation(path))
    values["threshold_kpa"] = values["object_threshold_kpa"]  # plan's t_o
    for p in leaf_parsers(parser):
        if p.prog.split()[1:2] == ["fem"]:  # fem's thresholds are another quantity
            continue
        for action in p._actions:
            if action.dest in values and action.dest != "help":
                action.default = values[action.dest]
