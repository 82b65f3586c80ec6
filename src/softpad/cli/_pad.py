"""``softpad pad probe|map``: press a rigid flat block on the simulated pad, read the response."""

from __future__ import annotations

import argparse
from typing import Any

from softpad import thesis
from softpad.cli._args import (
    add_box_option,
    add_command,
    add_group,
    add_number,
    finite_float,
    number_list,
)
from softpad.cli._output import emit, say
from softpad.cli._paths import atomic_path, check_output
from softpad.errors import InputError

#: The default box of both commands: the simulated pad at p0 with an ideal sensor.
DEFAULT_BOX = f"sim://?inflated_kpa={thesis.P0_PA / 1e3:g}&noise=0"

_PROBE_EPILOG = f"""examples:
  softpad pad probe --at 1.5,1.5 --force-n 0.2 --footprint-mm 10,10      module 2's centre
  softpad pad probe --at 1.5,1.5 --force-n 0.1236 --footprint-mm 42,31   a 12.6 g Duplo brick
  softpad pad probe --at 2,1.5 --force-n 0.2 --footprint-mm 10,10 --json on the seam of 2 and 3
  softpad pad probe --at 1.5,0.5 --force-n 1 --footprint-mm 8,16 --box 'sim://?inflated_kpa=2&noise=0'

--at is in module units as in 'softpad plan' (x along the columns, y up the rows; module 1's
centre is 0.5,1.5 on the 2x3 pad). The block's force is spread uniformly over its footprint
(sides along x and y); what each chamber feels of it is the FEM module response
(the cast pad's softpad/data/cast_pad_response.npz, 'softpad fem cast-response'; the clamped
modules' softpad/data/module_response.npz where it does not fit). Default box: {DEFAULT_BOX}
(the pad's physics with an ideal sensor; drop noise=0 to see the sensor too).
"""

_MAP_EPILOG = """examples:
  softpad pad map --force-n 0.1236 --footprint-mm 42,31 --png brick.png
  softpad pad map --force-n 1 --footprint-mm 8,16 --png tip.png --step-mm 1.5

Each pixel is a block centred there: the colour is the largest module rise (kPa), with the
module outlines, and contours at the object threshold t_o (50 Pa) and the contact threshold
t_g (90 Pa).
"""


_PROBE_DESCRIPTION = """\
Press a rigid flat block on the simulated pad and print, for every module:
  delta_kPa    its pressure rise on the simulated box: mean of 10 reads after the block was
               put down minus the mean of 10 before, kPa;
  delta_kPa/N  that rise per newton of the block's force (--force-n): the module's
               sensitivity at that point, kPa/N (README.md and docs/results.md quote it);
  FEM_kPa      the rise the FEM module response predicts for this block, linear in the
               force (the sealed chamber's squeeze per newton), kPa;
  FEM_kPa/N    that prediction per newton, kPa/N.
--json carries the same as delta_kpa, delta_kpa_per_n, fem_delta_kpa, fem_delta_kpa_per_n."""


def register(sub: Any) -> None:
    psub = add_group(
        sub,
        "pad",
        "press a block on the simulated pad: module pressure rises (FEM response)",
        "Probe the simulated pad with a rigid flat block.",
        "examples:\n"
        "  softpad pad probe --at 1.5,1.5 --force-n 0.2 --footprint-mm 10,10   rise, kPa and kPa/N\n"
        "  softpad pad map --force-n 0.1236 --footprint-mm 42,31 --png map.png  the brick anywhere\n",
    )
    pr = add_command(
        psub,
        "probe",
        "pressure rise of every module under a block pressed at one point",
        _PROBE_DESCRIPTION,
        _PROBE_EPILOG,
    )
    pr.add_argument("--at", required=True, metavar="X,Y", help="block centre, module units")
    _block_options(pr)
    pr.set_defaults(handler=_probe)
    mp = add_command(
        psub,
        "map",
        "heat map of the largest module rise for a block anywhere on the pad",
        "Draw the pad's response to a block centred at every point (PNG).",
        _MAP_EPILOG,
        force=True,
    )
    _block_options(mp)
    mp.add_argument("--png", required=True, metavar="FILE.png", help="output picture")
    add_number(
        mp,
        "--step-mm",
        "grid step of the block centres in mm (default 2.5)",
        2.5,
        lo=0.5,
        hi=20.0,
        unit="mm",
    )
    mp.set_defaults(handler=_map)
    _sensitivity_command(psub)


