"""Sealed-chamber coupling: the pressure rise a load causes once the valves are closed.

Beyond the thesis (which applied a constant pressure in its FEM, Section 6.1.2): after the
module is inflated to ``p0`` its valves close, so the air in the module and its tubing is a
fixed amount of gas. A load on the top squeezes the chamber and the pressure rises until the
isothermal ideal gas and the layer agree:

``(p_atm + p) (V(p, F) + V_dead) = (p_atm + p0) (V(p0, 0) + V_dead)``

where ``V(p, F)`` is the chamber volume from the finite-element model and ``V_dead`` the dead
volume of tubing and sensor. The smallest detectable mass is the one whose rise reaches the
detection threshold (thesis: about 6 g at 1.1 kPa with t_o = 0.05 kPa).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.fem._geometry import LoadPatch
from softpad.fem._model import ModuleModel, ModuleSetup, ProgressCallback
from softpad.fem._results import StudyResult, as_list, label_axes, new_axes, write_csv

#: Standard atmosphere, Pa.
ATMOSPHERIC_PRESSURE_PA = 101_325.0
#: Default dead volume, m^3 (3.34 mL): the channel's tubing plus the residual gap under a flat
#: layer (:data:`softpad.thesis.TUBING_VOLUME_M3` + :data:`~softpad.thesis.CHAMBER_GAP_VOLUME_M3`),
#: the same air the simulator's pneumatics count (the finite-element volume has no gap).
DEFAULT_DEAD_VOLUME_M3 = thesis.TUBING_VOLUME_M3 + thesis.CHAMBER_GAP_VOLUME_M3
#: Standard gravity, m/s^2.
GRAVITY_M_PER_S2 = 9.80665
#: Footprint of the thesis's Lego Duplo brick (42 x 31 mm, 12.6 g).
BRICK_FOOTPRINT = LoadPatch("rectangle", 0.042, 0.031)


@dataclass(frozen=True)
class ChamberResult(StudyResult):
    """Pressure rise of a sealed module under masses placed on a footprint.

    Attributes
    ----------
    initial_pressure_pa
        Pressure at which the valves closed, Pa.
    initial_volume_m3
        Chamber volume then, m^3.
    dead_volume_m3
        Tubing/sensor dead volume, m^3.
    footprint
        Loaded region of the top face.
    mass_kg
        Masses, kg.
    pressure_pa
        Sealed equilibrium pressure under each mass, Pa.
    volume_m3
        Chamber volume under each mass, m^3.
    height_m
        Centre height under each mass, m.
    rise_per_kg_pa
        Small-load slope ``dp/dm`` (linearised at the unloaded state), Pa/kg.
    compliance_m3_per_pa
        ``dV/dp`` of the unloaded module, m^3/Pa.
    """

    initial_pressure_pa: float
    initial_volume_m3: float
    dead_volume_m3: float
    footprint: LoadPatch
    mass_kg: np.ndarray
    pressure_pa: np.ndarray
    volume_m3: np.ndarray
    height_m: np.ndarray
    rise_per_kg_pa: float
    compliance_m3_per_pa: float

    @property
    def delta_pressure_pa(self) -> np.ndarray:
        """Pressure rise above the initial pressure, Pa."""
        return self.pressure_pa - self.initial_pressure_pa

    def min_detectable_mass_kg(self, threshold_pa: float = thesis.OBJECT_THRESHOLD_PA) -> float:
        """Smallest mass whose pressure rise reaches ``threshold_pa`` (Pa), kg.

        Uses the small-load slope (the response is linear for masses of a few grams). Pass
        ``n_sigma * noise_pa`` to express the threshold as a multiple of the sensor noise;
        the thesis's object threshold t_o is 50 Pa.
        """
        thr = check_finite("threshold_pa", threshold_pa)
        if thr <= 0:
            raise InputError(f"detection threshold must be > 0 Pa, got {thr!r} Pa")
        return thr / self.rise_per_kg_pa

    def to_dict(self, threshold_pa: float = thesis.OBJECT_THRESHOLD_PA) -> dict[str, Any]:
        """Results with units in the keys."""
        return {
            "model": self.model,
            "initial_pressure_kpa": self.initial_pressure_pa * 1e-3,
            "initial_volume_ml": self.initial_volume_m3 * 1e6,
            "dead_volume_ml": self.dead_volume_m3 * 1e6,
            "footprint": self.footprint.describe(),
            "mass_g": as_list(self.mass_kg, 1e3),
            "delta_pressure_kpa": as_list(self.delta_pressure_pa, 1e-3),
            "volume_ml": as_list(self.volume_m3, 1e6),
            "height_mm": as_list(self.height_m, 1e3),
            "rise_kpa_per_g": self.rise_per_kg_pa * 1e-6,
            "compliance_ml_per_kpa": self.compliance_m3_per_pa * 1e9,
            "threshold_kpa": threshold_pa * 1e-3,
            "min_detectable_mass_g": self.min_detectable_mass_kg(threshold_pa) * 1e3,
        }

    def to_csv(self, path: str | Path) -> Path:
        """Write ``mass_g,delta_pressure_kpa,volume_ml,height_mm`` rows."""
        rows = zip(
            self.mass_kg * 1e3,
            self.delta_pressure_pa * 1e-3,
            self.volume_m3 * 1e6,
            self.height_m * 1e3,
            strict=True,
        )
        return write_csv(
            path, ["mass_g", "delta_pressure_kpa", "volume_ml", "height_mm"], list(rows)
        )

    def plot(self, ax: Any = None, threshold_pa: float = thesis.OBJECT_THRESHOLD_PA) -> Any:
        """Plot the pressure rise (kPa) against mass (g) with the detection threshold."""
        ax = new_axes(ax)
        ax.plot(self.mass_kg * 1e3, self.delta_pressure_pa * 1e-3, marker="o", label="sealed FEM")
        m = np.linspace(0.0, float(self.mass_kg.max()), 50)
        ax.plot(m * 1e3, m * self.rise_per_kg_pa * 1e-3, "--", label="small-load slope")
        ax.axhline(threshold_pa * 1e-3, color="k", lw=0.8, label="threshold")
        return label_axes(
            ax,
            "mass on the footprint (g)",
            "pressure rise (kPa)",
            title=f"{self.model}, p0 = {self.initial_pressure_pa * 1e-3:g} kPa, {self.footprint.describe()}",
        )


def sealed_rise_per_force(
    model: ModuleModel,
    dead_volume_m3: float = DEFAULT_DEAD_VOLUME_M3,
    atmospheric_pa: float = ATMOSPHERIC_PRESSURE_PA,
) -> tuple[float, float]:
    """Small-load pressure rise per newton on the model's load patch, and ``dV/dp``.

    ``dp/dF = s / (C + (V + V_dead) / (p_atm + p))`` with ``s = -dV/dF`` from reciprocity
    (patch-weighted mean of ``dw/dp`` on the top face) and ``C = dV/dp``.

    Returns
    -------
    rise_pa_per_n, compliance_m3_per_pa
    """
    dwdp, compliance = model.pressure_sensitivity(with_compliance=True)
    weights = model.load_patch_weights
    s = float(np.dot(weights, dwdp[:, 2]))
    volume = model.volume_m3()
    gas = (volume + dead_volume_m3) / (atmospheric_pa + model.pressure_pa)
    return s / (compliance + gas), compliance


def sealed_chamber_study(
    setup: ModuleSetup | None = None,
    initial_pressure_pa: float = thesis.P0_PA,
    masses_kg: Sequence[float] = (0.006, 0.0126, 0.05, 0.1),
    footprint: LoadPatch = BRICK_FOOTPRINT,
    dead_volume_m3: float = DEFAULT_DEAD_VOLUME_M3,
    atmospheric_pa: float = ATMOSPHERIC_PRESSURE_PA,
    progress: ProgressCallback | None = None,
) -> ChamberResult:
    """Pressure rise of a sealed module when masses rest on a footprint of its top.

    Parameters
    ----------
    setup
        The module (default :class:`~softpad.fem.ModuleSetup`).
    initial_pressure_pa
        Pressure when the valves close, Pa (thesis: 1.1 kPa).
    masses_kg
        Increasing masses, kg; their whole weight rests on this module.
    footprint
        Centred contact region of the object (default: the 42 x 31 mm Duplo brick).
    dead_volume_m3
        Dead volume of the tubing and sensor, m^3 (default 1 m of 2 mm tubing).
    atmospheric_pa
        Ambient absolute pressure, Pa.
    progress
        As in :func:`~softpad.fem.inflation_sweep`.

    Notes
    -----
    For each mass the sealed equilibrium is found by a secant iteration on the pressure,
    each evaluation a finite-element solve at ``(p, F = m g)`` with base contact.
    """
    p0, vd, pa, masses = _checked_inputs(
        initial_pressure_pa, dead_volume_m3, atmospheric_pa, masses_kg
    )
    model = (setup or ModuleSetup()).model(load_patch=footprint, contact=True)
    v0 = model.solve(p0, 0.0).volume_m3
    rise_per_n, compliance = sealed_rise_per_force(model, vd, pa)
    gas_amount = (pa + p0) * (v0 + vd)

    pressures, volumes, heights = _sealed_series(
        model, masses, p0, rise_per_n, vd, pa, gas_amount, progress
    )
    return ChamberResult(
        model=model.material.name,
        initial_pressure_pa=p0,
        initial_volume_m3=v0,
        dead_volume_m3=vd,
        footprint=footprint,
        mass_kg=masses,
        pressure_pa=pressures,
        volume_m3=volumes,
        height_m=heights,
        rise_per_kg_pa=rise_per_n * GRAVITY_M_PER_S2,
        compliance_m3_per_pa=compliance,
    )


def _checked_inputs(
    initial_pressure_pa: float,
    dead_volume_m3: float,
    atmospheric_pa: float,
    masses_kg: Sequence[float],
) -> tuple[float, float, float, NDArray[np.float64]]:
    """The inputs of :func:`sealed_chamber_study`, checked: p0, dead volume, ambient, masses."""
    p0 = check_finite("initial_pressure_pa", initial_pressure_pa)
    if not 0.0 < p0 <= 10_000.0:
        raise InputError(f"initial pressure {p0:g} Pa outside (0, 10000] Pa")
    vd = check_finite("dead_volume_m3", dead_volume_m3)
    if vd < 0:
        raise InputError(f"dead volume must be >= 0 m^3, got {vd!r}")
    pa = check_finite("atmospheric_pa", atmospheric_pa)
    if pa <= 0:
        raise InputError(f"atmospheric pressure must be > 0 Pa, got {pa!r}")
    masses = np.asarray([check_finite("mass", m) for m in masses_kg], dtype=float)
    if masses.size == 0 or np.any(masses <= 0) or np.any(np.diff(masses) <= 0):
        raise InputError(f"masses must be positive and increasing, got {masses.tolist()} kg")

    return p0, vd, pa, masses


def _sealed_equilibrium(
    model: ModuleModel,
    force: float,
    x0: float,
    x1: float,
    vd: float,
    pa: float,
    gas_amount: float,
) -> None:
    """Solve ``model`` at the pressure where the sealed gas (amount ``gas_amount``, dead volume
    ``vd``, ambient ``pa``) balances ``force``: a secant iteration from ``x0`` and ``x1``, Pa."""

    def mismatch(p: float) -> float:
        st = model.solve(max(p, 0.0), force)
        return (pa + p) * (st.volume_m3 + vd) - gas_amount

    f0, f1 = mismatch(x0), mismatch(x1)
    for _ in range(30):
        if abs(f1) < 1e-9 * gas_amount or f1 == f0:
            break
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        x0, f0 = x1, f1
        x1, f1 = x2, mismatch(x2)
        if abs(x1 - x0) < 1e-3:
            break


def _sealed_series(
    model: ModuleModel,
    masses: NDArray[np.float64],
    p0: float,
    rise_per_n: float,
    vd: float,
    pa: float,
    gas_amount: float,
    progress: ProgressCallback | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Sealed equilibrium pressure (Pa), chamber volume (m^3) and centre height (m) for each
    of the increasing ``masses`` (kg), each solve starting from the previous one."""
    pressures, volumes, heights = [], [], []
    p_prev = p0
    for i, m in enumerate(masses):
        force = m * GRAVITY_M_PER_S2
        _sealed_equilibrium(model, force, p_prev, p0 + rise_per_n * force, vd, pa, gas_amount)
        st = model.state()
        pressures.append(model.pressure_pa)
        volumes.append(st.volume_m3)
        heights.append(st.height_m)
        p_prev = model.pressure_pa
        if progress is not None:
            progress(i + 1, len(masses))
    return np.array(pressures), np.array(volumes), np.array(heights)
