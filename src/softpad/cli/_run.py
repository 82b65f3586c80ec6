"""``softpad run``: the whole closed loop once, on the simulated box, for thesis objects."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from softpad import thesis
from softpad.cli._args import (
    Renamed,
    add_box_option,
    add_command,
    add_integer,
    add_number,
    add_p0_option,
)
from softpad.cli._installation import installed_pad_pose
from softpad.cli._output import emit, say
from softpad.cli._paths import atomic_path, check_output
from softpad.cli._record import add_record_option
from softpad.errors import EXIT_FAILED, EXIT_HARDWARE, EXIT_OK, HardwareFault, InputError

_EPILOG = """examples:
  softpad run --objects object-5
  softpad run --objects object-4 --png run.png --record run.mcap
  softpad run --objects object-1,object-4       two objects, grasped one after the other
  softpad run --box 'sim://?seed=3&rate_hz=200' --objects charger --json
  softpad run --objects object-5 --p0-kpa 1.5 --contact-threshold-kpa 0.12 --window 5

objects: object-1 .. object-6, banana, toy, limes, cylinder, charger (thesis, Table 6.1)
exit code: 0 every grasp held, 1 a grasp not held, 2 bad input, 3 hardware or link fault
"""


_DESCRIPTION = """\
Run the whole grasp loop of the thesis's Section 6.2 once on the simulated box: inflate every
module to p0 and save the reference, place the object(s) of the thesis set, plan the grasp
from the pressure increments, move over the centre of grasp, descend at the approach speed
until the pad senses the fingers (running average of 10 samples above t_g), close, lift,
hold for 15 s, and print the timeline."""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "run",
        "run the closed loop (inflate, reference, plan, approach, contact, grasp, hold)",
        _DESCRIPTION,
        _EPILOG,
    )
    add_box_option(p)
    _add_robot_option(p)
    p.add_argument(
        "--objects",
        metavar="NAME,...",
        help="thesis objects to place, comma-separated (default object-5)",
    )
    p.add_argument("--object", action="append", help=argparse.SUPPRESS)  # old spelling
    p.add_argument(
        "--gripper",
        choices=("10/4", "6/2", "4/0"),
        help="gripper mounting, max/min width in cm (default: the object's, Section 6.3)",
    )
    add_number(
        p,
        "--hold-s",
        "hold time in s (default %(default)g)",
        thesis.HOLD_S,
        lo=0.0,
        hi=3600.0,
        unit="s",
    )
    add_thesis_params(p)
    add_part_options(p)
    _add_attempt_options(p)
    p.add_argument(
        "--config",
        metavar="FILE.toml",
        help="installation file: thresholds (p0, t_adj, t_o, t_g, window, maximum), gripper and "
        "box link; the options above given on the command line win",
    )
    p.add_argument("--png", metavar="FILE.png", help="draw the pressure traces with the phases")
    p.add_argument("--plot", action=Renamed, new="--png FILE.png")
    add_record_option(p)
    _add_watch_options(p)
    p.set_defaults(handler=run)


def _add_watch_options(p: argparse.ArgumentParser) -> None:
    """``--ros``, ``--ros2`` and ``--foxglove``: who watches the run while it runs."""
    p.add_argument(
        "--ros",
        action="store_true",
        help="publish the run on ROS 1 while it runs, as 'softpad ros node' does (pressures, "
        "/softpad/phase, /softpad/plan/grasps, /softpad/contact, /softpad/outcome, /diagnostics; "
        "a simulated box paced to the wall clock; ROS_MASTER_URI on loopback; docs/ros.md)",
    )
    p.add_argument(
        "--ros2",
        action="store_true",
        help="publish the run on ROS 2 while it runs, as 'softpad ros2 node' does (the table's "
        "topics, /diagnostics, /tf_static; loopback only; docs/ros.md)",
    )
    p.add_argument(
        "--foxglove",
        type=int,
        metavar="PORT",
        help="serve the run live to Foxglove on ws://127.0.0.1:PORT (0: a free port)",
    )


def _add_attempt_options(p: argparse.ArgumentParser) -> None:
    """What the loop does after a landing on the object: retries, the landing height, the
    carried objects (docs/beat-the-thesis.md)."""
    add_integer(
        p,
        "--max-attempts",
        "grasps tried per object, 1..5: after the jaws landed on the object and closed on "
        "nothing, a planner with a retry (gripper-aware) tries another (default %(default)s)",
        2,
        1,
        5,
    )
    add_number(
        p,
        "--landing-height-mm",
        "fingertip height above the pad base over which a sensed contact is a landing on the "
        "object, mm, 5..200 (default %(default)g: the ~9 mm module at p0 plus 8)",
        17.0,
        lo=5.0,
        hi=200.0,
        unit="mm",
    )
    p.add_argument(
        "--retry-before-close",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="at a landing on the object that pressed one side of the jaws alone (a jaw on "
        "a brick's edge), try the planner's next grasp at once instead of closing, which "
        "would push the object (default: on; docs/beat-the-thesis.md)",
    )
    p.add_argument(
        "--drop-carried",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="after a grasp that held, do not grasp the planned objects whose modules "
        "unloaded while it was held: they went up with it (one object seen as two, a banana "
        "on its ends; default: on, with a planner that has a retry)",
    )


def _add_robot_option(p: argparse.ArgumentParser) -> None:
    from softpad.control import ROBOT_REGISTRY

    names = ROBOT_REGISTRY.names()
    robots = "; ".join(f"{n}://: {ROBOT_REGISTRY.summary(n)}" for n in names).replace("%", "%%")
    p.add_argument(
        "--robot",
        default="sim://",
        metavar="URL",
        help=f"robot URL: {robots} (default %(default)s; docs/ros.md)",
    )


def add_part_options(p: argparse.ArgumentParser) -> None:
    """``--planner`` and ``--detector``: the loop's parts by name, choices and help from the
    registries (docs/beat-the-thesis.md, docs/architecture.md)."""
    from softpad.cli._args import add_registry_option
    from softpad.planning import PLANNER_REGISTRY
    from softpad.sensing import CONTACT_DETECTOR_REGISTRY

    add_registry_option(p, "--planner", PLANNER_REGISTRY, "grasp planner")
    add_registry_option(p, "--detector", CONTACT_DETECTOR_REGISTRY, "contact detector")


def add_thesis_params(p: argparse.ArgumentParser) -> None:
    """The thesis's loop parameters (Section 6.2) as options with their physical ranges."""

    g = p.add_argument_group("loop parameters (thesis, Section 6.2)")
    add_p0_option(g)
    for flag, default_pa, meaning in (
        (
            "--object-threshold-kpa",
            thesis.OBJECT_THRESHOLD_PA,
            "t_o, a module holds an object when dP > t_o",
        ),
        (
            "--contact-threshold-kpa",
            thesis.CONTACT_THRESHOLD_PA,
            "t_g, the fingers touch the pad when the average rise > t_g",
        ),
    ):
        add_number(
            g,
            flag,
            f"{meaning}, kPa, 0.005..1 (default {default_pa / 1e3:g})",
            default_pa / 1e3,
            lo=0.005,
            hi=1.0,
            unit="kPa",
        )
    window_help = "running-average length of the detectors, samples, 1..200 (default 10)"
    add_integer(g, "--window", window_help, thesis.FILTER_WINDOW, 1, 200)
    add_number(
        g,
        "--approach-speed-mps",
        "descent speed towards the pad, m/s, 0.001..0.25 (default %(default)g)",
        thesis.APPROACH_SPEED_M_S,
        lo=0.001,
        hi=0.25,
        unit="m/s",
    )


