"""Module response from the FEM: how much a vertical load at a point of the pad squeezes a chamber.

By reciprocity (the tangent of the inflated layer is symmetric), a small vertical force ``dF`` at
a point ``x`` of a module's top face changes the chamber volume by ``dV = -s(x) dF``, where
``s(x) = dw/dp(x)`` is the rise of the top face there per unit chamber pressure. ``softpad fem
response`` computes ``s`` with the project's finite-element model (:mod:`softpad.fem`) over the
usable range of p0 and stores it in ``softpad/data/module_response.npz``; this module reads the
file (NumPy only) and turns loads into what the gas physics needs:

* :class:`ModuleResponse`: ``s(x, y, p)`` of one module (bilinear in the FEM's nodes, linear in
  p), the chamber volume and compliance at each pressure, and the small-load sealed-chamber
  pressure rise of a flat load of any footprint at any position (the FEM's prediction);
* :class:`PadResponse`: the same on a pad of modules (points on a seam between chambers load
  no chamber), and the *equivalent load* of each module: the load on the characteristic's
  central patch (:mod:`softpad.sim._characteristic`) that squeezes the chamber as much. The
  worlds give the gas physics equivalent loads, so a load's effect depends on where it is and
  how wide it is, and large loads keep the characteristic's nonlinearity (base contact).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from softpad import thesis
from softpad.errors import InputError
from softpad.fem import (
    PACKAGED_CAST_RESPONSE,
    PACKAGED_RESPONSE,
    PRESSURE_STEP_PA,
    RESPONSE_STEP_M,
    RESPONSE_VERSION,
    CastPadResponse,
    ModuleResponse,
    rect_points,
)
from softpad.layout import PadLayout

try:  # the cast pad's weighting in compiled code (src/softpad/sim/_fastworld.c; make ext)
    import softpad.sim._fastworld as _fastworld
except ImportError:  # pragma: no cover - depends on the build
    _fastworld = None  # type: ignore[assignment]

#: The pad models a :class:`PadResponse` offers.
PAD_MODELS = ("auto", "cast", "clamped")
#: Width of the band inside each chamber's border where ``line_gain`` acts on the 45 mm
#: pitch, m (scaled with the pitch): half the 25 mm strip over which the pad wraps the
#: thesis's can astride a line (``softpad.trials._validate.cylinder_line_budget``).
LINE_BAND_M = 0.0125
#: Largest line gain a :class:`PadResponse` accepts.
MAX_LINE_GAIN = 10.0
#: ``line_response_gain``'s (low, high, nominal): from the cast-pad FEM as it is (1, the
#: nominal: the physics, not a fit) to the gain at which the Duplo face's minimum detectable
#: mass falls to the thesis's 5 g (5.95); the can is seen on six modules from 3.26 on
#: (:func:`softpad.trials._line.line_gain_bracket` at 1.1 kPa on the packaged cast response;
#: a test checks the figures against it).
LINE_GAIN_RANGE = (1.0, 5.95, 1.0)
#: The line gain of a :class:`PadResponse` by default (``line_response_gain``'s nominal).
DEFAULT_LINE_GAIN = LINE_GAIN_RANGE[2]

__all__ = [
    "DEFAULT_LINE_GAIN",
    "LINE_BAND_M",
    "LINE_GAIN_RANGE",
    "MAX_LINE_GAIN",
    "PACKAGED_CAST_RESPONSE",
    "PACKAGED_RESPONSE",
    "PAD_MODELS",
    "PRESSURE_STEP_PA",
    "RESPONSE_STEP_M",
    "RESPONSE_VERSION",
    "ModuleResponse",
    "PadResponse",
    "default_cast_response",
    "default_response",
    "operating_pressure",
    "packaged_cast_response_path",
    "packaged_response_path",
    "rect_points",
]


def packaged_response_path() -> Path | None:
    """Path of the packaged FEM response, or None when it is not installed."""
    from softpad.sim._characteristic import packaged_data_path

    return packaged_data_path(PACKAGED_RESPONSE)


def packaged_cast_response_path() -> Path | None:
    """Path of the packaged cast-pad response, or None when it is not installed."""
    from softpad.sim._characteristic import packaged_data_path

    return packaged_data_path(PACKAGED_CAST_RESPONSE)


@lru_cache(maxsize=1)
def default_cast_response() -> CastPadResponse | None:
    """The packaged cast-pad response (``softpad/data/cast_pad_response.npz``), or None when
    it is missing (the pad then falls back to the clamped modules)."""
    path = packaged_cast_response_path()
    return None if path is None else CastPadResponse.from_file(path)


@lru_cache(maxsize=1)
def default_response() -> ModuleResponse:
    """The packaged FEM response (``softpad/data/module_response.npz``).

    Raises
    ------
    InputError
        When the file is missing (regenerate it with ``softpad fem response``).
    """
    path = packaged_response_path()
    if path is None:
        raise InputError(
            f"the packaged module response {PACKAGED_RESPONSE!r} is missing; regenerate it with "
            "'softpad fem response --out src/softpad/data/module_response.npz --force'"
        )
    return ModuleResponse.from_file(path)


class PadResponse:
    """The FEM response on a pad of modules: which chambers a point loads and how much.

    Two models of the pad (``pad_model``):

    * ``"cast"`` (the default where the packaged cast-pad response has the layout's rows and
      columns): the pad as it was cast, one continuous upper layer over every chamber
      (:class:`softpad.fem.CastPadResponse`, :mod:`softpad.fem._cast`); a load anywhere
      squeezes every chamber by that chamber's own ``s_k(x)``, so a load on the line between
      two chambers is felt by both;
    * ``"clamped"``: independent modules whose lateral faces are clamped (the thesis's
      Section 7.2 model, :class:`ModuleResponse`): module k's chamber is a square of the
      response's chamber side centred on the module; points between chambers load none.

    On a pad whose pitch differs from the FEM's the response is scaled to the pitch, an
    approximation: regenerate it for such a pad for its own figures.

    Parameters
    ----------
    layout
        Pad geometry (pitch, rows, columns).
    response
        Module response (the packaged clamped FEM one by default); it also gives the table's
        pressures (:func:`operating_pressure`).
    seam_width_m
        Bonded width between chambers instead of the FEM's, metres (an uncertain parameter,
        :mod:`softpad.sim._uncertain`): the chambers shrink to the pitch less it and the FEM
        response is stretched onto them (the cast pad's about each module centre, piecewise
        linearly in x and y), an approximation like a different pitch.
    pad_model
        ``"auto"`` (cast where the packaged cast response fits the layout, else clamped),
        ``"cast"`` or ``"clamped"``.
    cast
        A cast-pad response instead of the packaged one.
    line_gain
        Gain on every chamber's response within :data:`LINE_BAND_M` of its border, tapering
        linearly to 1 at that distance (``line_response_gain`` of
        :data:`softpad.sim.UNCERTAIN_PARAMETERS`, default its nominal; 1: the FEM as it is).
    """

    def __init__(
        self,
        layout: PadLayout | None = None,
        response: ModuleResponse | None = None,
        seam_width_m: float | None = None,
        pad_model: str = "auto",
        cast: CastPadResponse | None = None,
        line_gain: float = DEFAULT_LINE_GAIN,
    ):
        self.layout = layout or PadLayout()
        self.response = response or default_response()
        seam = float(self.response.meta.get("seam_width_m", 0.0))
        #: Pad pitch over the FEM module's pitch (1 for the default pad).
        self.scale = self.layout.pitch_m / (self.response.chamber_side_m + seam)
        self._seam = seam_width_m
        if seam_width_m is not None:
            if not 0.0 <= seam_width_m < self.layout.pitch_m:
                raise InputError(
                    f"seam width must be within 0..{self.layout.pitch_m * 1e3:g} mm, got "
                    f"{seam_width_m * 1e3:g} mm"
                )
            self.scale = (self.layout.pitch_m - seam_width_m) / self.response.chamber_side_m
        if not (np.isfinite(line_gain) and 1.0 <= line_gain <= MAX_LINE_GAIN):
            raise InputError(f"line gain must be within 1..{MAX_LINE_GAIN:g}, got {line_gain!r}")
        self.line_gain = float(line_gain)
        self.cast = _choose_cast(self.layout, pad_model, cast)
        self._refs: dict[float, NDArray[np.float64]] = {}
        #: Weigh the cast pad's contacts in compiled code where it is built (the same bits;
        #: False: NumPy only).
        self.compiled = True
        self._compiled_consts: tuple[tuple[Any, ...], NDArray[np.float64]] | None = None
        self._compiled_pads: dict[float, tuple[tuple[Any, ...], tuple[Any, ...]]] = {}

    @property
    def pad_model(self) -> str:
        """``"cast"`` or ``"clamped"``: which FEM the pad's response comes from."""
        return "clamped" if self.cast is None else "cast"

    @property
    def chamber_side_m(self) -> float:
        """Side of every chamber on this pad, metres."""
        if self.cast is not None and self._seam is None:
            side = self.cast.pitch_m - self.cast.wall_width_m
            return side * self.layout.pitch_m / self.cast.pitch_m
        return self.scale * self.response.chamber_side_m

    @property
    def seam_width_m(self) -> float:
        """Bonded width between neighbouring chambers, metres."""
        return max(self.layout.pitch_m - self.chamber_side_m, 0.0)

    def module_centers_m(self) -> NDArray[np.float64]:
        """Centre of every module in the pad frame, (n_modules, 2), metres (module order)."""
        lay = self.layout
        k = np.arange(lay.n_modules)
        row, col = k // lay.cols, k % lay.cols
        return np.column_stack(
            [(col + 0.5) * lay.pitch_m, (lay.rows - 1 - row + 0.5) * lay.pitch_m]
        )

    def locate(self, points_m: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """0-based module of each pad-frame point (-1 on a seam or off the pad) and the point
        relative to that module's centre, metres."""
        pts = np.asarray(points_m, dtype=float).reshape(-1, 2)
        lay, pitch = self.layout, self.layout.pitch_m
        col = np.floor(pts[:, 0] / pitch).astype(np.int64)
        rb = np.floor(pts[:, 1] / pitch).astype(np.int64)
        local = pts - (np.column_stack([col, rb]) + 0.5) * pitch
        half = 0.5 * self.chamber_side_m
        ok = (col >= 0) & (col < lay.cols) & (rb >= 0) & (rb < lay.rows)
        ok &= (np.abs(local[:, 0]) < half) & (np.abs(local[:, 1]) < half)
        idx = np.where(ok, (lay.rows - 1 - rb) * lay.cols + col, -1)
        return idx, local

    # --- the cast pad -------------------------------------------------------------------------
    def _to_cast_frame(self, points_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """Pad-frame points in the cast model's frame: scaled by the pitches, and with a seam
        of its own, stretched per axis about each module centre so that this pad's chamber
        edges fall on the model's."""
        assert self.cast is not None
        pitch, model_pitch = self.layout.pitch_m, self.cast.pitch_m
        if self._seam is None:
            return points_m * (model_pitch / pitch)
        cell = np.floor(points_m / pitch)
        u = points_m - (cell + 0.5) * pitch
        h, hm = 0.5 * self.chamber_side_m, 0.5 * (model_pitch - self.cast.wall_width_m)
        a = np.abs(u)
        inner = a * (hm / h) if h > 0 else np.full_like(a, hm)
        outer = hm + (a - h) * (0.5 * model_pitch - hm) / max(0.5 * pitch - h, 1e-12)
        mapped = np.sign(u) * np.where(a <= h, inner, outer)
        return (cell + 0.5) * model_pitch + mapped

    def _line_factor(self, points_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """``1 + (g - 1) max(0, 1 - d_k / b)`` of every point (n) for every module
        (n_modules), with ``d_k`` the distance inside module k's chamber from its border (0
        outside it) and ``b`` :data:`LINE_BAND_M` scaled with the pitch."""
        n = self.layout.n_modules
        if self.line_gain == 1.0:
            return np.ones((len(points_m), n))
        rel = np.abs(points_m[:, None, :] - self.module_centers_m()[None, :, :])
        d = np.maximum(0.5 * self.chamber_side_m - rel.max(axis=2), 0.0)
        band = LINE_BAND_M * self.layout.pitch_m / thesis_pitch()
        return 1.0 + (self.line_gain - 1.0) * np.maximum(1.0 - d / band, 0.0)

    def influences(self, points_m: ArrayLike, pressure_pa: float) -> NDArray[np.float64]:
        """``s_k`` of a point force at pad-frame points (n) on every module (n_modules), with
        the line gain, m^3/N (the clamped pad: only the module whose chamber holds the point)."""
        pts = np.asarray(points_m, dtype=float).reshape(-1, 2)
        if self.cast is None:
            idx, local = self.locate(pts)
            on = idx >= 0
            s = np.zeros((len(pts), self.layout.n_modules))
            s[np.flatnonzero(on), idx[on]] = self.response.influence(
                local[on] / self.scale, pressure_pa
            )
        else:
            s = self.cast.influence(self._to_cast_frame(pts), pressure_pa)
        # the gain raises what presses a chamber, not the slight lift beside it
        return np.asarray(s + (self._line_factor(pts) - 1.0) * np.maximum(s, 0.0))

    def reference_influences(self, pressure_pa: float) -> NDArray[np.float64]:
        """Each module's ``s_ref,k``, m^3/N: a load's equivalent load on module k is
        ``sum f s_k(x) / s_ref,k``, the load on the characteristic's central patch that raises
        the sealed chamber as much at small loads.

        Clamped: the mean of ``s_k`` (:meth:`influences`) over the module's own central patch
        (the characteristic's, :attr:`ModuleResponse.reference_patch_m`, scaled with the
        pad), so that a load there is its own equivalent load. Cast: the characteristic is
        the clamped module's, whose small-load rise per newton on its patch is
        ``s_cl / (C_cl + G_cl)``; chamber k of the cast pad rises ``s_k / (C_kk + G_k)``, so
        ``s_ref,k = s_cl (C_kk + G_k) / (C_cl + G_cl)`` (``G``: the gas at the nominal tubing).
        """
        key = round(float(pressure_pa), 3)
        ref = self._refs.get(key)
        if ref is None:
            if self.cast is None:
                local = rect_points((0.0, 0.0), self.response.reference_patch_m * self.scale)
                ref = np.array(
                    [
                        self.influences(local + c, pressure_pa)[:, k].mean()
                        for k, c in enumerate(self.module_centers_m())
                    ]
                )
            else:
                r, p = self.response, float(pressure_pa)
                c_cl = float(r._along_pressure(r.compliance_m3_pa, p)) + r.gas_compliance_m3_pa(p)
                gas = self.cast.volumes(p) + thesis.CHAMBER_GAP_VOLUME_M3 + thesis.TUBING_VOLUME_M3
                c_k = np.diag(self.cast.compliance(p)) + gas / (101325.0 + p)
                ref = r.reference_influence(p) * c_k / c_cl
            self._refs[key] = ref
        return np.asarray(ref)

    def factors(self, points_m: ArrayLike, pressure_pa: float) -> NDArray[np.float64]:
        """Equivalent-load factor ``s_k(x) / s_ref,k`` of every point (n) for every module
        (n_modules): what a newton at the point weighs on each module's central patch."""
        s = self.influences(points_m, pressure_pa)
        return np.asarray(s / self.reference_influences(pressure_pa)[None, :])

    def point_factors(
        self, modules: ArrayLike, points_m: ArrayLike, pressure_pa: float
    ) -> NDArray[np.float64]:
        """As :meth:`factors` for contacts on given module tops (0-based ``modules``): the
        clamped pad loads only that module (its ``s`` at the point even on a seam), the cast
        pad every module."""
        pts = np.asarray(points_m, dtype=float).reshape(-1, 2)
        ks = np.asarray(modules, dtype=np.int64).reshape(-1)
        if self.cast is not None:
            if _fastworld is not None and self.compiled:
                return self._cast_factors_compiled(pts, pressure_pa)
            return self.factors(pts, pressure_pa)
        local = (pts - self.module_centers_m()[ks]) / self.scale
        out = np.zeros((len(pts), self.layout.n_modules))
        out[np.arange(len(pts)), ks] = self.response.influence(local, pressure_pa)
        out *= self._line_factor(pts)
        return np.asarray(out / self.reference_influences(pressure_pa)[None, :])

    def _cast_factors_compiled(
        self, pts: NDArray[np.float64], pressure_pa: float
    ) -> NDArray[np.float64]:
        """:meth:`factors` of the cast pad in compiled code (:mod:`softpad.sim._fastworld`):
        the same operations in the same order, one call instead of some forty NumPy ones."""
        assert _fastworld is not None
        pad = self._compiled_pad(pressure_pa)
        pts = np.ascontiguousarray(pts)
        out = np.empty((len(pts), pad[3]))
        _fastworld.cast_factors(pad, len(pts), pts.ctypes.data, out.ctypes.data)
        return out

    def weigh_steps(
        self,
        steps: list[tuple[list[int], list[float], list[list[float]]]],
        pressure_pa: float,
        total: NDArray[np.float64],
    ) -> bool:
        """Add each step's equivalent loads to ``total`` (n_modules), as
        :class:`~softpad.sim._mujoco_contacts.ContactSensing` weighs a sample period's steps
        (modules, normal forces, points per step: the forces times :meth:`point_factors`,
        summed over a step's contacts in order), in compiled code; False (nothing added) where
        it does not run (the clamped pad, not built, switched off)."""
        if self.cast is None or _fastworld is None or not self.compiled:
            return False
        assert total.flags.c_contiguous and total.dtype == np.float64
        _fastworld.cast_weigh(self._compiled_pad(pressure_pa), steps, total.ctypes.data)
        return True

    def _compiled_pad(self, pressure_pa: float) -> tuple[Any, ...]:
        """The cast pad at ``pressure_pa`` as the compiled code takes it (the table and the
        reference influences at that pressure, the constants; arrays by address, kept alive
        by the caches)."""
        key = round(float(pressure_pa), 3)  # the table's and the references' cache key
        kept = self._compiled_pads.get(key)
        if kept is not None:
            return kept[0]
        cast = self.cast
        assert cast is not None
        if self._compiled_consts is None:
            self._compiled_consts = self._cast_constants(cast)
        consts, centres = self._compiled_consts
        table = cast.influence_table(pressure_pa)
        ref = np.asarray(self.reference_influences(pressure_pa), dtype=float)
        ax, ay = cast.x_axis_m, cast.y_axis_m
        arrays = (table, ax, ay, centres, ref)
        assert all(a.flags.c_contiguous and a.dtype == np.float64 for a in arrays)
        nx, ny, nk = table.shape
        head = (table.ctypes.data, nx, ny, nk, ax.ctypes.data, ay.ctypes.data)
        pad = (*head, *consts, centres.ctypes.data, ref.ctypes.data)
        self._compiled_pads[key] = (pad, arrays)  # the arrays kept alive with their addresses
        return pad

    def _cast_constants(self, cast: CastPadResponse) -> tuple[tuple[Any, ...], NDArray[np.float64]]:
        """The scalars of :meth:`_to_cast_frame` and :meth:`_line_factor`, computed as there,
        and the module centres, for :meth:`_cast_factors_compiled`."""
        pitch, model_pitch = self.layout.pitch_m, cast.pitch_m
        h, hm = 0.5 * self.chamber_side_m, 0.5 * (model_pitch - cast.wall_width_m)
        consts = (
            self._seam is not None,
            model_pitch / pitch,
            pitch,
            model_pitch,
            h,
            hm,
            hm / h if h > 0 else 0.0,
            0.5 * model_pitch - hm,
            not h > 0,
            max(0.5 * pitch - h, 1e-12),
            0.5 * self.chamber_side_m,
            self.line_gain - 1.0,
            LINE_BAND_M * self.layout.pitch_m / thesis_pitch(),
        )
        return consts, np.ascontiguousarray(self.module_centers_m(), dtype=float)

    # --- loads --------------------------------------------------------------------------------
    def weights(
        self, points_m: ArrayLike, pressure_pa: float
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """The module each point weighs on most and its equivalent-load factor there (>= 0):
        a force ``f`` at the point squeezes that chamber as much as ``f w`` spread over the
        characteristic's central patch (the other modules' shares: :meth:`factors`)."""
        m = self.factors(points_m, pressure_pa)
        idx = np.argmax(m, axis=1)
        w = np.maximum(m[np.arange(len(m)), idx], 0.0)
        return np.where(w > 0, idx, -1), w

    def equivalent_loads(
        self, points_m: ArrayLike, forces_n: ArrayLike, pressure_pa: float
    ) -> NDArray[np.float64]:
        """Equivalent central-patch load of every module, N, for forces at pad-frame points.

        Every module's share of every point (:meth:`factors`), each point's row scaled as
        :meth:`weights` scales its largest share (a subclass may scale the response there).
        A module's total is at least 0: on the cast pad a load beside a chamber's border lifts
        it very slightly (a negative share, under 1 % of the load's own); the chambers' gas
        model takes loads that press, so that lift is dropped.
        """
        m = self.factors(points_m, pressure_pa)
        own = np.max(m, axis=1)
        _, w = self.weights(points_m, pressure_pa)
        ratio = np.divide(w, own, out=np.ones_like(w), where=own > 0)
        f = np.broadcast_to(np.asarray(forces_n, dtype=float), own.shape)
        return np.maximum(np.asarray((f * ratio) @ m, dtype=float), 0.0)

    def rect_equivalent_loads(
        self,
        center_m: ArrayLike,
        size_m: ArrayLike,
        force_n: float,
        pressure_pa: float,
        yaw_rad: float = 0.0,
    ) -> NDArray[np.float64]:
        """Equivalent loads of a force spread uniformly over a rectangle of the pad, N."""
        pts = rect_points(center_m, size_m, yaw_rad)
        return self.equivalent_loads(pts, force_n / len(pts), pressure_pa)

    def sealed_rise_pa(
        self, equivalent_loads_n: ArrayLike, pressure_pa: float, **gas: float
    ) -> NDArray[np.float64]:
        """The FEM's small-load pressure rise of every sealed module, Pa, for its equivalent
        loads (e.g. :meth:`rect_equivalent_loads`).

        Clamped: ``F <s>_k / (dV/dp + (V + V_gap + V_t) / (p_atm + p))`` per module. Cast:
        ``(C + diag(G)) dp = s_ref F`` with the chambers' compliance matrix ``C`` (coupled
        through the shared layer) and ``G_k = (V_k + V_gap + V_t) / (p_atm + p)``.
        """
        eq = np.asarray(equivalent_loads_n, dtype=float)
        if self.cast is None:
            s_ref = self.response.reference_influence(pressure_pa)
            return np.asarray(eq * s_ref * self.response.sealed_rise_per_newton(pressure_pa, **gas))
        tubing = gas.get("tubing_volume_m3", thesis.TUBING_VOLUME_M3)
        gap = gas.get("gap_volume_m3", thesis.CHAMBER_GAP_VOLUME_M3)
        atm = gas.get("atmosphere_pa", 101325.0)
        g = (self.cast.volumes(pressure_pa) + gap + tubing) / (atm + pressure_pa)
        rhs = eq * self.reference_influences(pressure_pa)
        return np.asarray(np.linalg.solve(self.cast.compliance(pressure_pa) + np.diag(g), rhs))


def thesis_pitch() -> float:
    """The prototype's module pitch (the FEM's reference patch belongs to it), m."""
    return thesis.MODULE_PITCH_M


def _choose_cast(
    layout: PadLayout, pad_model: str, cast: CastPadResponse | None
) -> CastPadResponse | None:
    """The cast response a :class:`PadResponse` uses (None: the clamped modules)."""
    if pad_model not in PAD_MODELS:
        raise InputError(f"pad model must be one of {', '.join(PAD_MODELS)}, got {pad_model!r}")
    if pad_model == "clamped":
        return None
    table = cast if cast is not None else default_cast_response()
    fits = table is not None and table.shape == (layout.rows, layout.cols)
    if pad_model == "cast" and not fits:
        raise InputError(
            f"no cast-pad response for a {layout.rows} x {layout.cols} pad; regenerate one "
            "with 'softpad fem cast-response --rows R --cols C' or use the clamped model"
        )
    return table if fits else None


def operating_pressure(pressure_pa: float, response: ModuleResponse) -> float:
    """The pressure at which a world evaluates the response: rounded to
    :data:`PRESSURE_STEP_PA` and clamped to the table's range (below it, during inflation, the
    first row), Pa."""
    p = response.pressure_pa
    q = round(float(pressure_pa) / PRESSURE_STEP_PA) * PRESSURE_STEP_PA
    return float(min(max(q, p[0]), p[-1]))
