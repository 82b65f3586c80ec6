"""Fitting material parameters to measured (pressure, height) pairs (thesis Section 7.2).

The thesis compares the models of Table 7.1 against the mean height of three real modules
by the root-mean-square error (neo-Hookean 1.13 mm, Yeoh 0.93 mm, Mooney-Rivlin 1.28 mm,
Varga 1.24 mm). :func:`compare_models` ranks presets the same way; :func:`fit_material`
adjusts a model's parameters to the data by nonlinear least squares.
"""

from __future__ import annotations

import csv
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from softpad.errors import InputError, SoftPadError
from softpad.fem._geometry import MeshOptions, ModuleGeometry
from softpad.fem._materials import MODEL_NAMES, MaterialModel, get_material
from softpad.fem._model import ModuleSetup, ProgressCallback
from softpad.fem._results import as_list, label_axes, new_axes, write_csv
from softpad.fem._studies import InflationResult, inflation_sweep

#: The highest measured height must reach this, metres: below it every height was given in
#: metres where millimetres are expected (the thesis's module rises 6-15 mm).
MIN_TOP_HEIGHT_M = 0.05e-3


def read_measurements(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Read measured ``pressure_kpa,height_mm`` pairs from a CSV file with a header.

    Returns
    -------
    pressure_pa, height_m
        Sorted by pressure, in SI units.

    Raises
    ------
    InputError
        Missing file or columns, malformed numbers, negative pressures, fewer than two rows.
    """
    src = Path(path)
    if not src.is_file():
        raise InputError(f"measurement file {str(src)!r} does not exist")
    try:
        text = src.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(
            f"measurement file {str(src)!r} is not text (CSV expected; a binary file?)"
        ) from None
    import io

    with io.StringIO(text, newline="") as fh:
        reader = csv.DictReader(fh)
        fields = [f.strip() for f in (reader.fieldnames or [])]
        if "pressure_kpa" not in fields or "height_mm" not in fields:
            raise InputError(
                f"measurement file {str(src)!r} needs columns pressure_kpa,height_mm; got {fields}"
            )
        pressures, heights = [], []
        for line, row in enumerate(reader, start=2):
            row = {k.strip(): v for k, v in row.items() if k is not None}
            try:
                p = float(row["pressure_kpa"])
                h = float(row["height_mm"])
            except (TypeError, ValueError):
                raise InputError(
                    f"{src.name} line {line}: malformed number in "
                    f"{row.get('pressure_kpa')!r},{row.get('height_mm')!r}"
                ) from None
            if not (np.isfinite(p) and np.isfinite(h)):
                raise InputError(f"{src.name} line {line}: non-finite value {p!r},{h!r}")
            if p < 0 or p > 10.0:
                raise InputError(f"{src.name} line {line}: pressure {p!r} kPa outside 0..10 kPa")
            pressures.append(p * 1e3)
            heights.append(h * 1e-3)
    if len(pressures) < 2:
        raise InputError(f"measurement file {str(src)!r} has {len(pressures)} rows; need >= 2")
    if max(heights) < MIN_TOP_HEIGHT_M:  # an inflated module rises millimetres
        raise InputError(
            f"measurement file {str(src)!r}: every height_mm is under {MIN_TOP_HEIGHT_M * 1e3:g} "
            "mm (metres given as millimetres?)"
        )
    order = np.argsort(pressures)
    return np.asarray(pressures)[order], np.asarray(heights)[order]


def _simulate(
    material: MaterialModel,
    pressure_pa: np.ndarray,
    geometry: ModuleGeometry | None,
    mesh: MeshOptions | None,
) -> InflationResult:
    grid = np.unique(np.concatenate([[0.0], pressure_pa]))
    return inflation_sweep(ModuleSetup(material, geometry, mesh), grid)


def _rmse(result: InflationResult, pressure_pa: np.ndarray, height_m: np.ndarray) -> float:
    predicted = np.interp(pressure_pa, result.pressure_pa, result.height_m)
    return float(np.sqrt(np.mean((predicted - height_m) ** 2)))


@dataclass(frozen=True)
class FitResult:
    """Outcome of :func:`fit_material`.

    Attributes
    ----------
    material
        The fitted model.
    initial
        The starting model.
    rmse_m
        Root-mean-square height error of the fitted model, m.
    initial_rmse_m
        The same for the starting model, m.
    pressure_pa, height_m
        The data, SI units.
    predicted_m
        Fitted model's heights at the data pressures, m.
    evaluations
        Number of inflation sweeps run.
    """

    material: MaterialModel
    initial: MaterialModel
    rmse_m: float
    initial_rmse_m: float
    pressure_pa: np.ndarray
    height_m: np.ndarray
    predicted_m: np.ndarray
    evaluations: int

    def to_dict(self) -> dict[str, Any]:
        """Fitted parameters and errors (mm)."""
        return {
            "model": self.material.name,
            "kind": self.material.kind,
            "parameters": dict(self.material.parameters),
            "initial_parameters": dict(self.initial.parameters),
            "rmse_mm": self.rmse_m * 1e3,
            "initial_rmse_mm": self.initial_rmse_m * 1e3,
            "evaluations": self.evaluations,
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``pressure_kpa,measured_mm,fitted_mm`` rows."""
        rows = zip(
            self.pressure_pa * 1e-3, self.height_m * 1e3, self.predicted_m * 1e3, strict=True
        )
        return write_csv(path, ["pressure_kpa", "measured_mm", "fitted_mm"], list(rows))

    def plot(self, ax: Any = None) -> Any:
        """Measured points and the fitted curve."""
        ax = new_axes(ax)
        ax.plot(self.pressure_pa * 1e-3, self.height_m * 1e3, "ko", label="measured")
        ax.plot(
            self.pressure_pa * 1e-3,
            self.predicted_m * 1e3,
            "-",
            label=f"{self.material.name} fit (RMSE {self.rmse_m * 1e3:.3g} mm)",
        )
        return label_axes(ax, "pressure (kPa)", "centre height (mm)")


def fit_material(
    pressure_pa: Sequence[float] | np.ndarray,
    height_m: Sequence[float] | np.ndarray,
    model: str | MaterialModel = "yeoh",
    free: Sequence[str] | None = None,
    geometry: ModuleGeometry | None = None,
    mesh: MeshOptions | None = None,
    max_evaluations: int = 60,
    progress: ProgressCallback | None = None,
) -> FitResult:
    """Fit a model's parameters to measured centre heights by least squares.

    Parameters
    ----------
    pressure_pa, height_m
        Measured pairs, Pa and m.
    model
        Starting model (preset name or :class:`MaterialModel`).
    free
        Names of the parameters to adjust (default: all moduli; Ogden exponents stay fixed).
    geometry, mesh
        Module geometry and discretisation of the simulations.
    max_evaluations
        Budget of inflation sweeps.
    progress
        Optional ``progress(done, total)`` callback, one tick per sweep.

    Notes
    -----
    Parameters are scaled by their starting values (the unknowns are ratios); trial points
    whose energy is not convex at rest or that do not converge get a large residual.
    """
    p, h = _measurements(pressure_pa, height_m)
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(h))):
        raise InputError("measurements contain non-finite values")
    start = get_material(model)
    names = _free_parameters(start, free)
    scale = np.array([start.parameters[n] if start.parameters[n] != 0 else 1.0 for n in names])
    residuals = _HeightResiduals(start, names, scale, p, h, geometry, mesh)
    residuals.progress, residuals.budget = progress, max_evaluations
    initial_res = residuals(np.ones(len(names)))
    x = _least_squares(residuals, len(names), max_evaluations)
    fitted = start.with_parameters(**dict(zip(names, x * scale, strict=True)))
    final = residuals(x)
    return FitResult(
        material=fitted,
        initial=start,
        rmse_m=float(np.sqrt(np.mean(final**2))),
        initial_rmse_m=float(np.sqrt(np.mean(initial_res**2))),
        pressure_pa=p,
        height_m=h,
        predicted_m=final + h,
        evaluations=residuals.evaluations,
    )


