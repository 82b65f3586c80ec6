"""The module-response table: the FEM's ``s = -dV/dF`` of a point force at every point of the
top face, with the chamber's volume and compliance, over a range of pressures.

Written by ``softpad fem response`` (:func:`softpad.fem.module_response`), read by the simulator
(:class:`softpad.sim.PadResponse`); NumPy only. By reciprocity (the tangent of the inflated layer
is symmetric), a small vertical force ``dF`` at a point ``x`` changes the chamber volume by
``dV = -s(x) dF`` with ``s(x) = dw/dp(x)``, the rise of the top face there per unit pressure.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError

#: Name of the packaged response file (written by ``softpad fem response``).
PACKAGED_RESPONSE = "module_response.npz"
#: Version of the file layout.
RESPONSE_VERSION = 1
#: Sampling step of footprints when averaging the response, metres.
RESPONSE_STEP_M = 0.5e-3
#: Step of the operating pressure at which the worlds evaluate the response, Pa.
PRESSURE_STEP_PA = 50.0
#: Arrays of the file.
_ARRAYS = (
    "pressure_pa",
    "axis_m",
    "influence_m3_n",
    "volume_m3",
    "compliance_m3_pa",
    "reference_influence_m3_n",
    "reference_patch_m",
)


def rect_points(
    center_m: ArrayLike, size_m: ArrayLike, yaw_rad: float = 0.0, step_m: float = RESPONSE_STEP_M
) -> NDArray[np.float64]:
    """Centres of the cells of a rectangle sampled on a grid, (n, 2), metres.

    Parameters
    ----------
    center_m
        Rectangle centre (x, y), metres.
    size_m
        Side along its own x and y before the rotation, metres.
    yaw_rad
        Rotation about z, radians.
    step_m
        Largest cell side, metres.
    """
    lx, ly = (float(v) for v in np.asarray(size_m, dtype=float))
    nx, ny = max(1, math.ceil(lx / step_m - 1e-9)), max(1, math.ceil(ly / step_m - 1e-9))
    xs = (np.arange(nx) + 0.5) * (lx / nx) - lx / 2
    ys = (np.arange(ny) + 0.5) * (ly / ny) - ly / 2
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    local = np.column_stack([gx.ravel(), gy.ravel()])
    c, s = math.cos(yaw_rad), math.sin(yaw_rad)
    return local @ np.array([[c, -s], [s, c]]).T + np.asarray(center_m, dtype=float)


@dataclass(frozen=True)
class ModuleResponse:
    """FEM response of one module to vertical loads on its top face.

    Parameters
    ----------
    pressure_pa
        Increasing chamber pressures p0 of the table, shape (P,), Pa.
    axis_m
        FEM node coordinates from the module centre (0) to the clamped edge, shape (N,), m;
        the field is symmetric in x and y, so one axis serves both.
    influence_m3_n
        ``s = -dV/dF`` of a point force at node (i, j), shape (P, N, N), m^3/N.
    volume_m3
        Air under the unloaded layer at each pressure (no gap, no tubing), shape (P,), m^3.
    compliance_m3_pa
        Chamber compliance ``dV/dp`` at each pressure, shape (P,), m^3/Pa.
    reference_influence_m3_n
        The FEM's mean of ``s`` over the characteristic's load patch, shape (P,), m^3/N.
    reference_patch_m
        That patch (a centred rectangle), (x, y) sides, m.
    meta
        Provenance: model, mesh, convergence figures, command.
    """

    pressure_pa: NDArray[np.float64]
    axis_m: NDArray[np.float64]
    influence_m3_n: NDArray[np.float64]
    volume_m3: NDArray[np.float64]
    compliance_m3_pa: NDArray[np.float64]
    reference_influence_m3_n: NDArray[np.float64]
    reference_patch_m: NDArray[np.float64]
    meta: dict[str, Any] = field(default_factory=dict)
    _cache: dict[Any, Any] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_cache", {})
        p = np.asarray(self.pressure_pa, float)
        ax = np.asarray(self.axis_m, float)
        infl = np.asarray(self.influence_m3_n, float)
        if p.ndim != 1 or p.size < 1 or (p.size > 1 and not (np.diff(p) > 0).all()):
            raise InputError(f"response pressure_pa must be increasing values, got shape {p.shape}")
        if ax.ndim != 1 or ax.size < 2 or ax[0] != 0 or not (np.diff(ax) > 0).all():
            raise InputError("response axis_m must increase from 0 to the chamber's half side")
        if infl.shape != (p.size, ax.size, ax.size) or not np.isfinite(infl).all():
            raise InputError(
                f"response influence_m3_n must be finite with shape {(p.size, ax.size, ax.size)}, "
                f"got {infl.shape}"
            )
        for name in ("volume_m3", "compliance_m3_pa", "reference_influence_m3_n"):
            a = np.asarray(getattr(self, name), float)
            if a.shape != p.shape or not (np.isfinite(a).all() and (a > 0).all()):
                raise InputError(f"response {name} must be {p.size} positive numbers")
            object.__setattr__(self, name, a)
        object.__setattr__(self, "pressure_pa", p)
        object.__setattr__(self, "axis_m", ax)
        object.__setattr__(self, "influence_m3_n", infl)
        object.__setattr__(self, "reference_patch_m", np.asarray(self.reference_patch_m, float))

    # --- file ---------------------------------------------------------------------------------
    @classmethod
    def from_file(cls, path: str | Path) -> ModuleResponse:
        """Read a response ``.npz``; InputError names what is missing or wrong."""
        arrays, meta = read_tables(path, _ARRAYS, "module response")
        return cls(**arrays, meta=meta)

    def to_npz(self, path: str | Path) -> Path:
        """Write the table (arrays of :data:`_ARRAYS` plus ``meta`` as a JSON string)."""
        p = Path(path)
        np.savez_compressed(
            p,
            pressure_pa=self.pressure_pa,
            axis_m=self.axis_m,
            influence_m3_n=self.influence_m3_n,
            volume_m3=self.volume_m3,
            compliance_m3_pa=self.compliance_m3_pa,
            reference_influence_m3_n=self.reference_influence_m3_n,
            reference_patch_m=self.reference_patch_m,
            meta=np.array(json.dumps(self.meta, sort_keys=True)),
        )
        return p

    # --- evaluation ---------------------------------------------------------------------------
    @property
    def chamber_side_m(self) -> float:
        """Side of the chamber (twice the last node coordinate), metres."""
        return 2.0 * float(self.axis_m[-1])

    def _row(self, pressure_pa: float) -> tuple[int, int, float]:
        p = self.pressure_pa
        if p.size == 1:
            return 0, 0, 0.0
        x = min(max(float(pressure_pa), p[0]), p[-1])
        i = min(int(np.searchsorted(p, x, side="right")) - 1, p.size - 2)
        return i, i + 1, (x - p[i]) / (p[i + 1] - p[i])

    def _along_pressure(self, values: NDArray[np.float64], pressure_pa: float) -> Any:
        i, j, t = self._row(pressure_pa)
        return values[i] * (1 - t) + values[j] * t

    def influence(self, local_m: ArrayLike, pressure_pa: float) -> NDArray[np.float64]:
        """``s = -dV/dF`` of a point force at module-centred points (n, 2), m^3/N.

        Bilinear between the FEM's nodes, linear between the table's pressures (clamped to its
        range); zero outside the chamber.
        """
        pts = np.abs(np.asarray(local_m, dtype=float).reshape(-1, 2))
        key = ("slice", round(float(pressure_pa), 3))
        table = self._cache.get(key)
        if table is None:
            table = self._cache[key] = np.asarray(
                self._along_pressure(self.influence_m3_n, float(pressure_pa))
            )
        ax = self.axis_m
        i = np.clip(np.searchsorted(ax, pts[:, 0], side="right") - 1, 0, ax.size - 2)
        j = np.clip(np.searchsorted(ax, pts[:, 1], side="right") - 1, 0, ax.size - 2)
        tx = np.clip((pts[:, 0] - ax[i]) / (ax[i + 1] - ax[i]), 0.0, 1.0)
        ty = np.clip((pts[:, 1] - ax[j]) / (ax[j + 1] - ax[j]), 0.0, 1.0)
        v = (
            table[i, j] * (1 - tx) * (1 - ty)
            + table[i + 1, j] * tx * (1 - ty)
            + table[i, j + 1] * (1 - tx) * ty
            + table[i + 1, j + 1] * tx * ty
        )
        inside = (pts[:, 0] <= ax[-1]) & (pts[:, 1] <= ax[-1])
        return np.where(inside, v, 0.0)

    def mean_influence(
        self,
        center_m: ArrayLike,
        size_m: ArrayLike,
        pressure_pa: float,
        yaw_rad: float = 0.0,
        step_m: float = RESPONSE_STEP_M,
    ) -> float:
        """Mean of ``s`` over a rectangle (uniform pressure on it), module-centred, m^3/N."""
        return float(
            self.influence(rect_points(center_m, size_m, yaw_rad, step_m), pressure_pa).mean()
        )

    def reference_influence(self, pressure_pa: float) -> float:
        """Mean of ``s`` over the characteristic's centred load patch, sampled like every other
        load (so a load on that patch has an equivalent load equal to itself), m^3/N."""
        key = ("reference", round(float(pressure_pa), 3))
        value = self._cache.get(key)
        if value is None:
            value = self._cache[key] = self.mean_influence(
                (0.0, 0.0), self.reference_patch_m, pressure_pa
            )
        return float(value)

    def gas_compliance_m3_pa(
        self,
        pressure_pa: float,
        tubing_volume_m3: float = thesis.TUBING_VOLUME_M3,
        gap_volume_m3: float = thesis.CHAMBER_GAP_VOLUME_M3,
        atmosphere_pa: float = 101325.0,
    ) -> float:
        """``(V + V_gap + V_t) / (p_atm + p)``: the gas's share of a sealed chamber's give, m^3/Pa."""
        v = float(self._along_pressure(self.volume_m3, pressure_pa))
        return (v + gap_volume_m3 + tubing_volume_m3) / (atmosphere_pa + pressure_pa)

    def sealed_rise_per_newton(self, pressure_pa: float, **gas: float) -> float:
        """Small-load pressure rise of a sealed chamber per newton of ``s = 1 m^3/N``, Pa/m^3:
        ``1 / (dV/dp + (V + V_gap + V_t) / (p_atm + p))`` (multiply by ``F s``)."""
        c = float(self._along_pressure(self.compliance_m3_pa, pressure_pa))
        return 1.0 / (c + self.gas_compliance_m3_pa(pressure_pa, **gas))


def read_tables(
    path: str | Path, names: Sequence[str], what: str
) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The float arrays ``names`` and the JSON ``meta`` of a response ``.npz`` (``what`` names
    the file in errors); InputError names what is missing or unreadable."""
    p = Path(path)
    try:
        with np.load(p, allow_pickle=False) as z:
            missing = [k for k in names if k not in z]
            if missing:
                raise InputError(f"{what} {str(p)!r} lacks array(s) {missing}")
            arrays = {k: np.array(z[k], dtype=float) for k in names}
            meta = json.loads(str(z["meta"][()])) if "meta" in z else {}
    except InputError:
        raise
    except FileNotFoundError:
        raise InputError(f"{what} file {str(p)!r} does not exist") from None
    except (OSError, ValueError, EOFError) as exc:
        raise InputError(f"{what} {str(p)!r} is not a readable .npz: {exc}") from None
    return arrays, meta
