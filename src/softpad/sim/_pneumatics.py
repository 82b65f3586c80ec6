"""Gas physics of the box channels: chamber + tubing, valves, supply, leaks.

Each channel (thesis, Section 6.1.1: one inflation valve, one deflation valve, one differential
pressure sensor per channel, one shared supply) is modelled as an isothermal ideal gas in the
module's chamber plus a tubing dead volume. The state is the amount of air expressed as
``n = (p_atm + p) (V(p, F) + V_t)`` (Pa m^3, proportional to moles at constant temperature),
changed by the valve and leak flows; the gauge pressure follows from ``n`` and the load ``F``
through the module characteristic by Newton's method.

Valves and leaks are orifices with an effective area ``Cd A``. The mass flow through an
orifice, for the small pressure differences here (< 0.2 bar, nearly incompressible), is

    m_dot = Cd A sqrt(2 rho) dp / sqrt(|dp| + p_lam)

(turbulent ``Cd A sqrt(2 rho dp)`` for ``|dp| >> p_lam``, linear - laminar - near zero so the
integration stays smooth), and ``dn/dt = m_dot R T`` with ``R T = p_atm / rho_atm``.

Integration (stable at every sample rate)
-----------------------------------------
A channel is stiff when its capacity ``C = dn/dp`` is small against the conductance of its
open orifices: a loaded module with a 1 mm^2 leak relaxes with a time constant of about
0.1 ms, far below a 10 ms (100 Hz) or even a 1 ms (1 kHz) sample period, and explicit Euler
then swings without bound (it did: -75 to +12.7 kPa). Every channel is therefore advanced by
exact exponential relaxation of the linearised flow, all channels at once:

* the open orifices of a channel (inflation to the supply ``p_s``, deflation and leak to the
  atmosphere) have one equilibrium pressure ``p_eq`` where their flows cancel (``p_s``, 0, or
  the root of ``A_i g(p_s - p) = A_o g(p)`` in between, ``g(x) = x / sqrt(|x| + p_lam)``);
  it depends only on the valves, the supply and the leak, so it is computed when they change;
* at the start of a *stretch* the pressure is solved exactly from ``n``, the flow ``F(p0)``
  is evaluated, and the flow is replaced by its secant through the equilibrium,
  ``F(p) ~ G (p - p_eq)`` with ``G = F(p0) / (p0 - p_eq) <= 0``; with ``C`` frozen the
  pressure then follows ``p(t) = p_eq + (p0 - p_eq) exp(-lambda t)``, ``lambda = -G / C``,
  exactly, for as long as the stretch lasts (``resolve_s``, 20 ms: the gas's own time
  constants at the nominal valves are > 0.1 s), and ``n = n0 + C (p - p0)``.

The scheme is unconditionally stable and never overshoots the equilibrium: a pressure stays
between where it started and ``p_eq`` (so between 0 and the supply for a module that starts
there, whatever the load); a sealed leaking module decays monotonically to the ambient. Exact
for a linear (laminar) orifice in a rigid vessel; for the turbulent law its error is first
order in the stretch length, the same at every sample rate because the stretches are timed in
seconds, not samples (tests/sim/test_pneumatics.py checks both against analytic solutions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import (
    KPA_AS_PA,
    CheckedFields,
    InputError,
    Positive,
    check_finite,
    check_range,
)
from softpad.sim._characteristic import ModuleCharacteristic

#: Lowest non-zero supply pressure, pascals: a supply this low cannot lift a module off its
#: base (the thesis's p0 is 1.1 kPa); a lower figure is kilopascals given as pascals.
MIN_SUPPLY_PA = 100.0


@dataclass(frozen=True)
class PneumaticParams(CheckedFields, what="pneumatic"):
    """Parameters of the pneumatic channels."""

    #: Absolute atmospheric pressure, pascals.
    atmosphere_pa: Positive = 101325.0
    #: Air density at atmospheric pressure and room temperature, kg/m^3.
    air_density_kg_m3: Positive = 1.204
    #: Dead volume of the tube and valve manifold of one channel, m^3
    #: (:data:`softpad.thesis.TUBING_VOLUME_M3`, 3.14 mL, the figure the FEM's sealed chamber
    #: uses too).
    tubing_volume_m3: Positive = thesis.TUBING_VOLUME_M3
    #: Regulated supply gauge pressure, pascals (our choice: 10 kPa).
    supply_pa: float = 10.0e3
    #: Effective area Cd A of the inflation path, m^2 (about 2 mL/s from 10 kPa into a module
    #: at 1 kPa: inflation to 1.1 kPa takes a few seconds, like Fig. 6.8).
    inflate_orifice_m2: Positive = 1.6e-8
    #: Effective area Cd A of the deflation path to atmosphere, m^2. Sized so that venting
    #: beats a stuck-open inflation valve: with both open a module settles at
    #: ``supply / (1 + (A_def / A_inf)^2)`` = 2.2 kPa, below the 3 kPa maximum.
    deflate_orifice_m2: Positive = 3.0e-8
    #: Pressure difference below which orifice flow turns linear, pascals.
    laminar_pa: Positive = 10.0

    def __post_init__(self) -> None:
        super().__post_init__()
        supply = check_finite("pneumatic supply_pa", self.supply_pa)
        if not 0 <= supply <= 500e3:
            raise InputError(f"supply pressure must be within 0..500 kPa, got {supply / 1e3:g} kPa")
        if 0 < supply < MIN_SUPPLY_PA:  # too low to inflate a module at all: not a supply
            raise InputError(
                f"pneumatic supply_pa must be 0 (none) or >= {MIN_SUPPLY_PA:g} Pa, got "
                f"{supply:g} Pa ({KPA_AS_PA})"
            )
        # a channel's tubing is millilitres (thesis: 3.14 ml); a litre or more is millilitres
        # (or cm^3) given as cubic metres
        check_range(
            "pneumatic tubing_volume_m3",
            self.tubing_volume_m3,
            0.0,
            1e-3,
            "m^3",
            "millilitres given as cubic metres?",
        )

    @property
    def gas_constant_rt(self) -> float:
        """R T of air per unit mass, m^2/s^2 (``p_atm / rho_atm``, isothermal)."""
        return self.atmosphere_pa / self.air_density_kg_m3


#: A channel this close to the equilibrium of its open orifices is settled, pascals (far below
#: the sensors' 2.44 Pa resolution): its relaxation no longer limits the stretch.
SETTLED_PA = 1e-3


def _g(x: NDArray[np.float64], laminar_pa: float) -> NDArray[np.float64]:
    """The orifice law's pressure dependence ``x / sqrt(|x| + p_lam)``, sqrt(Pa)."""
    return x / np.sqrt(np.abs(x) + laminar_pa)