def _least_squares(residuals: Any, n: int, max_evaluations: int) -> np.ndarray:
    """The ``n`` scaled parameters (start: all 1) that minimise ``residuals``, within
    ``max_evaluations`` sweeps (:func:`scipy.optimize.least_squares`)."""
    from scipy.optimize import least_squares

    solution = least_squares(
        residuals,
        np.ones(n),
        x_scale=np.ones(n),
        diff_step=1e-3,
        max_nfev=max_evaluations,
        xtol=1e-6,
        ftol=1e-8,
    )
    return np.asarray(solution.x)


@dataclass(frozen=True)
class ComparisonResult:
    """Models ranked by RMSE against measured heights (thesis Section 7.2).

    Attributes
    ----------
    models
        Model names, best first.
    rmse_m
        Their RMSE, m (``inf`` where the model failed to converge).
    curves
        Simulated inflation curves by model name.
    pressure_pa, height_m
        The data.
    """

    models: tuple[str, ...]
    rmse_m: np.ndarray
    curves: dict[str, InflationResult]
    pressure_pa: np.ndarray
    height_m: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """Ranking with RMSE in mm."""
        return {
            "ranking": [
                {"model": m, "rmse_mm": float(r * 1e3)}
                for m, r in zip(self.models, self.rmse_m, strict=True)
            ],
            "pressure_kpa": as_list(self.pressure_pa, 1e-3),
            "height_mm": as_list(self.height_m, 1e3),
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``rank,model,rmse_mm`` rows."""
        rows = [
            [i + 1, m, r * 1e3]
            for i, (m, r) in enumerate(zip(self.models, self.rmse_m, strict=True))
        ]
        return write_csv(path, ["rank", "model", "rmse_mm"], rows)

    def plot(self, ax: Any = None) -> Any:
        """Measured points and every model's curve."""
        ax = new_axes(ax)
        ax.plot(self.pressure_pa * 1e-3, self.height_m * 1e3, "ko", label="measured")
        for name in self.models:
            if name in self.curves:
                c = self.curves[name]
                ax.plot(c.pressure_pa * 1e-3, c.height_m * 1e3, label=name)
        return label_axes(ax, "pressure (kPa)", "centre height (mm)")


def compare_models(
    pressure_pa: Sequence[float] | np.ndarray,
    height_m: Sequence[float] | np.ndarray,
    models: Sequence[str | MaterialModel] = MODEL_NAMES,
    geometry: ModuleGeometry | None = None,
    mesh: MeshOptions | None = None,
    progress: ProgressCallback | None = None,
) -> ComparisonResult:
    """Rank material models by the RMSE of their centre height against the data."""
    p, h = _measurements(pressure_pa, height_m)
    mats = [get_material(m) for m in models]
    curves: dict[str, InflationResult] = {}
    errors = []
    for i, mat in enumerate(mats):
        try:
            curve = _simulate(mat, p, geometry, mesh)
            curves[mat.name] = curve
            errors.append(_rmse(curve, p, h))
        except SoftPadError:
            errors.append(float("inf"))
        if progress is not None:
            progress(i + 1, len(mats))
    order = np.argsort(errors, kind="stable")
    return ComparisonResult(
        tuple(mats[i].name for i in order), np.asarray(errors)[order], curves, p, h
    )


def _measurements(
    pressure_pa: Sequence[float] | np.ndarray, height_m: Sequence[float] | np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Measured pressures (Pa) and heights (m) as matching 1-D arrays of >= 2 entries."""
    p = np.asarray(pressure_pa, dtype=float)
    h = np.asarray(height_m, dtype=float)
    if p.shape != h.shape or p.ndim != 1 or p.size < 2:
        raise InputError(
            f"need matching 1-D pressure and height arrays (>= 2), got {p.shape}, {h.shape}"
        )
    return p, h


def _free_parameters(start: MaterialModel, free: Sequence[str] | None) -> tuple[str, ...]:
    """Names of the parameters to fit: ``free``, or every modulus (not Ogden's exponents)."""
    names = (
        tuple(free)
        if free is not None
        else tuple(n for n in start.parameter_names if not n.startswith("alpha"))
    )
    unknown = [n for n in names if n not in start.parameters]
    if unknown or not names:
        raise InputError(
            f"cannot fit {unknown or 'no'} parameter(s) of {start.name!r}; "
            f"it has {list(start.parameter_names)}"
        )
    return names


class _HeightResiduals:
    """Simulated minus measured heights (m) of ``start`` with parameters ``names`` set to
    ``x * scale``; counts its evaluations (one inflation sweep each)."""

    def __init__(
        self,
        start: MaterialModel,
        names: tuple[str, ...],
        scale: np.ndarray,
        p: np.ndarray,
        h: np.ndarray,
        geometry: ModuleGeometry | None,
        mesh: MeshOptions | None,
    ) -> None:
        self.start, self.names, self.scale = start, names, scale
        self.p, self.h, self.geometry, self.mesh = p, h, geometry, mesh
        self.evaluations = 0
        self.progress: ProgressCallback | None = None
        self.budget = 0
        self._penalty = np.full(p.size, 1.0)  # 1 m: far worse than any real fit

    def __call__(self, x: np.ndarray) -> np.ndarray:
        self.evaluations += 1
        if self.progress is not None:
            self.progress(self.evaluations, self.budget)
        try:
            trial = self.start.with_parameters(**dict(zip(self.names, x * self.scale, strict=True)))
            sim = _simulate(trial, self.p, self.geometry, self.mesh)
        except SoftPadError:
            return self._penalty
        return np.interp(self.p, sim.pressure_pa, sim.height_m) - self.h
