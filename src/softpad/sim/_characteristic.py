"""Module characteristic: air volume and top height of a module vs pressure and load.

The characteristic is the small interface between the mechanics of a module (the FEM model of
chapter 7, or an analytic fit) and the gas physics of the simulated box:

* ``volume_m3(p, F)``: volume of air under the upper layer (tubing excluded), m^3;
* ``height_m(p, F)``: height of the top centre of the module above the base, m;

for gauge pressure ``p`` (Pa) and a vertical external load ``F`` (N) spread over the module.
A sealed module under a load settles where the amount of air is unchanged, which is how an
object's weight becomes a pressure increment (thesis, Section 6.2.1).

Two implementations: :class:`AnalyticCharacteristic` (documented fit, default when no table
is packaged) and :class:`TabulatedCharacteristic` (bilinear interpolation of a table, e.g. the
FEM's ``softpad/data/module_characteristic.npz``). :func:`default_characteristic` picks one.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from functools import cached_property
from importlib import resources
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError

#: Name of the packaged FEM table (written by ``softpad fem characteristic``).
PACKAGED_TABLE = "module_characteristic.npz"
#: Side of the FEM table's default load patch (a centred square), m.
DEFAULT_LOAD_PATCH_M = 0.030


@runtime_checkable
class ModuleCharacteristic(Protocol):
    """Volume and height of a module as functions of gauge pressure and external load."""

    def volume_m3(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        """Air volume under the layer, m^3 (broadcasts over arrays of pressures/loads)."""
        ...

    def height_m(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        """Height of the module's top centre above the base, m."""
        ...

    def volume_slope_m3_pa(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        """Partial derivative dV/dp at constant load, m^3/Pa (membrane compliance)."""
        ...


@dataclass(frozen=True)
class AnalyticCharacteristic:
    """A documented analytic characteristic of a 45 mm module with a 1.5 mm EcoFlex layer.

    The load acts on the membrane like a pressure ``F / A_eff`` pushing back, so the volume is
    that of the free membrane at the net pressure ``x = p - F / A_eff``::

        V(p, F) = V_free(x),
        V_free(x) = V_gap + a ((x + x0)^n - x0^n)          for x >= 0,
        V_free(x) = V_gap exp(x V_free'(0) / V_gap)        for x < 0 (layer pushed onto base),
        h(p, F)   = h_ref V(p, F) / V_ref.

    ``a`` and ``n`` are fitted so that ``V(p_ref) = V_ref`` and ``dV/dp(p_ref) = compliance``.
    Defaults, all from the project's FEM at 1.1 kPa (``softpad fem response``, neo-Hookean,
    docs/fem.md) except the height: 7.73 mL of air under the layer plus the 0.2 mL gap,
    3.71 mL/kPa, and ``A_eff = (dV/dp) / (-dV/dF)`` = 1.466e-3 m^2 for a load on the
    characteristic's central 30 x 30 mm patch (``-dV/dF`` = 2.53 mL/N); the thesis's height of
    9 mm at 1.1 kPa (Section 6.3).
    """

    #: p_ref, pascals (1.1 kPa, the thesis's inflating pressure).
    reference_pressure_pa: float = thesis.P0_PA
    #: V_ref, air volume at p_ref without load, gap included, m^3 (7.93 mL).
    reference_volume_m3: float = 7.73e-6 + thesis.CHAMBER_GAP_VOLUME_M3
    #: dV/dp at p_ref, m^3/Pa (3.71 mL/kPa).
    compliance_m3_pa: float = 3.71e-9
    #: h_ref, top height at p_ref without load, m (9 mm).
    reference_height_m: float = 9.0e-3
    #: V_gap, air left under a flat layer (the acetate sheet's gap), m^3 (0.2 mL).
    gap_volume_m3: float = thesis.CHAMBER_GAP_VOLUME_M3
    #: x0, pressure scale where the slack membrane stiffens, pascals (50 Pa).
    knee_pa: float = 50.0
    #: A_eff, area on which a load acts like a pressure, m^2.
    effective_area_m2: float = 1.466e-3

    def __post_init__(self) -> None:
        for n in (
            "reference_pressure_pa",
            "reference_volume_m3",
            "compliance_m3_pa",
            "reference_height_m",
            "gap_volume_m3",
            "knee_pa",
            "effective_area_m2",
        ):
            v = getattr(self, n)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise InputError(f"characteristic {n} must be a positive number, got {v!r}")
        if self.gap_volume_m3 >= self.reference_volume_m3:
            raise InputError("gap volume must be smaller than the reference volume")

    @cached_property
    def _fit(self) -> tuple[float, float, float]:
        """(a, n, slope at x = 0) of the power law."""
        x0, p = self.knee_pa, self.reference_pressure_pa
        dv = self.reference_volume_m3 - self.gap_volume_m3
        target = self.compliance_m3_pa / dv

        def ratio(n: float) -> float:
            return n * (p + x0) ** (n - 1) / ((p + x0) ** n - x0**n) - target

        lo, hi = 1e-3, 5.0  # ratio increases with n on this bracket: bisection
        if not ratio(lo) < 0 < ratio(hi):
            raise InputError(
                "no power law fits the given reference volume and compliance; "
                f"compliance {self.compliance_m3_pa:g} m^3/Pa is out of reach"
            )
        for _ in range(100):
            n = 0.5 * (lo + hi)
            if ratio(n) < 0:
                lo = n
            else:
                hi = n
        a = dv / ((p + x0) ** n - x0**n)
        return a, n, a * n * x0 ** (n - 1)

    def _free(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        a, n, s0 = self._fit
        x0, vg = self.knee_pa, self.gap_volume_m3
        if np.ndim(x) and x.min() >= 0:  # the usual case: one power per element
            t = x + x0
            tn = t**n
            return vg + a * (tn - x0**n), a * n * tn / t
        xp = np.maximum(x, 0.0)
        xn = np.minimum(x, 0.0)
        pos = vg + a * ((xp + x0) ** n - x0**n)
        dpos = a * n * (xp + x0) ** (n - 1)
        e = np.exp(xn * s0 / vg)
        v = np.where(x >= 0, pos, vg * e)
        dv = np.where(x >= 0, dpos, s0 * e)
        return v, dv

    def volume_m3(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        x = (
            np.asarray(pressure_pa, dtype=float)
            - np.asarray(load_n, dtype=float) / self.effective_area_m2
        )
        return self._free(x)[0]

    def volume_slope_m3_pa(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        x = (
            np.asarray(pressure_pa, dtype=float)
            - np.asarray(load_n, dtype=float) / self.effective_area_m2
        )
        return self._free(x)[1]

    def volume_and_slope(
        self, pressure_pa: NDArray[np.float64], load_n: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """V and dV/dp in one evaluation (the gas solver's hot path)."""
        return self._free(pressure_pa - load_n / self.effective_area_m2)

    def height_m(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        return self.volume_m3(pressure_pa, load_n) * (
            self.reference_height_m / self.reference_volume_m3
        )


@dataclass(frozen=True)
class TabulatedCharacteristic:
    """Bilinear interpolation of a table V(p, F), h(p, F).

    A negative load is clamped to the first column and a pressure below the first row is
    clamped; above the last row the table is extrapolated linearly along p with the slope of
    its last interval. A load beyond the last column acts like a pressure on the layer: its
    excess ``F - F_max`` is taken off the pressure as ``(F - F_max) / A``, ``A`` the area of
    the table's load patch (``meta["load_patch"]``, 30 x 30 mm by default): at the table's
    largest loads the layer under the patch is pressed flat, so further load on it is carried
    by the gas over the patch (loads of a few newtons no longer saturate at the table's edge). A membrane keeps growing with pressure, and a sealed chamber squeezed
    by a load beyond the table's range (a gripper pressing hard) must still find its pressure:
    with a clamped (flat) table the gas law would have no volume left to give and the
    pressure would run away to the sensor's full scale.
    """

    #: Strictly increasing gauge pressures, shape (P,), pascals.
    pressure_pa: NDArray[np.float64]
    #: Strictly increasing loads, shape (L,), newtons.
    load_n: NDArray[np.float64]
    #: Air volume under the layer (tubing excluded), shape (P, L), m^3.
    volume_m3_table: NDArray[np.float64]
    #: Top-centre height, shape (P, L), metres.
    height_m_table: NDArray[np.float64]
    #: Provenance (model, material, mesh...), free JSON-ready dict.
    meta: dict[str, Any] = field(default_factory=dict)
    _cache: dict[str, Any] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        p, f = np.asarray(self.pressure_pa, float), np.asarray(self.load_n, float)
        v, h = np.asarray(self.volume_m3_table, float), np.asarray(self.height_m_table, float)
        if p.ndim != 1 or p.size < 2 or not (np.diff(p) > 0).all():
            raise InputError(
                f"table pressure_pa must be >= 2 strictly increasing values, got shape {p.shape}"
            )
        if f.ndim != 1 or f.size < 1 or (f.size > 1 and not (np.diff(f) > 0).all()):
            raise InputError(
                f"table load_n must be strictly increasing values, got shape {f.shape}"
            )
        for name, a in (("volume_m3", v), ("height_m", h)):
            if a.shape != (p.size, f.size):
                raise InputError(
                    f"table {name} must have shape ({p.size}, {f.size}), got {a.shape}"
                )
            if not np.isfinite(a).all():
                raise InputError(f"table {name} contains NaN or infinite values")
        if (v <= 0).any():
            raise InputError("table volume_m3 must be > 0 everywhere (air volume under the layer)")
        object.__setattr__(self, "pressure_pa", p)
        object.__setattr__(self, "load_n", f)
        object.__setattr__(self, "volume_m3_table", v)
        object.__setattr__(self, "height_m_table", h)
        object.__setattr__(self, "_cache", {})

    @classmethod
    def from_file(cls, path: str | Path) -> TabulatedCharacteristic:
        """Read an ``.npz`` with arrays ``pressure_pa``, ``load_n``, ``volume_m3``, ``height_m``
        and optionally ``meta`` (0-d JSON string); InputError names what is missing or wrong."""
        p = Path(path)
        try:
            with np.load(p, allow_pickle=False) as z:
                missing = [
                    k for k in ("pressure_pa", "load_n", "volume_m3", "height_m") if k not in z
                ]
                if missing:
                    raise InputError(f"module characteristic {str(p)!r} lacks array(s) {missing}")
                arrays = {
                    k: np.array(z[k], dtype=float)
                    for k in ("pressure_pa", "load_n", "volume_m3", "height_m")
                }
                meta: dict[str, Any] = {}
                if "meta" in z:
                    try:
                        meta = json.loads(str(z["meta"][()]))
                    except (json.JSONDecodeError, TypeError):
                        raise InputError(
                            f"module characteristic {str(p)!r}: 'meta' is not a JSON string"
                        ) from None
        except InputError:
            raise
        except FileNotFoundError:
            raise InputError(f"module characteristic file {str(p)!r} does not exist") from None
        except (OSError, ValueError, EOFError) as exc:
            raise InputError(
                f"module characteristic {str(p)!r} is not a readable .npz file: {exc}"
            ) from None
        return cls(
            arrays["pressure_pa"], arrays["load_n"], arrays["volume_m3"], arrays["height_m"], meta
        )

    def _locate(
        self, grid: NDArray[np.float64], x: NDArray[np.float64], extrapolate_above: bool = False
    ) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64]]:
        if grid.size == 1:
            z = np.zeros(x.shape, dtype=np.intp)
            return z, np.zeros(x.shape), np.zeros(x.shape)
        # np.clip's values without its Python wrapper (the gas solver's hot path)
        xc = np.maximum(x, grid[0])
        if not extrapolate_above:
            xc = np.minimum(xc, grid[-1])
        i = np.minimum(np.maximum(np.searchsorted(grid, xc, side="right") - 1, 0), grid.size - 2)
        width = grid[i + 1] - grid[i]
        t = (xc - grid[i]) / width
        inside = (x >= grid[0]) & ((x <= grid[-1]) | extrapolate_above)
        return i, t, np.where(inside, 1.0 / width, 0.0)

    @property
    def excess_load_area_m2(self) -> float:
        """``A``: area of the table's load patch, m^2 (from ``meta["load_patch"]``, e.g.
        ``"centred rectangle 30 x 30 mm ..."``; 30 x 30 mm when the meta does not say)."""
        m = re.search(r"(\d+(?:\.\d+)?) x (\d+(?:\.\d+)?) mm", str(self.meta.get("load_patch", "")))
        if m is None:
            return DEFAULT_LOAD_PATCH_M**2
        return float(m.group(1)) * float(m.group(2)) * 1e-6

    def _shift(
        self, p: NDArray[np.float64], f: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(p, F) with a load beyond the last column turned into a pressure reduction."""
        fmax = self.load_n[-1]
        if f.size == 0 or f.max() <= fmax:
            return p, f
        excess = np.maximum(f - fmax, 0.0)
        return p - excess / self.excess_load_area_m2, np.minimum(f, fmax)

    def _interp(
        self, table: NDArray[np.float64], p: ArrayLike, f: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        pa, fa = np.broadcast_arrays(np.asarray(p, float), np.asarray(f, float))
        pa, fa = self._shift(pa, fa)
        i, t, dti = self._locate(self.pressure_pa, pa, extrapolate_above=True)
        if self.load_n.size == 1:
            j, u = np.zeros(pa.shape, dtype=np.intp), np.zeros(pa.shape)
            j1 = j
        else:
            j, u, _ = self._locate(self.load_n, fa)
            j1 = j + 1
        v00, v10 = table[i, j], table[i + 1, j]
        v01, v11 = table[i, j1], table[i + 1, j1]
        lo = v00 + (v10 - v00) * t
        hi = v01 + (v11 - v01) * t
        val = lo + (hi - lo) * u
        dval = ((v10 - v00) * (1 - u) + (v11 - v01) * u) * dti
        return val, dval

    def volume_m3(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        return self._interp(self.volume_m3_table, pressure_pa, load_n)[0]

    def volume_slope_m3_pa(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        return self._interp(self.volume_m3_table, pressure_pa, load_n)[1]

    def volume_and_slope(
        self, pressure_pa: NDArray[np.float64], load_n: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """V and dV/dp in one evaluation (the gas solver's hot path).

        Same values as :meth:`volume_m3` and :meth:`volume_slope_m3_pa` for 1-D arrays: the
        table is first interpolated along the load (cached while the loads stay the same, as
        they do through a Newton solve), then along the pressure.
        """
        p = np.asarray(pressure_pa, dtype=float)
        f = np.asarray(load_n, dtype=float)
        if p.ndim != 1 or f.shape != p.shape:
            return self._interp(self.volume_m3_table, p, f)
        return self._along_pressure("volume", p, f)

    def _along_pressure(
        self, which: str, p: NDArray[np.float64], f: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Interpolate the cached load columns of a table along the pressure (1-D inputs).

        The same values as :meth:`_interp`, with what depends on the loads only (the columns
        at each module's load, the pressure taken off by a load beyond the table) cached while
        the loads stay the same, and ufuncs only (no ``np.clip``: its Python wrapper cost more
        than the interpolation on a few modules)."""
        key = f.tobytes()
        entry = self._cache.get(which)
        if entry is None or entry[0] != key:
            entry = self._cache[which] = self._load_columns(which, f, key)
        _, cols, slopes, drop, k = entry
        if drop is not None:
            p = p - drop
        grid = self.pressure_pa
        pc = np.maximum(p, grid[0])
        i = np.searchsorted(grid, pc, side="right")  # >= 1: pc is at least grid[0]
        i -= 1
        np.minimum(i, grid.size - 2, out=i)
        slope = slopes[i, k]
        value = cols[i, k] + slope * (pc - grid[i])
        return value, np.where(p >= grid[0], slope, 0.0)

    def _load_columns(
        self, which: str, f: NDArray[np.float64], key: bytes
    ) -> tuple[bytes, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None, Any]:
        """The table's columns at each module's load ``f`` (interpolated along the load), their
        slopes along the pressure, the pressure a load beyond the table takes off (None: none;
        :meth:`_shift`) and the modules' indices: the cache entry of :meth:`_along_pressure`."""
        fmax = self.load_n[-1]
        drop = None
        if f.size and f.max() > fmax:  # as _shift: the excess load acts as a pressure
            drop = np.maximum(f - fmax, 0.0) / self.excess_load_area_m2
            f = np.minimum(f, fmax)
        table = self.volume_m3_table if which == "volume" else self.height_m_table
        j, u, _ = self._locate(self.load_n, f)
        j1 = np.minimum(j + 1, self.load_n.size - 1)
        cols = table[:, j] * (1 - u) + table[:, j1] * u  # (P, m) at each module's load
        # np.diff's values (a[1:] - a[:-1]) without its wrapper; the grid's steps kept
        steps = self._cache.get("steps")
        if steps is None:
            grid = self.pressure_pa
            steps = self._cache["steps"] = (grid[1:] - grid[:-1])[:, None]
        slopes = (cols[1:] - cols[:-1]) / steps
        return key, cols, slopes, drop, np.arange(f.size)

    def height_m(self, pressure_pa: ArrayLike, load_n: ArrayLike) -> NDArray[np.float64]:
        p = np.asarray(pressure_pa, dtype=float)
        f = np.asarray(load_n, dtype=float)
        if p.ndim == 1 and f.shape == p.shape:
            return self._along_pressure("height", p, f)[0]
        return self._interp(self.height_m_table, p, f)[0]


def packaged_table_path() -> Path | None:
    """Path of the packaged FEM table, or None when it is not installed."""
    return packaged_data_path(PACKAGED_TABLE)


def packaged_data_path(name: str) -> Path | None:
    """Path of the package data file ``softpad/data/NAME``, or None when it is not installed."""
    res = resources.files("softpad").joinpath("data", name)
    try:
        p = Path(str(res))
    except TypeError:  # pragma: no cover - zipped installs
        return None
    return p if p.is_file() else None


def default_characteristic() -> ModuleCharacteristic:
    """The packaged FEM table when present, else the :class:`AnalyticCharacteristic`."""
    path = packaged_table_path()
    if path is not None:
        return TabulatedCharacteristic.from_file(path)
    return AnalyticCharacteristic()


def sealed_sensitivity_pa_n(
    characteristic: ModuleCharacteristic,
    pressure_pa: float = thesis.P0_PA,
    tubing_volume_m3: float = thesis.TUBING_VOLUME_M3,
    atmosphere_pa: float = 101325.0,
    load_n: float = 0.0,
) -> float:
    """Pressure rise per newton of load of a sealed module, Pa/N (isothermal ideal gas).

    From ``d[(p_atm + p)(V(p, F) + V_t)] = 0``:
    ``dp/dF = -(p_atm + p) dV/dF / ((p_atm + p) dV/dp + V + V_t)``, with dV/dF by differences
    over 0.01 N on either side of ``load_n``, one-sided where the load cannot go below zero (a
    table clamps negative loads to its first column, which halved a central difference at 0 N).
    """
    dF = 0.01
    lo, hi = max(load_n - dF, 0.0), load_n + dF
    p = np.array([pressure_pa])
    dv_df = float(
        (characteristic.volume_m3(p, np.array([hi])) - characteristic.volume_m3(p, np.array([lo])))[
            0
        ]
        / (hi - lo)
    )
    f = np.array([load_n])
    dv_dp = float(characteristic.volume_slope_m3_pa(p, f)[0])
    v = float(characteristic.volume_m3(p, f)[0])
    pabs = atmosphere_pa + pressure_pa
    return -pabs * dv_df / (pabs * dv_dp + v + tubing_volume_m3)
