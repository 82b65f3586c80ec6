"""Module response: the chamber's volume change per newton of load at every point of the top face.

For each pressure p0 of the usable range the inflated, unloaded layer is solved, then one linear
solve gives ``dw/dp`` of every top-face node (:meth:`ModuleModel.pressure_sensitivity`); by
reciprocity that is ``s = -dV/dF`` of a point force there. With the chamber compliance and
volume this gives the small-load pressure rise of a sealed chamber for a flat load of any
footprint at any position (:class:`ModuleResponse`), which the simulator reads from
``softpad/data/module_response.npz``; ``softpad fem response`` regenerates it.

Mesh convergence (:func:`response_convergence`): the responses that matter to the simulator
(a centred brick, a 10 mm block at the centre and 15 mm off it, a fingertip on the clamped edge)
on the default mesh against a refined one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.fem._geometry import LoadPatch, MeshOptions
from softpad.fem._model import ModuleModel, ModuleSetup, ProgressCallback
from softpad.fem._response_table import RESPONSE_VERSION, ModuleResponse

#: Pressures of the shipped response, Pa: the usable range of p0 (Section 6.2.1.1).
DEFAULT_RESPONSE_PRESSURES_PA = (
    500.0,
    700.0,
    900.0,
    thesis.P0_PA,
    1400.0,
    1700.0,
    2000.0,
    2400.0,
    2800.0,
)
#: The characteristic's load patch (the response's equivalent loads refer to it).
REFERENCE_PATCH = LoadPatch.square(0.030)

#: Loads of the convergence check: name -> (centre from the module centre, footprint), metres.
CONVERGENCE_PROBES: dict[str, tuple[tuple[float, float], tuple[float, float]]] = {
    "brick 42x31 mm, centred": ((0.0, 0.0), (0.042, 0.031)),
    "10x10 mm at the centre": ((0.0, 0.0), (0.010, 0.010)),
    "10x10 mm, 15 mm off": ((0.015, 0.0), (0.010, 0.010)),
    "8x16 mm tip on the edge": ((0.0225, 0.0), (0.008, 0.016)),
}


def _top_grid(model: ModuleModel, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The top-face nodal ``values`` of the quarter as an (N, N) array on its node axis."""
    pts = model.mesh.points
    t, a = model.geometry.thickness_m, model.geometry.half_width_m
    top = np.flatnonzero(np.abs(pts[:, 2] - t) < 1e-9 * a)
    axis = np.unique(np.round(pts[top, 0], 12))
    i = np.searchsorted(axis, np.round(pts[top, 0], 12))
    j = np.searchsorted(axis, np.round(pts[top, 1], 12))
    grid = np.full((axis.size, axis.size), np.nan)
    grid[i, j] = values[top]
    if np.isnan(grid).any():
        raise InputError("the top face of the mesh is not a tensor grid; use a hex8 mesh")
    return axis, grid


def module_response(
    setup: ModuleSetup | None = None,
    pressures_pa: Sequence[float] = DEFAULT_RESPONSE_PRESSURES_PA,
    progress: ProgressCallback | None = None,
) -> ModuleResponse:
    """Tabulate the module's response to vertical loads over a range of pressures.

    Parameters
    ----------
    setup
        The module (default :class:`~softpad.fem.ModuleSetup`; the mesh must be hex8).
    pressures_pa
        Increasing chamber pressures, Pa (default: the usable range 0.5..2.8 kPa).
    progress
        As in :func:`~softpad.fem.inflation_sweep`.

    Returns
    -------
    ModuleResponse
        ``s`` on the quarter's top nodes, volume and compliance per pressure.
    """
    p = _response_pressures(pressures_pa)
    model = (setup or ModuleSetup()).model(load_patch=REFERENCE_PATCH)
    rows, volumes, compliances, refs = [], [], [], []
    axis = np.zeros(0)
    for k, pk in enumerate(p):
        model.solve(float(pk), 0.0)
        dudp, compliance = model.pressure_sensitivity(with_compliance=True)
        axis, grid = _top_grid(model, dudp[:, 2])
        rows.append(grid)
        volumes.append(model.volume_m3())
        compliances.append(compliance)
        refs.append(float(np.dot(model.load_patch_weights, dudp[:, 2])))
        if progress is not None:
            progress(k + 1, p.size)
    return ModuleResponse(
        pressure_pa=p,
        axis_m=axis,
        influence_m3_n=np.array(rows),
        volume_m3=np.array(volumes),
        compliance_m3_pa=np.array(compliances),
        reference_influence_m3_n=np.array(refs),
        reference_patch_m=np.array([REFERENCE_PATCH.size_x_m, REFERENCE_PATCH.size_y_m]),
        meta=_response_meta(model),
    )