def _sensitivity_command(psub: Any) -> None:
    se = add_command(
        psub,
        "sensitivity",
        "line, corner and centre sensitivity (Pa/N) and the minimum detectable mass",
        "The pad's small-load sealed rise per newton for a load on a module's centre, on the "
        "line between two modules and at the corner of four, and the minimum detectable mass "
        "at t_o, from the FEM response the simulator uses (the cast pad by default).",
    )
    se.add_argument(
        "--pad-model",
        choices=("auto", "cast", "clamped"),
        default="auto",
        help="cast: one upper layer over every chamber (softpad fem cast-response); clamped: "
        "independent modules with clamped edges (softpad fem response); auto: cast (default)",
    )
    add_number(
        se,
        "--pressure-kpa",
        "pressure of every module, kPa (default 1.1)",
        thesis.P0_PA / 1e3,
        lo=0.5,
        hi=2.8,
        unit="kPa",
    )
    add_number(
        se,
        "--line-gain",
        "gain on the response near the lines (uncertain input line_response_gain; default "
        "its nominal; 1: the FEM alone)",
        None,
        lo=1.0,
        hi=10.0,
    )
    se.set_defaults(handler=_sensitivity)


def _sensitivity(args: argparse.Namespace) -> int:
    from softpad.sim import PadResponse, pad_sensitivities, sensitivity_lines

    gain = {} if args.line_gain is None else {"line_gain": args.line_gain}
    response = PadResponse(pad_model=args.pad_model, **gain)
    out = pad_sensitivities(response, args.pressure_kpa * 1e3)
    if args.json:
        emit({"command": "pad sensitivity", **out})
        return 0
    for line in sensitivity_lines(out, args.pressure_kpa):
        say(line)
    return 0


def _block_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--force-n",
        required=True,
        type=finite_float("--force-n", lo=1e-6, hi=50.0, unit="N"),
        help="force on the block in N (0..50)",
    )
    p.add_argument(
        "--footprint-mm",
        required=True,
        metavar="W,L",
        help="block sides along x and y in mm (each 0..200)",
    )
    add_box_option(p, DEFAULT_BOX, f"a simulated box URL (default {DEFAULT_BOX})")


def _pair(text: str, flag: str, lo: float, hi: float, unit: str) -> tuple[float, float]:
    """Two numbers ``A,B`` each within [lo, hi] (the flag, value and limits named on error)."""
    values = number_list(text, flag)
    if len(values) != 2:
        raise InputError(f"{flag} needs two comma-separated numbers, got {text!r}")
    for v in values:
        if not lo <= v <= hi:
            raise InputError(f"{flag}: {v:g} {unit} is outside {lo:g}..{hi:g} {unit}")
    return values[0], values[1]


def _footprint(args: argparse.Namespace) -> tuple[float, float]:
    w, length = _pair(args.footprint_mm, "--footprint-mm", 0.0, 200.0, "mm")
    if w < 0.5 or length < 0.5:  # a fingertip's pad is millimetres: below, metres given as mm
        raise InputError(
            f"--footprint-mm sides must be at least 0.5 mm, got {args.footprint_mm!r} "
            "(metres given as millimetres?)"
        )
    return w * 1e-3, length * 1e-3


def _open_sim(url: str) -> Any:
    from softpad.box import open_box

    if not str(url).startswith("sim://"):
        raise InputError(f"--box must be a simulated box (sim://...) to press its pad, got {url!r}")
    return open_box(url)


def _probe(args: argparse.Namespace) -> int:
    from softpad.sim import probe_report

    size = _footprint(args)
    with _open_sim(args.box) as box:
        lay = box.world.layout
        at = _pair(args.at, "--at", 0.0, float(max(lay.cols, lay.rows)), "module units")
        out, lines = probe_report(box, at, size, args.force_n, args.box)
    if args.json:
        emit(out)
        return 0
    for line in lines:
        say(line)
    return 0


def _map(args: argparse.Namespace) -> int:
    from softpad.sim import pad_map

    size = _footprint(args)
    png = check_output(args.png, "--png", force=args.force, suffix=".png")
    assert png is not None  # --png is required
    with _open_sim(args.box) as box:
        heat = pad_map(box, args.force_n, size, args.step_mm * 1e-3)
    with atomic_path(png) as tmp:
        heat.save_png(tmp)
    out = {"command": "pad map", "box": args.box, "png": str(png), **heat.to_dict()}
    if args.json:
        emit(out)
        return 0
    say(
        f"wrote {png}: largest module rise {out['largest_kpa']:.4f} kPa, "
        f"{100 * out['share_above_object_threshold']:.0f} % of block centres above t_o"
    )
    return 0
