"""Module response from the FEM: how much a vertical load at a point of the pad squeezes a chamber.

By reciprocity (the tangent of the inflated layer is symmetric), a small vertical force ``dF`` at
a point ``x`` of a module's top face changes the chamber volume by ``dV = -s(x) dF``, where
``s(x) = dw/dp(x)`` is the rise of the top face there per unit chamber pressure. ``softpad fem
response`` computes ``s`` with the project's finite-element model (:mod:`softpad.fem`) over the
usable range of p0 and stores it in ``softpad/data/module_response.npz``; this module reads the
file (NumPy only) and turns loads into what the gas physics needs:

* :class:`ModuleResponse`: ``s(x, y, p)`` of one module (bilinear in the FEM's nodes, linear in
  p), the chamber volume and compliance at each pressure, and the small-load sealed-chamber
  pressure rise of a flat load of any footprint at any position (the FEM's prediction);
* :class:`PadResponse`: the same on a pad of modules (points on a seam between chambers load
  no chamber), and the *equivalent load* of each module: the load on the characteristic's
  central patch (:mod:`softpad.sim._characteristic`) that squeezes the chamber as much. The
  worlds give the gas physics equivalent loads, so a load's effect depends on where it is and
  how wide it is, and large loads keep the characteristic's nonlinearity (base contact).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import InputError
from softpad.fem import (
    PACKAGED_RESPONSE,
    PRESSURE_STEP_PA,
    RESPONSE_STEP_M,
    RESPONSE_VERSION,
    ModuleResponse,
    rect_points,
)
from softpad.layout import PadLayout

__all__ = [
    "PACKAGED_RESPONSE",
    "PRESSURE_STEP_PA",
    "RESPONSE_STEP_M",
    "RESPONSE_VERSION",
    "ModuleResponse",
    "PadResponse",
    "default_response",
    "operating_pressure",
    "packaged_response_path",
    "rect_points",
]


def packaged_response_path() -> Path | None:
    """Path of the packaged FEM response, or None when it is not installed."""
    from softpad.sim._characteristic import packaged_data_path

    return packaged_data_path(PACKAGED_RESPONSE)


@lru_cache(maxsize=1)
def default_response() -> ModuleResponse:
    """The packaged FEM response (``softpad/data/module_response.npz``).

    Raises
    ------
    InputError
        When the file is missing (regenerate it with ``softpad fem response``).
    """
    path = packaged_response_path()
    if path is None:
        raise InputError(
            f"the packaged module response {PACKAGED_RESPONSE!r} is missing; regenerate it with "
            "'softpad fem response --out src/softpad/data/module_response.npz --force'"
        )
    return ModuleResponse.from_file(path)


class PadResponse:
    """The FEM response on a pad of modules: which chamber a point loads and how much.

    Module k's chamber is a square of the response's chamber side centred on the module;
    points between chambers (the bonded seam, :data:`softpad.thesis.SEAM_WIDTH_M`) or off the
    pad load none. On a pad whose pitch differs from the FEM module's (chamber side plus seam)
    the response is scaled to the pitch, an approximation: regenerate it for such a module
    (``softpad fem response --width-mm``) for its own figures.

    Parameters
    ----------
    layout
        Pad geometry (pitch, rows, columns).
    response
        Module response (the packaged FEM one by default).
    seam_width_m
        Bonded width between chambers instead of the response's, metres (an uncertain
        parameter, :mod:`softpad.sim._uncertain`): the chambers shrink to the pitch less it and
        the FEM response is scaled onto them, an approximation like a different pitch.
    """

    def __init__(
        self,
        layout: PadLayout | None = None,
        response: ModuleResponse | None = None,
        seam_width_m: float | None = None,
    ):
        self.layout = layout or PadLayout()
        self.response = response or default_response()
        seam = float(self.response.meta.get("seam_width_m", 0.0))
        #: Pad pitch over the FEM module's pitch (1 for the default pad).
        self.scale = self.layout.pitch_m / (self.response.chamber_side_m + seam)
        if seam_width_m is not None:
            if not 0.0 <= seam_width_m < self.layout.pitch_m:
                raise InputError(
                    f"seam width must be within 0..{self.layout.pitch_m * 1e3:g} mm, got "
                    f"{seam_width_m * 1e3:g} mm"
                )
            self.scale = (self.layout.pitch_m - seam_width_m) / self.response.chamber_side_m

    @property
    def chamber_side_m(self) -> float:
        """Side of every chamber on this pad, metres."""
        return self.scale * self.response.chamber_side_m

    @property
    def seam_width_m(self) -> float:
        """Bonded width between neighbouring chambers, metres."""
        return max(self.layout.pitch_m - self.chamber_side_m, 0.0)

    def module_centers_m(self) -> NDArray[np.float64]:
        """Centre of every module in the pad frame, (n_modules, 2), metres (module order)."""
        lay = self.layout
        k = np.arange(lay.n_modules)
        row, col = k // lay.cols, k % lay.cols
        return np.column_stack(
            [(col + 0.5) * lay.pitch_m, (lay.rows - 1 - row + 0.5) * lay.pitch_m]
        )

    def locate(self, points_m: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """0-based module of each pad-frame point (-1 on a seam or off the pad) and the point
        relative to that module's centre, metres."""
        pts = np.asarray(points_m, dtype=float).reshape(-1, 2)
        lay, pitch = self.layout, self.layout.pitch_m
        col = np.floor(pts[:, 0] / pitch).astype(np.int64)
        rb = np.floor(pts[:, 1] / pitch).astype(np.int64)
        local = pts - (np.column_stack([col, rb]) + 0.5) * pitch
        half = 0.5 * self.chamber_side_m
        ok = (col >= 0) & (col < lay.cols) & (rb >= 0) & (rb < lay.rows)
        ok &= (np.abs(local[:, 0]) < half) & (np.abs(local[:, 1]) < half)
        idx = np.where(ok, (lay.rows - 1 - rb) * lay.cols + col, -1)
        return idx, local

    def weights(
        self, points_m: ArrayLike, pressure_pa: float
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Module of each point and its equivalent-load factor ``s(x) / s_ref`` (>= 0).

        A force ``f`` at the point squeezes its chamber as much as ``f s(x) / s_ref`` spread over
        the characteristic's central patch.
        """
        idx, local = self.locate(points_m)
        s = self.response.influence(local / self.scale, pressure_pa)
        w = np.where(idx >= 0, s, 0.0) / self.response.reference_influence(pressure_pa)
        return idx, w

    def equivalent_loads(
        self, points_m: ArrayLike, forces_n: ArrayLike, pressure_pa: float
    ) -> NDArray[np.float64]:
        """Equivalent central-patch load of every module, N, for forces at pad-frame points."""
        idx, w = self.weights(points_m, pressure_pa)
        f = np.broadcast_to(np.asarray(forces_n, dtype=float), w.shape)
        on = idx >= 0
        loads = np.bincount(idx[on], weights=(f * w)[on], minlength=self.layout.n_modules)
        return loads.astype(float)

    def rect_equivalent_loads(
        self,
        center_m: ArrayLike,
        size_m: ArrayLike,
        force_n: float,
        pressure_pa: float,
        yaw_rad: float = 0.0,
    ) -> NDArray[np.float64]:
        """Equivalent loads of a force spread uniformly over a rectangle of the pad, N."""
        pts = rect_points(center_m, size_m, yaw_rad)
        return self.equivalent_loads(pts, force_n / len(pts), pressure_pa)

    def sealed_rise_pa(
        self, equivalent_loads_n: ArrayLike, pressure_pa: float, **gas: float
    ) -> NDArray[np.float64]:
        """The FEM's small-load pressure rise of every sealed module, Pa, for its equivalent
        loads (e.g. :meth:`rect_equivalent_loads`): ``F <s>_k / (dV/dp + (V + V_gap + V_t) /
        (p_atm + p))``."""
        eq = np.asarray(equivalent_loads_n, dtype=float)
        s_ref = self.response.reference_influence(pressure_pa)
        return np.asarray(eq * s_ref * self.response.sealed_rise_per_newton(pressure_pa, **gas))


def operating_pressure(pressure_pa: float, response: ModuleResponse) -> float:
    """The pressure at which a world evaluates the response: rounded to
    :data:`PRESSURE_STEP_PA` and clamped to the table's range (below it, during inflation, the
    first row), Pa."""
    p = response.pressure_pa
    q = round(float(pressure_pa) / PRESSURE_STEP_PA) * PRESSURE_STEP_PA
    return float(min(max(q, p[0]), p[-1]))
