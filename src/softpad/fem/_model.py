"""Finite-element model of one SoftPad module on FElupe (thesis Sections 6.1.2 and 7.2).

The upper silicone layer is a ``W x W x t`` block whose lateral faces are fixed; the air
pressure ``p`` acts as a follower load on its lower face. Both symmetry planes are used, so
only the quarter ``0 <= x, y <= W/2`` is meshed. Optional extras: a vertical dead load spread
uniformly over a centred patch of the top face, and frictionless penalty contact of the lower
face against the rigid base plane ``z = 0`` (the thesis's stiffening when the layer touches
the lower layer, Section 6.1.2).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NoReturn

import numpy as np

from softpad.errors import InputError, SoftPadError, check_finite
from softpad.fem._geometry import DEFAULT_MESH, LoadPatch, MeshOptions, ModuleGeometry
from softpad.fem._materials import MaterialModel, get_material

#: Callback ``progress(done, total)`` used by long studies (e.g. to drive a tqdm bar).
ProgressCallback = Callable[[int, int], None]


class ConvergenceError(SoftPadError, RuntimeError):
    """The Newton iterations did not converge even with the smallest load increment."""


@dataclass(frozen=True)
class SolverOptions:
    """Newton-Raphson and load-stepping settings.

    Parameters
    ----------
    initial_step_pa
        First pressure increment from the flat layer, Pa. The flat plate is far softer than
        the inflated membrane, so the first steps must be small.
    max_step_pa
        Largest pressure increment, Pa.
    initial_step_n
        First load increment, N.
    max_step_n
        Largest load increment, N.
    relative_tolerance
        Convergence when the residual norm of the free degrees of freedom is below this
        times the applied force scale (p A + F).
    max_iterations
        Newton iterations per increment before the increment is halved.
    min_fraction
        Smallest increment as a fraction of the first one before giving up.
    contact_stiffness_pa_per_m
        Penalty of the base contact, Pa/m (contact pressure per unit penetration);
        1e11 Pa/m keeps the penetration under 0.1 um at 10 kPa.
    """

    initial_step_pa: float = 40.0
    max_step_pa: float = 600.0
    initial_step_n: float = 0.05
    max_step_n: float = 0.5
    relative_tolerance: float = 1.0e-7
    max_iterations: int = 14
    min_fraction: float = 1.0 / 256.0
    contact_stiffness_pa_per_m: float = 1.0e11


@dataclass(frozen=True)
class ModuleState:
    """Scalar outputs of one converged equilibrium.

    Attributes
    ----------
    pressure_pa
        Air pressure (gauge), Pa.
    load_n
        Total vertical load on the top patch, N.
    height_m
        Vertical displacement of the top-face centre from its flat rest position, m.
    volume_m3
        Air volume between the base and the deformed layer (whole module), m^3.
    contact_area_m2
        Area of the lower face touching the base (whole module), m^2.
    iterations
        Newton iterations spent on the last increment.
    """

    pressure_pa: float
    load_n: float
    height_m: float
    volume_m3: float
    contact_area_m2: float
    iterations: int


class ModuleModel:
    """Quarter model of one module's upper layer under pressure, load and base contact.

    Parameters
    ----------
    material
        A :class:`~softpad.fem.MaterialModel` or a preset name (``neo-hookean``, ...).
    geometry
        Width and thickness of the layer (default: 45 x 1.5 mm).
    mesh
        Discretisation (default :data:`DEFAULT_MESH`).
    load_patch
        Region of the top face that carries the load (default: centred 30 mm square).
    contact
        Whether the lower face contacts the rigid base plane ``z = 0``.
    solver
        Newton / stepping options.

    Notes
    -----
    Energy (thesis Section 7.1.1): ``W = W_iso(C_bar) + kappa/2 (J - 1)^2``, the volumetric
    part enforced through the u/p/J formulation of the chosen element (see
    :class:`MeshOptions`). The pressure is a follower load on the deformed lower face
    (FElupe ``SolidBodyPressure``); the load is a dead load (fixed direction, per reference
    area). The model keeps its current state; :meth:`solve` marches from it to a new
    ``(pressure, load)`` pair with adaptive increments.

    Examples
    --------
    >>> model = ModuleModel("neo-hookean")          # doctest: +SKIP
    >>> model.solve(1100.0).height_m * 1e3          # doctest: +SKIP
    8.3...
    """

    def __init__(
        self,
        material: str | MaterialModel = "neo-hookean",
        geometry: ModuleGeometry | None = None,
        mesh: MeshOptions | None = None,
        load_patch: LoadPatch | None = None,
        contact: bool = True,
        solver: SolverOptions | None = None,
    ) -> None:
        import felupe as fem

        self.material = get_material(material)
        self.geometry = geometry or ModuleGeometry()
        self.mesh_options = mesh or DEFAULT_MESH
        self.load_patch = load_patch or LoadPatch.square(0.030)
        self.contact = bool(contact)
        self.solver = solver or SolverOptions()

        self._fem = fem
        quadratic = self._build_mesh()
        self._build_fields(quadratic)
        self._build_boundaries()

        self.pressure_pa = 0.0
        self.load_n = 0.0
        self._last_iterations = 0
        self._previous: tuple[float, float, list[np.ndarray]] | None = None

    def _build_mesh(self) -> bool:
        """Mesh one quarter of the layer (symmetry) and its lower and upper faces; True for
        quadratic (hex27) elements."""
        fem = self._fem
        a, t = self.geometry.half_width_m, self.geometry.thickness_m
        n, nz = self.mesh_options.cells_in_plane, self.mesh_options.cells_through_thickness
        mesh_ = fem.Cube(a=(0.0, 0.0, 0.0), b=(1.0, 1.0, t), n=(n + 1, n + 1, nz + 1))
        mesh_.points[:, :2] = a * self.mesh_options.map_coordinate(mesh_.points[:, :2])
        quadratic = self.mesh_options.element == "hex27"
        if quadratic:
            mesh_ = mesh_.add_midpoints_edges().add_midpoints_faces().add_midpoints_volumes()
            region = fem.RegionTriQuadraticHexahedron(mesh_)
            boundary_region: Any = fem.RegionTriQuadraticHexahedronBoundary
        else:
            region = fem.RegionHexahedron(mesh_)
            boundary_region = fem.RegionHexahedronBoundary
        self.mesh = mesh_
        points = mesh_.points
        tol = 1e-9 * a
        bottom = np.abs(points[:, 2]) < tol
        top = np.abs(points[:, 2] - t) < tol
        self._bottom_region = boundary_region(mesh_, mask=bottom)
        self._top_region = boundary_region(mesh_, mask=top)
        self._region = region
        return quadratic

    def _build_fields(self, quadratic: bool) -> None:
        """The displacement field(s), the nearly incompressible solid and the chamber pressure."""
        fem = self._fem
        region = self._region
        umat = self.material.felupe_material()
        bulk = self.material.bulk_modulus_pa
        if quadratic:
            self.field = fem.FieldsMixed(region, n=3)
            self._solid: Any = fem.SolidBody(fem.NearlyIncompressible(umat, bulk=bulk), self.field)
        else:
            self.field = fem.FieldContainer([fem.Field(region, dim=3)])
            self._solid = fem.SolidBodyNearlyIncompressible(umat, self.field, bulk=bulk)
        self._bottom_field = fem.FieldContainer([fem.Field(self._bottom_region, dim=3)])
        self._bottom_field.link(self.field)
        self._pressure = fem.SolidBodyPressure(self._bottom_field)

    def _build_boundaries(self) -> None:
        """Symmetry and clamping, the centre point, the contact candidates and the patch load."""
        fem = self._fem
        a, t = self.geometry.half_width_m, self.geometry.thickness_m
        points = self.mesh.points
        tol = 1e-9 * a
        bottom = np.abs(points[:, 2]) < tol
        top = np.abs(points[:, 2] - t) < tol
        u = self.field[0]
        boundaries = {
            "symmetry-x": fem.Boundary(u, fx=0.0, skip=(0, 1, 1)),
            "symmetry-y": fem.Boundary(u, fy=0.0, skip=(1, 0, 1)),
            "clamped-x": fem.Boundary(u, fx=a),
            "clamped-y": fem.Boundary(u, fy=a),
        }
        self._dof0, self._dof1 = fem.dof.partition(self.field, boundaries)
        self._ndisp = points.size

        centre = np.flatnonzero((np.abs(points[:, 0]) < tol) & (np.abs(points[:, 1]) < tol) & top)
        self._centre_top = int(centre[0])
        # contact candidates: lower-face points that are not clamped
        clamped = (np.abs(points[:, 0] - a) < tol) | (np.abs(points[:, 1] - a) < tol)
        self._contact_points = np.flatnonzero(bottom & ~clamped)
        self._contact_area = self._lumped_area(self._bottom_region)[self._contact_points]
        self._load_unit = self._patch_load_vector(self.load_patch)

    # ------------------------------------------------------------------ set-up helpers
    def _lumped_area(self, region: Any) -> np.ndarray:
        """Reference area ``int N_a dA`` attributed to each mesh point, m^2."""
        h = np.asarray(region.h)  # (points per cell, quadrature points[, cells])
        da = np.asarray(region.dV)  # (quadrature points, cells)
        cells = region.mesh.cells
        if h.ndim == 2:
            h = h[:, :, None]
        values = np.einsum("aqc,qc->ca", h * np.ones_like(da)[None], da)
        area = np.zeros(self.mesh.npoints)
        np.add.at(area, cells, values)
        return area

    def _quadrature_points(self, region: Any) -> np.ndarray:
        """Reference coordinates of the quadrature points of a boundary region (3, q, c)."""
        fem = self._fem
        coords = fem.Field(region, dim=3, values=self.mesh.points.copy())
        return np.asarray(coords.interpolate())

    def _patch_load_vector(self, patch: LoadPatch) -> np.ndarray:
        """Nodal forces of a unit total downward load on ``patch`` (quarter share), N."""
        region = self._top_region
        xq = self._quadrature_points(region)
        inside = patch.contains(xq[0], xq[1]).astype(float)
        h = np.asarray(region.h)
        da = np.asarray(region.dV)
        if h.ndim == 2:
            h = h[:, :, None]
        values = np.einsum("aqc,qc->ca", h * np.ones_like(da)[None], da * inside)
        nodal = np.zeros(self.mesh.npoints)
        np.add.at(nodal, region.mesh.cells, values)
        total = nodal.sum()
        if total <= 0:
            raise InputError(
                f"load patch ({patch.describe()}) misses every quadrature point of the top face; "
                "refine the mesh or enlarge the patch"
            )
        vector = np.zeros(self._ndisp)
        # quarter model carries a quarter of the total force, downward (-z)
        vector[2::3] = -0.25 * nodal / total
        return vector

    # ------------------------------------------------------------------ state access
    @property
    def displacement(self) -> np.ndarray:
        """Point displacements of the quarter mesh, m, shape (npoints, 3)."""
        return np.asarray(self.field[0].values)

    @property
    def centre_top_point(self) -> int:
        """Index of the mesh point at the centre of the top face."""
        return self._centre_top

    def top_face_area_weights(self) -> np.ndarray:
        """Reference area (m^2) attributed to each point of the quarter's top face, 0 elsewhere."""
        weights = self._lumped_area(self._top_region)
        top = (
            np.abs(self.mesh.points[:, 2] - self.geometry.thickness_m)
            < 1e-9 * self.geometry.width_m
        )
        return np.where(top, weights, 0.0)

    @property
    def load_patch_weights(self) -> np.ndarray:
        """Share of the quarter's load carried by each point (sums to one), shape (npoints,)."""
        return -self._load_unit[2::3] / 0.25

    @property
    def height_m(self) -> float:
        """Vertical displacement of the top-face centre, m."""
        return float(self.field[0].values[self._centre_top, 2])

    def volume_m3(self) -> float:
        """Air volume between the base (``z = 0``) and the deformed lower face, m^3.

        ``V = -4 int_S z (J F^-T N)_z dA`` over the quarter's lower face (the divergence
        theorem with the field ``(0, 0, z)``; the base contributes nothing at ``z = 0``).
        """
        fem = self._fem
        region = self._bottom_region
        F = np.asarray(self._bottom_field[0].extract())  # (3, 3, q, c)
        cof = np.asarray(fem.math.cof(F))
        normals = np.asarray(region.normals)
        da_z = np.einsum("jqc,jqc->qc", cof[2], normals)  # (cof F)_zj N_j
        z = self._quadrature_points(region)[2] + np.asarray(self._bottom_field[0].interpolate())[2]
        return float(-4.0 * np.sum(z * da_z * np.asarray(region.dV)))

    def contact_area_m2(self) -> float:
        """Reference area of the lower face in contact with the base (whole module), m^2."""
        if not self.contact:
            return 0.0
        uz = self.field[0].values[self._contact_points, 2]
        return float(4.0 * self._contact_area[uz < 0.0].sum())

    def state(self) -> ModuleState:
        """Scalar outputs of the current equilibrium."""
        return ModuleState(
            pressure_pa=self.pressure_pa,
            load_n=self.load_n,
            height_m=self.height_m,
            volume_m3=self.volume_m3(),
            contact_area_m2=self.contact_area_m2(),
            iterations=self._last_iterations,
        )

    def checkpoint(self) -> dict[str, Any]:
        """Copy of the current state (fields, internal pressure/volume, load levels)."""
        return {
            "solid": self._solid.checkpoint(),
            "pressure_pa": self.pressure_pa,
            "load_n": self.load_n,
            "previous": self._previous,
        }

    def restore(self, checkpoint: dict[str, Any]) -> None:
        """Return to a state saved by :meth:`checkpoint`."""
        self._solid.restore(checkpoint["solid"])
        self.pressure_pa = checkpoint["pressure_pa"]
        self.load_n = checkpoint["load_n"]
        self._previous = checkpoint["previous"]

    def _sync_internal_state(self) -> None:
        """After a predictor jump, keep the cell-wise pressure/volume ratio (hex8) as they are.

        FElupe's mean-dilatation body updates its condensed volume ratio linearly from the
        displacement change since its last evaluation; that linearisation is poor for a
        large predictor jump, so the jump is declared as already accounted for.
        """
        state = getattr(getattr(self._solid, "results", None), "state", None)
        if state is not None and hasattr(state, "u"):
            state.u[:] = self.field[0].values

    def _values(self) -> list[np.ndarray]:
        return [f.values.copy() for f in self.field.fields]

    def _set_values(self, values: list[np.ndarray]) -> None:
        for f, v in zip(self.field.fields, values, strict=True):
            f.values[:] = v

    # ------------------------------------------------------------------ assembly
    def _system(
        self, pressure_pa: float, load_n: float, matrix: bool = True
    ) -> tuple[np.ndarray, Any]:
        """Residual vector and (optionally) tangent matrix at the current field."""
        r = self._residual(pressure_pa, load_n)
        return r, (self._tangent() if matrix else None)

    def _contact_terms(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Degrees of freedom, penalty stiffnesses and active flags of the base contact."""
        uz = self.field[0].values[self._contact_points, 2]
        k = self.solver.contact_stiffness_pa_per_m * self._contact_area
        return 3 * self._contact_points + 2, k, uz < 0.0

    def _residual(self, pressure_pa: float, load_n: float) -> np.ndarray:
        """Out-of-balance force vector at the current field (updates the kinematics), N."""
        solid, pres = self._solid, self._pressure
        self._bottom_field.link(self.field)
        pres.update(pressure_pa)
        r = np.asarray(solid.assemble.vector(self.field).toarray()).ravel()
        r[: self._ndisp] -= np.asarray(pres.assemble.vector(self._bottom_field).toarray()).ravel()
        r[: self._ndisp] -= load_n * self._load_unit
        if self.contact and len(self._contact_points):
            dofs, k, active = self._contact_terms()
            uz = self.field[0].values[self._contact_points, 2]
            r[dofs] += np.where(active, k * uz, 0.0)
        return r

    def _tangent(self) -> Any:
        """Tangent matrix at the kinematics of the last :meth:`_residual` call."""
        K = self._solid.assemble.matrix().tocsr()
        Kp = self._pressure.assemble.matrix().tocsr()
        Kp.resize(K.shape)
        K = K - Kp
        if self.contact and len(self._contact_points):
            from scipy.sparse import diags

            dofs, k, active = self._contact_terms()
            diag = np.zeros(K.shape[0])
            diag[dofs] = np.where(active, k, 0.0)
            K = K + diags(diag)
        return K

    def _apply(self, du: np.ndarray, alpha: float) -> None:
        offset = 0
        for f in self.field.fields:
            size = f.values.size
            f.values[:] += alpha * du[offset : offset + size].reshape(f.values.shape)
            offset += size

    def _newton(self, pressure_pa: float, load_n: float) -> int:
        # a diverging trial (later halved) may pass through inverted cells; keep NumPy quiet
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            return self._newton_iterations(pressure_pa, load_n)

    def _newton_iterations(self, pressure_pa: float, load_n: float) -> int:
        """Iterate to equilibrium at fixed loads; return iterations or -1 on failure.

        Newton-Raphson; an increment whose largest displacement exceeds the layer thickness
        is scaled down to it (guards the first iterates from the flat, bending-dominated
        layer, whose linear response overshoots the membrane solution).
        """
        from scipy.sparse.linalg import splu

        dof1 = self._dof1
        scale = abs(pressure_pa) * self.geometry.half_width_m**2 + 0.25 * abs(load_n)
        scale = max(scale, 1e-3 * self.material.shear_modulus_pa * self.geometry.thickness_m**2)
        tol = self.solver.relative_tolerance * scale
        r = self._residual(pressure_pa, load_n)
        rnorm = float(np.linalg.norm(r[dof1]))
        step_norm = np.inf
        for iteration in range(self.solver.max_iterations + 1):
            if not np.isfinite(rnorm):
                return -1
            # converged: small residual, or (at tiny loads, where round-off of the stiff
            # volumetric terms dominates the residual) a negligible Newton correction
            if rnorm <= tol or step_norm <= 1e-10 * self.geometry.thickness_m:
                return iteration
            if iteration == self.solver.max_iterations:
                break
            K = self._tangent()
            du = np.zeros_like(r)
            du[dof1] = splu(K[dof1][:, dof1].tocsc()).solve(-r[dof1])
            if not np.all(np.isfinite(du)):
                return -1
            # limit wild first iterates (flat plate -> membrane): cap the largest
            # displacement increment at the layer thickness
            umax = float(np.abs(du[: self._ndisp]).max())
            step_norm = umax
            cap = self.geometry.thickness_m
            self._apply(du, 1.0 if umax <= cap else cap / umax)
            r = self._residual(pressure_pa, load_n)
            rnorm = float(np.linalg.norm(r[dof1]))
        return -1

    # ------------------------------------------------------------------ solving
    def solve(self, pressure_pa: float, load_n: float | None = None) -> ModuleState:
        """March from the current state to ``(pressure_pa, load_n)`` and return the new state.

        Parameters
        ----------
        pressure_pa
            Target air pressure (gauge), Pa; >= 0.
        load_n
            Target total vertical load on the top patch, N; >= 0. None keeps the current load.

        Raises
        ------
        InputError
            For a negative or non-finite pressure or load.
        ConvergenceError
            When the increments fall below ``min_fraction`` of the first one (e.g. beyond
            a pressure maximum of the inflation curve); the message names the pressure and
            load reached.
        """
        p1, f1 = self._target(pressure_pa, load_n)
        p0, f0 = self.pressure_pa, self.load_n
        dp, df = p1 - p0, f1 - f0
        if dp == 0 and df == 0:
            return self.state()
        # Pure inflation paths are stepped in the cube root of the pressure: the inflated
        # membrane's deflection grows about as p^(1/3), so equal steps in p^(1/3) give
        # similar displacement increments and a good secant predictor.
        cube = df == 0 and dp != 0

        at = _path(p0, p1, f0, f1, cube)
        step, max_step = self._initial_steps(p0, p1, dp, df, cube)
        min_step = step * self.solver.min_fraction
        s = 0.0
        history = self._start_history(p0, p1, f0, cube)
        while s < 1.0 - 1e-12:
            trial = min(1.0, s + step)
            iterations = self._attempt(history, trial, at(trial))
            if iterations < 0:
                step *= 0.5
                history = history[-1:]
                if step < min_step:
                    self._give_up(*at(s), p1, f1)
                continue
            s = trial
            self._last_iterations = iterations
            history.append((s, self._values()))
            history = history[-2:]
            if iterations <= 3:
                step = min(step * 2.0, max_step)
            elif iterations >= 7:
                step *= 0.5
        self._previous = None
        if cube and len(history) >= 2:
            self._previous = (at(history[-2][0])[0], f0, history[-2][1])
        self.pressure_pa, self.load_n = p1, f1
        return self.state()

    def _attempt(
        self,
        history: list[tuple[float, list[np.ndarray]]],
        trial: float,
        target: tuple[float, float],
    ) -> int:
        """Predict the state at path fraction ``trial`` and solve at ``target`` (Pa, N); the
        Newton iterations, or -1 with the state before the attempt restored."""
        start = self._values()
        saved = self._solid.checkpoint() if self.mesh_options.element == "hex8" else None
        self._predict(history, trial)
        p_trial, f_trial = target
        iterations = self._newton(p_trial, f_trial)
        if iterations < 0:
            if saved is not None:
                self._solid.restore(saved)
            else:
                self._set_values(start)
        return iterations

    def _target(self, pressure_pa: float, load_n: float | None) -> tuple[float, float]:
        """Checked target pressure (Pa) and load (N) of :meth:`solve`."""
        p1 = check_finite("pressure_pa", pressure_pa)
        f1 = self.load_n if load_n is None else check_finite("load_n", load_n)
        if p1 < 0:
            raise InputError(f"pressure must be >= 0 Pa, got {p1!r} Pa")
        if f1 < 0:
            raise InputError(f"load must be >= 0 N, got {f1!r} N")
        return p1, f1

    def _give_up(self, p_reached: float, f_reached: float, p1: float, f1: float) -> NoReturn:
        """Keep the state reached and raise :class:`ConvergenceError` naming it."""
        self.pressure_pa, self.load_n = p_reached, f_reached
        raise ConvergenceError(
            f"no equilibrium beyond pressure {p_reached:.1f} Pa and load "
            f"{f_reached:.3g} N on the way to {p1:.1f} Pa / {f1:.3g} N for model "
            f"{self.material.name!r} (beyond its convergence: a pressure maximum "
            "of the inflation curve or a snap-through)"
        )

    def _initial_steps(
        self, p0: float, p1: float, dp: float, df: float, cube: bool
    ) -> tuple[float, float]:
        """First and largest step of a path from ``p0`` to ``p1`` (and a load change ``df``),
        as fractions of the path (in the cube root of the pressure when ``cube``)."""
        opts = self.solver
        if cube:
            c0, c1 = np.cbrt(p0), np.cbrt(p1)
            inflated = p0 > 0 and self.height_m > self.geometry.thickness_m
            first_pa = opts.max_step_pa if inflated else opts.initial_step_pa
            first = np.cbrt(max(p0 + np.sign(dp) * first_pa, 0.0)) - c0
            step = min(1.0, abs(first / (c1 - c0)))
            max_step = 1.0
        else:
            candidates = [opts.initial_step_pa / abs(dp)] if dp else []
            candidates += [opts.initial_step_n / abs(df)] if df else []
            step = min(1.0, *candidates)
            limits = [opts.max_step_pa / abs(dp)] if dp else []
            limits += [opts.max_step_n / abs(df)] if df else []
            max_step = max(step, min(1.0, *limits))
        return step, max_step

    def _start_history(
        self, p0: float, p1: float, f0: float, cube: bool
    ) -> list[tuple[float, list[np.ndarray]]]:
        """Solutions at known path fractions for the secant predictor: the current state, and
        the previous inflation call's last state when this call continues it."""
        history: list[tuple[float, list[np.ndarray]]] = []
        if self._previous is not None and cube and self._previous[1] == f0:
            # continue the secant predictor of the previous inflation call
            prev_p, _, prev_values = self._previous
            c_prev, c0_, c1_ = np.cbrt(prev_p), np.cbrt(p0), np.cbrt(p1)
            if c1_ != c0_ and c_prev != c0_:
                history.append(((c_prev - c0_) / (c1_ - c0_), prev_values))
        history.append((0.0, self._values()))
        return history

    def _predict(self, history: list[tuple[float, list[np.ndarray]]], trial: float) -> None:
        """Set the field to the secant extrapolation of the last two solutions to ``trial``."""
        if len(history) >= 2:
            (s_a, u_a), (s_b, u_b) = history[-2], history[-1]
            ratio = (trial - s_b) / (s_b - s_a)
            self._set_values([b + ratio * (b - a_) for a_, b in zip(u_a, u_b, strict=True)])
            self._sync_internal_state()

    def pressure_sensitivity(self, with_compliance: bool = False) -> Any:
        """``du/dp`` of every point at the current state, m/Pa, shape (npoints, 3).

        Solves the tangent system with the load vector of a unit pressure increment
        (follower load on the current lower face). By reciprocity (symmetric tangent of a
        conservative system) ``-du_z/dp`` at a top point equals the chamber-volume change per
        unit downward force applied there, ``dV/dF`` (m^3/N).

        Parameters
        ----------
        with_compliance
            Also return the chamber compliance ``dV/dp`` of the whole module, m^3/Pa.
        """
        from scipy.sparse.linalg import spsolve

        r0, K = self._system(self.pressure_pa, self.load_n)
        r1, _ = self._system(self.pressure_pa + 1.0, self.load_n, matrix=False)
        # the pressure load is linear in p at a fixed configuration
        g = -(r1 - r0)
        du = np.zeros_like(g)
        du[self._dof1] = spsolve(K[self._dof1][:, self._dof1].tocsc(), g[self._dof1])
        dudp = du[: self._ndisp].reshape(-1, 3)
        if with_compliance:
            # g = dV_quarter/du for a follower pressure, so dV/dp = 4 g . du/dp
            return dudp, float(4.0 * np.dot(g[self._dof1], du[self._dof1]))
        return dudp

    def patch_weights(self, patch: LoadPatch) -> np.ndarray:
        """Share of a load spread evenly on ``patch`` carried by each point (sums to one)."""
        return -self._patch_load_vector(patch)[2::3] / 0.25

    def patch_load_compliance(self, patch: LoadPatch) -> float:
        """Load-weighted mean downward deflection of ``patch`` per newton of a load spread
        evenly on it, at constant chamber pressure (an open chamber), m/N, at the current
        state: one tangent solve (the quarter carries a quarter of the load)."""
        from scipy.sparse.linalg import spsolve

        _, K = self._system(self.pressure_pa, self.load_n)
        f = np.zeros(K.shape[0])
        f[: self._ndisp] = self._patch_load_vector(patch)
        du = np.zeros_like(f)
        du[self._dof1] = spsolve(K[self._dof1][:, self._dof1].tocsc(), f[self._dof1])
        return float(-np.dot(self.patch_weights(patch), du[: self._ndisp][2::3]))

    # ------------------------------------------------------------------ output
    def full_mesh(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Whole-module points, hexahedral cells and displacements by mirroring the quarter.

        Returns
        -------
        points, cells, displacement
            Reference coordinates (m) centred on the module, cell connectivity (corner
            points of each hexahedron), point displacements (m).
        """
        pts = self.mesh.points
        u = self.field[0].values
        ncorner = 8
        cells = self.mesh.cells[:, :ncorner]
        all_pts, all_u, all_cells = [], [], []
        offset = 0
        for sx in (1.0, -1.0):
            for sy in (1.0, -1.0):
                scale = np.array([sx, sy, 1.0])
                all_pts.append(pts * scale)
                all_u.append(u * scale)
                c = cells + offset
                if sx * sy < 0:  # keep positive orientation of mirrored hexahedra
                    c = c[:, [1, 0, 3, 2, 5, 4, 7, 6]]
                all_cells.append(c)
                offset += len(pts)
        return np.vstack(all_pts), np.vstack(all_cells), np.vstack(all_u)

    def write_vtu(self, path: str) -> None:
        """Write the deformed whole module (mirrored quarters) as a VTU file for ParaView."""
        import meshio

        points, cells, disp = self.full_mesh()
        mesh = meshio.Mesh(
            points=points,
            cells=[("hexahedron", cells)],
            point_data={"displacement": disp},
            field_data={},
        )
        mesh.write(path)


@dataclass(frozen=True)
class ModuleSetup:
    """The module a study solves: its material, geometry and discretisation.

    Parameters
    ----------
    material
        Preset name or :class:`~softpad.fem.MaterialModel`.
    geometry
        Module geometry (None: 45 x 45 x 1.5 mm).
    mesh
        Discretisation (None: :data:`DEFAULT_MESH`).
    """

    material: str | MaterialModel = "neo-hookean"
    geometry: ModuleGeometry | None = None
    mesh: MeshOptions | None = None

    def model(self, load_patch: LoadPatch | None = None, contact: bool = True) -> ModuleModel:
        """A fresh :class:`ModuleModel` of this module (``load_patch`` and ``contact`` as there)."""
        return ModuleModel(
            self.material, self.geometry, self.mesh, load_patch=load_patch, contact=contact
        )


def _path(
    p0: float, p1: float, f0: float, f1: float, cube: bool
) -> Callable[[float], tuple[float, float]]:
    """Pressure (Pa) and load (N) at fraction ``s`` of the path from ``(p0, f0)`` to
    ``(p1, f1)``: linear, or linear in the cube root of the pressure when ``cube``."""
    dp, df = p1 - p0, f1 - f0

    def at(s: float) -> tuple[float, float]:
        if cube:
            c0, c1 = np.cbrt(p0), np.cbrt(p1)
            return float((c0 + s * (c1 - c0)) ** 3), f0
        return p0 + s * dp, f0 + s * df

    return at
