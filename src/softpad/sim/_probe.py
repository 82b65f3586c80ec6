"""Probing the simulated pad: press a rigid flat block and read every module's pressure rise.

:func:`probe_box` presses a block on the world of a simulated box and measures the rise the way
the controller would (mean of reads before and after); :func:`sealed_rise_map` computes, for a
block centred at every point of a grid, the sealed pressure rise of every module with the same
physics (FEM response -> equivalent loads -> gas law on the module characteristic, ideal sensor)
vectorised over the grid.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.sim._characteristic import ModuleCharacteristic
from softpad.sim._pneumatics import ChamberBank, PneumaticParams
from softpad.sim._response import PadResponse, operating_pressure, rect_points

#: Simulated time between pressing the block and reading, seconds (the gas settles in ms).
SETTLE_S = 0.5
#: Sampling step of a block's footprint in a map, metres.
MAP_FOOTPRINT_STEP_M = 1e-3


@dataclass(frozen=True)
class ProbeResult:
    """Pressure rise of every module under a probe block."""

    #: Mean reading of every module before the block, Pa.
    reference_pa: NDArray[np.float64]
    #: Mean reading with the block minus the reference, Pa (module order).
    delta_pa: NDArray[np.float64]
    #: The FEM's small-load prediction of the same rise (linear, no sensor), Pa.
    fem_delta_pa: NDArray[np.float64]


def check_block(
    at_m: tuple[float, float],
    size_m: tuple[float, float],
    force_n: float,
    width_m: float,
    height_m: float,
) -> None:
    """InputError unless the block's centre lies on the pad, its sides are within (0, 0.2] m
    and the force within (0, 50] N."""
    x, y = at_m
    if not (0.0 <= x <= width_m and 0.0 <= y <= height_m):
        raise InputError(
            f"block centre ({x * 1e3:g}, {y * 1e3:g}) mm is off the pad "
            f"(0..{width_m * 1e3:g} x 0..{height_m * 1e3:g} mm)"
        )
    for name, v in zip(("width", "length"), size_m, strict=True):
        if not (0.0 < v <= 0.2):
            raise InputError(f"block {name} must be within 0..200 mm, got {v * 1e3:g} mm")
    if not (0.0 < force_n <= 50.0):
        raise InputError(f"block force must be within 0..50 N, got {force_n:g} N")


def probe_box(
    box: Any,
    at_m: tuple[float, float],
    size_m: tuple[float, float],
    force_n: float,
    settle_s: float = SETTLE_S,
    reads: int = thesis.REFERENCE_READS,
) -> ProbeResult:
    """Press a block on a simulated box's pad and measure every module's rise.

    Parameters
    ----------
    box
        A simulated box (:class:`softpad.box.SimBox`) whose world has ``press``.
    at_m
        Block centre, pad frame, metres.
    size_m
        Block sides along x and y, metres.
    force_n
        Force on the block, newtons.
    settle_s
        Simulated time waited before each measurement, seconds.
    reads
        Reads averaged for the reference and for the loaded state.
    """
    world = getattr(box, "world", None)
    if world is None or not hasattr(world, "press"):
        raise InputError(
            "pad probe needs a simulated box whose pad it can press (sim://...); "
            f"{type(box).__name__} has none"
        )
    lay = world.layout
    check_block(at_m, size_m, force_n, lay.cols * lay.pitch_m, lay.rows * lay.pitch_m)
    n = lay.n_modules
    frames = max(1, round(settle_s * box.sample_rate_hz))
    box.read_many(frames)
    ref = np.mean([f.pressures_pa[:n] for f in box.read_many(reads)], axis=0)
    p_op = float(np.median(ref))
    world.press(at_m, size_m, force_n)
    box.read_many(frames)
    after = np.mean([f.pressures_pa[:n] for f in box.read_many(reads)], axis=0)
    world.press(at_m, size_m, 0.0)
    gas = {"tubing_volume_m3": box.pneumatics.tubing_volume_m3}
    eq = world.response.rect_equivalent_loads(at_m, size_m, force_n, p_op)
    fem = world.response.sealed_rise_pa(eq, p_op, **gas)
    return ProbeResult(ref, after - ref, np.asarray(fem))


def sealed_rise_map(
    response: PadResponse,
    characteristic: ModuleCharacteristic,
    pressure_pa: float,
    force_n: float,
    size_m: tuple[float, float],
    xs_m: NDArray[np.float64],
    ys_m: NDArray[np.float64],
    pneumatics: PneumaticParams | None = None,
) -> NDArray[np.float64]:
    """Sealed pressure rise of every module for a block centred at every grid point, Pa.

    Returns
    -------
    ndarray, shape (len(ys_m), len(xs_m), n_modules)
    """
    n = response.layout.n_modules
    p_op = operating_pressure(pressure_pa, response.response)
    local = rect_points((0.0, 0.0), size_m, 0.0, MAP_FOOTPRINT_STEP_M)
    f_point = force_n / len(local)
    loads = np.zeros((len(ys_m), len(xs_m), n))
    for i, y in enumerate(ys_m):
        for j, x in enumerate(xs_m):
            loads[i, j] = response.equivalent_loads(local + np.array([x, y]), f_point, p_op)
    flat = loads.reshape(-1)
    bank = ChamberBank(flat.size, flat.size, characteristic, pneumatics)
    bank.set_state(np.full(flat.size, float(pressure_pa)), np.zeros(flat.size))
    closed = np.zeros(flat.size, dtype=bool)
    bank.step(1e-3, closed, closed, flat, 0.0, False, same_load=False)
    return (bank.pressure_pa - pressure_pa).reshape(loads.shape)


#: Loads of :func:`pad_sensitivities` on the 2 x 3 pad: name -> (centre in module units, block
#: sides in metres (-1: one pitch), modules read (0-based)). The can's strip: the thesis's can
#: (50 mm across) astride the line between the rows, wrapped over 25 mm
#: (``softpad.trials._validate.cylinder_line_budget``).
SENSITIVITY_LOADS: dict[str, tuple[tuple[float, float], tuple[float, float], tuple[int, ...]]] = {
    "centre: Duplo face 42x31 mm on module 1": ((0.5, 1.5), (0.042, 0.031), (0,)),
    "centre: 10x10 mm weight on module 1": ((0.5, 1.5), (0.010, 0.010), (0,)),
    "line: can strip 45x25 mm on the line 1|4": ((0.5, 1.0), (-1.0, 0.025), (0, 3)),
    "line: 10x10 mm on the line 1|2": ((1.0, 1.5), (0.010, 0.010), (0, 1)),
    "corner: 10x10 mm at the corner 1|2|4|5": ((1.0, 1.0), (0.010, 0.010), (0, 1, 3, 4)),
}


def pad_sensitivities(
    response: PadResponse | None = None,
    pressure_pa: float = thesis.P0_PA,
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA,
    tubing_volume_m3: float = thesis.TUBING_VOLUME_M3,
) -> dict[str, Any]:
    """The pad's small-load sensitivities as the simulator has them (the FEM's sealed rise,
    :meth:`PadResponse.sealed_rise_pa`): every module's rise per newton for the loads of
    :data:`SENSITIVITY_LOADS` and the minimum detectable masses at ``threshold_pa`` (t_o).

    Parameters
    ----------
    response
        The pad's response (default: the packaged one, the cast pad where it fits).
    pressure_pa
        Pressure of every module when the valves closed, Pa.
    threshold_pa
        Detection threshold t_o, Pa.
    tubing_volume_m3
        Tubing per channel, m^3.

    Returns
    -------
    dict
        ``pad_model``, ``pressure_pa``, ``loads``: {name: {"rise_pa_n": every module,
        "read_on": 1-based modules, "min_rise_pa_n"}}, ``line_pa_n``, ``corner_pa_n`` (the
        can strip's and the corner block's least-raised module read), ``min_detectable_mass_g``:
        {footprint: g}.
    """
    r = response or PadResponse()
    lay = r.layout
    if (lay.rows, lay.cols) != (2, 3):
        raise InputError(f"the sensitivity loads are laid out for the 2 x 3 pad, not {lay}")
    loads: dict[str, Any] = {}
    for name, (at, size, read_on) in SENSITIVITY_LOADS.items():
        side = tuple(lay.pitch_m if v < 0 else v for v in size)
        centre = (at[0] * lay.pitch_m, at[1] * lay.pitch_m)
        eq = r.rect_equivalent_loads(centre, side, 1.0, pressure_pa)
        rise = r.sealed_rise_pa(eq, pressure_pa, tubing_volume_m3=tubing_volume_m3)
        loads[name] = {
            "rise_pa_n": [float(v) for v in rise],
            "read_on": [k + 1 for k in read_on],
            "min_rise_pa_n": float(min(rise[k] for k in read_on)),
        }
    g = 9.80665
    names = list(SENSITIVITY_LOADS)
    return {
        "pad_model": r.pad_model,
        "line_gain": r.line_gain,
        "pressure_pa": float(pressure_pa),
        "loads": loads,
        "line_pa_n": loads[names[2]]["min_rise_pa_n"],
        "corner_pa_n": loads[names[4]]["min_rise_pa_n"],
        "min_detectable_mass_g": {
            name.split(": ")[1].split(" on ")[0]: threshold_pa
            / (g * loads[name]["min_rise_pa_n"])
            * 1e3
            for name in names[:2]
        },
    }