def equilibrium_pa(
    inflow_m2: NDArray[np.float64],
    outflow_m2: NDArray[np.float64],
    supply_pa: float,
    laminar_pa: float,
) -> NDArray[np.float64]:
    """Pressure at which the flows of a channel's open orifices cancel, pascals.

    ``inflow_m2`` (Cd A to the supply) and ``outflow_m2`` (Cd A to the atmosphere) per
    channel: ``A_i g(p_s - p) = A_o g(p)``, monotone in ``p``, solved by bisection on
    ``[min(0, p_s), max(0, p_s)]`` where both are open (to 1e-6 Pa); ``p_s`` where only the
    supply is open, 0 where only the atmosphere is (and where nothing is: no flow).
    """
    a_in = np.asarray(inflow_m2, dtype=float)
    a_out = np.asarray(outflow_m2, dtype=float)
    p_eq = np.where((a_in > 0) & (a_out <= 0), supply_pa, 0.0)
    both = (a_in > 0) & (a_out > 0)
    if both.any():
        ai, ao = a_in[both], a_out[both]
        lo = np.full(ai.shape, min(0.0, supply_pa))
        hi = np.full(ai.shape, max(0.0, supply_pa))
        for _ in range(60):  # 10 kPa / 2^60: far below 1e-6 Pa
            mid = 0.5 * (lo + hi)
            net = ai * _g(supply_pa - mid, laminar_pa) - ao * _g(mid, laminar_pa)
            up = net > 0
            lo = np.where(up, mid, lo)
            hi = np.where(up, hi, mid)
            if (hi - lo).max() < 1e-6:
                break
        p_eq[both] = 0.5 * (lo + hi)
    return p_eq


