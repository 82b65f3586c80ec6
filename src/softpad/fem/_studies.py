"""Design studies of one module (thesis Sections 6.1.2 and 7.2, Figs. 6.3 and 7.2-7.3).

Each study is a function that returns a frozen result object with ``.to_dict()``,
``.to_csv(path)`` and ``.plot(ax=None)``. Solvers never plot; progress is reported through
an optional ``progress(done, total)`` callback.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.fem._geometry import LoadPatch, MeshOptions, ModuleGeometry
from softpad.fem._materials import get_material
from softpad.fem._model import ModuleModel, ModuleSetup, ProgressCallback
from softpad.fem._results import StudyResult, as_list, label_axes, new_axes, write_csv

#: Highest pressure the studies accept, Pa (thesis Fig. 7.2 spans 0..3 kPa).
MAX_PRESSURE_PA = 10_000.0


def _pressures(values: Sequence[float] | np.ndarray, name: str = "pressure") -> np.ndarray:
    arr = np.asarray([check_finite(name, v) for v in np.ravel(values)], dtype=float)
    if arr.size == 0:
        raise InputError(f"{name} list is empty")
    if np.any(arr < 0) or np.any(arr > MAX_PRESSURE_PA):
        bad = arr[(arr < 0) | (arr > MAX_PRESSURE_PA)][0]
        raise InputError(
            f"{name} {bad:g} Pa outside 0..{MAX_PRESSURE_PA:g} Pa (gauge pressure of a module)"
        )
    if np.any(np.diff(arr) <= 0):
        raise InputError(f"{name} values must be strictly increasing, got {arr.tolist()}")
    return arr


def _tick(progress: ProgressCallback | None, done: int, total: int) -> None:
    if progress is not None:
        progress(done, total)


# ---------------------------------------------------------------------------- inflation
@dataclass(frozen=True)
class InflationResult(StudyResult):
    """Height of the top-face centre against pressure (thesis Fig. 7.2b).

    Attributes
    ----------
    geometry
        Module geometry.
    pressure_pa
        Pressures, Pa.
    height_m
        Centre height above the flat rest position, m.
    volume_m3
        Air volume under the layer (whole module), m^3.
    mesh
        Discretisation used.
    """

    geometry: ModuleGeometry
    pressure_pa: np.ndarray
    height_m: np.ndarray
    volume_m3: np.ndarray
    mesh: MeshOptions = field(default_factory=MeshOptions)

    def height_at(self, pressure_pa: float) -> float:
        """Centre height at ``pressure_pa`` (Pa) by linear interpolation, m."""
        return float(np.interp(pressure_pa, self.pressure_pa, self.height_m))

    def volume_at(self, pressure_pa: float) -> float:
        """Air volume at ``pressure_pa`` (Pa) by linear interpolation, m^3."""
        return float(np.interp(pressure_pa, self.pressure_pa, self.volume_m3))

    def to_json_dict(self) -> dict[str, Any]:
        """The ``softpad fem sweep --json`` payload: model, pressure_kpa, height_mm."""
        return {
            "model": self.model,
            "pressure_kpa": as_list(self.pressure_pa, 1e-3),
            "height_mm": as_list(self.height_m, 1e3),
        }

    def to_dict(self) -> dict[str, Any]:
        """All results with units in the keys (kPa, mm, mL)."""
        return {
            **self.to_json_dict(),
            "volume_ml": as_list(self.volume_m3, 1e6),
            "thickness_mm": self.geometry.thickness_m * 1e3,
            "width_mm": self.geometry.width_m * 1e3,
            "mesh": {
                "cells_in_plane": self.mesh.cells_in_plane,
                "cells_through_thickness": self.mesh.cells_through_thickness,
                "element": self.mesh.element,
            },
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``pressure_kpa,height_mm,volume_ml`` rows."""
        rows = zip(self.pressure_pa * 1e-3, self.height_m * 1e3, self.volume_m3 * 1e6, strict=True)
        return write_csv(path, ["pressure_kpa", "height_mm", "volume_ml"], list(rows))

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Plot height (mm) against pressure (kPa); return the axes."""
        ax = new_axes(ax)
        ax.plot(
            self.pressure_pa * 1e-3, self.height_m * 1e3, marker="o", label=self.model, **kwargs
        )
        return label_axes(ax, "pressure (kPa)", "centre height (mm)")


def inflation_sweep(
    setup: ModuleSetup | ModuleModel | None = None,
    pressures_pa: Sequence[float] | np.ndarray | None = None,
    progress: ProgressCallback | None = None,
) -> InflationResult:
    """Inflate a free module step by step and record its centre height (thesis Fig. 7.2b).

    Parameters
    ----------
    setup
        The module (default :class:`ModuleSetup`: neo-Hookean, 45 x 45 x 1.5 mm), or a fresh
        :class:`ModuleModel` without base contact to use instead of building one.
    pressures_pa
        Increasing pressures, Pa (default 0, 0.25, ..., 3 kPa: 13 values).
    progress
        Optional ``progress(done, total)`` callback.

    Raises
    ------
    ConvergenceError
        When the model has no equilibrium on the way to a pressure (a pressure maximum).
    """
    p = _pressures(
        np.linspace(0.0, thesis.MAX_PRESSURE_PA, 13) if pressures_pa is None else pressures_pa
    )
    m = setup if isinstance(setup, ModuleModel) else (setup or ModuleSetup()).model(contact=False)
    heights, volumes = [], []
    for i, pi in enumerate(p):
        state = m.solve(float(pi), 0.0)
        heights.append(state.height_m)
        volumes.append(state.volume_m3)
        _tick(progress, i + 1, len(p))
    return InflationResult(
        m.material.name, m.geometry, p, np.array(heights), np.array(volumes), m.mesh_options
    )


# ---------------------------------------------------------------------------- design
@dataclass(frozen=True)
class DesignResult:
    """Centre height at one pressure against a construction parameter (thesis Fig. 7.3).

    Attributes
    ----------
    parameter
        ``"thickness"`` (upper-layer thickness) or ``"width"`` (module width).
    values_m
        Parameter values, m.
    models
        Material preset names (rows of ``height_m``).
    height_m
        Centre heights, m, shape ``(len(models), len(values_m))``.
    pressure_pa
        Inflating pressure, Pa.
    """

    parameter: str
    values_m: np.ndarray
    models: tuple[str, ...]
    height_m: np.ndarray
    pressure_pa: float

    def to_dict(self) -> dict[str, Any]:
        """Results with units in the keys."""
        return {
            "parameter": self.parameter,
            f"{self.parameter}_mm": as_list(self.values_m, 1e3),
            "pressure_kpa": self.pressure_pa * 1e-3,
            "height_mm": {
                m: as_list(h, 1e3) for m, h in zip(self.models, self.height_m, strict=True)
            },
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``<parameter>_mm,<model>_height_mm,...`` rows."""
        header = [f"{self.parameter}_mm", *[f"{m}_height_mm" for m in self.models]]
        rows = [[v * 1e3, *(self.height_m[:, j] * 1e3)] for j, v in enumerate(self.values_m)]
        return write_csv(path, header, rows)

    def plot(self, ax: Any = None) -> Any:
        """Plot height (mm) against the parameter (mm), one line per model."""
        ax = new_axes(ax)
        for name, h in zip(self.models, self.height_m, strict=True):
            ax.plot(self.values_m * 1e3, h * 1e3, marker="o", label=name)
        label = "upper-layer thickness" if self.parameter == "thickness" else "module width"
        return label_axes(
            ax, f"{label} (mm)", f"centre height at {self.pressure_pa * 1e-3:g} kPa (mm)"
        )


