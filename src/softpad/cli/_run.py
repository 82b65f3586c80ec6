"""``softpad run``: the whole closed loop once, on the simulated box, for thesis objects."""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any

from softpad import SCHEMA_VERSION, thesis
from softpad.cli._args import finite_float
from softpad.cli._record import add_record_option, open_recorder, run_metadata
from softpad.errors import HardwareFault

#: Exit code of a run ended by a hardware or link fault (after the verified safe state).
EXIT_HARDWARE = 3

_EPILOG = """examples:
  softpad run --object banana
  softpad run --object object-4 --png run.png --record run.mcap
  softpad run --object object-1 --object object-4       two objects, grasped one after the other
  softpad run --box 'sim://?seed=3&rate_hz=200' --object charger --json

objects: object-1 .. object-6, banana, toy, limes, cylinder, charger (seed, Table 6.1)
"""


def register(sub: Any) -> None:
    p = sub.add_parser(
        "run",
        help="run the closed loop (inflate, reference, plan, approach, contact, grasp, hold)",
        description=(
            "Run the whole grasp loop of the seed's Section 6.2 once on the simulated box: inflate "
            "every module to p0 and save the reference, place the object(s) of the thesis set, plan "
            "the grasp from the pressure increments, move over the centre of grasp, descend at "
            "the approach speed until the pad senses the fingers (running average of 10 samples above t_g), "
            "close, lift, hold for 15 s, and print the timeline."
        ),
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--box", default="sim://", metavar="URL", help="box URL (default sim://)")
    p.add_argument(
        "--object",
        action="append",
        metavar="NAME",
        help="thesis object to place (repeat for several; default banana)",
    )
    p.add_argument(
        "--gripper",
        choices=("10/4", "6/2", "4/0"),
        help="gripper mounting, max/min width in cm (default: the object's, Section 6.3)",
    )
    p.add_argument(
        "--hold-s",
        type=finite_float("hold time", lo=0.0, hi=3600.0, unit="s"),
        default=thesis.HOLD_S,
        help="hold time in s (default %(default)g)",
    )
    p.add_argument(
        "--config",
        metavar="FILE.toml",
        help="installation file: thresholds (p0, t_adj, t_o, t_g, window, maximum) and gripper",
    )
    p.add_argument("--json", action="store_true", help="print the timeline as one JSON object")
    p.add_argument("--png", metavar="FILE.png", help="draw the pressure traces with the phases")
    add_record_option(p)
    p.add_argument(
        "--foxglove",
        type=int,
        metavar="PORT",
        help="serve the run live to Foxglove on ws://127.0.0.1:PORT (0: a free port)",
    )
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from softpad.box import open_box
    from softpad.control import ExecutionParams
    from softpad.harness import resolve_objects, run_simulated
    from softpad.record import RunLog, Tee, check_output

    specs = resolve_objects(args.object)  # unknown names fail before anything starts
    if args.record:
        check_output(args.record, args.force)
    names = [s.name for s in specs]
    log = RunLog({"box": args.box, "objects": names})
    params = ExecutionParams(hold_s=args.hold_s)
    parts: dict[str, Any] = {}
    gripper = args.gripper
    if args.config:
        params, parts, mounting = _from_installation(args.config, params)
        gripper = gripper or mounting
    with open_box(args.box) as box:
        meta = run_metadata("run", box, args.box, names, params, gripper=gripper)
        recorder = open_recorder(args.record, box, meta, args.force)
        live = _live(args.foxglove, box)
        try:
            tee = Tee(log, recorder, live)
            result = run_simulated(names, box, params, tee, gripper=gripper, **parts)
        except HardwareFault as exc:
            return _report_fault(args, log, exc)
        finally:
            # whatever happened, what was recorded is kept
            for r in (recorder, live):
                if r is not None:
                    r.close()
            if args.png and len(log):
                log.plot(args.png, title=f"softpad run: {', '.join(names)}")
    d = {"schema_version": SCHEMA_VERSION, **result.to_dict()}
    if args.json:
        print(json.dumps(d))
        return 0
    print(f"softpad run: {', '.join(names)} on {args.box}")
    for line in _timeline(log, result):
        print("  " + line)
    print(f"outcome: {result.outcome}")
    if args.png:
        print(f"pressure traces: {args.png}")
    if args.record:
        print(f"recording: {args.record}")
    return 0


def _from_installation(path: str, params: Any) -> tuple[Any, dict[str, Any], str | None]:
    """Loop parameters, detector parts and gripper mounting from an installation file."""
    import dataclasses

    from softpad.config import load_installation
    from softpad.sensing import ThesisObjectDetector

    inst = load_installation(path)
    th = inst.thresholds
    inflation = dataclasses.replace(
        params.inflation,
        target_pa=th.p0_pa,
        tolerance_pa=th.adjust_tolerance_pa,
        max_pressure_pa=th.max_pressure_pa,
        filter_length=th.filter_window,
    )
    params = dataclasses.replace(
        params,
        inflation=inflation,
        contact_threshold_pa=th.contact_threshold_pa,
        filter_length=th.filter_window,
    )
    parts = {"object_detector": ThesisObjectDetector(threshold_pa=th.object_threshold_pa)}
    return params, parts, inst.gripper_mounting


def _live(port: int | None, box: Any) -> Any:
    if port is None:
        return None
    from softpad.box import SimBox
    from softpad.errors import InputError
    from softpad.record import FoxgloveLive

    if not 0 <= port <= 65535:
        raise InputError(f"--foxglove port must be within 0..65535, got {port}")
    robot = box.world.gripper_state if isinstance(box, SimBox) else None
    live = FoxgloveLive(port, robot_state=robot)
    print(f"foxglove: {live.url} (port {live.port})", flush=True)
    return live


def _report_fault(args: argparse.Namespace, log: Any, exc: Exception) -> int:
    """Print what was detected and the safe state reached; the hardware-fault exit code."""
    faults = [f.to_dict() for f in getattr(exc, "faults", ())]
    safe = getattr(exc, "safe_state", None)
    d = {
        "schema_version": SCHEMA_VERSION,
        "outcome": "fault",
        "error": str(exc),
        "faults": faults,
        "safe_state": None if safe is None else safe.to_dict(),
        "phases": [
            {"phase": e["phase"], "t_s": round(t, 4)} for t, k, e in log.events if k == "phase"
        ],
    }
    if args.json:
        print(json.dumps(d))
    else:
        for f in faults:
            print(f"t = {f['t_s']:7.2f} s  fault on channel {f['channel']} ({f['cause']})")
        if safe is not None:
            kpa = ", ".join("nan" if v != v else f"{v / 1e3:.3f}" for v in safe.pressures_pa)
            state = "verified" if safe.verified else f"NOT verified: {safe.reason}"
            print(f"safe state {state}; pressures {kpa} kPa")
    print(f"softpad run: hardware fault: {exc}", file=sys.stderr)
    return EXIT_HARDWARE


def _kpa(values: Any) -> str:
    return " ".join(f"{v / 1e3:.3f}" for v in values)


def _modules(d: dict[str, Any]) -> str:
    return ", ".join(map(str, d["modules"]))


def _plan_lines(d: dict[str, Any]) -> list[str]:
    lines = [f"increments (kPa): {_kpa(d['increments_pa'])}"]
    for o in d["objects"]:
        lines.append(
            f"plan: modules {','.join(map(str, o['modules']))}  PCOM "
            f"({o['pcom'][0]:.2f}, {o['pcom'][1]:.2f})  COG ({o['cog'][0]:.2f}, {o['cog'][1]:.2f})  "
            f"theta {o['theta']:+.3f} rad ({math.degrees(o['theta']):+.0f} deg)  [{o['rule']}]"
        )
    return lines


#: How each event kind of a run reads in the timeline (kinds not listed are not shown).
_EVENT_TEXT: dict[str, Any] = {
    "adjusted": lambda d: [
        f"adjusted: every module within tolerance of {d['target_pa'] / 1e3:.3f} kPa"
    ],
    "reference": lambda d: [f"reference saved (kPa): {_kpa(d['reference_pa'])}"],
    "object_seen": lambda d: [f"object detected on module(s) {_modules(d)}"],
    "plan": _plan_lines,
    "contact": lambda d: [f"contact detected on module(s) {_modules(d)}"],
    "no_contact": lambda d: [
        f"no contact detected down to {d['z_m'] * 1e3:.1f} mm: gripper not closed"
    ],
    "outcome": lambda d: [d["outcome"]],
}
_SHOWN_PHASES = ("approach", "descend", "close", "lift", "hold", "release")


def _timeline(log: Any, result: Any) -> list[str]:
    lines = []
    for t, kind, d in log.events:
        if kind == "phase" and d["phase"] in _SHOWN_PHASES:
            lines.append(f"t = {t:7.2f} s  {d['phase']}")
        elif kind in _EVENT_TEXT:
            lines += [f"t = {t:7.2f} s  {text}" for text in _EVENT_TEXT[kind](d)]
    for i, g in enumerate(result.result.grasps):
        delay, travel = result.contact_delay_s(i), result.finger_travel_m(i)
        if delay is not None and travel is not None:
            lines.append(
                f"grasp {i + 1}: contact {delay * 1e3:.0f} ms after the first fingertip touch, "
                f"finger travel {travel * 1e3:.1f} mm; outcome {g.outcome}"
            )
        else:
            lines.append(f"grasp {i + 1}: outcome {g.outcome}")
    return lines


if __name__ == "__main__":  # pragma: no cover
    sys.exit(0)
