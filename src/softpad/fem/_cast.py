"""The pad as it was cast: one continuous upper layer over every chamber (seed, Section 6.1.1).

The seed's mould: a cured base layer; an ABS grid on it that divides it into squares; a
45 x 45 mm acetate sheet in each square (the chamber: silicone does not bond to acetate); a
second 1.5 mm layer of EcoFlex 00-30 cast over all of it. The upper layer is therefore one
sheet over the whole pad, bonded to the grid's walls between the acetate sheets and to the
mould's border, not a set of modules whose lateral faces are clamped (:class:`ModuleModel`,
the thesis's Section 7.2 model).

:class:`CastPadModel` meshes that sheet over ``rows x cols`` chambers with FElupe (hex8,
mean-dilatation u/p/J as :class:`ModuleModel`): the lower face is bonded (fixed) on the grid's
walls, a strip of width ``wall_width_m`` centred on every line between chambers and half of it
along the border; the outer lateral faces are fixed (the mould's frame); each chamber's
acetate square carries its own follower pressure. Optionally the walls stand on an elastic
foundation (the soft base layer under the grid's feet), a Winkler stiffness per area of the
wall's top, instead of being rigid.

At an inflated state (every chamber at ``p``), one factorisation of the tangent and one solve
per chamber give ``s_k(x) = dw(x)/dp_k``, the rise of every top-face point per unit pressure of
chamber ``k``; by reciprocity a small downward force ``dF`` at ``x`` changes chamber ``k``'s
volume by ``-s_k(x) dF``, every chamber at once (:func:`cast_pad_response`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from softpad import thesis
from softpad.errors import InputError, check_finite
from softpad.fem._cast_table import CAST_RESPONSE_VERSION, CastPadResponse
from softpad.fem._geometry import MeshOptions, ModuleGeometry
from softpad.fem._materials import MaterialModel
from softpad.fem._model import ModuleModel, ProgressCallback, SolverOptions

#: Width of the grid's walls between acetate sheets, m. The seed gives 45 x 45 mm acetate
#: sheets and 45 mm modules, not the wall: 1 mm is the thinnest wall a printer lays reliably
#: (two perimeters of a 0.4-0.5 mm nozzle); the range of
#: :data:`softpad.sim.UNCERTAIN_PARAMETERS`' ``seam_width_m`` (0-3 mm) spans the rest.
DEFAULT_WALL_WIDTH_M = 1.0e-3
#: Default mesh of the cast pad: ``cells_in_plane`` cells from a chamber's centre to its wall
#: (graded toward it), two through the layer (see :func:`cast_convergence`).
DEFAULT_CAST_MESH = MeshOptions(cells_in_plane=8, cells_through_thickness=2)


@dataclass(frozen=True)
class CastPadGeometry:
    """The cast pad: chambers on a grid under one continuous upper layer.

    Parameters
    ----------
    rows, cols
        Chambers of the grid (prototype 2 x 3, seed Fig. 6.4a).
    chamber_side_m
        Side of each acetate sheet, m (seed Section 6.1.1: 45 mm).
    wall_width_m
        Width of the grid's walls between sheets, m (the border strip is half of it).
    thickness_m
        Upper layer above the acetate, m (seed: 1.5 mm).
    foundation_pa_per_m
        Winkler stiffness under the walls, Pa/m (vertical pressure per unit sinking of the
        wall's top); ``inf`` (default): rigid walls.
    """

    rows: int = thesis.PROTOTYPE_ROWS
    cols: int = thesis.PROTOTYPE_COLS
    chamber_side_m: float = thesis.CHAMBER_SIDE_M
    wall_width_m: float = DEFAULT_WALL_WIDTH_M
    thickness_m: float = thesis.LAYER_THICKNESS_M
    foundation_pa_per_m: float = float("inf")

    def __post_init__(self) -> None:
        for name in ("rows", "cols"):
            v = getattr(self, name)
            if int(v) != v or not 1 <= v <= 8:
                raise InputError(f"cast pad {name} must be an integer in 1..8, got {v!r}")
        ModuleGeometry(self.chamber_side_m, self.thickness_m)  # checks the sizes
        w = check_finite("wall_width_m", self.wall_width_m)
        if not 0.0 < w <= 0.5 * self.chamber_side_m:
            raise InputError(
                f"wall width must be within (0, {self.chamber_side_m * 500:g}] mm, got "
                f"{w * 1e3:g} mm"
            )
        k = float(self.foundation_pa_per_m)
        if not k > 0 or np.isnan(k):
            raise InputError(f"wall foundation stiffness must be > 0 Pa/m, got {k!r}")

    @property
    def pitch_m(self) -> float:
        """Centre-to-centre distance of neighbouring chambers, m."""
        return self.chamber_side_m + self.wall_width_m

    @property
    def size_m(self) -> tuple[float, float]:
        """Pad extent (x along the columns, y along the rows), m."""
        return self.cols * self.pitch_m, self.rows * self.pitch_m

    @property
    def n_chambers(self) -> int:
        """Number of chambers."""
        return self.rows * self.cols

    def chamber_centers_m(self) -> np.ndarray:
        """Centre of every chamber in the pad frame (thesis numbering), (n, 2), m."""
        k = np.arange(self.n_chambers)
        row, col = k // self.cols, k % self.cols
        return np.column_stack(
            [(col + 0.5) * self.pitch_m, (self.rows - 1 - row + 0.5) * self.pitch_m]
        )


def grid_axis(n_chambers: int, pitch_m: float, wall_m: float, mesh: MeshOptions) -> np.ndarray:
    """Node coordinates along one side of the pad, m: one cell on each half wall, and each
    chamber ``2 * cells_in_plane`` cells graded toward its walls as :class:`MeshOptions`."""
    half = 0.5 * (pitch_m - wall_m)
    xi = mesh.map_coordinate(np.linspace(0.0, 1.0, mesh.cells_in_plane + 1))
    nodes = [0.0, n_chambers * pitch_m]
    for m in range(n_chambers):
        c = (m + 0.5) * pitch_m
        nodes += list(c - half * xi) + list(c + half * xi)
        nodes.append(m * pitch_m)
    return np.unique(np.round(np.array(nodes), 12))


class CastPadModel(ModuleModel):
    """The cast pad's continuous upper layer over ``rows x cols`` chambers (no symmetry).

    Parameters
    ----------
    material
        A :class:`~softpad.fem.MaterialModel` or a preset name.
    pad
        The cast pad (default: the prototype, 2 x 3 chambers of 45 mm under 1.5 mm).
    mesh
        Discretisation: ``cells_in_plane`` cells from a chamber's centre to its wall, graded
        as there; hex8 only.
    solver
        Newton / stepping options (as :class:`ModuleModel`).

    Notes
    -----
    The inherited :meth:`solve` inflates every chamber to one pressure (no load, no base
    contact: at the operating pressures the layer stands millimetres above the acetate).
    """

    def __init__(
        self,
        material: str | MaterialModel = "neo-hookean",
        pad: CastPadGeometry | None = None,
        mesh: MeshOptions | None = None,
        solver: SolverOptions | None = None,
    ) -> None:
        self.pad = pad or CastPadGeometry()
        mesh = mesh or MeshOptions(cells_in_plane=6, cells_through_thickness=1)
        if mesh.element != "hex8":
            raise InputError("the cast pad model supports hex8 meshes only")
        foundation = self.pad.foundation_pa_per_m
        solver = solver or SolverOptions()
        if np.isfinite(foundation):
            from dataclasses import replace

            solver = replace(solver, contact_stiffness_pa_per_m=foundation)
        super().__init__(
            material,
            ModuleGeometry(self.pad.chamber_side_m, self.pad.thickness_m),
            mesh,
            contact=bool(np.isfinite(foundation)),
            solver=solver,
        )

    # ------------------------------------------------------------------ set-up
    def _build_mesh(self) -> bool:
        fem = self._fem
        pad, t = self.pad, self.pad.thickness_m
        ax_x = grid_axis(pad.cols, pad.pitch_m, pad.wall_width_m, self.mesh_options)
        ax_y = grid_axis(pad.rows, pad.pitch_m, pad.wall_width_m, self.mesh_options)
        nz = self.mesh_options.cells_through_thickness
        mesh_ = fem.Grid(ax_x, ax_y, np.linspace(0.0, t, nz + 1))
        self.mesh = mesh_
        self._axes = (ax_x, ax_y)
        pts = mesh_.points
        tol = 1e-9 * pad.pitch_m
        bottom = np.abs(pts[:, 2]) < tol
        self._chamber_of = self._chamber_index(pts[:, :2], closed=True)
        self._chamber_regions = [
            fem.RegionHexahedronBoundary(mesh_, mask=bottom & (self._chamber_of == k))
            for k in range(pad.n_chambers)
        ]
        self._bottom_region = fem.RegionHexahedronBoundary(
            mesh_, mask=bottom & (self._chamber_of >= 0)
        )
        self._top_region = fem.RegionHexahedronBoundary(mesh_, mask=np.abs(pts[:, 2] - t) < tol)
        self._region = fem.RegionHexahedron(mesh_)
        return False

    def _chamber_index(self, xy: np.ndarray, closed: bool) -> np.ndarray:
        """0-based chamber over each pad-frame point (closed or open squares), -1 elsewhere."""
        pad = self.pad
        half = 0.5 * pad.chamber_side_m + (1e-9 if closed else -1e-9) * pad.pitch_m
        centres = pad.chamber_centers_m()
        d = np.abs(xy[:, None, :] - centres[None, :, :]).max(axis=2)
        inside = d <= half
        return np.where(inside.any(axis=1), inside.argmax(axis=1), -1)

    def _build_fields(self, quadratic: bool) -> None:
        super()._build_fields(quadratic)
        fem = self._fem
        self._chamber_fields = []
        self._chamber_pressures = []
        for region in self._chamber_regions:
            f = fem.FieldContainer([fem.Field(region, dim=3)])
            f.link(self.field)
            self._chamber_fields.append(f)
            self._chamber_pressures.append(fem.SolidBodyPressure(f))

    def _build_boundaries(self) -> None:
        fem = self._fem
        pad = self.pad
        pts = self.mesh.points
        tol = 1e-9 * pad.pitch_m
        lx, ly = pad.size_m
        bottom = np.abs(pts[:, 2]) < tol
        wall = bottom & (self._chamber_index(pts[:, :2], closed=False) < 0)
        u = self.field[0]
        boundaries = {
            "frame-x0": fem.Boundary(u, fx=0.0),
            "frame-x1": fem.Boundary(u, fx=lx),
            "frame-y0": fem.Boundary(u, fy=0.0),
            "frame-y1": fem.Boundary(u, fy=ly),
        }
        rigid = not np.isfinite(pad.foundation_pa_per_m)
        boundaries["walls"] = fem.Boundary(u, mask=wall, skip=(0, 0, 0) if rigid else (0, 0, 1))
        self._dof0, self._dof1 = fem.dof.partition(self.field, boundaries)
        self._ndisp = pts.size
        top = np.abs(pts[:, 2] - pad.thickness_m) < tol
        centre = pad.chamber_centers_m()[0]
        d = np.linalg.norm(pts[:, :2] - centre, axis=1) + np.where(top, 0.0, np.inf)
        self._centre_top = int(np.argmin(d))
        # the foundation's springs: wall-bottom points (the inherited contact terms, always on)
        self._contact_points = np.flatnonzero(wall)
        wall_region = fem.RegionHexahedronBoundary(self.mesh, mask=wall)
        self._contact_area = self._lumped_area(wall_region)[self._contact_points]
        self._load_unit = np.zeros(self._ndisp)

    def _contact_terms(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The walls' foundation: a bonded two-sided spring (active in tension too)."""
        k = self.solver.contact_stiffness_pa_per_m * self._contact_area
        return 3 * self._contact_points + 2, k, np.ones(k.shape, dtype=bool)

    # ------------------------------------------------------------------ outputs
    def chamber_volumes_m3(self) -> np.ndarray:
        """Air under the layer in each chamber (above the acetate plane), m^3."""
        fem = self._fem
        out = []
        for region, field in zip(self._chamber_regions, self._chamber_fields, strict=True):
            field.link(self.field)
            F = np.asarray(field[0].extract())
            cof = np.asarray(fem.math.cof(F))
            da_z = np.einsum("jqc,jqc->qc", cof[2], np.asarray(region.normals))
            z = self._quadrature_points(region)[2] + np.asarray(field[0].interpolate())[2]
            out.append(float(-np.sum(z * da_z * np.asarray(region.dV))))
        return np.array(out)

    def volume_m3(self) -> float:
        """Air under the layer, all chambers, m^3."""
        return float(self.chamber_volumes_m3().sum())

    def chamber_sensitivity(self) -> tuple[np.ndarray, np.ndarray]:
        """``du/dp_k`` of every point for each chamber's pressure, and ``dV_k/dp_l``.

        One factorisation of the tangent at the current state (every chamber at
        :attr:`pressure_pa`), one solve per chamber with its unit follower-pressure load.

        Returns
        -------
        dudp : ndarray, shape (n_chambers, npoints, 3)
            m/Pa.
        compliance : ndarray, shape (n_chambers, n_chambers)
            ``C[k, l] = dV_k/dp_l``, m^3/Pa (symmetric by reciprocity).
        """
        from scipy.sparse.linalg import splu

        _, K = self._system(self.pressure_pa, self.load_n)
        dof1 = self._dof1
        lu = splu(K[dof1][:, dof1].tocsc())
        loads = []
        for field, pres in zip(self._chamber_fields, self._chamber_pressures, strict=True):
            field.link(self.field)
            pres.update(1.0)
            g = np.zeros(K.shape[0])
            g[: self._ndisp] = np.asarray(pres.assemble.vector(field).toarray()).ravel()
            loads.append(g)
        self._residual(self.pressure_pa, self.load_n)  # restore every body's state
        g_all = np.array(loads)
        du = np.zeros_like(g_all)
        du[:, dof1] = lu.solve(g_all[:, dof1].T).T
        compliance = g_all[:, dof1] @ du[:, dof1].T
        dudp = du[:, : self._ndisp].reshape(len(loads), -1, 3)
        return dudp, compliance

    def top_grid(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Top-face nodal ``values`` (npoints,) as an (Nx, Ny) array on the node axes, m."""
        pts = self.mesh.points
        top = np.flatnonzero(np.abs(pts[:, 2] - self.pad.thickness_m) < 1e-9 * self.pad.pitch_m)
        ax_x, ax_y = self._axes
        i = np.searchsorted(ax_x, np.round(pts[top, 0], 12) - 1e-13)
        j = np.searchsorted(ax_y, np.round(pts[top, 1], 12) - 1e-13)
        grid = np.full((ax_x.size, ax_y.size), np.nan)
        grid[i, j] = values[top]
        return ax_x, ax_y, grid

    def describe(self) -> dict[str, Any]:
        """What the model is (for the response file's provenance)."""
        pad, m = self.pad, self.mesh_options
        return {
            "model": self.material.name,
            "rows": pad.rows,
            "cols": pad.cols,
            "chamber_side_m": pad.chamber_side_m,
            "wall_width_m": pad.wall_width_m,
            "thickness_m": pad.thickness_m,
            "foundation_pa_per_m": pad.foundation_pa_per_m
            if np.isfinite(pad.foundation_pa_per_m)
            else "rigid",
            "mesh": f"hex8, {m.cells_in_plane} cells centre-to-wall x {m.cells_through_thickness}"
            f" through, grading {m.grading:g}, one cell per half wall",
            "source": "softpad fem cast-response (FElupe; reciprocity: s_k = dw/dp_k of the top "
            "face)",
            "version": CAST_RESPONSE_VERSION,
            "definition": "influence_m3_n[p, k, i, j] = -dV_k/dF of a vertical point force at "
            "(x_axis_m[i], y_axis_m[j]) of the pad frame, every chamber at pressure_pa[p]",
        }


def cast_pad_response(
    material: str | MaterialModel = "neo-hookean",
    pad: CastPadGeometry | None = None,
    mesh: MeshOptions | None = None,
    pressures_pa: Sequence[float] | None = None,
    progress: ProgressCallback | None = None,
) -> CastPadResponse:
    """Tabulate every chamber's response to vertical loads anywhere on the cast pad.

    For each pressure (every chamber alike) the inflated layer is solved, then one
    factorisation and one solve per chamber give ``s_k = dw/dp_k`` on every top-face node
    (:meth:`CastPadModel.chamber_sensitivity`), the chambers' volumes and compliance matrix.

    Parameters
    ----------
    material
        Preset name or :class:`~softpad.fem.MaterialModel` (default: the thesis's neo-Hookean).
    pad
        The cast pad (default: the prototype).
    mesh
        Discretisation (default :data:`DEFAULT_CAST_MESH`).
    pressures_pa
        Increasing pressures, Pa (default: those of the module response, 0.5..2.8 kPa).
    progress
        Called ``progress(done, total)`` after each pressure.

    Returns
    -------
    CastPadResponse
    """
    from softpad.fem._response import DEFAULT_RESPONSE_PRESSURES_PA, _response_pressures

    p = _response_pressures(DEFAULT_RESPONSE_PRESSURES_PA if pressures_pa is None else pressures_pa)
    model = CastPadModel(material, pad, mesh or DEFAULT_CAST_MESH)
    rows, volumes, compliances = [], [], []
    for k, pk in enumerate(p):
        model.solve(float(pk), 0.0)
        dudp, compliance = model.chamber_sensitivity()
        rows.append([model.top_grid(d[:, 2])[2] for d in dudp])
        volumes.append(model.chamber_volumes_m3())
        compliances.append(compliance)
        if progress is not None:
            progress(k + 1, p.size)
    ax, ay = model._axes
    return CastPadResponse(
        pressure_pa=p,
        x_axis_m=ax,
        y_axis_m=ay,
        influence_m3_n=np.array(rows),
        volume_m3=np.array(volumes),
        compliance_m3_pa=np.array(compliances),
        centers_m=model.pad.chamber_centers_m(),
        meta=model.describe(),
    )


def sealed_rises_pa(
    table: CastPadResponse,
    points_m: np.ndarray,
    forces_n: np.ndarray | float,
    pressure_pa: float,
    dead_volume_m3: float = thesis.TUBING_VOLUME_M3 + thesis.CHAMBER_GAP_VOLUME_M3,
    atmosphere_pa: float = 101_325.0,
) -> np.ndarray:
    """Small-load pressure rise of every sealed chamber for point forces on the pad, Pa.

    ``(C + diag(G)) dp = S f`` with ``S[k, i] = s_k(x_i)``, ``C`` the compliance matrix and
    ``G_k = (V_k + V_dead) / (p_atm + p)`` each chamber's gas (the chambers are coupled
    through the shared layer as well as by the loads).

    Parameters
    ----------
    table
        The cast pad's response.
    points_m
        Load points in the model's pad frame, (n, 2), m.
    forces_n
        Downward force at each point (or one for all), N.
    pressure_pa
        Every chamber's pressure when the valves closed, Pa.
    dead_volume_m3
        Tubing and gap per chamber, m^3.
    atmosphere_pa
        Ambient pressure, Pa.
    """
    s = table.influence(points_m, pressure_pa)
    f = np.broadcast_to(np.asarray(forces_n, dtype=float), (s.shape[0],))
    gas = (table.volumes(pressure_pa) + dead_volume_m3) / (atmosphere_pa + pressure_pa)
    return np.asarray(np.linalg.solve(table.compliance(pressure_pa) + np.diag(gas), s.T @ f))


#: Probes of the cast pad (name -> centre in units of the pitch from the pad's bottom-left
#: corner, footprint in metres), the modules they are read on (0-based) and what they show.
CAST_PROBES: dict[str, tuple[tuple[float, float], tuple[float, float], tuple[int, ...]]] = {
    "Duplo face 42x31 mm, module 1's centre": ((0.5, 1.5), (0.042, 0.031), (0,)),
    "10x10 mm weight, module 1's centre": ((0.5, 1.5), (0.010, 0.010), (0,)),
    "can strip, one pitch x 25 mm, on the line 1|4": ((0.5, 1.0), (-1.0, 0.025), (0, 3)),
    "10x10 mm on the line 1|2": ((1.0, 1.5), (0.010, 0.010), (0, 1)),
    "10x10 mm at the corner 1|2|4|5": ((1.0, 1.0), (0.010, 0.010), (0, 1, 3, 4)),
}


def cast_sensitivities(
    table: CastPadResponse,
    pressure_pa: float = thesis.P0_PA,
    threshold_pa: float = thesis.OBJECT_THRESHOLD_PA,
) -> dict[str, Any]:
    """The cast pad's small-load sealed rises of :data:`CAST_PROBES`, Pa/N, in the model's
    own frame (its pitch), and the minimum detectable masses at ``threshold_pa``.

    A footprint side of -1 means one pitch. Returns ``{"pressure_pa", "pitch_m", "probes":
    {name: {"rise_pa_n": [every module], "read_on": [modules], "min_rise_pa_n"}},
    "min_detectable_mass_g": {footprint: g}}``.
    """
    if table.shape != (2, 3):
        raise InputError(f"the probes are laid out for the 2 x 3 pad, not {table.shape}")
    from softpad.fem._response_table import rect_points

    pitch = table.pitch_m
    probes: dict[str, Any] = {}
    for name, (at, size, read_on) in CAST_PROBES.items():
        side = tuple(pitch if v < 0 else v for v in size)
        pts = rect_points(np.array(at) * pitch, side)
        rise = sealed_rises_pa(table, pts, 1.0 / len(pts), pressure_pa)
        probes[name] = {
            "rise_pa_n": [float(v) for v in rise],
            "read_on": [k + 1 for k in read_on],
            "min_rise_pa_n": float(min(rise[k] for k in read_on)),
        }
    g = 9.80665
    masses = {
        name.split(",")[0]: threshold_pa / (g * v["min_rise_pa_n"]) * 1e3
        for name, v in probes.items()
        if "centre" in name
    }
    return {
        "pressure_pa": float(pressure_pa),
        "pitch_m": pitch,
        "probes": probes,
        "min_detectable_mass_g": masses,
    }


def cast_convergence(
    coarse: MeshOptions,
    fine: MeshOptions,
    pressure_pa: float = thesis.P0_PA,
    pad: CastPadGeometry | None = None,
) -> dict[str, Any]:
    """The probes' rises (:func:`cast_sensitivities`) on a coarse and a fine mesh.

    Returns
    -------
    dict
        ``{"coarse", "fine": mesh text, "probes": {name: {"rise_pa_n": [coarse, fine],
        "difference": relative}}, "largest_difference"}`` (each probe's least-loaded module
        it is read on).
    """
    out: dict[str, Any] = {"pressure_pa": pressure_pa, "probes": {}}
    rises = []
    for key, mesh in (("coarse", coarse), ("fine", fine)):
        table = cast_pad_response(pad=pad, mesh=mesh, pressures_pa=[pressure_pa])
        out[key] = table.meta["mesh"]
        rises.append(cast_sensitivities(table, pressure_pa)["probes"])
    for name in CAST_PROBES:
        a, b = rises[0][name]["min_rise_pa_n"], rises[1][name]["min_rise_pa_n"]
        out["probes"][name] = {"rise_pa_n": [a, b], "difference": (a - b) / b}
    out["largest_difference"] = max(abs(v["difference"]) for v in out["probes"].values())
    return out
