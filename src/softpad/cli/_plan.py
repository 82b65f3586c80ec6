"""``softpad plan``: plan grasps from pressure increments."""

from __future__ import annotations

import argparse
import csv
import io
import sys
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.cli._args import Renamed, add_command, add_number, kpa_list
from softpad.cli._output import emit, say
from softpad.cli._paths import atomic_path, check_output
from softpad.errors import InputError, parse_json

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


def _read_frame(path: str) -> tuple[list[float], list[float] | None]:
    """Read a frame file; returns (values_pa, reference_pa or None)."""
    if path == "-":
        text = sys.stdin.read()
    else:
        try:
            text = Path(path).read_bytes().decode("utf-8")
        except OSError as exc:
            raise InputError(f"cannot read frame file {path!r}: {exc.strerror}") from None
        except UnicodeDecodeError:
            raise InputError(
                f"frame file {path!r} is not text (CSV or JSON expected; a binary file?)"
            ) from None
    stripped = text.strip()
    if not stripped:
        raise InputError(f"frame file {path!r} is empty")
    if stripped.startswith("{"):
        data = parse_json(stripped, f"frame file {path!r}")
        if not isinstance(data, dict):
            raise InputError(f"frame file {path!r} must hold a JSON object")
        keys = [k for k in ("delta_kpa", "pressures_kpa", "reference_kpa") if k in data]
        if "delta_kpa" in keys and len(keys) > 1:
            raise InputError(
                f"frame file {path!r} gives both delta_kpa and {keys[1]}: give one of "
                "delta_kpa, or pressures_kpa with reference_kpa"
            )
        if "delta_kpa" in data:
            return _numbers(data["delta_kpa"], "delta_kpa"), None
        if "pressures_kpa" in data and "reference_kpa" in data:
            return _numbers(data["pressures_kpa"], "pressures_kpa"), _numbers(
                data["reference_kpa"], "reference_kpa"
            )
        raise InputError(
            f"frame file {path!r} needs key delta_kpa, or pressures_kpa and reference_kpa"
        )
    return _csv_frame(path, stripped)


def _csv_frame(path: str, stripped: str) -> tuple[list[float], list[float] | None]:
    """A CSV frame file's (values_pa, reference_pa or None)."""
    try:  # newline="" semantics: a lone \r ends a line as \n does
        rows = [
            r for r in csv.reader(io.StringIO(stripped, newline=None)) if any(c.strip() for c in r)
        ]
    except csv.Error as exc:
        raise InputError(f"frame file {path!r} is not valid CSV: {exc}") from None
    if not rows:
        raise InputError(f"frame file {path!r} has no values (CSV or JSON expected)")
    header = [c.strip().lower() for c in rows[0]]
    if all(_is_number(c) for c in header):
        if len(rows) != 1:
            raise InputError(
                f"frame file {path!r}: without a header give one line of increments in kPa"
            )
        return kpa_list(",".join(rows[0]), "frame"), None
    body = rows[1:]
    if not body:
        raise InputError(f"frame file {path!r} has a header but no data rows")

    def column(name: str) -> list[float]:
        i = header.index(name)
        try:
            return kpa_list(",".join(r[i] for r in body), name)
        except IndexError:
            raise InputError(f"frame file {path!r}: a row has no {name} column") from None

    if "delta_kpa" in header:
        if "pressure_kpa" in header or "reference_kpa" in header:
            raise InputError(
                f"frame file {path!r}: header names delta_kpa and pressures; give one of them"
            )
        return column("delta_kpa"), None
    if "pressure_kpa" in header and "reference_kpa" in header:
        return column("pressure_kpa"), column("reference_kpa")
    raise InputError(
        f"frame file {path!r}: header must name delta_kpa, or pressure_kpa and reference_kpa; "
        f"got {', '.join(header)}"
    )