def execution_params(args: argparse.Namespace) -> Any:
    """ExecutionParams from the options of :func:`add_thesis_params` and ``--hold-s``."""
    from softpad.control import ExecutionParams, InflationParams
    from softpad.planning import PlannerParams

    return ExecutionParams(
        inflation=InflationParams(target_pa=args.p0_kpa * 1e3),
        planner=PlannerParams(object_threshold_pa=args.object_threshold_kpa * 1e3),
        contact_threshold_pa=args.contact_threshold_kpa * 1e3,
        filter_length=args.window,
        approach_speed_m_s=args.approach_speed_mps,
        hold_s=args.hold_s,
        max_attempts=args.max_attempts,
        landing_height_m=args.landing_height_mm * 1e-3,
        retry_before_close=args.retry_before_close,
        drop_carried=args.drop_carried,
    )


def _object_names(args: argparse.Namespace) -> list[str]:
    from softpad.cli._args import name_list

    names: list[str] = name_list(args.objects, "--objects") if args.objects is not None else []
    for text in args.object or []:
        names += name_list(text, "--object")
    return names or ["object-5"]


def run(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.errors import SoftPadError
    from softpad.harness import resolve_objects, run_objects
    from softpad.record import RunLog, Tee

    names = [s.name for s in resolve_objects(_object_names(args))]  # fail before any work
    params = execution_params(args)
    record_path = check_output(args.record, "--record", force=args.force, suffix=".mcap")
    png_path = check_output(args.png, "--png", force=args.force, suffix=".png")
    if args.foxglove is not None and not 0 <= args.foxglove <= 65535:
        raise InputError(f"--foxglove port must be within 0..65535, got {args.foxglove}")
    log = RunLog({"box": args.box, "objects": names})
    gripper = args.gripper  # the installation file's mounting when it names one
    if args.config:
        params = _from_installation(args.config, params)
    with open_box(args.box) as box:
        if not args.json:  # first: which box (the JSON's stderr is the error line alone)
            print(f"softpad run: {', '.join(names)} on {args.box}", flush=True)
        recorder, live, ros, ros2 = _watchers(args, box, names, params, record_path)
        try:
            tee = Tee(log, recorder, live, ros, ros2)
            result = run_objects(
                names, box, params, tee, gripper, args.robot, args.planner, args.detector
            )
            for r in (ros, ros2):
                if r is not None:
                    r.finish(result.result)
        except HardwareFault as exc:
            return _report_fault(args, log, names, exc)
        except SoftPadError as exc:
            exc.partial = {"objects": names, "events": _events(log), "frames": len(log)}
            for r in (ros, ros2):
                if r is not None:
                    r.error(str(exc))
            raise
        finally:  # whatever happened, what was recorded is kept
            for r in (recorder, live):
                if r is not None:
                    r.close()
            _save_png(log, png_path, names)
    return _report(args, log, result, names, png_path, record_path)


def _watchers(
    args: argparse.Namespace, box: Any, names: list[str], params: Any, record_path: Any
) -> tuple[Any, Any, Any, Any]:
    """The run's recorder (``--record``), Foxglove view and ROS publishers, those asked for."""
    from softpad.record import open_recorder, run_metadata

    meta = run_metadata(
        "run", box, args.box, names, params, gripper=args.gripper,
        planner=args.planner, contact_detector=args.detector,
    )  # fmt: skip
    _add_ambient(meta, args.config)
    pad = installed_pad_pose(args.config)  # where the pad stands: /tf_static everywhere
    recorder = open_recorder(
        str(record_path) if record_path else None, box, meta, args.force, pad=pad
    )
    live = _live(args.foxglove, box, args.json, pad)
    ros = _ros_watch(args.ros, box, args.box, pad)
    ros2 = _ros2_watch(args.ros2, box, args.box, pad)
    return recorder, live, ros, ros2


def _add_ambient(meta: dict[str, Any], config: str | None) -> None:
    """FluidPressure is absolute: the site's ambient pressure from the installation file."""
    if config:
        from softpad.config import load_installation

        meta["ambient_pressure_pa"] = load_installation(config).box.ambient_pressure_pa


def _report(args: Any, log: Any, result: Any, names: list[str], png: Any, record: Any) -> int:
    from softpad.harness import timeline

    d = result.to_dict()
    held = result.outcome == "held"
    if args.json:
        if not held:
            d["error"] = {"kind": "failed", "message": f"grasp not held: {result.outcome}"}
        emit(d)
    else:
        for line in timeline(log.events, result):
            print("  " + line)
        print(f"outcome: {result.outcome}")
    for path, what in ((png, "pressure traces"), (record, "recording")):
        if path is not None:
            say(f"{what}: {path}", args.json)
    return EXIT_OK if held else EXIT_FAILED


def _events(log: Any) -> list[Any]:
    return [[t, kind, data] for t, kind, data in log.events]


def _save_png(log: Any, png_path: Any, names: list[str]) -> None:
    if png_path is None or not len(log):
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with atomic_path(png_path) as tmp:
        fig = log.plot(tmp, title=f"softpad run: {', '.join(names)}")
    plt.close(fig)


def _from_installation(path: str, params: Any) -> Any:
    """What the options do not cover from an installation file: the adjustment tolerance,
    the maximum pressure and the inflation's window (its thresholds, window and gripper are
    already the options' defaults, ``softpad.cli._installation``)."""
    from softpad.config import load_installation
    from softpad.harness import execution_params as with_installation

    return with_installation(params, load_installation(path))


def _live(port: int | None, box: Any, json_mode: bool, pad: Any = None) -> Any:
    if port is None:
        return None
    from softpad.box import simulator_of
    from softpad.record import FoxgloveLive

    sim = simulator_of(box)
    robot = sim.world.gripper_state if sim is not None else None
    layout = sim.world.layout if sim is not None else None  # the pad's modules only
    live = FoxgloveLive(port, layout, robot_state=robot, pad=pad)
    say(f"foxglove: {live.url} (port {live.port})", json_mode)
    return live


def _ros_watch(enabled: bool, box: Any, url: str, pad: Any = None) -> Any:
    """``--ros``: the publisher of :mod:`softpad.ros` the run reports to, else None."""
    if not enabled:
        return None
    from softpad.harness import box_layout
    from softpad.ros import watch_loop

    return watch_loop(box_layout(box), box, url, pad=pad)


def _ros2_watch(enabled: bool, box: Any, url: str, pad: Any = None) -> Any:
    """``--ros2``: the publisher of :mod:`softpad.ros2` the run reports to, else None."""
    if not enabled:
        return None
    from softpad.harness import box_layout
    from softpad.ros2 import watch_loop2

    return watch_loop2(box_layout(box), box, url, pad=pad)


def _report_fault(args: argparse.Namespace, log: Any, names: list[str], exc: Exception) -> int:
    """Print what was detected and the safe state reached (:func:`softpad.harness.fault_report`);
    the hardware-fault exit code."""
    from softpad.harness import fault_report

    d, lines = fault_report(exc, names, log.events, len(log))
    if args.json:
        emit(d)
    else:
        for line in lines:
            print(line)
    print(f"softpad run: error: hardware fault: {exc}", file=sys.stderr)
    return EXIT_HARDWARE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(0)
