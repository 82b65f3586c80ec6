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

A calibration recording (protocol in docs/validation.md) holds the sealed pad idle, then known
masses put down one at a time, each a 'calibration_load' event (mass_g, x_mm, y_mm, size_mm)
and lifted with a 'calibration_unload' event; softpad.trials.record_calibration writes one
from any box. The fit: sensor noise and leak from the idle minute, response scale and seam
width by least squares of every module's increment on the simulator's sealed rise.
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
    p.add_argument("recordings", nargs="+", metavar="REC.mcap", help="calibration recordings")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from softpad.trials import calibrate

    for path in args.recordings:
        if not Path(path).is_file():
            raise InputError(f"recording {path!r} does not exist")
    result = calibrate(args.recordings)
    say(result.to_text(), args.json)
    if args.json:
        emit(result.to_dict())
    return 0