def design_sweep(
    parameter: str,
    values_m: Sequence[float] | np.ndarray,
    setups: Sequence[ModuleSetup] | None = None,
    pressure_pa: float = 1000.0,
    progress: ProgressCallback | None = None,
) -> DesignResult:
    """Centre height at ``pressure_pa`` against layer thickness or module width (Fig. 7.3).

    Parameters
    ----------
    parameter
        ``"thickness"`` or ``"width"``.
    values_m
        Values of the parameter, m (the other dimension is taken from each setup's geometry).
    setups
        Modules to compare, one row each (default, as the thesis: neo-Hookean and Yeoh on the
        45 x 45 x 1.5 mm geometry).
    pressure_pa
        Inflating pressure, Pa (thesis: 1 kPa).
    progress
        Optional ``progress(done, total)`` callback.
    """
    if parameter not in ("thickness", "width"):
        raise InputError(f"design parameter must be 'thickness' or 'width', got {parameter!r}")
    values = np.asarray([check_finite(parameter, v) for v in np.ravel(values_m)], dtype=float)
    if values.size == 0:
        raise InputError(f"no {parameter} values given")
    p = float(_pressures([pressure_pa])[0])
    setups = (ModuleSetup("neo-hookean"), ModuleSetup("yeoh")) if setups is None else setups
    mats = [get_material(s.material) for s in setups]
    heights = np.zeros((len(mats), len(values)))
    total, done = len(mats) * len(values), 0
    for i, (setup, mat) in enumerate(zip(setups, mats, strict=True)):
        base = setup.geometry or ModuleGeometry()
        for j, v in enumerate(values):
            geo = (
                ModuleGeometry(base.width_m, v)
                if parameter == "thickness"
                else ModuleGeometry(v, base.thickness_m)
            )
            model = replace(setup, material=mat, geometry=geo).model(contact=False)
            heights[i, j] = model.solve(p, 0.0).height_m
            done += 1
            _tick(progress, done, total)
    return DesignResult(parameter, values, tuple(m.name for m in mats), heights, p)


