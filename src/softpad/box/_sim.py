"""The plain simulated box: gas physics, valves and sensors (the heart of ``sim://``).

The box is the clock master: every :meth:`SimBox.read` advances the virtual clock by one
sample period, steps the world (objects, gripper) and the gas physics of every channel, and
returns the sensors' noisy readings, as fast as the computer allows. Everything is
deterministic for a given ``seed``. Its physical faults (a stuck valve, a leak, a lost supply)
and the slow disturbances of the gas are physics here; what acts on the readings or on the
link (sensor faults, the sensors' thermal zero shift, a lost link) and the wall-clock pacing
are layers around it (:mod:`softpad.box._sim_layers`), composed by ``sim://``
(:func:`softpad.box.open_sim_url`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.box._base import (
    _SET_P,
    _SET_S,
    _SET_T,
    Box,
    PressureFrame,
    ValveCommand,
    unchecked_frame,
)
from softpad.box._safety import SafetyGuard
from softpad.box._sim_faults import (
    DEFAULT_LEAK_M2,
    FAULT_KINDS,
    PHYSICAL_FAULTS,
    Fault,
    FaultSchedule,
)
from softpad.errors import InputError, check_range
from softpad.sim import (
    AnalyticWorld,
    ChamberBank,
    DisturbanceParams,
    Disturbances,
    ModuleCharacteristic,
    PneumaticParams,
    SensorBank,
    SensorParams,
    TabulatedCharacteristic,
    World,
    default_characteristic,
)

try:  # the exact solve in compiled code (src/softpad/box/_fastsim.c; make ext / pip install)
    import softpad.box._fastsim as _fastsim
except ImportError:  # pragma: no cover - no C compiler: the NumPy reference alone
    _fastsim = None  # type: ignore[assignment]

_new_frame = object.__new__

#: The shortest ramp whose rows' spans the sensors compute (``softpad.sim._sensor.SPAN_ROWS``;
#: tests/box/test_fastsim.py checks they agree).
SPAN_ROWS = 8

#: (inflation valve open, deflation valve open) for each command.
_VALVE_OPEN = {
    ValveCommand.CLOSED: (False, False),
    ValveCommand.INFLATE: (True, False),
    ValveCommand.DEFLATE: (False, True),
}


def _median(values: list[float]) -> float:
    """``statistics.median(values)`` (the same value: the middle of the sorted values, or
    the mean of the two middle ones), without its generic checks and conversions."""
    data = sorted(values)
    i = len(data) // 2
    return data[i] if len(data) % 2 else (data[i - 1] + data[i]) / 2


def _check_args(n_modules: int, channels: int, sample_rate_hz: float, seed: int) -> None:
    """Raise InputError naming a bad channel count, sample rate or seed."""
    if not isinstance(channels, int) or not n_modules <= channels <= 64:
        raise InputError(
            f"channels must be an integer from {n_modules} (modules of the pad) to 64, "
            f"got {channels!r}"
        )
    check_range("sample rate (sample_rate_hz)", sample_rate_hz, 1.0, 100e3, "Hz")
    try:
        s = int(seed)
    except (TypeError, ValueError):
        raise InputError(f"seed must be an integer >= 0, got {seed!r}") from None
    if s < 0:
        raise InputError(f"seed must be >= 0, got {seed!r}")


class CompiledChambers(ChamberBank):
    """The gas physics with its exact pressure solve, the start of each stretch and the module
    heights in compiled code.

    The same bits as :class:`~softpad.sim.ChamberBank` (the reference; tested on random valve
    schedules): the compiled kernel (:mod:`softpad.box._fastsim`) runs Newton's method with the
    tabulated characteristic's interpolation along the pressure, the load columns taken from
    the characteristic's own cache, and the relaxation rates and pressures of each stretch.
    Any other characteristic (for the solve and heights), a solve that does not converge in
    Newton's six steps, a stiff or collapsed stretch start or an input that is not finite runs
    the NumPy reference.
    """

    def __init__(
        self,
        n_channels: int,
        n_modules: int,
        characteristic: ModuleCharacteristic,
        params: PneumaticParams | None = None,
    ) -> None:
        super().__init__(n_channels, n_modules, characteristic, params)
        #: The compiled kernels (None: not built; the reference alone), fixed at construction.
        self._kernel = _fastsim
        tab = characteristic if isinstance(characteristic, TabulatedCharacteristic) else None
        self._tab = tab if _fastsim is not None and tab is not None else None
        #: The area over which a load beyond the table acts as a pressure, m^2 (a property of
        #: the characteristic that parses its metadata: read once).
        self._patch_m2 = self._tab.excess_load_area_m2 if self._tab is not None else 0.0

    def _columns(
        self, which: str
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None]:
        """The table's columns at the current loads, their slopes along the pressure and the
        pressure a load beyond the table takes off: the cache the reference fills
        (``TabulatedCharacteristic._along_pressure``), filled the same way."""
        tab = self._tab
        assert tab is not None
        f = self.loads_n
        key = f.tobytes()
        entry = tab._cache.get(which)
        if entry is None or entry[0] != key:
            entry = tab._cache[which] = self._load_columns(tab, which, f, key)
        return entry[1], entry[2], entry[3]

    def _load_columns(
        self, tab: TabulatedCharacteristic, which: str, f: NDArray[np.float64], key: bytes
    ) -> tuple[bytes, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None, Any]:
        """``TabulatedCharacteristic._load_columns``'s cache entry, its columns, slopes and
        pressure taken off by a load beyond the table from the kernel (the reference's where a
        load is not finite, or a module built before the kernel: ``make ext`` again)."""
        kernel = getattr(self._kernel, "columns", None)
        table = tab.volume_m3_table if which == "volume" else tab.height_m_table
        grid, m = tab.pressure_pa, f.size
        cols, slopes, drop = np.empty((grid.size, m)), np.empty((grid.size - 1, m)), np.empty(m)
        beyond = (
            0
            if kernel is None
            else kernel(f, tab.load_n, table, grid, self._patch_m2, cols, slopes, drop)
        )
        if not beyond:
            return tab._load_columns(which, f, key)
        return key, cols, slopes, drop if beyond == 2 else None, np.arange(m)

    def _solve(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        tab = self._tab
        if tab is None or not self.loads_n.shape == p.shape == (self.n_modules,):
            return super()._solve(p)
        cols, slopes, drop = self._columns("volume")
        out, dn_dp = np.empty_like(p), np.empty_like(p)
        creep = self._creep if self._creeping else None
        par = self.params
        amount = np.ascontiguousarray(self._amount, dtype=float)
        assert self._kernel is not None
        if self._kernel.solve(
            p, amount, cols, slopes, tab.pressure_pa, drop, creep,
            par.atmosphere_pa, par.tubing_volume_m3, out, dn_dp,
        ):  # fmt: skip
            self._dn_dp = dn_dp
            return out
        return super()._solve(p)

    def _relaxation(
        self, p: NDArray[np.float64], supply_pa: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        kernel = self._kernel
        if kernel is None:
            return super()._relaxation(p, supply_pa)
        mode = 1 if self._no_outflow else 2 if self._no_inflow else 0  # the reference's order
        flowing = None if self._all_flowing else self._flowing
        lam, p_eq = np.empty_like(p), np.empty_like(p)
        par = self.params
        if kernel.relax(
            p, self._eq, flowing, self._a_in, self._a_out, self._dn_dp, supply_pa,
            par.laminar_pa, self._k, mode, lam, p_eq,
        ):  # fmt: skip
            return lam, p_eq
        return super()._relaxation(p, supply_pa)

    def _no_crossing(
        self, p: NDArray[np.float64], p_start: NDArray[np.float64], p_eq: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        if self._kernel is not None and not self._kernel.crosses(p, p_start, p_eq):
            return p  # the reference's test, without its three array operations
        return super()._no_crossing(p, p_start, p_eq)

    def _start_stretch(
        self,
        dt_s: float,
        inflate_open: NDArray[np.bool_],
        deflate_open: NDArray[np.bool_],
        supply_pa: float,
        valve_key: object,
    ) -> None:
        """The reference's stretch (:meth:`ChamberBank._start_stretch`, which runs a stiff or
        collapsed start) with its pressures written by the kernel; the decay ``exp(-lambda t)``
        by NumPy (whose exp is not the C library's)."""
        args = (dt_s, inflate_open, deflate_open, supply_pa, valve_key)
        kernel = self._kernel
        if kernel is None:
            return super()._start_stretch(*args)
        self._update_equilibrium(inflate_open, deflate_open, supply_pa, valve_key)
        p0 = self._p_modules.copy()
        lam, p_eq = self._relaxation(p0, supply_pa)
        theta = self.relaxation_per_stretch
        lam_max = float(np.maximum.reduce(lam))
        collapsed = not np.minimum.reduce(p0) >= 0.0 and bool(
            np.any((p0 < 0.0) & (p_eq > p0) & (lam > 0.0))
        )
        if lam_max * dt_s > theta or collapsed:
            return super()._start_stretch(*args)
        self._valve_key, self._supply, self._stretch_dt = valve_key, supply_pa, dt_s
        steps = self._step_times(dt_s)
        if lam_max * steps[-1, 0] > theta:
            steps = steps[: max(1, int(theta / (lam_max * dt_s)))]
        decay = np.exp(-lam * steps)
        path = np.zeros((decay.shape[0], self.n_channels))
        rows = kernel.ramp(p0, p_eq, decay, lam, self.resolve_pa, path)
        self._path, self._pos, self._applied = path[:rows], 1, 0
        self._p0, self._n0, self._c0, self._p_eq = p0, self._amount.copy(), self._dn_dp, p_eq
        return None

    def heights_m(self) -> NDArray[np.float64]:
        tab = self._tab
        p = self.pressure_pa[: self.n_modules]
        if tab is None or self.loads_n.shape != p.shape:
            return super().heights_m()
        cols, slopes, drop = self._columns("height")
        out = np.empty_like(p)
        assert self._kernel is not None
        if self._kernel.interp(p, cols, slopes, tab.pressure_pa, drop, out):
            return out
        return super().heights_m()


class CompiledSensors(SensorBank):
    """The sensors with the readings of each stretch of the gas physics computed in compiled
    code (:func:`softpad.box._fastsim.readings`): the same readings as
    :class:`~softpad.sim.SensorBank` (the reference), which computes them where a value is
    not finite or a range bound is zero."""

    def __init__(
        self,
        n_channels: int,
        dt_s: float,
        params: SensorParams,
        rng: np.random.Generator,
    ) -> None:
        super().__init__(n_channels, dt_s, params, rng)
        self._kernel = _fastsim

    def sample(
        self, true_pa: NDArray[np.float64], supply_pa: float, changed: bool = True
    ) -> tuple[NDArray[np.float64], float]:
        """:meth:`SensorBank.sample`, the reading of changed pressures from the kernel (the
        same bits; an unchanged box's block of readings as the reference computes it)."""
        reading = getattr(self._kernel, "reading", None)  # None: a module built before it
        if not changed or reading is None:
            return super().sample(true_pa, supply_pa, changed)
        if self._i >= self.block:
            self._refill()
            self._static = None
        i = self._i
        out = np.empty(self.n)
        if not reading(true_pa, self._noise, i, self._q, self._inv_q, self._lo, self._hi, out):
            return super().sample(true_pa, supply_pa, changed)  # the same block, row i
        self._i = i + 1
        self._ramp = None
        self._ramp_end = -1
        self._same = 0
        self._static = None
        self.span = None
        return out, supply_pa + self._supply_noise[i]

    def sample_path(
        self, path: NDArray[np.float64], row: int, key: int, supply_pa: float
    ) -> tuple[NDArray[np.float64], float]:
        """:meth:`SensorBank.sample_path`, line for line, with the ramp's readings and their
        rows' spans from the kernel."""
        if self._kernel is None:
            return super().sample_path(path, row, key, supply_pa)
        hit = self.next_on_ramp(key, supply_pa)
        if hit is not None:
            return hit
        if self._i >= self.block:
            self._refill()
        i = self._i
        k = min(path.shape[0] - row, self.block - i)
        ramp = np.empty((k, path.shape[1]))
        spans = self._kernel.readings(
            path[row : row + k], self._noise[i : i + k], self._q, self._inv_q, self._lo,
            self._hi, ramp,
        )  # fmt: skip
        if spans is None:
            return super().sample_path(path, row, key, supply_pa)
        self._i = i + 1
        self._same = 0
        self._static = None
        ramp.flags.writeable = False
        self._ramp, self._ramp_key, self._ramp_start = ramp, key, i
        self._ramp_end = i + k
        self._ramp_next = i + 1
        reading = ramp[0]
        if k >= SPAN_ROWS:
            self._ramp_lo, self._ramp_hi = spans
            self.span = (reading, self._ramp_lo[0], self._ramp_hi[0])
        else:  # as the reference: too short a ramp to pay for the reductions
            self._ramp_lo, self.span = None, None
        return reading, supply_pa + self._supply_noise[i]


class SimBox(Box):
    """A simulated pneumatic box driving the modules of a world: the plain physical box.

    Gas physics, valves (with their physical faults: stuck, leaking, no supply) and the
    sensors with their noise. What acts on the readings or the link (sensor NaN and dropout,
    the sensors' thermal zero shift, a lost link) and the wall-clock pacing are layers around
    it: :func:`~softpad.box.compose_sim_box` adds them in their order, as ``sim://`` does.

    Parameters
    ----------
    world
        What loads the modules (an :class:`~softpad.sim.AnalyticWorld` by default); module k
        of its layout is channel k.
    channels
        Number of channels (8 like the thesis's box); channels beyond the pad's modules are
        unconnected ports open to the atmosphere.
    sample_rate_hz
        Frames per second, hertz (100 Hz by default).
    seed
        Seed of the sensor noise and offsets.
    characteristic
        Module characteristic (:func:`~softpad.sim.default_characteristic` by default).
    pneumatics
        Gas and valve parameters.
    sensor
        Sensor parameters.
    initial_pressure_pa
        Start with every module at this gauge pressure (0: deflated).
    disturbances
        Slow temperature swing, membrane creep and small leaks of the gas
        (:class:`~softpad.sim.DisturbanceParams`; None: off); the sensors' thermal zero shift
        they also give is the :class:`~softpad.box.SensorZeroShift` layer.
    """

    def __init__(
        self,
        world: World | None = None,
        channels: int = 8,
        sample_rate_hz: float = 100.0,
        seed: int = 0,
        characteristic: ModuleCharacteristic | None = None,
        pneumatics: PneumaticParams | None = None,
        sensor: SensorParams | None = None,
        initial_pressure_pa: float = 0.0,
        disturbances: DisturbanceParams | None = None,
    ) -> None:
        super().__init__()
        self.world: World = world if world is not None else AnalyticWorld()
        # worlds that weight loads by the FEM response evaluate it at the chambers' pressure
        self._operate = getattr(self.world, "set_operating_pressure", lambda p: None)
        n_mod = self.world.layout.n_modules
        _check_args(n_mod, channels, sample_rate_hz, seed)
        self._channels = channels
        self._rate = float(sample_rate_hz)
        self._dt = 1.0 / self._rate
        self.seed = int(seed)
        self.characteristic = (
            characteristic if characteristic is not None else default_characteristic()
        )
        self.pneumatics = pneumatics or PneumaticParams()
        self.sensor_params = sensor or SensorParams()
        rng = np.random.default_rng(self.seed)
        self.chambers = CompiledChambers(channels, n_mod, self.characteristic, self.pneumatics)
        if initial_pressure_pa:
            self._start_inflated(float(initial_pressure_pa))
        self.sensors = CompiledSensors(channels, self._dt, self.sensor_params, rng)
        self._setup_disturbances(disturbances, rng)
        self._n_mod = n_mod
        self._valve_count = 0
        self._cmd_inf = np.zeros(n_mod, dtype=bool)
        self._cmd_def = np.zeros(n_mod, dtype=bool)
        self._stuck: dict[int, ValveCommand] = {}
        self._inf = self._cmd_inf.copy()
        self._def = self._cmd_def.copy()
        self._any_open = False
        self._t = 0.0
        self._heights = self.chambers.heights_m()
        self._loads_key = self.chambers.loads_n.tobytes()
        self._supply_true = self.pneumatics.supply_pa
        self._faults = FaultSchedule()
        self._leaking = False
        #: The outermost layer around this box found passing every frame on unchanged (it
        #: then lets this box read and check the frames itself; softpad.box._sim_layers).
        self._passed_by: object = None
        #: The compiled kernels (None: not built), and the frame along a stretch in one call
        #: for the current guard (made by the first read; None: the Python path alone).
        self._kernel = _fastsim
        self._frames: Any = None
        self._frames_for: SafetyGuard | None = None

    def _start_inflated(self, pressure_pa: float) -> None:
        """Every module at ``pressure_pa`` under the world's loads (0..5 kPa)."""
        if not (0 <= pressure_pa <= 5e3):
            raise InputError(
                f"initial pressure must be within 0..5 kPa, got {pressure_pa / 1e3:g} kPa"
            )
        self._operate(pressure_pa)
        n_mod = self.world.layout.n_modules
        self.chambers.set_state(np.full(n_mod, pressure_pa), self.world.module_loads_n())

    def _setup_disturbances(
        self, params: DisturbanceParams | None, rng: np.random.Generator
    ) -> None:
        """The slow disturbances (None: off) and the leak area that loses their rate at p0.

        Drawn from the sensors' generator right after them (the random phase of the room's
        temperature, the sensors' thermal coefficients), before any noise block."""
        self.disturbances = None if params is None else Disturbances(params, self._channels, rng)
        self._dist_leak_m2 = 0.0
        if self.disturbances is not None:
            ch, p0 = self.chambers, np.array([thesis.P0_PA])
            char = self.characteristic
            v = float(char.volume_m3(p0, np.zeros(1))[0]) + self.pneumatics.tubing_volume_m3
            dv = float(char.volume_slope_m3_pa(p0, np.zeros(1))[0])
            dn_dp = v + (self.pneumatics.atmosphere_pa + thesis.P0_PA) * dv
            self._dist_leak_m2 = self.disturbances.leak_area_m2(
                dn_dp, ch.orifice_gain, self.pneumatics.laminar_pa
            )

    def _disturb(self, t: float) -> None:
        """Apply the slow disturbances up to ``t`` (every ``update_s``)."""
        dist = self.disturbances
        assert dist is not None
        ratio, elapsed = dist.advance(t)
        p = dist.params
        self.chambers.disturb(ratio, elapsed, self._dist_leak_m2, p.creep_fraction, p.creep_time_s)

    # --- Box API --------------------------------------------------------------------
    @property
    def channels(self) -> int:
        return self._channels

    @property
    def sample_rate_hz(self) -> float:
        return self._rate

    @property
    def simulated(self) -> bool:
        return True

    @property
    def time_s(self) -> float:
        """Virtual time of the last frame, seconds."""
        return self._t

    @property
    def true_pressures_pa(self) -> NDArray[np.float64]:
        """Noise-free gauge pressure of every channel, pascals (simulation only)."""
        return self.chambers.pressure_pa.copy()

    @property
    def module_heights_m(self) -> NDArray[np.float64]:
        """Top height of every module, metres (simulation only)."""
        return self._heights.copy()

    def between_ticks(self) -> None:
        """Work that may run between two reads instead of inside one (a box daemon calls it
        after each tick): the next block of sensor noise, drawn before it is needed (the
        same values as drawn on demand)."""
        self.sensors.refill_if_due()

    def read(self) -> PressureFrame:
        """Read one frame (:meth:`Box.read`); the guard is given the readings' lowest and
        highest value where the sensors computed them for a block of frames at once."""
        if self._closed:
            self._check_open()  # raises
        guard = self._guard if self._guard is not None else self.safety
        if self._frames_for is not guard:  # the first read, or a new guard (new limits)
            self._frames_for, self._frames = guard, self._new_frames(guard)
        frames = self._frames
        if frames is None:
            return self._checked(self._read(), guard)
        # _read's step, inlined: a shared helper costs ~2 % of the every-valve-open bench
        # (355x -> 347x); keep the two in step
        dt = self._dt
        t = self._t + dt
        self._t = t
        if t >= self._faults.next_s:
            self._activate_faults()
        world = self.world
        world.step(dt, self._heights)
        loads = world.module_loads_n()
        key = loads.tobytes()
        dist = self.disturbances
        if key == self._loads_key and (dist is None or t < dist.next_s):
            # a step along the stretch, its reading, the frame and the guard's usual decision
            # in one compiled call; None: not the usual frame, nothing changed
            frame = frames.next(t, dt, self._valve_count, self._supply_true)
            if frame is not None:
                return frame  # type: ignore[no-any-return]
        return self._checked(self._after_step(t, dt, loads, key), guard)

    def _checked(self, frame: PressureFrame, guard: SafetyGuard) -> PressureFrame:
        """``frame`` after the guard's check (the channels it trips vented)."""
        span = self.sensors.span
        if span is not None and span[0] is frame.pressures_pa:  # not replaced by a layer
            new = guard.check_span(frame.t_s, span[0], span[1], span[2])
        else:
            new = guard.check(frame.t_s, frame.pressures_pa)
        for ch in new:
            self._vent(ch)
        return frame

    def _new_frames(self, guard: SafetyGuard) -> Any:
        """The compiled frame along a stretch (:class:`softpad.box._fastsim.Frames`) for
        ``guard``; None without the kernel, or where a subclass reads its own way."""
        kernel = getattr(self._kernel, "Frames", None)
        if kernel is None or type(self)._read is not SimBox._read:
            return None
        slots = (PressureFrame.__dict__[n] for n in ("t_s", "pressures_pa", "supply_pa"))
        return kernel(self.chambers, self.sensors, guard, PressureFrame, *slots)

    def _read(self) -> PressureFrame:
        dt = self._dt
        t = self._t + dt
        self._t = t
        if t >= self._faults.next_s:
            self._activate_faults()
        world = self.world
        world.step(dt, self._heights)
        loads = world.module_loads_n()
        return self._after_step(t, dt, loads, loads.tobytes())

    def _after_step(
        self, t: float, dt: float, loads: NDArray[np.float64], key: bytes
    ) -> PressureFrame:
        """The frame at ``t`` once the world has stepped (its ``loads``, their bytes ``key``)."""
        # the loads equal those of the last step (the chambers' loads_n) iff their bytes do;
        # far cheaper than np.array_equal on the hot path
        dist = self.disturbances
        chambers = self.chambers
        if (
            key == self._loads_key
            and (dist is None or t < dist.next_s)
            and (self._any_open or self._leaking or chambers._path is not None)
            and chambers.hold(dt, self._valve_count, self._supply_true)
        ):  # the hot path of an inflating box: a step along the stretch of the gas physics
            sensors = self.sensors
            hit = sensors.next_on_ramp(chambers.solve_count, self._supply_true)
            if hit is None:  # _sense's path, as the step changed the pressures
                path = chambers._path
                assert path is not None  # hold() stepped along it
                hit = sensors.sample_path(
                    path, chambers._pos - 1, chambers.solve_count, self._supply_true
                )
            frame = _new_frame(PressureFrame)  # unchecked_frame, inline
            _SET_T(frame, t)
            _SET_P(frame, hit[0])
            _SET_S(frame, hit[1])
            return frame
        values, supply = self._sense(self._step_physics(t, dt, loads, key))
        return unchecked_frame(t, values, supply)  # t is finite, values 1-D

    def _step_physics(self, t: float, dt: float, loads: NDArray[np.float64], key: bytes) -> bool:
        """Step the gas physics to ``t`` under the world's ``loads`` (their bytes ``key``; the
        world stepped already); True when the true pressures changed."""
        chambers = self.chambers
        same_load = key == self._loads_key
        if not same_load:
            self._loads_key = key
        dist = self.disturbances
        disturbed = dist is not None and t >= dist.next_s
        if disturbed:
            self._disturb(t)
        if not same_load:
            changed = True
        elif self._any_open or self._leaking or chambers.path is not None:
            # a step along the stretch of the gas physics (a stretch left running by closing
            # every valve ends with an exact solve)
            if chambers.hold(dt, self._valve_count, self._supply_true):
                return True
            changed = True
        else:
            changed = False
        if changed:
            changed = chambers.step(
                dt,
                self._inf,
                self._def,
                loads,
                self._supply_true,
                self._any_open,
                same_load=same_load,
                valve_key=self._valve_count,
            )
        return changed or disturbed

    def _sense(self, changed: bool) -> tuple[NDArray[np.float64], float]:
        """The sensors' readings of the true pressures."""
        chambers, sensors, supply_true = self.chambers, self.sensors, self._supply_true
        if not changed:
            values, supply = sensors.sample(chambers.pressure_pa, supply_true, False)
        else:
            if chambers.solved:  # heights follow the exact solves (every <= 20 ms)
                self._heights = chambers.heights_m()
                self._operate(_median(chambers.pressure_pa[: self._n_mod].tolist()))
            path = chambers.path
            if path is None:  # a load change of sealed modules
                values, supply = sensors.sample(chambers.pressure_pa, supply_true, True)
            else:  # along a stretch of the gas physics: readings precomputed for it
                hit = sensors.next_on_ramp(chambers.solve_count, supply_true)
                if hit is None:
                    hit = sensors.sample_path(
                        path, chambers.position - 1, chambers.solve_count, supply_true
                    )
                values, supply = hit
        return values, supply

    def firmware_vent(self, channel: int) -> None:
        """Open the deflation valve of ``channel`` as the box's own firmware does when its guard
        trips with no client to command it (:class:`~softpad.box.Unreachable`): no command,
        so :attr:`valves` (the commanded states) stays as it was."""
        self._apply_valve(channel, ValveCommand.DEFLATE)

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        if channel > self._n_mod:
            return  # unconnected port: nothing to drive
        self._cmd_inf[channel - 1], self._cmd_def[channel - 1] = _VALVE_OPEN[command]
        self._update_effective()

    def _update_effective(self) -> None:
        self._valve_count += 1
        inf, dfl = self._cmd_inf.copy(), self._cmd_def.copy()
        for ch, state in self._stuck.items():
            if state is ValveCommand.INFLATE:
                inf[ch - 1] = True
            elif state is ValveCommand.DEFLATE:
                dfl[ch - 1] = True
            else:
                inf[ch - 1] = dfl[ch - 1] = False
        self._inf, self._def = inf, dfl
        self._any_open = bool(inf.any() or dfl.any())

    def _close(self) -> None:
        pass

    # --- faults ---------------------------------------------------------------------
    def inject_fault(self, fault: Fault) -> None:
        """Schedule a physical fault (``stuck``, ``leak``, ``supply_loss``; it starts at
        ``fault.at_s`` of virtual time, or at once).

        Sensor faults and a lost link act on what leaves the box: the layers of
        :func:`~softpad.box.compose_sim_box` take them (a ``sim://`` box has them).
        """
        if fault.channel is not None:
            self.check_channel(fault.channel)
            if fault.kind in ("stuck", "leak") and fault.channel > self._n_mod:
                raise InputError(
                    f"channel {fault.channel} has no module: a {fault.kind} fault needs one"
                )
        if fault.kind not in PHYSICAL_FAULTS:
            raise InputError(
                f"a {fault.kind} fault acts on the readings or the link, not the physics: "
                f"inject it into the box's layers (softpad.box.compose_sim_box, as sim:// does)"
            )
        self._faults.add(fault)
        if fault.at_s <= self._t:
            self._activate_faults()

    def _activate_faults(self) -> None:
        for f in self._faults.due(self._t):
            ch = f.channel
            if f.kind == "stuck" and ch is not None:
                self._stuck[ch] = ValveCommand.parse(str(f.arg))
                self._update_effective()
            elif f.kind == "leak" and ch is not None:
                self.chambers.set_leak(
                    ch - 1, float(f.arg) if f.arg is not None else DEFAULT_LEAK_M2
                )
                self._leaking = True
            elif f.kind == "supply_loss":
                self._supply_true = 0.0


__all__ = ["DEFAULT_LEAK_M2", "FAULT_KINDS", "Fault", "SimBox"]
