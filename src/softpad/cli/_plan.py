"""``softpad plan``: plan grasps from pressure increments."""

from __future__ import annotations

import argparse
import csv
import io
import json
import sys
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.cli._args import finite_float, kpa_list
from softpad.errors import InputError

_EPILOG = """examples:
  softpad plan --delta 0,0.124,0.078,0.109,0,0          banana on modules 2, 3, 4
  softpad plan --pressures 1.2,1.1,1.1,1.1,1.1,1.15 --reference 1.1,1.1,1.1,1.1,1.1,1.1
  echo '{"delta_kpa": [0,0,0.062,0,0,0.062]}' | softpad plan --frame - --json

frame files: JSON {"delta_kpa": [...]} or {"pressures_kpa": [...], "reference_kpa": [...]};
CSV with a header row naming delta_kpa (or pressure_kpa and reference_kpa), one row per module
in module order, or a single line of N increments in kPa.
"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "plan",
        help="plan top grasps from module pressure increments",
        description=(
            "Detect the objects on the pad (modules with dP above t_o, 8-connected groups), "
            "compute each one's pressure-based centre of mass (PCOM, Eq. 6.1) and plan a top "
            "grasp: centre of grasp COG (module units and metres) and the direction theta in "
            "which the jaws close (radians from the pad x axis)."
        ),
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
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
    p.add_argument(
        "--threshold-kpa",
        type=finite_float("threshold", lo=0.0, unit="kPa"),
        default=thesis.OBJECT_THRESHOLD_PA / 1e3,
        help="object-detection threshold t_o in kPa (default %(default)g)",
    )
    p.add_argument(
        "--pitch-mm",
        type=finite_float("pitch", lo=1.0, hi=1000.0, unit="mm"),
        default=45.0,
        help="module side in mm (default 45)",
    )
    p.add_argument(
        "--safety-shift",
        type=finite_float("safety shift", lo=0.0, hi=0.49, unit="module units"),
        default=0.2,
        help="c_s, safety shift of corner-shaped objects in module units (default 0.2)",
    )
    p.add_argument("--json", action="store_true", help="print the plans as JSON")
    p.add_argument(
        "--png", metavar="FILE.png", help="draw the pad, increments, PCOM, COG and fingertips"
    )
    p.set_defaults(handler=run)


def _read_frame(path: str) -> tuple[list[float], list[float] | None]:
    """Read a frame file; returns (values_pa, reference_pa or None)."""
    if path == "-":
        text = sys.stdin.read()
    else:
        try:
            text = Path(path).read_text()
        except OSError as exc:
            raise InputError(f"cannot read frame file {path!r}: {exc.strerror}") from None
    stripped = text.strip()
    if not stripped:
        raise InputError(f"frame file {path!r} is empty")
    if stripped.startswith("{"):
        try:
            data = json.loads(stripped)
        except json.JSONDecodeError as exc:
            raise InputError(
                f"frame file {path!r} is not valid JSON: {exc.msg} at line {exc.lineno}"
            ) from None
        if "delta_kpa" in data:
            return _numbers(data["delta_kpa"], "delta_kpa"), None
        if "pressures_kpa" in data and "reference_kpa" in data:
            return _numbers(data["pressures_kpa"], "pressures_kpa"), _numbers(
                data["reference_kpa"], "reference_kpa"
            )
        raise InputError(
            f"frame file {path!r} needs key delta_kpa, or pressures_kpa and reference_kpa"
        )
    rows = [r for r in csv.reader(io.StringIO(stripped)) if any(c.strip() for c in r)]
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


def run(args: argparse.Namespace) -> int:
    from softpad.layout import parse_layout
    from softpad.planning import PlannerParams, format_plans, plan_grasps
    from softpad.sensing import increments

    layout = parse_layout(args.layout, pitch_m=args.pitch_mm / 1e3)
    reference: list[float] | None
    if args.delta is not None:
        values, reference = kpa_list(args.delta, "--delta"), None
    elif args.pressures is not None:
        if args.reference is None:
            raise InputError("--pressures needs --reference (the pressures saved after inflation)")
        values, reference = (
            kpa_list(args.pressures, "--pressures"),
            kpa_list(args.reference, "--reference"),
        )
    else:
        values, reference = _read_frame(args.frame)
    if reference is not None:
        if len(values) != layout.n_modules or len(reference) != layout.n_modules:
            raise InputError(
                f"a {layout.name} pad needs {layout.n_modules} pressures and {layout.n_modules} "
                f"reference values, got {len(values)} and {len(reference)}"
            )
        delta = list(increments(values, reference))
    else:
        delta = values
    params = PlannerParams(
        object_threshold_pa=args.threshold_kpa * 1e3, safety_shift=args.safety_shift
    )
    plans = plan_grasps(delta, layout, params)
    if args.json:
        print(json.dumps({"objects": [p.to_dict(layout) for p in plans]}))
    else:
        print(format_plans(delta, plans, layout, params.object_threshold_pa))
    if args.png:
        _save_plot(args.png, delta, plans, layout)
    return 0


def _save_plot(path: str, delta: list[float], plans: Any, layout: Any) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from softpad.planning import plot_plans

    ax = plot_plans(delta, plans, layout, title="SoftPad plan")
    try:
        ax.figure.savefig(path, dpi=130, bbox_inches="tight")
    except (OSError, ValueError) as exc:
        raise InputError(f"cannot write plot {path!r}: {exc}") from None
    finally:
        plt.close(ax.figure)
    print(f"plot written to {path}", file=sys.stderr)