class ChamberBank:
    """The gas state of every channel, stepped together (vectorised with NumPy).

    Channels ``0 .. n_modules-1`` hold a module; further channels are unconnected ports,
    open to the atmosphere (gauge pressure 0). See the module's notes for the integration
    (exact exponential relaxation per *stretch* of at most ``resolve_s``).

    Parameters
    ----------
    n_channels
        Channels of the box.
    n_modules
        Channels connected to a module (first ones).
    characteristic
        Volume of a module vs pressure and load.
    params
        Pneumatic parameters.
    """

    def __init__(
        self,
        n_channels: int,
        n_modules: int,
        characteristic: ModuleCharacteristic,
        params: PneumaticParams | None = None,
    ) -> None:
        if not 1 <= n_modules <= n_channels:
            raise InputError(f"a box with {n_channels} channels cannot drive {n_modules} modules")
        self.params = params or PneumaticParams()
        self.characteristic = characteristic
        self.n_channels = n_channels
        self.n_modules = n_modules
        m = n_modules
        self._vol_slope = getattr(characteristic, "volume_and_slope", None)
        self._pressure = np.zeros(n_channels)
        self._p_modules = self._pressure[:n_modules]  # a view: _pressure is never rebound
        self.loads_n = np.zeros(m)
        v0 = characteristic.volume_m3(np.zeros(m), np.zeros(m))
        self._amount = self.params.atmosphere_pa * (v0 + self.params.tubing_volume_m3)
        self._leak_m2 = np.zeros(m)
        self._leaking = False
        self._creep = np.zeros(m)  # creep volume of each membrane (Disturbances), m^3
        self._creeping = False  # any creep volume yet (else V + creep is V: not added)
        self._flat_m3 = v0  # volume under the flat, unloaded layer, m^3
        #: Longest stretch between exact pressure solves, seconds.
        self.resolve_s = 20e-3
        #: Largest pressure change of any channel along one stretch (longer than one step),
        #: pascals: the capacity ``dn/dp`` frozen for the stretch stays close to the true one.
        self.resolve_pa = 20.0
        #: Most relaxation ``lambda T`` of any channel over one stretch (longer than one step):
        #: bounds the secant's error where the orifice law curves (see the module's notes).
        self.relaxation_per_stretch = 0.1
        #: Most sub-steps of one stiff step (then the step's last sub-step takes the rest).
        self.max_substeps = 64
        self._init_stretch(m)
        #: Whether the last step solved the pressures exactly (module heights are updated then).
        self.solved = True
        #: Number of exact solves so far (identifies the current stretch).
        self.solve_count = 0
        rho = self.params.air_density_kg_m3
        self._k = self.params.gas_constant_rt * math.sqrt(2 * rho)

    def _init_stretch(self, m: int) -> None:
        """The state of the current stretch between exact solves, and the caches keyed on what
        it depends on (valves, supply, leaks), for ``m`` modules."""
        self._dn_dp = np.ones(m)
        # the current stretch: true pressures after each of its steps (rows), the steps taken
        # and applied to _pressure/_amount, and its start (p0, n0, C) and equilibrium
        self._path: NDArray[np.float64] | None = None
        self._pos = 0
        self._applied = 0
        self._p0 = np.zeros(m)
        self._n0 = self._amount.copy()
        self._c0 = np.ones(m)
        self._p_eq = np.zeros(m)
        self._stretch_dt = 0.0
        self._valve_key: object = None
        self._supply = math.nan
        self._eq_key: tuple[object, float, int] | None = None
        self._eq = np.zeros(m)
        self._a_in = np.zeros(m)
        self._a_out = np.zeros(m)
        self._flowing = np.zeros(m, dtype=bool)
        self._all_flowing = False
        self._no_outflow = self._no_inflow = False  # no orifice to the atmosphere / supply
        self._leak_version = 0
        self._steps_cache: tuple[float, int, NDArray[np.float64]] = (0.0, 0, np.zeros((0, 1)))

    @property
    def orifice_gain(self) -> float:
        """``R T sqrt(2 rho)``: an orifice ``Cd A`` passes ``gain Cd A dp / sqrt(|dp| + p_lam)``
        of amount per second."""
        return self._k

    @property
    def leak_m2(self) -> NDArray[np.float64]:
        """Effective leak area Cd A of each module channel, m^2 (0: tight; read-only view)."""
        v = self._leak_m2.view()
        v.flags.writeable = False
        return v

    @property
    def path(self) -> NDArray[np.float64] | None:
        """True pressures of every channel after each step of the current stretch (rows),
        pascals; None when no stretch runs (sealed, nothing flowing)."""
        return self._path

    @property
    def position(self) -> int:
        """Steps of the current stretch taken (the current row of :attr:`path` is one less)."""
        return self._pos

    def set_leak(self, channel_index: int, area_m2: float) -> None:
        """Set the leak area Cd A of one module channel (0-based), m^2."""
        self._end_stretch()
        self._leak_m2[channel_index] = area_m2
        self._leaking = bool(self._leak_m2.any())
        self._leak_version += 1

    def set_state(
        self, pressure_pa: NDArray[np.float64], loads_n: NDArray[np.float64] | None = None
    ) -> None:
        """Set module pressures (and loads) directly, e.g. to start already inflated."""
        self._end_stretch()
        p = np.asarray(pressure_pa, dtype=float)[: self.n_modules]
        if loads_n is not None:
            self.loads_n = np.asarray(loads_n, dtype=float).copy()
        v, dv = self._volume_and_slope(p, self.loads_n)
        vt = self.params.tubing_volume_m3
        self._amount = (self.params.atmosphere_pa + p) * (v + vt)
        self._dn_dp = (v + vt) + (self.params.atmosphere_pa + p) * dv
        self._pressure[: self.n_modules] = p

    def step(
        self,
        dt_s: float,
        inflate_open: NDArray[np.bool_],
        deflate_open: NDArray[np.bool_],
        loads_n: NDArray[np.float64],
        supply_pa: float,
        any_open: bool,
        same_load: bool | None = None,
        valve_key: object = None,
    ) -> bool:
        """Advance by ``dt_s``; return True when the module pressures changed.

        Parameters
        ----------
        dt_s
            Time step, seconds.
        inflate_open, deflate_open
            Which inflation / deflation valves are open, shape (n_modules,).
        loads_n
            External load on each module, newtons, shape (n_modules,).
        supply_pa
            Current supply gauge pressure, pascals.
        any_open
            Whether any valve is open (lets a quiet step skip the flow computation).
        same_load
            Whether ``loads_n`` equals the previous step's (computed when None).
        valve_key
            Any value that changes whenever the valve states change (the box's command
            counter); None: derived from the valve arrays.
        """
        if same_load is None:
            same_load = np.array_equal(loads_n, self.loads_n)
        if valve_key is None:
            valve_key = (inflate_open.tobytes(), deflate_open.tobytes())
        flowing = any_open or self._leaking
        if same_load:
            if flowing and self.hold(dt_s, valve_key, supply_pa):
                return True
            if not flowing and self._path is None:
                return False  # sealed, unloaded change: nothing moves
        ended = self._end_stretch()
        if not same_load:
            self.loads_n = loads_n.copy()
        p = self._solve(self._p_modules.copy())
        if ended is not None and same_load:
            p = self._no_crossing(p, *ended)
        self._pressure[: self.n_modules] = p
        if flowing:
            self._start_stretch(dt_s, inflate_open, deflate_open, supply_pa, valve_key)
        self.solved = True
        self.solve_count += 1
        return True

    def hold(self, dt_s: float, valve_key: object, supply_pa: float) -> bool:
        """The hot path of :meth:`step` while loads, valves and supply are unchanged: True when
        the step was taken along the current stretch (nothing solved; see :attr:`path`).

        The step is only counted here; :attr:`amount` and :attr:`pressure_pa` apply it when
        read.
        """
        path = self._path
        if (
            path is None
            or self._pos >= path.shape[0]
            or valve_key != self._valve_key
            or supply_pa != self._supply
            or dt_s != self._stretch_dt
        ):
            return False
        self._pos += 1
        self.solved = False
        return True

    def _start_stretch(
        self,
        dt_s: float,
        inflate_open: NDArray[np.bool_],
        deflate_open: NDArray[np.bool_],
        supply_pa: float,
        valve_key: object,
    ) -> None:
        """Linearise the flows at the solved pressure and take the stretch's first step.

        A stretch lasts ``resolve_s`` or until the fastest channel has relaxed by
        ``relaxation_per_stretch`` (``lambda T``), at least one step; where even one step
        relaxes more, the step is split into sub-steps of that bound, each from an exact
        solve (at most ``max_substeps``; beyond, the channel is at its equilibrium anyway).
        """
        self._update_equilibrium(inflate_open, deflate_open, supply_pa, valve_key)
        self._valve_key, self._supply, self._stretch_dt = valve_key, supply_pa, dt_s
        p0 = self._p_modules.copy()
        lam, p_eq = self._relaxation(p0, supply_pa)
        theta = self.relaxation_per_stretch
        lam_max = float(np.maximum.reduce(lam))
        # a collapsed module (below ambient, where the layer's volume no longer changes) filling
        # up: its compliance jumps at 0 Pa, so the secant from below would overshoot (606 Pa in
        # one 10 ms step with the disturbances' creep); sub-steps re-solve from the amount
        collapsed = not np.minimum.reduce(p0) >= 0.0 and bool(
            np.any((p0 < 0.0) & (p_eq > p0) & (lam > 0.0))
        )
        if lam_max * dt_s > theta or collapsed:
            self._substeps(dt_s, supply_pa, lam, p_eq)
            self._path = np.zeros((1, self.n_channels))
            self._path[0, : self.n_modules] = self._p_modules
            self._pos, self._applied = 1, 1
            self._p0, self._n0, self._c0 = self._p_modules.copy(), self._amount, self._dn_dp
            self._p_eq = p_eq
            return
        steps = self._step_times(dt_s)
        if lam_max * steps[-1, 0] > theta:
            steps = steps[: max(1, int(theta / (lam_max * dt_s)))]
        ahead = p_eq + (p0 - p_eq) * np.exp(-lam * steps)
        if ahead.shape[0] > 1:  # C is frozen along the stretch: end it where p moved far
            rising = lam > 0
            if rising.all():  # no channel to leave out
                moved = np.abs(ahead - p0).max(axis=1, initial=0.0)
            else:
                moved = np.abs(ahead[:, rising] - p0[rising]).max(axis=1, initial=0.0)
            far = int(np.searchsorted(moved, self.resolve_pa, side="right"))
            ahead = ahead[: max(1, far)]
        path = np.zeros((ahead.shape[0], self.n_channels))
        path[:, : self.n_modules] = ahead
        self._path, self._pos, self._applied = path, 1, 0
        self._p0, self._n0, self._c0, self._p_eq = p0, self._amount.copy(), self._dn_dp, p_eq

    def _relaxation(
        self, p: NDArray[np.float64], supply_pa: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Relaxation rate ``lambda`` (1/s) of every module channel at ``p`` and the pressure
        it relaxes to (the open orifices' equilibrium; ``p`` itself where nothing is open)."""
        # every channel open (the equilibrium is only rebound, never written in place)
        p_eq = self._eq if self._all_flowing else np.where(self._flowing, self._eq, p)
        d = p - p_eq
        lam_pa = self.params.laminar_pa
        # the flow of the open orifices; terms of areas all zero left out (they are zeros: the
        # flow differs at most in the sign of a zero, which no rate or pressure below keeps)
        if self._no_outflow:
            flow = self._k * (self._a_in * _g(supply_pa - p, lam_pa))
        elif self._no_inflow:
            flow = self._k * -(self._a_out * _g(p, lam_pa))
        else:
            flow = self._k * (self._a_in * _g(supply_pa - p, lam_pa) - self._a_out * _g(p, lam_pa))
        # a channel within SETTLED_PA of its equilibrium stays there (rate 0): it does not
        # shorten the stretch however stiff it is; the secant through the root has slope <= 0
        far = np.abs(d) > SETTLED_PA
        lam = np.maximum(-flow / np.where(far, d, 1.0) / self._dn_dp, 0.0)
        return np.where(far, lam, 0.0), p_eq

    def _substeps(
        self,
        dt_s: float,
        supply_pa: float,
        lam: NDArray[np.float64],
        p_eq: NDArray[np.float64],
    ) -> None:
        """Advance one stiff step in sub-steps of ``lambda h <= relaxation_per_stretch``."""
        theta, left, p = self.relaxation_per_stretch, dt_s, self._p_modules.copy()
        for i in range(self.max_substeps):
            h = left if i == self.max_substeps - 1 else min(left, theta / float(lam.max()))
            ahead = p_eq + (p - p_eq) * np.exp(-lam * h)
            self._amount = self._amount + self._dn_dp * (ahead - p)
            p = self._no_crossing(self._solve(ahead), p, p_eq)
            left -= h
            if left <= 1e-12 * dt_s:
                break
            lam, p_eq = self._relaxation(p, supply_pa)
            if not lam.max() > 0:
                break
        self._pressure[: self.n_modules] = p

    def _step_times(self, dt_s: float) -> NDArray[np.float64]:
        """Times of the steps of one stretch, ``dt, 2 dt, .. K dt`` (column), seconds; a stretch
        is ``resolve_s`` long (at least one step), so stretches start at the same times at
        every sample rate that divides it."""
        cached_dt, cached_k, times = self._steps_cache
        k = max(1, round(self.resolve_s / dt_s))
        if cached_dt != dt_s or cached_k != k:
            times = dt_s * np.arange(1, k + 1, dtype=float)[:, None]
            self._steps_cache = (dt_s, k, times)
        return times

    def _update_equilibrium(
        self,
        inflate_open: NDArray[np.bool_],
        deflate_open: NDArray[np.bool_],
        supply_pa: float,
        valve_key: object,
    ) -> None:
        key = (valve_key, supply_pa, self._leak_version)
        if key == self._eq_key:
            return
        par = self.params
        self._a_in = np.where(inflate_open, par.inflate_orifice_m2, 0.0)
        self._a_out = np.where(deflate_open, par.deflate_orifice_m2, 0.0) + self._leak_m2
        self._flowing = (self._a_in > 0) | (self._a_out > 0)
        self._all_flowing = bool(self._flowing.all())
        self._no_outflow, self._no_inflow = not self._a_out.any(), not self._a_in.any()
        self._eq = equilibrium_pa(self._a_in, self._a_out, supply_pa, par.laminar_pa)
        self._eq_key = key

    def _end_stretch(self) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """Apply the steps taken and end the stretch; its (start, equilibrium) pressures."""
        if self._path is None:
            return None
        self._sync()
        self._path = None
        return self._p0, self._p_eq

    def _no_crossing(
        self, p: NDArray[np.float64], p_start: NDArray[np.float64], p_eq: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Where the exact solve lands past the equilibrium the stretch relaxed towards (the
        frozen C of the stretch slightly off the true one), put it on the equilibrium."""
        crossed = (p - p_eq) * (p_start - p_eq) < 0
        if not crossed.any():
            return p
        p = np.where(crossed, p_eq, p)
        v, dv = self._volume_and_slope(p, self.loads_n)
        patm, vt = self.params.atmosphere_pa, self.params.tubing_volume_m3
        self._amount = np.where(crossed, (patm + p) * (v + vt), self._amount)
        self._dn_dp = (v + vt) + (patm + p) * dv
        return p

    def _sync(self) -> None:
        path = self._path
        if path is not None and self._applied != self._pos:
            self._applied = self._pos
            row = path[self._pos - 1]
            self._pressure[:] = row
            self._amount = self._n0 + self._c0 * (row[: self.n_modules] - self._p0)

    def _solve(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """Gauge pressure with ``(p_atm + p)(V(p, F) + V_t) = n``.

        Newton's method from the previous pressure (1-3 steps normally); if it has not
        converged after 6 steps (a heavy load collapsing the layer), a bracketed Newton:
        the residual increases monotonically with p, so a bracket [lo, hi] is kept and a
        step that leaves it is replaced by the midpoint.
        """
        patm, vt, n, f = (
            self.params.atmosphere_pa,
            self.params.tubing_volume_m3,
            self._amount,
            self.loads_n,
        )
        start = p
        for _ in range(6):
            v, dv = self._volume_and_slope(p, f)
            dn_dp = (v + vt) + (patm + p) * dv
            step = ((patm + p) * (v + vt) - n) / dn_dp
            p = p - step
            # Newton converges quadratically: after a step of s Pa the error is about
            # s^2 |n''| / (2 n') < 1e-8 Pa for s < 1e-2 Pa (n' > 1e-6 m^3, |n''| < 1e-9 m^3/Pa
            # here; 0 within a segment of the tabulated characteristic): one evaluation from the
            # stretch's prediction usually suffices
            if np.maximum.reduce(np.abs(step)) < 1e-2:
                self._dn_dp = dn_dp  # at the last iterate, within 1e-4 Pa of the solution
                return p
        p = start
        lo = np.full_like(p, -0.999 * patm)
        hi = np.full_like(p, 1e6)
        for _ in range(200):
            v, dv = self._volume_and_slope(p, f)
            r = (patm + p) * (v + vt) - n
            neg = r < 0
            lo = np.where(neg, p, lo)
            hi = np.where(neg, hi, p)
            new = p - r / ((v + vt) + (patm + p) * dv)
            bad = (new <= lo) | (new >= hi)
            if bad.any():
                new = np.where(bad, 0.5 * (lo + hi), new)
            done = np.abs(new - p).max() < 1e-6
            p = new
            if done:
                break
        v, dv = self._volume_and_slope(p, f)
        self._dn_dp = (v + vt) + (patm + p) * dv
        return p

    def _volume_and_slope(
        self, p: NDArray[np.float64], f: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        if self._vol_slope is not None:
            v, dv = self._vol_slope(p, f)
        else:
            v = self.characteristic.volume_m3(p, f)
            dv = self.characteristic.volume_slope_m3_pa(p, f)
        return (v + self._creep if self._creeping else v), dv

    @property
    def creep_m3(self) -> NDArray[np.float64]:
        """Creep volume of every module's membrane, m^3 (read-only copy)."""
        return self._creep.copy()

    def disturb(
        self,
        temperature_ratio: float,
        elapsed_s: float,
        leak_area_m2: float,
        creep_fraction: float,
        creep_time_s: float,
    ) -> None:
        """Apply ``elapsed_s`` of slow disturbances and solve the pressures again.

        Parameters
        ----------
        temperature_ratio
            T_new / T_old of the air: the state ``n R T`` scales with it.
        elapsed_s
            Time since the last call, seconds.
        leak_area_m2
            ``Cd A`` of every module's small leak to the atmosphere, m^2 (relaxed exactly,
            like the valves: the secant of the orifice law through the ambient).
        creep_fraction, creep_time_s
            The creep volume relaxes towards ``creep_fraction`` of the stretched volume
            ``V(p, F) - V(0, 0)`` with this time constant.
        """
        self._end_stretch()
        m = self.n_modules
        p = self._pressure[:m].copy()
        if leak_area_m2 > 0:
            conductance = self._k * leak_area_m2 / np.sqrt(np.abs(p) + self.params.laminar_pa)
            lost = p * (1.0 - np.exp(-conductance / self._dn_dp * elapsed_s))
            self._amount = self._amount - self._dn_dp * lost
        self._amount = self._amount * temperature_ratio
        stretched = self.characteristic.volume_m3(p, self.loads_n) - self._flat_m3
        target = creep_fraction * np.maximum(stretched, 0.0)
        self._creep = target + (self._creep - target) * math.exp(-elapsed_s / creep_time_s)
        self._creeping = True
        self._pressure[:m] = self._solve(p)
        self._eq_key = None
        self.solved = True
        self.solve_count += 1

    def heights_m(self) -> NDArray[np.float64]:
        """Top height of every module, metres."""
        return self.characteristic.height_m(self.pressure_pa[: self.n_modules], self.loads_n)

    @property
    def amount(self) -> NDArray[np.float64]:
        """Amount of air of every module channel, ``(p_atm + p)(V + V_t)``, Pa m^3."""
        if self._applied != self._pos:
            self._sync()
        return self._amount

    @property
    def pressure_pa(self) -> NDArray[np.float64]:
        """Gauge pressure of every channel, pascals (unconnected ports: 0)."""
        if self._applied != self._pos:
            self._sync()
        return self._pressure
