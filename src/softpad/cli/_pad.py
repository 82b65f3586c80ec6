"""``softpad pad probe|map``: press a rigid flat block on the simulated pad, read the response."""

from __future__ import annotations

import argparse
import math
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
    from softpad.sim import PadResponse, pad_sensitivities

    gain = {} if args.line_gain is None else {"line_gain": args.line_gain}
    response = PadResponse(pad_model=args.pad_model, **gain)
    out = pad_sensitivities(response, args.pressure_kpa * 1e3)
    if args.json:
        emit({"command": "pad sensitivity", **out})
        return 0
    say(
        f"{out['pad_model']} pad at {args.pressure_kpa:g} kPa, line gain {out['line_gain']:g}: "
        "sealed rise per newton (Pa/N)"
    )
    for name, v in out["loads"].items():
        rises = " ".join(f"{r:6.0f}" for r in v["rise_pa_n"])
        say(f"  {name:45s} modules 1-6: {rises}")
    say(f"line sensitivity (can strip, least of modules 1, 4): {out['line_pa_n']:.0f} Pa/N")
    say(f"corner sensitivity (least of modules 1, 2, 4, 5): {out['corner_pa_n']:.0f} Pa/N")
    for name, g in out["min_detectable_mass_g"].items():
        say(f"minimum detectable mass at t_o = 50 Pa, {name}: {g:.2f} g")
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
    from softpad.sim import probe_box

    size = _footprint(args)
    with _open_sim(args.box) as box:
        lay = box.world.layout
        x, y = _pair(args.at, "--at", 0.0, float(max(lay.cols, lay.rows)), "module units")
        if x > lay.cols or y > lay.rows:
            raise InputError(
                f"--at {x:g},{y:g} is off the {lay.rows}x{lay.cols} pad (x 0..{lay.cols}, "
                f"y 0..{lay.rows} module units)"
            )
        at_m = (x * lay.pitch_m, y * lay.pitch_m)
        result = probe_box(box, at_m, size, args.force_n)
    out = {
        "command": "pad probe",
        "box": args.box,
        "at": [x, y],
        "at_m": list(at_m),
        "force_n": args.force_n,
        "footprint_mm": [size[0] * 1e3, size[1] * 1e3],
        "reference_kpa": [round(v / 1e3, 6) for v in result.reference_pa],
        "delta_kpa": [round(v / 1e3, 6) for v in result.delta_pa],
        "fem_delta_kpa": [round(v / 1e3, 6) for v in result.fem_delta_pa],
        "delta_kpa_per_n": [round(v / 1e3 / args.force_n, 6) for v in result.delta_pa],
        "fem_delta_kpa_per_n": [round(v / 1e3 / args.force_n, 6) for v in result.fem_delta_pa],
    }
    if args.json:
        emit(out)
        return 0
    say(
        f"block {size[0] * 1e3:g} x {size[1] * 1e3:g} mm, {args.force_n:g} N at ({x:g}, {y:g}) "
        f"module units on {args.box}"
    )
    say("module  delta_kPa  delta_kPa/N  FEM_kPa  FEM_kPa/N")
    per_n = 1e3 * args.force_n  # Pa -> kPa/N
    for k, (d, f) in enumerate(zip(result.delta_pa, result.fem_delta_pa, strict=True), 1):
        say(f"{k:6d}  {d / 1e3:9.4f}  {d / per_n:11.3f}  {f / 1e3:7.4f}  {f / per_n:9.3f}")
    return 0


def _map(args: argparse.Namespace) -> int:
    import numpy as np

    from softpad.sim import sealed_rise_map

    size = _footprint(args)
    png = check_output(args.png, "--png", force=args.force, suffix=".png")
    assert png is not None  # --png is required
    with _open_sim(args.box) as box:
        world, step = box.world, args.step_mm * 1e-3
        lay = world.layout
        xs = np.arange(0.5 * step, lay.cols * lay.pitch_m, step)
        ys = np.arange(0.5 * step, lay.rows * lay.pitch_m, step)
        p0 = float(np.median(box.true_pressures_pa[: lay.n_modules]))
        if p0 < thesis.P0_RANGE_PA[0] - 1.0:
            raise InputError(
                f"the box's modules are at {p0 / 1e3:g} kPa; inflate them first "
                f"(e.g. sim://?inflated_kpa=1.1), p0 range {thesis.P0_RANGE_PA[0] / 1e3:g}.."
                f"{thesis.P0_RANGE_PA[1] / 1e3:g} kPa"
            )
        rise = sealed_rise_map(
            world.response, box.characteristic, p0, args.force_n, size, xs, ys, box.pneumatics
        )
    top = rise.max(axis=2)
    with atomic_path(png) as tmp:
        _draw_map(tmp, xs, ys, top, lay, size, args.force_n, p0)
    out = {
        "command": "pad map",
        "box": args.box,
        "png": str(png),
        "force_n": args.force_n,
        "footprint_mm": [size[0] * 1e3, size[1] * 1e3],
        "pressure_kpa": p0 / 1e3,
        "largest_kpa": float(top.max()) / 1e3,
        "smallest_kpa": float(top.min()) / 1e3,
        "share_above_object_threshold": float((top >= thesis.OBJECT_THRESHOLD_PA).mean()),
    }
    if args.json:
        emit(out)
        return 0
    say(
        f"wrote {png}: largest module rise {out['largest_kpa']:.4f} kPa, "
        f"{100 * out['share_above_object_threshold']:.0f} % of block centres above t_o"
    )
    return 0


def _draw_map(
    path: Any,
    xs: Any,
    ys: Any,
    top: Any,
    lay: Any,
    size: tuple[float, float],
    force: float,
    p0: float,
) -> None:
    """The heat map (kPa) with module outlines and threshold contours, saved as PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    fig, ax = plt.subplots(figsize=(1.6 + 2.2 * lay.cols, 0.8 + 2.2 * lay.rows))
    units = 1.0 / lay.pitch_m
    ext = (0.0, lay.cols, 0.0, lay.rows)
    im = ax.imshow(top / 1e3, origin="lower", extent=ext, cmap="viridis", aspect="equal")
    fig.colorbar(im, ax=ax, label="largest module rise (kPa)")
    levels = [thesis.OBJECT_THRESHOLD_PA / 1e3, thesis.CONTACT_THRESHOLD_PA / 1e3]
    if top.max() / 1e3 > levels[0]:
        cs = ax.contour(xs * units, ys * units, top / 1e3, levels=levels, colors=["w", "r"])
        ax.clabel(cs, fmt=lambda v: f"{v * 1e3:.0f} Pa")
    for k in range(lay.n_modules):
        r, c = divmod(k, lay.cols)
        ax.add_patch(Rectangle((c, lay.rows - 1 - r), 1, 1, fill=False, ec="k", lw=1.2))
        ax.text(c + 0.05, lay.rows - 1 - r + 0.05, str(k + 1), color="w", fontsize=9)
    ax.set_xlabel("x (module units)")
    ax.set_ylabel("y (module units)")
    ax.set_title(
        f"{force:g} N on {size[0] * 1e3:g} x {size[1] * 1e3:g} mm, p0 = {p0 / 1e3:.2f} kPa",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(path, format="png", dpi=110)
    plt.close(fig)
    if not math.isfinite(float(top.max())):  # pragma: no cover - guarded by the physics
        raise InputError("the map has no finite values")
