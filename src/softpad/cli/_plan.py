"""``softpad plan``: plan grasps from pressure increments."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.cli._args import Renamed, add_command, add_number, kpa_list
from softpad.cli._output import emit, say
from softpad.cli._paths import atomic_path, check_output
from softpad.errors import InputError

_EPILOG = """examples:
  softpad plan --delta 0,0.124,0.078,0.109,0,0          banana on modules 2, 3, 4
  softpad plan --pressures 1.2,1.1,1.1,1.1,1.1,1.15 --reference 1.1,1.1,1.1,1.1,1.1,1.1
  echo '{"delta_kpa": [0,0,0.062,0,0,0.062]}' | softpad plan --frame - --json

frame files: JSON {"delta_kpa": [...]} or {"pressures_kpa": [...], "reference_kpa": [...]};
CSV with a header row naming delta_kpa (or pressure_kpa and reference_kpa), one row per module
in module order, or a single line of N increments in kPa.
"""


_DESCRIPTION = """\
Detect the objects on the pad (modules with dP above t_o, 8-connected groups), compute each
one's pressure-based centre of mass (PCOM, Eq. 6.1) and plan a top grasp: centre of grasp COG
(module units and metres) and the direction theta in which the jaws close (radians from the
pad x axis)."""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "plan",
        "plan top grasps from module pressure increments",
        _DESCRIPTION,
        _EPILOG,
        force=True,
    )
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--delta", metavar="D1,...,DN", help="increments dP in kPa, modules 1..N")
    src.add_argument(
        "--pressures", metavar="P1,...,PN", help="absolute readings in kPa (needs --reference)"
    )
    src.add_argument("--frame", metavar="FILE", help="CSV or JSON frame file, '-' for stdin")
    p.add_argument(
        "--reference", metavar="R1,...,RN", help="reference pressures in kPa for --pressures"
    )
    p.add_argument("--layout", default="2x3", help="pad layout ROWSxCOLS (default 2x3)")
    add_number(
        p,
        "--threshold-kpa",
        "object-detection threshold t_o in kPa (default %(default)g)",
        thesis.OBJECT_THRESHOLD_PA / 1e3,
        lo=0.001,
        hi=10.0,
        unit="kPa",
    )
    add_number(
        p, "--pitch-mm", "module side in mm (default 45)", 45.0, lo=1.0, hi=1000.0, unit="mm"
    )
    add_number(
        p,
        "--safety-shift",
        "c_s, safety shift of corner-shaped objects in module units (default 0.2)",
        0.2,
        lo=0.0,
        hi=0.49,
        unit="module units",
    )
    p.add_argument(
        "--planner",
        default="thesis",
        help=f"planner by name: {_planner_help()} (default thesis)",
    )
    p.add_argument(
        "--gripper",
        default="10/4",
        metavar="MOUNTING",
        help="gripper mounting the planner plans for: 10/4, 6/2 or 4/0 cm (default 10/4)",
    )
    p.add_argument(
        "--png", metavar="FILE.png", help="draw the pad, increments, PCOM, COG and fingertips"
    )
    p.add_argument("--plot", action=Renamed, new="--png FILE.png")
    p.set_defaults(handler=run)


def _read_frame(path: str) -> Any:
    """The readings of a frame file (``-``: stdin), :class:`softpad.sensing.PadReadings`."""
    from softpad.sensing import parse_readings, read_readings

    if path == "-":
        return parse_readings(sys.stdin.read(), f"frame file {path!r}")
    return read_readings(path)


def run(args: argparse.Namespace) -> int:
    from softpad.layout import parse_layout
    from softpad.planning import PlannerParams, check_planner_choice, format_plans, plan_by_name

    try:
        layout = parse_layout(args.layout, pitch_m=args.pitch_mm / 1e3)
    except InputError as exc:
        raise InputError(f"--layout {args.layout!r}: {exc}") from None
    check_planner_choice(args.planner, args.gripper)
    png = check_output(args.png, "--png", force=args.force, suffix=".png")
    source, readings = _readings(args)
    delta = readings.increments_pa(layout, source)
    params = PlannerParams(
        object_threshold_pa=args.threshold_kpa * 1e3, safety_shift=args.safety_shift
    )
    try:
        plans = plan_by_name(args.planner, args.gripper, delta, layout, params)
    except InputError as exc:
        raise InputError(f"{source}: {exc}") from None
    if png is not None:
        _save_plot(png, delta, plans, layout, args.json)
    if args.json:
        emit({"objects": [p.to_dict(layout) for p in plans]})
    else:
        print(format_plans(delta, plans, layout, params.object_threshold_pa))
    return 0


def _readings(args: argparse.Namespace) -> tuple[str, Any]:
    """Where the readings come from (for messages) and the readings
    (:class:`softpad.sensing.PadReadings`, pascals)."""
    from softpad.sensing import PadReadings

    if args.reference is not None and args.pressures is None:
        source = "--delta" if args.delta is not None else f"--frame {args.frame!r}"
        raise InputError(f"--reference goes with --pressures only, not with {source}")
    if args.delta is not None:
        return "--delta", PadReadings(tuple(kpa_list(args.delta, "--delta")))
    if args.pressures is not None:
        if args.reference is None:
            raise InputError("--pressures needs --reference (the pressures saved after inflation)")
        pressures = tuple(kpa_list(args.pressures, "--pressures"))
        reference = tuple(kpa_list(args.reference, "--reference"))
        return "--pressures/--reference", PadReadings(pressures, reference)
    try:
        readings = _read_frame(args.frame)
    except InputError as exc:
        if repr(args.frame) in str(exc):
            raise
        raise InputError(f"frame file {args.frame!r}: {exc}") from None
    return f"--frame {args.frame!r}", readings


def _planner_help() -> str:
    from softpad.planning import PLANNER_REGISTRY

    return PLANNER_REGISTRY.help().replace("%", "%%")


def _save_plot(path: Path, delta: list[float], plans: Any, layout: Any, json_mode: bool) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from softpad.planning import plot_plans

    ax = plot_plans(delta, plans, layout, title="SoftPad plan")
    try:
        with atomic_path(path) as tmp:
            ax.figure.savefig(tmp, dpi=130, bbox_inches="tight")
    finally:
        plt.close(ax.figure)
    say(f"plot written to {path}", json_mode)
