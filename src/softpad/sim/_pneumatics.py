"""Gas physics of the box channels: chamber + tubing, valves, supply, leaks.

Each channel (seed, Section 6.1.1: one inflation valve, one deflation valve, one differential
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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import CheckedFields, InputError, Positive
from softpad.sim._characteristic import ModuleCharacteristic


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
        if not (math.isfinite(self.supply_pa) and 0 <= self.supply_pa <= 500e3):
            raise InputError(
                f"supply pressure must be within 0..500 kPa, got {self.supply_pa / 1e3:g} kPa"
            )

    @property
    def gas_constant_rt(self) -> float:
        """R T of air per unit mass, m^2/s^2 (``p_atm / rho_atm``, isothermal)."""
        return self.atmosphere_pa / self.air_density_kg_m3


class ChamberBank:
    """The gas state of every channel, stepped together (vectorised with NumPy).

    Channels ``0 .. n_modules-1`` hold a module; further channels are unconnected ports,
    open to the atmosphere (gauge pressure 0).

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
        self._pending = 0  # held steps not yet applied to _amount and _pressure (see hold)
        self.loads_n = np.zeros(m)
        v0 = characteristic.volume_m3(np.zeros(m), np.zeros(m))
        self._amount = self.params.atmosphere_pa * (v0 + self.params.tubing_volume_m3)
        self._leak_m2 = np.zeros(m)
        self._leaking = False
        self._creep = np.zeros(m)  # creep volume of each membrane (Disturbances), m^3
        self._flat_m3 = v0  # volume under the flat, unloaded layer, m^3
        #: Longest time between exact pressure solves while nothing changes, seconds.
        self.resolve_s = 20e-3
        self._flow: NDArray[np.float64] | None = None
        self._rate = np.zeros(m)
        self._held = 0.0
        self._dt_cached = -1.0
        self._dn_dp = np.ones(m)
        self._flow_dt = np.zeros(m)
        self._rate_dt = np.zeros(m)
        #: Whether the last step solved the pressures exactly (module heights are updated then).
        self.solved = True
        #: Number of exact solves so far (identifies the current linear stretch).
        self.solve_count = 0
        #: Pressure change per step of every channel between solves, pascals.
        self.rate_dt_pa = np.zeros(n_channels)
        self._key: tuple[object, float] | None = None
        rho = self.params.air_density_kg_m3
        self._k = self.params.gas_constant_rt * math.sqrt(2 * rho)

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

    def set_leak(self, channel_index: int, area_m2: float) -> None:
        """Set the leak area Cd A of one module channel (0-based), m^2."""
        self._leak_m2[channel_index] = area_m2
        self._leaking = bool(self._leak_m2.any())

    def set_state(
        self, pressure_pa: NDArray[np.float64], loads_n: NDArray[np.float64] | None = None
    ) -> None:
        """Set module pressures (and loads) directly, e.g. to start already inflated."""
        p = np.asarray(pressure_pa, dtype=float)[: self.n_modules]
        if loads_n is not None:
            self.loads_n = np.asarray(loads_n, dtype=float).copy()
        v = self.characteristic.volume_m3(p, self.loads_n)
        self._pending = 0
        self._amount = (self.params.atmosphere_pa + p) * (v + self.params.tubing_volume_m3)
        self._pressure[: self.n_modules] = p

    def _orifice(
        self, area: NDArray[np.float64] | float, dp: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        return self._k * area * dp / np.sqrt(np.abs(dp) + self.params.laminar_pa)

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
        leaking = self._leaking
        if same_load is None:
            same_load = np.array_equal(loads_n, self.loads_n)
        if valve_key is None:
            valve_key = (inflate_open.tobytes(), deflate_open.tobytes())
        if same_load:
            if not any_open and not leaking:
                return False
            # Between exact solves, hold the flows of the last solve and advance p along
            # dp/dt = flow / (dn/dp): the gas time constants (> 0.1 s) are far longer than the
            # interval (<= resolve_s, 20 ms); any change of valves, load or supply forces a solve.
            if self.hold(dt_s, valve_key, supply_pa):
                return True
        self._sync()
        p = self._p_modules
        key = (valve_key, supply_pa)
        flow = None
        if any_open or leaking:
            flow = self._flows(p, inflate_open, deflate_open, supply_pa, any_open, leaking)
            self._amount = np.maximum(self._amount + flow * dt_s, 1e-12)
        if not same_load:
            self.loads_n = loads_n.copy()
        self._pressure[: self.n_modules] = self._solve(p.copy())
        self._key, self._held, self._flow = key, 0.0, flow
        self.solved = True
        self.solve_count += 1
        if flow is not None:
            self._rate = flow / self._dn_dp
            self._dt_cached = -1.0
        return True

    def _flows(
        self,
        p: NDArray[np.float64],
        inflate_open: NDArray[np.bool_],
        deflate_open: NDArray[np.bool_],
        supply_pa: float,
        any_open: bool,
        leaking: bool,
    ) -> NDArray[np.float64]:
        """Gas flow into every module through its open valves and its leak, amount/s."""
        flow = np.zeros(self.n_modules)
        if any_open:
            if inflate_open.any():
                flow[inflate_open] += self._orifice(
                    self.params.inflate_orifice_m2, supply_pa - p[inflate_open]
                )
            if deflate_open.any():
                flow[deflate_open] -= self._orifice(self.params.deflate_orifice_m2, p[deflate_open])
        if leaking:
            flow -= self._orifice(self._leak_m2, p)
        return flow

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
            if np.abs(step).max() < 1e-4:  # far below the sensors' resolution
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
        return v + self._creep, dv

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
            ``Cd A`` of every module's small leak to the atmosphere, m^2.
        creep_fraction, creep_time_s
            The creep volume relaxes towards ``creep_fraction`` of the stretched volume
            ``V(p, F) - V(0, 0)`` with this time constant.
        """
        self._sync()
        m = self.n_modules
        p = self._pressure[:m].copy()
        if leak_area_m2 > 0:
            leak = self._orifice(leak_area_m2, p) * elapsed_s
            self._amount = np.maximum(self._amount - leak, 1e-12)
        self._amount = self._amount * temperature_ratio
        stretched = self.characteristic.volume_m3(p, self.loads_n) - self._flat_m3
        target = creep_fraction * np.maximum(stretched, 0.0)
        self._creep = target + (self._creep - target) * math.exp(-elapsed_s / creep_time_s)
        self._pressure[:m] = self._solve(p)
        self._key, self._flow, self._held = None, None, 0.0
        self.solved = True
        self.solve_count += 1

    def heights_m(self) -> NDArray[np.float64]:
        """Top height of every module, metres."""
        return self.characteristic.height_m(self.pressure_pa[: self.n_modules], self.loads_n)

    def hold(self, dt_s: float, valve_key: object, supply_pa: float) -> bool:
        """The hot path of :meth:`step` while the loads are unchanged: True when the step was
        taken with the held flows (no solve due; nothing changed since the last solve).

        The held steps are only counted here; :attr:`amount` and :attr:`pressure_pa` apply
        them when read (``k`` held steps add ``k`` times the per-step change, computed as
        one product: the same state as adding it ``k`` times, to rounding).
        """
        held = self._held + dt_s
        if held > self.resolve_s or self._flow is None or self._key != (valve_key, supply_pa):
            return False
        self._held = held
        if dt_s != self._dt_cached:
            self._sync()
            self._dt_cached = dt_s
            self._flow_dt = self._flow * dt_s
            self._rate_dt = self._rate * dt_s
            self.rate_dt_pa = np.zeros(self.n_channels)
            self.rate_dt_pa[: self.n_modules] = self._rate_dt
        self._pending += 1
        self.solved = False
        return True

    def _sync(self) -> None:
        k = self._pending
        if k:
            self._pending = 0
            if k == 1:
                self._amount += self._flow_dt
                self._p_modules += self._rate_dt
            else:
                self._amount += self._flow_dt * k
                self._p_modules += self._rate_dt * k

    @property
    def amount(self) -> NDArray[np.float64]:
        """Amount of air of every module channel, ``(p_atm + p)(V + V_t)``, Pa m^3."""
        if self._pending:
            self._sync()
        return self._amount

    @property
    def pressure_pa(self) -> NDArray[np.float64]:
        """Gauge pressure of every channel, pascals (unconnected ports: 0)."""
        if self._pending:
            self._sync()
        return self._pressure