# ---------------------------------------------------------------------------- stiffness
@dataclass(frozen=True)
class StiffnessResult(StudyResult):
    """Equivalent stiffness ``k = F / (h_free - h_load)`` (thesis Section 6.1.2, Fig. 6.3c).

    Attributes
    ----------
    pressure_pa
        Inflating pressures, Pa.
    force_n
        Loads on the central disc, N.
    radius_m
        Radius of the loaded disc, m.
    height_free_m
        Centre height without load, m, shape (P,).
    height_load_m
        Centre height under each load, m, shape (P, F).
    contact_area_m2
        Area of the layer touching the base under each load, m^2, shape (P, F).
    """

    pressure_pa: np.ndarray
    force_n: np.ndarray
    radius_m: float
    height_free_m: np.ndarray
    height_load_m: np.ndarray
    contact_area_m2: np.ndarray

    @property
    def stiffness_n_per_m(self) -> np.ndarray:
        """``k = F / (h_free - h_load)``, N/m, shape (P, F)."""
        drop = self.height_free_m[:, None] - self.height_load_m
        return self.force_n[None, :] / drop

    @property
    def touches_base(self) -> np.ndarray:
        """Whether the layer touches the base, shape (P, F)."""
        return self.contact_area_m2 > 0.0

    def to_dict(self) -> dict[str, Any]:
        """Results with units in the keys."""
        return {
            "model": self.model,
            "pressure_kpa": as_list(self.pressure_pa, 1e-3),
            "force_n": as_list(self.force_n),
            "radius_mm": self.radius_m * 1e3,
            "height_free_mm": as_list(self.height_free_m, 1e3),
            "height_load_mm": [as_list(r, 1e3) for r in self.height_load_m],
            "stiffness_n_per_mm": [as_list(r, 1e-3) for r in self.stiffness_n_per_m],
            "contact_area_mm2": [as_list(r, 1e6) for r in self.contact_area_m2],
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write one row per (pressure, force)."""
        rows = []
        k = self.stiffness_n_per_m
        for i, p in enumerate(self.pressure_pa):
            for j, f in enumerate(self.force_n):
                rows.append(
                    [
                        p * 1e-3,
                        f,
                        self.height_free_m[i] * 1e3,
                        self.height_load_m[i, j] * 1e3,
                        k[i, j] * 1e-3,
                        self.contact_area_m2[i, j] * 1e6,
                    ]
                )
        header = [
            "pressure_kpa",
            "force_n",
            "height_free_mm",
            "height_load_mm",
            "stiffness_n_per_mm",
            "contact_area_mm2",
        ]
        return write_csv(path, header, rows)

    def plot(self, ax: Any = None) -> Any:
        """Plot stiffness (N/mm) against pressure (kPa), one line per force."""
        ax = new_axes(ax)
        k = self.stiffness_n_per_m * 1e-3
        for j, f in enumerate(self.force_n):
            ax.plot(self.pressure_pa * 1e-3, k[:, j], marker="o", label=f"F = {f:g} N")
            touch = self.touches_base[:, j]
            if np.any(touch):
                ax.plot(self.pressure_pa[touch] * 1e-3, k[touch, j], "kx")
        return label_axes(
            ax,
            "pressure (kPa)",
            "equivalent stiffness (N/mm)",
            title=f"{self.model}; x: layer touches the base",
        )


def stiffness_study(
    setup: ModuleSetup | None = None,
    pressures_pa: Sequence[float] | np.ndarray | None = None,
    forces_n: Sequence[float] = (0.2, 0.5, 0.8),
    radius_m: float = 0.010,
    progress: ProgressCallback | None = None,
) -> StiffnessResult:
    """Equivalent stiffness of an inflated module under a central load (thesis Fig. 6.3c).

    A vertical force ``F`` is spread uniformly over a central disc of radius ``radius_m``;
    the layer may touch the rigid base (penalty contact), which stiffens it when a high force
    meets a low pressure.

    Parameters
    ----------
    setup
        The module (default :class:`ModuleSetup`).
    pressures_pa
        Increasing inflating pressures, Pa (default 0.5..2.8 kPa, 6 values).
    forces_n
        Increasing loads, N (thesis: 0.2, 0.5, 0.8 N).
    radius_m
        Radius of the loaded disc, m (thesis: 10 mm).
    progress
        Optional ``progress(done, total)`` callback.
    """
    p = _pressures(np.linspace(500.0, 2800.0, 6) if pressures_pa is None else pressures_pa)
    forces = np.asarray([check_finite("force", f) for f in forces_n], dtype=float)
    if forces.size == 0 or np.any(forces <= 0) or np.any(np.diff(forces) <= 0):
        raise InputError(f"forces must be positive and increasing, got {forces.tolist()} N")
    r = check_finite("radius_m", radius_m)
    if r <= 0:
        raise InputError(f"load radius must be > 0 m, got {r!r} m")
    model = (setup or ModuleSetup()).model(load_patch=LoadPatch.disc(r), contact=True)
    free = np.zeros(len(p))
    loaded = np.zeros((len(p), len(forces)))
    contact = np.zeros((len(p), len(forces)))
    total = len(p) * (len(forces) + 1)
    done = 0
    for i, pi in enumerate(p):
        free[i] = model.solve(float(pi), 0.0).height_m
        done += 1
        _tick(progress, done, total)
        saved = model.checkpoint()
        for j, f in enumerate(forces):
            state = model.solve(float(pi), float(f))
            loaded[i, j] = state.height_m
            contact[i, j] = state.contact_area_m2
            done += 1
            _tick(progress, done, total)
        model.restore(saved)
    return StiffnessResult(model.material.name, p, forces, r, free, loaded, contact)


# ---------------------------------------------------------------------------- sensitive area
@dataclass(frozen=True)
class SensitivityResult(StudyResult):
    """Sensitive area of a module against pressure (thesis Section 6.1.2).

    Definition: by reciprocity, a small vertical force ``dF`` at a top-face point ``x``
    changes the chamber volume by ``dV = -dF * dw(x)/dp``, where ``dw/dp`` is the local
    rise of the top face per unit pressure. The sensitive area is the part of the top face
    where that response is at least ``fraction`` of the response at the centre; ``side_m``
    is the side of the square with the same area.

    Attributes
    ----------
    pressure_pa
        Pressures, Pa.
    fraction
        Threshold relative to the centre response (default 0.5: half-maximum).
    area_m2
        Sensitive area, m^2.
    centre_response_m3_per_n
        ``-dV/dF`` for a force at the centre, m^3/N.
    probe_mass_kg, threshold_pa
        Second, absolute definition: a small probe of this mass (kg) resting at ``x`` on a
        sealed module (valves closed, tubing dead volume included) raises the pressure by
        ``m g s(x) / (dV/dp + (V + V_dead) / (p_atm + p))``; the detectable area is where
        that rise reaches ``threshold_pa`` (Pa, thesis t_o = 50 Pa).
    detectable_area_m2
        Area of the top face where the probe is detected, m^2.
    """

    pressure_pa: np.ndarray
    fraction: float
    area_m2: np.ndarray
    centre_response_m3_per_n: np.ndarray
    probe_mass_kg: float = 0.0126
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA
    detectable_area_m2: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def side_m(self) -> np.ndarray:
        """Side of the equivalent square, m."""
        return np.sqrt(self.area_m2)

    def to_dict(self) -> dict[str, Any]:
        """Results with units in the keys."""
        return {
            "model": self.model,
            "fraction": self.fraction,
            "pressure_kpa": as_list(self.pressure_pa, 1e-3),
            "area_mm2": as_list(self.area_m2, 1e6),
            "side_mm": as_list(self.side_m, 1e3),
            "centre_response_ml_per_n": as_list(self.centre_response_m3_per_n, 1e6),
            "probe_mass_g": self.probe_mass_kg * 1e3,
            "threshold_kpa": self.threshold_pa * 1e-3,
            "detectable_side_mm": as_list(np.sqrt(self.detectable_area_m2), 1e3),
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``pressure_kpa,area_mm2,side_mm,centre_response_ml_per_n`` rows."""
        rows = zip(
            self.pressure_pa * 1e-3,
            self.area_m2 * 1e6,
            self.side_m * 1e3,
            self.centre_response_m3_per_n * 1e6,
            np.sqrt(self.detectable_area_m2) * 1e3,
            strict=True,
        )
        header = [
            "pressure_kpa",
            "area_mm2",
            "side_mm",
            "centre_response_ml_per_n",
            "detectable_side_mm",
        ]
        return write_csv(path, header, list(rows))

    def plot(self, ax: Any = None) -> Any:
        """Plot the side of the sensitive square (mm) against pressure (kPa)."""
        ax = new_axes(ax)
        ax.plot(
            self.pressure_pa * 1e-3,
            self.side_m * 1e3,
            marker="o",
            label=f"response >= {self.fraction:g} x centre",
        )
        ax.plot(
            self.pressure_pa * 1e-3,
            np.sqrt(self.detectable_area_m2) * 1e3,
            marker="s",
            label=f"{self.probe_mass_kg * 1e3:g} g probe detected at {self.threshold_pa:g} Pa",
        )
        return label_axes(ax, "pressure (kPa)", f"side of the sensitive square (mm), {self.model}")


def sensitive_area_study(
    setup: ModuleSetup | None = None,
    pressures_pa: Sequence[float] | np.ndarray | None = None,
    fraction: float = 0.5,
    progress: ProgressCallback | None = None,
    probe_mass_kg: float = 0.0126,
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA,
    dead_volume_m3: float | None = None,
) -> SensitivityResult:
    """Sensitive area against pressure (thesis Section 6.1.2; definition in the result).

    Parameters
    ----------
    setup
        The module (default :class:`ModuleSetup`).
    pressures_pa
        Increasing pressures > 0, Pa (default 0.5..2.8 kPa, 6 values).
    fraction
        Response threshold relative to the centre, in (0, 1).
    progress
        As in :func:`inflation_sweep`.
    probe_mass_kg
        Probe mass of the absolute definition, kg (default 12.6 g, the thesis's brick).
    threshold_pa
        Detection threshold of the absolute definition, Pa (default t_o = 50 Pa).
    dead_volume_m3
        Tubing dead volume, m^3 (default :data:`~softpad.fem.DEFAULT_DEAD_VOLUME_M3`).
    """
    from softpad.fem._chamber import GRAVITY_M_PER_S2

    p, probe, thr, vd, frac = _sensitivity_inputs(
        pressures_pa, probe_mass_kg, threshold_pa, dead_volume_m3, fraction
    )
    model = (setup or ModuleSetup()).model(contact=False)
    areas, centre, detectable = [], [], []
    for i, pi in enumerate(p):
        area, c, reach = _sensitive_area_at(
            model, float(pi), frac, probe * GRAVITY_M_PER_S2, thr, vd
        )
        areas.append(area)
        centre.append(c)
        detectable.append(reach)
        _tick(progress, i + 1, len(p))
    return SensitivityResult(
        model.material.name,
        p,
        frac,
        np.array(areas),
        np.array(centre),
        probe,
        thr,
        np.array(detectable),
    )


def _sensitive_area_at(
    model: ModuleModel, pressure_pa: float, frac: float, weight_n: float, thr: float, vd: float
) -> tuple[float, float, float]:
    """At ``pressure_pa``: the area whose response is >= ``frac`` x the centre's (m^2), the
    centre's response (m/Pa) and the area where ``weight_n`` raises the sealed pressure by
    ``thr`` Pa or more (m^2)."""
    from softpad.fem._chamber import ATMOSPHERIC_PRESSURE_PA

    area_weights = model.top_face_area_weights()
    top = area_weights > 0
    model.solve(pressure_pa, 0.0)
    dudp, compliance = model.pressure_sensitivity(with_compliance=True)
    dw = dudp[:, 2]
    c = dw[model.centre_top_point]
    sensitive = top & (dw >= frac * c)
    gas = (model.volume_m3() + vd) / (ATMOSPHERIC_PRESSURE_PA + pressure_pa)
    rise = weight_n * dw / (compliance + gas)
    detectable = 4.0 * float(area_weights[top & (rise >= thr)].sum())
    return 4.0 * float(area_weights[sensitive].sum()), float(c), detectable


def _sensitivity_inputs(
    pressures_pa: Sequence[float] | np.ndarray | None,
    probe_mass_kg: float,
    threshold_pa: float,
    dead_volume_m3: float | None,
    fraction: float,
) -> tuple[np.ndarray, float, float, float, float]:
    """The inputs of :func:`sensitive_area_study`, checked and with their defaults."""
    from softpad.fem._chamber import DEFAULT_DEAD_VOLUME_M3

    p = _pressures(np.linspace(500.0, 2800.0, 6) if pressures_pa is None else pressures_pa)
    probe = check_finite("probe_mass_kg", probe_mass_kg)
    thr = check_finite("threshold_pa", threshold_pa)
    if probe <= 0 or thr <= 0:
        raise InputError(f"probe mass and threshold must be > 0, got {probe!r} kg, {thr!r} Pa")
    vd = (
        DEFAULT_DEAD_VOLUME_M3
        if dead_volume_m3 is None
        else check_finite("dead_volume", dead_volume_m3)
    )
    if p[0] <= 0:
        raise InputError("sensitive area needs pressures > 0 Pa (the flat layer has no dome)")
    frac = check_finite("fraction", fraction)
    if not 0.0 < frac < 1.0:
        raise InputError(f"fraction must be in (0, 1), got {frac!r}")
    return p, probe, thr, vd, frac