def _response_pressures(pressures_pa: Sequence[float]) -> np.ndarray:
    """The pressures as an array, Pa; InputError unless finite, increasing, > 0 and at most
    the thesis's maximum."""
    p = np.array([check_finite("pressure", v) for v in pressures_pa], dtype=float)
    if p.size < 1 or (p.size > 1 and not (np.diff(p) > 0).all()) or p[0] <= 0:
        raise InputError(f"response pressures must be increasing and > 0 Pa, got {list(p)}")
    if p[-1] > thesis.MAX_PRESSURE_PA:
        raise InputError(
            f"response pressure {p[-1] / 1e3:g} kPa exceeds {thesis.MAX_PRESSURE_PA / 1e3:g} kPa"
        )
    return p


def _response_meta(model: ModuleModel) -> dict[str, Any]:
    """What the response was computed from and what its table means."""
    return {
        "model": model.material.name,
        "width_m": model.geometry.width_m,
        "thickness_m": model.geometry.thickness_m,
        "mesh": _mesh_text(model.mesh_options),
        "seam_width_m": max(thesis.MODULE_PITCH_M - model.geometry.width_m, 0.0),
        "source": "softpad fem response (FElupe; reciprocity: s = dw/dp of the top face)",
        "version": RESPONSE_VERSION,
        "definition": "influence_m3_n[p, i, j] = -dV/dF of a vertical point force at "
        "(axis_m[i], axis_m[j]) from the module centre, unloaded layer at pressure_pa[p]",
    }


def _mesh_text(mesh: MeshOptions) -> str:
    n, nz = mesh.cells_in_plane, mesh.cells_through_thickness
    return f"{mesh.element} {n} x {n} x {nz} quarter cells, grading {mesh.grading:g}"


def response_convergence(
    setup: ModuleSetup | None = None,
    pressure_pa: float = thesis.P0_PA,
    reference_mesh: MeshOptions | None = None,
) -> dict[str, Any]:
    """Mean responses of :data:`CONVERGENCE_PROBES` on the mesh of ``setup`` and on a finer
    mesh (``reference_mesh``, default: twice as fine).

    Returns
    -------
    dict
        ``pressure_pa``, ``mesh``, ``reference_mesh``, per probe ``{"s_mm3_n": [mesh,
        reference], "difference": relative}``, and ``largest_difference``.
    """
    from softpad.fem._geometry import DEFAULT_MESH

    setup = setup or ModuleSetup()
    mesh = setup.mesh or DEFAULT_MESH
    reference_mesh = reference_mesh or mesh.refined(2)
    coarse = module_response(replace(setup, mesh=mesh), [pressure_pa])
    fine = module_response(replace(setup, mesh=reference_mesh), [pressure_pa])
    probes: dict[str, Any] = {}
    for name, (centre, size) in CONVERGENCE_PROBES.items():
        a = coarse.mean_influence(centre, size, pressure_pa)
        b = fine.mean_influence(centre, size, pressure_pa)
        probes[name] = {"s_mm3_n": [a * 1e9, b * 1e9], "difference": (a - b) / b}
    return {
        "pressure_pa": pressure_pa,
        "mesh": _mesh_text(mesh),
        "reference_mesh": _mesh_text(reference_mesh),
        "probes": probes,
        "largest_difference": max(abs(v["difference"]) for v in probes.values()),
    }
