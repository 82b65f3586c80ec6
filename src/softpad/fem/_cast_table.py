"""The cast pad's response table: every chamber's ``s_k = -dV_k/dF`` of a point force anywhere
on the pad's top face, with the chambers' volumes and compliance matrix, over a range of
pressures.

Written by ``softpad fem cast-response`` (:func:`softpad.fem.cast_pad_response`), read by the
simulator (:class:`softpad.sim.PadResponse`); NumPy only.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad.errors import InputError

#: Name of the packaged cast-pad response file.
PACKAGED_CAST_RESPONSE = "cast_pad_response.npz"
#: Version of the file layout.
CAST_RESPONSE_VERSION = 1
_ARRAYS = (
    "pressure_pa",
    "x_axis_m",
    "y_axis_m",
    "influence_m3_n",
    "volume_m3",
    "compliance_m3_pa",
    "centers_m",
)


@dataclass(frozen=True)
class CastPadResponse:
    """FEM response of every chamber of a cast pad to vertical loads anywhere on its top.

    Parameters
    ----------
    pressure_pa
        Increasing pressures (every chamber alike), shape (P,), Pa.
    x_axis_m, y_axis_m
        Top-face node coordinates in the pad frame (origin at the bottom-left corner), (Nx,),
        (Ny,), m.
    influence_m3_n
        ``s_k = -dV_k/dF`` of a downward point force at node (i, j), shape (P, K, Nx, Ny),
        m^3/N (``dw/dp_k`` there, by reciprocity).
    volume_m3
        Air under the layer of each chamber, (P, K), m^3.
    compliance_m3_pa
        ``dV_k/dp_l``, (P, K, K), m^3/Pa.
    centers_m
        Chamber centres in the pad frame, thesis numbering, (K, 2), m.
    meta
        Provenance (model, mesh, pad: rows, cols, chamber_side_m, wall_width_m, ...).
    """

    pressure_pa: NDArray[np.float64]
    x_axis_m: NDArray[np.float64]
    y_axis_m: NDArray[np.float64]
    influence_m3_n: NDArray[np.float64]
    volume_m3: NDArray[np.float64]
    compliance_m3_pa: NDArray[np.float64]
    centers_m: NDArray[np.float64]
    meta: dict[str, Any] = field(default_factory=dict)
    _cache: dict[Any, Any] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_cache", {})
        arrays = {k: np.asarray(getattr(self, k), float) for k in _ARRAYS}
        p, ax, ay = arrays["pressure_pa"], arrays["x_axis_m"], arrays["y_axis_m"]
        if p.ndim != 1 or p.size < 1 or (p.size > 1 and not (np.diff(p) > 0).all()):
            raise InputError("cast response pressure_pa must be increasing values")
        for name, a in (("x_axis_m", ax), ("y_axis_m", ay)):
            if a.ndim != 1 or a.size < 2 or not (np.diff(a) > 0).all():
                raise InputError(f"cast response {name} must be increasing node coordinates")
        k = arrays["centers_m"].shape[0]
        shapes = {
            "influence_m3_n": (p.size, k, ax.size, ay.size),
            "volume_m3": (p.size, k),
            "compliance_m3_pa": (p.size, k, k),
            "centers_m": (k, 2),
        }
        for name, shape in shapes.items():
            a = arrays[name]
            if a.shape != shape or not np.isfinite(a).all():
                raise InputError(
                    f"cast response {name} must be finite with shape {shape}, got {a.shape}"
                )
        for name, a in arrays.items():
            object.__setattr__(self, name, a)

    # --- file ---------------------------------------------------------------------------------
    @classmethod
    def from_file(cls, path: str | Path) -> CastPadResponse:
        """Read a cast response ``.npz``; InputError names what is missing or wrong."""
        from softpad.fem._response_table import read_tables

        arrays, meta = read_tables(path, _ARRAYS, "cast pad response")
        return cls(**arrays, meta=meta)

    def to_npz(self, path: str | Path) -> Path:
        """Write the table (the arrays plus ``meta`` as a JSON string)."""
        p = Path(path)
        arrays = {k: getattr(self, k) for k in _ARRAYS}
        np.savez_compressed(p, **arrays, meta=np.array(json.dumps(self.meta, sort_keys=True)))
        return p

    # --- evaluation ---------------------------------------------------------------------------
    @property
    def n_chambers(self) -> int:
        """Number of chambers K."""
        return int(self.centers_m.shape[0])

    @property
    def pitch_m(self) -> float:
        """Chamber pitch of the model, m."""
        return float(self.meta.get("chamber_side_m", 0.045)) + self.wall_width_m

    @property
    def wall_width_m(self) -> float:
        """Width of the grid's walls of the model, m."""
        return float(self.meta.get("wall_width_m", 0.0))

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) of the model's pad."""
        return int(self.meta.get("rows", 0)), int(self.meta.get("cols", 0))

    def _weights(self, pressure_pa: float) -> tuple[int, int, float]:
        p = self.pressure_pa
        if p.size == 1:
            return 0, 0, 0.0
        x = min(max(float(pressure_pa), p[0]), p[-1])
        i = min(int(np.searchsorted(p, x, side="right")) - 1, p.size - 2)
        return i, i + 1, (x - p[i]) / (p[i + 1] - p[i])

    def along_pressure(self, values: NDArray[np.float64], pressure_pa: float) -> Any:
        """``values`` (leading axis: the table's pressures) at ``pressure_pa``, linear and
        clamped to the table's range."""
        i, j, t = self._weights(pressure_pa)
        return values[i] * (1 - t) + values[j] * t

    def influence(self, points_m: ArrayLike, pressure_pa: float) -> NDArray[np.float64]:
        """``s_k`` of a point force at pad-frame points (n, 2), (n, K), m^3/N: bilinear between
        the nodes, linear in pressure; zero off the pad."""
        pts = np.asarray(points_m, dtype=float).reshape(-1, 2)
        table = self.influence_table(pressure_pa)
        ax, ay = self.x_axis_m, self.y_axis_m
        x, y = pts[:, 0], pts[:, 1]
        # np.clip's values without its Python wrapper (a simulated trial's hot path)
        i = np.minimum(np.maximum(np.searchsorted(ax, x, side="right") - 1, 0), ax.size - 2)
        j = np.minimum(np.maximum(np.searchsorted(ay, y, side="right") - 1, 0), ay.size - 2)
        i1, j1 = i + 1, j + 1
        tx = np.minimum(np.maximum(0.0, (x - ax[i]) / (ax[i1] - ax[i])), 1.0)[:, None]
        ty = np.minimum(np.maximum(0.0, (y - ay[j]) / (ay[j1] - ay[j])), 1.0)[:, None]
        sx, sy = 1 - tx, 1 - ty
        v = (
            table[i, j] * sx * sy
            + table[i1, j] * tx * sy
            + table[i, j1] * sx * ty
            + table[i1, j1] * tx * ty
        )
        on = (x >= ax[0]) & (x <= ax[-1]) & (y >= ay[0])
        on &= y <= ay[-1]
        return np.where(on[:, None], v, 0.0)

    def influence_table(self, pressure_pa: float) -> NDArray[np.float64]:
        """``s_k`` at every node at ``pressure_pa`` (linear, clamped), (Nx, Ny, K), C-contiguous:
        a node's K values side by side (cached per pressure, rounded to 1 mPa)."""
        key = round(float(pressure_pa), 3)
        table = self._cache.get(key)
        if table is None:  # (x, y, K): a point's K values side by side (one gather a corner)
            at = np.asarray(self.along_pressure(self.influence_m3_n, float(pressure_pa)))
            table = self._cache[key] = np.ascontiguousarray(np.moveaxis(at, 0, -1))
        return np.asarray(table)

    def compliance(self, pressure_pa: float) -> NDArray[np.float64]:
        """``dV_k/dp_l`` at ``pressure_pa``, (K, K), m^3/Pa."""
        return np.asarray(self.along_pressure(self.compliance_m3_pa, pressure_pa))

    def volumes(self, pressure_pa: float) -> NDArray[np.float64]:
        """Air under the layer of each chamber at ``pressure_pa``, (K,), m^3."""
        return np.asarray(self.along_pressure(self.volume_m3, pressure_pa))
