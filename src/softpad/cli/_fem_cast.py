"""``softpad fem cast-response``: the pad as it was cast (one upper layer over every chamber)."""

from __future__ import annotations

import argparse
from typing import Any

from softpad import thesis
from softpad.cli._args import add_command, add_number, number_list
from softpad.cli._output import emit
from softpad.cli._paths import atomic_path, check_output
from softpad.errors import InputError

_HELP = "every chamber's response to a load anywhere on the cast 2 x 3 pad, 0.5..2.8 kPa (.npz)"
_DESCRIPTION = """The pad as the thesis's mould makes it (Section 6.1.1): a continuous 1.5 mm upper
layer of EcoFlex 00-30 over 45 x 45 mm acetate chambers, bonded to the grid's walls between them
and to the border. One FElupe model of the whole layer; at each pressure one factorisation and
one solve per chamber give every chamber's s_k = -dV_k/dF of a point force anywhere on the pad
(reciprocity). The simulator reads the shipped table (softpad/data/cast_pad_response.npz);
developers regenerate it with --out src/softpad/data/cast_pad_response.npz --force."""
_MESHES = {"coarse": (4, 1), "default": (8, 2), "fine": (12, 2)}


def register(fem_sub: Any) -> None:
    """Add ``cast-response`` to ``softpad fem``."""
    p = add_command(fem_sub, "cast-response", _HELP, _DESCRIPTION, force=True)
    p.add_argument("--model", default="neo-hookean", help="material preset (default neo-hookean)")
    add_number(
        p,
        "--wall-mm",
        "width of the grid's walls between acetate sheets, mm (default 1; the thesis gives none)",
        1.0,
        lo=0.05,
        hi=10.0,
        unit="mm",
    )
    add_number(
        p,
        "--foundation-mpa-per-m",
        "Winkler stiffness under the walls, MPa/m (default: rigid walls)",
        None,
        lo=1e-3,
        hi=1e6,
        unit="MPa/m",
    )
    p.add_argument(
        "--mesh",
        choices=tuple(_MESHES),
        default="default",
        help="cells from a chamber's centre to its wall x through the layer: "
        + ", ".join(f"{k} {a}x{b}" for k, (a, b) in _MESHES.items()),
    )
    p.add_argument(
        "--pressures-kpa", help="increasing pressures in kPa (default 0.5..2.8, 9 values)"
    )
    p.add_argument(
        "--out",
        metavar="FILE.npz",
        default="cast_pad_response.npz",
        help="output file (default ./cast_pad_response.npz)",
    )
    p.set_defaults(handler=_cast_response)


def _cast_response(args: argparse.Namespace) -> int:
    from softpad.fem import StudyFiles, run_cast_response

    out = check_output(args.out, "--out", force=args.force, suffix=".npz")
    if out is None:
        raise InputError("--out needs a file name")
    pressures = _pressures(args.pressures_kpa)
    shape = (args.wall_mm, args.foundation_mpa_per_m, _MESHES[args.mesh])
    files = StudyFiles(out=out, atomic=atomic_path)
    report = run_cast_response(args.model, *shape, pressures, files)
    if args.json:
        emit(report.data)
    else:
        print("\n".join(report.lines))
    return 0


def _pressures(text: str | None) -> list[float]:
    """``--pressures-kpa`` in Pa (empty when not given); InputError names a value outside
    (0, the module's maximum]."""
    if not text:
        return []
    values = [v * 1e3 for v in number_list(text, "--pressures-kpa")]
    for v in values:
        if not 0.0 < v <= thesis.MAX_PRESSURE_PA:
            raise InputError(
                f"--pressures-kpa: {v / 1e3:g} kPa is outside 0..{thesis.MAX_PRESSURE_PA / 1e3:g} kPa"
            )
    return values
