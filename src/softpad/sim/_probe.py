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