def _is_number(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


def _numbers(values: Any, key: str) -> list[float]:
    if not isinstance(values, list):
        raise InputError(f"{key} must be a list of numbers in kPa, got {type(values).__name__}")
    return kpa_list(",".join(str(v) for v in values), key)


def _check_increment_range(delta_pa: list[float], source: str) -> None:
    """A module's pressure cannot fall below ambient, so its increment is at least -p0, and p0
    is at most 2.8 kPa (thesis Section 6.2); above, the sensor's 10 kPa full scale bounds it."""
    from softpad.sensing import SENSOR_FULL_SCALE_PA

    lo = -thesis.P0_RANGE_PA[1]
    for k, d in enumerate(delta_pa, 1):
        if not lo <= d <= SENSOR_FULL_SCALE_PA:
            hint = ": were pascals given as kPa?" if d > SENSOR_FULL_SCALE_PA else ""
            raise InputError(
                f"{source}: increment of module {k} is {d / 1e3:g} kPa, outside "
                f"{lo / 1e3:g} to {SENSOR_FULL_SCALE_PA / 1e3:g} kPa (a module cannot fall "
                f"below ambient, nor read above the sensor's full scale){hint}"
            )


def run(args: argparse.Namespace) -> int:
    from softpad.layout import parse_layout
    from softpad.planning import PlannerParams, format_plans

    try:
        layout = parse_layout(args.layout, pitch_m=args.pitch_mm / 1e3)
    except InputError as exc:
        raise InputError(f"--layout {args.layout!r}: {exc}") from None
    _check_planner(args.planner, args.gripper)
    png = check_output(args.png, "--png", force=args.force, suffix=".png")
    source, values, reference = _readings(args)
    delta = _increments(values, reference, layout, source)
    params = PlannerParams(
        object_threshold_pa=args.threshold_kpa * 1e3, safety_shift=args.safety_shift
    )
    try:
        plans = _plans(args, delta, layout, params)
    except InputError as exc:
        raise InputError(f"{source}: {exc}") from None
    if png is not None:
        _save_plot(png, delta, plans, layout, args.json)
    if args.json:
        emit({"objects": [p.to_dict(layout) for p in plans]})
    else:
        print(format_plans(delta, plans, layout, params.object_threshold_pa))
    return 0


def _readings(args: argparse.Namespace) -> tuple[str, list[float], list[float] | None]:
    """Where the readings come from (for messages), the values and the reference (None for
    increments), pascals."""
    if args.reference is not None and args.pressures is None:
        source = "--delta" if args.delta is not None else f"--frame {args.frame!r}"
        raise InputError(f"--reference goes with --pressures only, not with {source}")
    if args.delta is not None:
        return "--delta", kpa_list(args.delta, "--delta"), None
    if args.pressures is not None:
        if args.reference is None:
            raise InputError("--pressures needs --reference (the pressures saved after inflation)")
        pressures = kpa_list(args.pressures, "--pressures")
        return "--pressures/--reference", pressures, kpa_list(args.reference, "--reference")
    try:
        values, reference = _read_frame(args.frame)
    except InputError as exc:
        if repr(args.frame) in str(exc):
            raise
        raise InputError(f"frame file {args.frame!r}: {exc}") from None
    return f"--frame {args.frame!r}", values, reference


def _increments(
    values: list[float], reference: list[float] | None, layout: Any, source: str
) -> list[float]:
    """The increments of every module, pascals, checked against the pad's module count."""
    from softpad.sensing import increments

    n = layout.n_modules
    if reference is None:
        if len(values) != n:
            raise InputError(
                f"{source}: a {layout.name} pad needs {n} increments (modules 1..{n}), "
                f"got {len(values)}"
            )
        _check_increment_range(values, source)
        return values
    _check_readings(values, "pressures")
    _check_readings(reference, "reference")
    if len(values) != n or len(reference) != n:
        raise InputError(
            f"--pressures/--reference: a {layout.name} pad needs {n} pressures "
            f"and {n} reference values, got {len(values)} and {len(reference)}"
        )
    return list(increments(values, reference))


def _planner_help() -> str:
    from softpad.planning import PLANNER_REGISTRY

    return PLANNER_REGISTRY.help().replace("%", "%%")


def _check_planner(planner: str, mounting: str) -> None:
    """``--planner`` and ``--gripper`` known, else an InputError naming them."""
    from softpad import thesis as t
    from softpad.planning import available_planners

    if planner not in (names := available_planners()):
        raise InputError(f"--planner must be one of {', '.join(names)}, got {planner!r}")
    if mounting not in t.GRIPPER_MOUNTINGS_M:
        raise InputError(
            f"--gripper must be one of {', '.join(t.GRIPPER_MOUNTINGS_M)}, got {mounting!r}"
        )


def _plans(args: argparse.Namespace, delta: list[float], layout: Any, params: Any) -> Any:
    """The plans of ``--planner`` (the thesis's: :func:`softpad.planning.plan_grasps`)."""
    from softpad.layout import GripperSpec
    from softpad.planning import make_planner, plan_grasps
    from softpad.sensing import detect_objects

    gripper = GripperSpec.from_mounting(args.gripper)
    if args.planner == "thesis":
        return plan_grasps(delta, layout, params)
    planner = make_planner(args.planner, layout=layout, gripper=gripper, params=params)
    return planner.plan(delta, detect_objects(delta, layout, params.object_threshold_pa), layout)


def _check_readings(values_pa: list[float], what: str) -> None:
    """Readings within the sensor range (-2..10 kPa), else a message suggesting Pa given as kPa."""
    for i, v in enumerate(values_pa, 1):
        if not -2e3 <= v <= 10e3:
            hint = ": pascals given as kPa?" if v > 10e3 else ""
            raise InputError(
                f"--{what}: module {i} reads {v / 1e3:g} kPa, outside the sensor range "
                f"-2..10 kPa{hint}"
            )


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
