"""Finite-element response of a design's module: what the pad feels before any trial.

One quarter model of the module's upper layer (:class:`softpad.fem.ModuleModel`, base contact
on, the Duplo brick's footprint scaled to the module as the load patch) is inflated to p0;
at that state one tangent solve gives (:meth:`~softpad.fem.ModuleModel.pressure_sensitivity`):

* the chamber compliance ``C = dV/dp`` and, by reciprocity, ``-dV/dF`` for a load anywhere on
  the top face (``-dw/dp`` there);
* the sealed-chamber rise per newton ``dp/dF = s / (C + (V + V_dead) / (p_atm + p0))``, the
  same law as :func:`softpad.fem.sealed_chamber_study` (Section "sealed chamber" of
  docs/fem.md), on the footprint and as a map over the top face (a point load at each node);
* the minimum detectable mass at t_o: ``m = t_o / (g dp/dF)`` (thesis: about 6 g at 1.1 kPa),
  on the brick's footprint scaled to the module and on a fixed 10 x 10 mm weight at the centre
  (the same object on every pad: the figure pads of different pitch are compared by);
* the centre's sensitivity (the sealed rise per newton of a point load there) and its
  stiffness (a load on the 10 x 10 mm centre patch per metre of the patch's deflection, the
  chamber open: one more tangent solve).

The simulated box then runs on an :class:`softpad.sim.AnalyticCharacteristic` fitted to these
numbers (volume, compliance, height and effective area at p0), see :meth:`FemResponse.characteristic`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from softpad import thesis

#: Standard gravity, m/s^2.
GRAVITY_M_S2 = 9.80665
#: The thesis's 12.6 g Lego Duplo brick's footprint on a 45 mm module (42 x 31 mm); other
#: modules use it scaled with the pitch.
BRICK_FOOTPRINT_M = (0.042, 0.031)
#: Residual air under a flat layer, m^3 (as the packaged characteristic, 0.2 mL).
GAP_VOLUME_M3 = 0.2e-6
#: Side of the compact weight whose minimum detectable mass every pad is compared by, m
#: (10 x 10 mm at the module's centre, as ``softpad pad sensitivity``'s compact probe).
COMPACT_SIDE_M = 0.010


@dataclass(frozen=True)
class FemResponse:
    """Response of one module design at its inflating pressure."""

    #: The module (the FEM variables of :class:`~softpad.design.PadDesign`).
    width_m: float
    #: The module (the FEM variables of :class:`~softpad.design.PadDesign`).
    thickness_m: float
    #: The module (the FEM variables of :class:`~softpad.design.PadDesign`).
    material: str
    #: The module (the FEM variables of :class:`~softpad.design.PadDesign`).
    p0_pa: float
    #: Centre height of the free module at p0, m.
    height_m: float
    #: Air volume under the layer at p0, m^3 (finite-element volume, no gap).
    volume_m3: float
    #: ``dV/dp`` at p0, m^3/Pa.
    compliance_m3_pa: float
    #: ``-dV/dF`` for a load spread on the footprint, m^3/N.
    volume_per_force_m3_n: float
    #: Sealed-chamber pressure rise per newton on the footprint, Pa/N.
    rise_pa_n: float
    #: Smallest mass on the footprint whose rise reaches t_o, kg.
    min_detectable_mass_kg: float
    #: Share of the module's area where a point load raises the pressure at least half as
    #: much as at the centre (the rest: the "non-sensitive" border of Section 6.1.2).
    sensitive_fraction: float
    #: The sensitivity map's points: top-face points of the quarter (x, y from the module
    #: centre), metres.
    map_xy_m: tuple[tuple[float, float], ...]
    #: The sensitivity map's values: the sealed rise per newton of a point load at each point
    #: of ``map_xy_m``, Pa/N.
    map_rise_pa_n: tuple[float, ...]
    #: Wall time of the finite-element work, s.
    solve_time_s: float = 0.0
    #: Sealed-chamber rise per newton of a point load at the module's centre, Pa/N.
    centre_rise_pa_n: float = float("nan")
    #: Sealed-chamber rise per newton of a 10 x 10 mm weight at the centre, Pa/N.
    compact_rise_pa_n: float = float("nan")
    #: Smallest 10 x 10 mm weight at the centre whose rise reaches t_o, kg.
    compact_min_detectable_mass_kg: float = float("nan")
    #: Open chamber (constant pressure): a load spread on the 10 x 10 mm centre patch per
    #: metre of the patch's mean deflection, N/m.
    centre_stiffness_n_m: float = float("nan")

    def characteristic(self) -> Any:
        """An :class:`softpad.sim.AnalyticCharacteristic` through this response at p0.

        Reference volume ``V + V_gap``, compliance ``C``, height ``h`` and effective area
        ``A_eff = C / (-dV/dF)`` (a load acts like a back-pressure F / A_eff), so the simulated
        sealed module rises as the finite-element one does.
        """
        from softpad.sim import AnalyticCharacteristic

        return AnalyticCharacteristic(
            reference_pressure_pa=self.p0_pa,
            reference_volume_m3=self.volume_m3 + GAP_VOLUME_M3,
            compliance_m3_pa=self.compliance_m3_pa,
            reference_height_m=self.height_m,
            gap_volume_m3=GAP_VOLUME_M3,
            effective_area_m2=self.compliance_m3_pa / self.volume_per_force_m3_n,
        )

    def to_dict(self) -> dict[str, Any]:
        """Every field (SI), JSON-ready (the cache's format)."""
        d = asdict(self)
        d["map_xy_m"] = [list(p) for p in self.map_xy_m]
        d["map_rise_pa_n"] = list(self.map_rise_pa_n)
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> FemResponse:
        """Inverse of :meth:`to_dict`."""
        d = dict(d)
        d["map_xy_m"] = tuple(tuple(p) for p in d["map_xy_m"])
        d["map_rise_pa_n"] = tuple(d["map_rise_pa_n"])
        return cls(**d)

    def summary(self) -> dict[str, Any]:
        """The headline figures with units in the keys."""
        return {
            "height_mm": round(self.height_m * 1e3, 3),
            "volume_ml": round(self.volume_m3 * 1e6, 3),
            "compliance_ml_per_kpa": round(self.compliance_m3_pa * 1e9, 3),
            "rise_kpa_per_n": round(self.rise_pa_n * 1e-3, 4),
            "min_detectable_mass_g": round(self.min_detectable_mass_kg * 1e3, 2),
            "sensitive_fraction": round(self.sensitive_fraction, 3),
            "centre_rise_kpa_per_n": round(self.centre_rise_pa_n * 1e-3, 4),
            "compact_min_detectable_mass_g": round(self.compact_min_detectable_mass_kg * 1e3, 2),
            "centre_stiffness_n_per_mm": round(self.centre_stiffness_n_m * 1e-3, 4),
        }


def fem_response(
    width_m: float,
    thickness_m: float,
    material: str,
    p0_pa: float,
    cells_in_plane: int = 12,
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA,
) -> FemResponse:
    """Solve one module at p0 and read its response (see the module's docstring).

    Parameters
    ----------
    width_m, thickness_m, material, p0_pa
        Module width (= pitch), layer thickness, material preset, inflating pressure (SI).
    cells_in_plane
        Cells along the quarter's side (12 = :data:`softpad.fem.DEFAULT_MESH`; 8 for quick
        sweeps: heights within 0.2 %, sensitivity within 2 %).
    threshold_pa
        t_o, the object threshold, Pa.
    """
    import time

    from softpad.fem import ATMOSPHERIC_PRESSURE_PA, DEFAULT_DEAD_VOLUME_M3

    t0 = time.perf_counter()
    model = _module_model(width_m, thickness_m, material, cells_in_plane)
    state = model.solve(p0_pa, 0.0)
    dudp, compliance = model.pressure_sensitivity(with_compliance=True)
    gas = (state.volume_m3 + DEFAULT_DEAD_VOLUME_M3) / (ATMOSPHERIC_PRESSURE_PA + p0_pa)
    per_force = float(np.dot(model.load_patch_weights, dudp[:, 2]))
    rise = per_force / (compliance + gas)
    xy, point_rise, fraction = _sensitivity_map(model, dudp, compliance + gas)
    from softpad.fem import LoadPatch

    centre = float(dudp[model.centre_top_point, 2]) / (compliance + gas)
    compact_patch = LoadPatch("rectangle", COMPACT_SIDE_M, COMPACT_SIDE_M)
    compact = float(np.dot(model.patch_weights(compact_patch), dudp[:, 2])) / (compliance + gas)
    stiffness = 1.0 / model.patch_load_compliance(compact_patch)
    return FemResponse(
        width_m=width_m,
        thickness_m=thickness_m,
        material=material,
        p0_pa=p0_pa,
        height_m=state.height_m,
        volume_m3=state.volume_m3,
        compliance_m3_pa=compliance,
        volume_per_force_m3_n=per_force,
        rise_pa_n=rise,
        min_detectable_mass_kg=threshold_pa / (rise * GRAVITY_M_S2),
        sensitive_fraction=fraction,
        map_xy_m=xy,
        map_rise_pa_n=point_rise,
        solve_time_s=time.perf_counter() - t0,
        centre_rise_pa_n=centre,
        compact_rise_pa_n=compact,
        compact_min_detectable_mass_kg=threshold_pa / (compact * GRAVITY_M_S2),
        centre_stiffness_n_m=stiffness,
    )


def _module_model(width_m: float, thickness_m: float, material: str, cells_in_plane: int) -> Any:
    """The module's model with contact, loaded by the brick's footprint scaled to its width."""
    from softpad.fem import LoadPatch, MeshOptions, ModuleGeometry, ModuleModel

    scale = width_m / 0.045
    patch = LoadPatch("rectangle", BRICK_FOOTPRINT_M[0] * scale, BRICK_FOOTPRINT_M[1] * scale)
    return ModuleModel(
        material,
        geometry=ModuleGeometry(width_m, thickness_m),
        mesh=MeshOptions(cells_in_plane=cells_in_plane),
        load_patch=patch,
        contact=True,
    )


def _sensitivity_map(
    model: Any, dudp: np.ndarray, denominator: float
) -> tuple[tuple[tuple[float, float], ...], tuple[float, ...], float]:
    """Top-face points, their point-load rise (Pa/N) and the sensitive share of the area."""
    weights = model.top_face_area_weights()
    top = weights > 0
    pts = model.mesh.points[top]
    rise = dudp[top, 2] / denominator
    centre = float(rise[np.argmin(np.hypot(pts[:, 0], pts[:, 1]))])
    sensitive = float(weights[top][rise >= 0.5 * centre].sum() / weights[top].sum())
    xy = tuple((round(float(x), 6), round(float(y), 6)) for x, y in pts[:, :2])
    return xy, tuple(round(float(r), 3) for r in rise), sensitive
