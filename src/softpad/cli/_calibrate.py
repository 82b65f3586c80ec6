"""``softpad calibrate``: the pad's uncertain parameters fitted to recordings of known loads."""

from __future__ import annotations

import argparse
from typing import Any

from softpad.cli._args import add_command
from softpad.cli._output import emit, say
from softpad.errors import InputError

_EPILOG = """examples:
  softpad calibrate session.mcap                 fit response scale, seam, noise and leak
  softpad calibrate a.mcap b.mcap --json         several sessions pooled
  softpad calibrate --objects                    fit the objects' unknowns to Table 6.1's plans

A calibration recording (protocol in docs/validation.md) holds the sealed pad idle, then known
masses put down one at a time, each a 'calibration_load' event (mass_g, x_mm, y_mm, size_mm)
and lifted with a 'calibration_unload' event; softpad.trials.record_calibration writes one
from any box. The fit: sensor noise and leak from the idle minute, response scale and seam
width by least squares of every module's increment on the simulator's sealed rise.

--objects fits instead each Table 6.1 object's unknown the thesis does not give (the can's end
weight, the charger's mass split, the limes' arrangement, the toy's shape, the banana's
curve) to the thesis's plan of that object, the only evidence for it: the value of its
sourced range whose modal plan over placement draws (analytic world, noisy box) lies nearest
the thesis's (COG distance in modules plus the direction's error in 45-degree steps), on an
even grid; ties to the middle one. Those plan rows are 'calibration' in softpad validate.
"""

_DESCRIPTION = """\
Fit the pad's uncertain parameters (response scale, seam width, sensor noise, leak) to
calibration recordings of known loads, so that the simulator answers to this pad."""


def register(sub: Any) -> None:
    p = add_command(
        sub,
        "calibrate",
        "fit the pad's uncertain parameters to recordings of known loads",
        _DESCRIPTION,
        _EPILOG,
        json="print the fitted parameters as one JSON object",
    )
    p.add_argument("recordings", nargs="*", metavar="REC.mcap", help="calibration recordings")
    p.add_argument(
        "--objects",
        action="store_true",
        help="fit the Table 6.1 objects' unknowns to the thesis's plans (no recordings)",
    )
    p.add_argument(
        "--draws", type=int, default=20, help="--objects: placement draws per value (default 20)"
    )
    p.add_argument(
        "--grid", type=int, default=13, help="--objects: values over each range (default 13)"
    )
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from softpad.trials import calibrate

    if args.objects:
        return _objects(args)
    if not args.recordings:
        raise InputError("give calibration recordings (REC.mcap ...) or --objects")
    for path in args.recordings:
        if not Path(path).is_file():
            raise InputError(f"recording {path!r} does not exist")
    result = calibrate(args.recordings)
    say(result.to_text(), args.json)
    if args.json:
        emit(result.to_dict())
    return 0


def _objects(args: argparse.Namespace) -> int:
    """``--objects``: the objects' unknowns fitted to Table 6.1's plans."""
    from softpad.trials import fit_object_unknowns, object_fits_table

    if args.recordings:
        raise InputError("--objects fits to the thesis's plans and takes no recordings")
    fits = fit_object_unknowns(draws=args.draws, grid=args.grid)
    say(object_fits_table(fits), args.json)
    if args.json:
        emit({"draws": args.draws, "grid": args.grid, "fits": [f.to_dict() for f in fits]})
    return 0
