"""The simulated box (``sim://``), the default back-end.

The box is the clock master: every :meth:`SimBox.read` advances the virtual clock by one
sample period, steps the world (objects, gripper) and the gas physics of every channel, and
returns the sensors' noisy readings. It runs as fast as the computer allows, or at real time
on request (``realtime=1``). Everything is deterministic for a given ``seed``.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.errors import InputError, check_range
from softpad.layout import PadLayout, parse_layout
from softpad.sim import (
    AnalyticCharacteristic,
    AnalyticWorld,
    ChamberBank,
    DisturbanceParams,
    Disturbances,
    ModuleCharacteristic,
    PneumaticParams,
    SensorBank,
    SensorParams,
    SimGripper,
    World,
    default_characteristic,
    get_object,
)

#: (inflation valve open, deflation valve open) for each command.
_VALVE_OPEN = {
    ValveCommand.CLOSED: (False, False),
    ValveCommand.INFLATE: (True, False),
    ValveCommand.DEFLATE: (False, True),
}

#: Fault kinds the simulated box can inject.
FAULT_KINDS = ("nan", "dropout", "stuck", "leak", "supply_loss", "disconnect")

#: Default leak effective area (Cd A) when a leak is given without size, m^2.
DEFAULT_LEAK_M2 = 1.0e-8


@dataclass(frozen=True)
class Fault:
    """A fault injected into the simulated box.

    Parameters
    ----------
    kind
        ``"nan"`` (sensor reads NaN), ``"dropout"`` (sensor wire broken: reads its lower rail),
        ``"stuck"`` (valves stuck in state ``arg``: closed/inflate/deflate), ``"leak"`` (an
        orifice to atmosphere of ``Cd A = arg`` m^2), ``"supply_loss"`` (supply drops to 0),
        ``"disconnect"`` (the box stops answering: reads and valve commands raise
        :class:`ConnectionLost`; its physics and its own safety guard go on with every read
        tried, and the valves stay as they were).
    channel
        1-based channel for channel faults, None for box-wide ones.
    at_s
        Virtual time at which the fault starts, seconds.
    arg
        Stuck state (str) or leak area (float, m^2).
    """

    kind: str
    channel: int | None = None
    at_s: float = 0.0
    arg: str | float | None = None

    def __post_init__(self) -> None:
        if self.kind not in FAULT_KINDS:
            raise InputError(f"unknown fault {self.kind!r}; known faults: {', '.join(FAULT_KINDS)}")
        if self.kind in ("nan", "dropout", "stuck", "leak") and self.channel is None:
            raise InputError(f"fault {self.kind!r} needs a channel")
        if not math.isfinite(self.at_s) or self.at_s < 0:
            raise InputError(f"fault time must be >= 0 s, got {self.at_s!r}")
        if self.kind == "stuck":
            ValveCommand.parse(str(self.arg))
        if self.kind == "leak" and self.arg is not None:
            a = float(self.arg)  # type: ignore[arg-type]
            if not (math.isfinite(a) and 0 < a <= 1e-5):
                raise InputError(f"leak area must be > 0 and at most 10 mm^2, got {a * 1e6:g} mm^2")

    @classmethod
    def parse(cls, text: str) -> Fault:
        """Parse ``KIND[:CHANNEL[:ARG]][@T_S]``, e.g. ``stuck:3:inflate@2``, ``leak:2:0.02``
        (leak area in mm^2), ``supply_loss@5``."""
        spec, _, at = text.partition("@")
        fields = spec.split(":")
        kind = fields[0].strip()
        try:
            at_s = float(at) if at else 0.0
            if kind in ("supply_loss", "disconnect"):
                if len(fields) > 1:
                    raise ValueError
                return cls(kind, None, at_s)
            channel = int(fields[1]) if len(fields) > 1 else None
            arg: str | float | None = None
            if kind == "stuck":
                arg = fields[2] if len(fields) > 2 else "inflate"
            elif kind == "leak":
                arg = float(fields[2]) * 1e-6 if len(fields) > 2 else DEFAULT_LEAK_M2
            elif len(fields) > 2:
                raise ValueError
        except ValueError:
            raise InputError(
                f"malformed fault {text!r}; use KIND[:CHANNEL[:ARG]][@T_S], e.g. stuck:3:inflate@2"
            ) from None
        return cls(kind, channel, at_s, arg)


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


class SimBox(Box):
    """A simulated pneumatic box driving the modules of a world.

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
    realtime
        Pace :meth:`read` to the wall clock.
    disturbances
        Slow temperature swing, membrane creep, small leaks and the sensors' thermal zero
        shift (:class:`~softpad.sim.DisturbanceParams`; None: off).
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
        realtime: bool = False,
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
        self.chambers = ChamberBank(channels, n_mod, self.characteristic, self.pneumatics)
        if initial_pressure_pa:
            self._start_inflated(float(initial_pressure_pa))
        self.sensors = SensorBank(channels, self._dt, self.sensor_params, rng)
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
        self._faults: list[Fault] = []
        self._next_fault_s = math.inf
        self._nan = np.zeros(channels, dtype=bool)
        self._dropout = np.zeros(channels, dtype=bool)
        self._bad_sensor = False
        self._leaking = False
        self._disconnected = False
        self.realtime = bool(realtime)
        self._wall0: float | None = None

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
        """The slow disturbances (None: off) and the leak area that loses their rate at p0."""
        self.disturbances = None if params is None else Disturbances(params, self._channels, rng)
        self._sensor_shift: NDArray[np.float64] | None = None
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
        self._sensor_shift = dist.sensor_shift_pa()

    # --- Box API --------------------------------------------------------------------
    @property
    def channels(self) -> int:
        return self._channels

    @property
    def sample_rate_hz(self) -> float:
        return self._rate

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

    def _read(self) -> PressureFrame:
        dt = self._dt
        t = self._t + dt
        self._t = t
        if t >= self._next_fault_s:
            self._activate_faults()
        values, supply = self._sense(self._step_physics(t, dt))
        if self._disconnected:
            self._unreachable(t, values)
        if self.realtime:
            now = time.perf_counter()
            if self._wall0 is None:
                self._wall0 = now - t
            wait = self._wall0 + t - now
            if wait > 0:
                time.sleep(wait)
        return PressureFrame(t, values, supply)

    def _step_physics(self, t: float, dt: float) -> bool:
        """Step the world and the gas physics to ``t``; True when the true pressures changed."""
        world = self.world
        world.step(dt, self._heights)
        loads = world.module_loads_n()
        chambers = self.chambers
        # the loads equal those of the last step (the chambers' loads_n) iff their bytes do;
        # far cheaper than np.array_equal on the hot path
        key = loads.tobytes()
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
            # the hot path of an inflating box: a step along the stretch of the gas physics
            # (a stretch left running by closing every valve ends with an exact solve)
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
        """The sensors' readings of the true pressures (and the sensor faults)."""
        chambers, sensors, supply_true = self.chambers, self.sensors, self._supply_true
        if not changed:
            values, supply = sensors.sample(chambers.pressure_pa, supply_true, False)
        else:
            if chambers.solved:  # heights follow the exact solves (every <= 20 ms)
                self._heights = chambers.heights_m()
                self._operate(statistics.median(chambers.pressure_pa[: self._n_mod].tolist()))
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
        if self._sensor_shift is not None:
            values = values + self._sensor_shift
        if self._bad_sensor:
            values = values.copy()
            values[self._dropout] = self.sensor_params.range_min_pa
            values[self._nan] = np.nan
        return values, supply

    def _unreachable(self, t: float, values: NDArray[np.float64]) -> None:
        """A disconnected box: its physics and its own guard go on (the box's firmware vents
        an over-pressure whatever the link does), but no frame reaches the client."""
        for ch in self.safety.check(t, values):
            if ch <= self._n_mod:
                self._cmd_inf[ch - 1], self._cmd_def[ch - 1] = _VALVE_OPEN[ValveCommand.DEFLATE]
                self._update_effective()
        raise ConnectionLost(f"the simulated box stopped answering at t = {t:.3f} s")

    def _apply_valve(self, channel: int, command: ValveCommand) -> None:
        if self._disconnected:
            raise ConnectionLost(
                f"the simulated box stopped answering at t = {self._t:.3f} s: "
                f"channel {channel} not commanded"
            )
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
        """Schedule a fault (it starts at ``fault.at_s`` of virtual time, or at once)."""
        if fault.channel is not None:
            self.check_channel(fault.channel)
            if fault.kind in ("stuck", "leak") and fault.channel > self._n_mod:
                raise InputError(
                    f"channel {fault.channel} has no module: a {fault.kind} fault needs one"
                )
        self._faults.append(fault)
        self._next_fault_s = min(self._next_fault_s, fault.at_s)
        if fault.at_s <= self._t:
            self._activate_faults()

    def _activate_faults(self) -> None:
        pending = []
        for f in self._faults:
            if f.at_s > self._t + 1e-12:
                pending.append(f)
                continue
            ch = f.channel
            if f.kind == "nan" and ch is not None:
                self._nan[ch - 1] = True
                self._bad_sensor = True
            elif f.kind == "dropout" and ch is not None:
                self._dropout[ch - 1] = True
                self._bad_sensor = True
            elif f.kind == "stuck" and ch is not None:
                self._stuck[ch] = ValveCommand.parse(str(f.arg))
                self._update_effective()
            elif f.kind == "leak" and ch is not None:
                self.chambers.set_leak(
                    ch - 1, float(f.arg) if f.arg is not None else DEFAULT_LEAK_M2
                )
                self._leaking = True
            elif f.kind == "supply_loss":
                self._supply_true = 0.0
            elif f.kind == "disconnect":
                self._disconnected = True
        self._faults = pending
        self._next_fault_s = min((f.at_s for f in pending), default=math.inf)

    def close_valves(self) -> None:
        """Close every valve; a disconnected box cannot be reached (its valves stay as they are)."""
        if self._disconnected:
            return
        super().close_valves()

    def close_inflation(self) -> None:
        """Close inflation; a disconnected box cannot be reached (its valves stay as they are)."""
        if self._disconnected:
            return
        super().close_inflation()


_SIM_OPTIONS = {
    "seed": "integer seed of the sensor noise (0)",
    "channels": "number of channels (8)",
    "rate_hz": "frames per second (100)",
    "layout": "pad layout RxC (2x3)",
    "pitch_mm": "module pitch in mm (45)",
    "realtime": "1 to pace reads to the wall clock (0)",
    "inflated_kpa": "start with every module at this pressure (0: deflated)",
    "supply_kpa": "regulated supply pressure (10)",
    "noise": "0 for an ideal noise-free sensor (1)",
    "disturbances": "1 for slow temperature swing, membrane creep, small leaks and sensors' "
    "thermal zero shift (0)",
    "characteristic": "analytic, or default (the FEM table when packaged)",
    "gripper": "gripper mounting 10/4, 6/2 or 4/0 (10/4)",
    "object": "name of a catalogue object placed on the pad at start",
    "faults": "comma-separated KIND[:CHANNEL[:ARG]][@T_S], e.g. leak:2:0.01,stuck:3:inflate@1",
}


def _num(options: dict[str, str], key: str, default: float) -> float:
    if key not in options:
        return default
    try:
        v = float(options[key])
    except ValueError:
        raise InputError(f"sim:// option {key}={options[key]!r} must be a number") from None
    if not math.isfinite(v):
        raise InputError(f"sim:// option {key}={options[key]!r} must be finite")
    return v


def _int(options: dict[str, str], key: str, default: int) -> int:
    if key not in options:
        return default
    try:
        return int(options[key])
    except ValueError:
        raise InputError(f"sim:// option {key}={options[key]!r} must be an integer") from None


def open_sim_url(location: str, options: dict[str, str]) -> SimBox:
    """Build a :class:`SimBox` from a ``sim://`` URL's options (see ``_SIM_OPTIONS``)."""
    if location.strip("/"):
        raise InputError(f"sim:// takes no host or path, got {location!r} (options go after '?')")
    unknown = sorted(set(options) - set(_SIM_OPTIONS))
    if unknown:
        raise InputError(
            f"unknown sim:// option {unknown[0]!r}; known options: {', '.join(_SIM_OPTIONS)}"
        )
    layout = parse_layout(options.get("layout", "2x3")) if "layout" in options else PadLayout()
    if "pitch_mm" in options:
        layout = PadLayout(layout.rows, layout.cols, _num(options, "pitch_mm", 45.0) / 1e3)
    gripper = SimGripper.mounting(options.get("gripper", "10/4"))
    world = AnalyticWorld(layout, gripper)
    if "object" in options:
        world.place_object(get_object(options["object"]))
    char_name = options.get("characteristic", "default")
    if char_name == "analytic":
        characteristic: ModuleCharacteristic = AnalyticCharacteristic()
    elif char_name == "default":
        characteristic = default_characteristic()
    else:
        raise InputError(
            f"sim:// option characteristic={char_name!r} must be 'analytic' or 'default'"
        )
    noise = options.get("noise", "1")
    if noise not in ("0", "1"):
        raise InputError(f"sim:// option noise={noise!r} must be 0 or 1")
    disturb = options.get("disturbances", "0")
    if disturb not in ("0", "1"):
        raise InputError(f"sim:// option disturbances={disturb!r} must be 0 or 1")
    realtime = options.get("realtime", "0")
    if realtime not in ("0", "1"):
        raise InputError(f"sim:// option realtime={realtime!r} must be 0 or 1")
    supply_pa = _num(options, "supply_kpa", 10.0) * 1e3
    box = SimBox(
        world,
        channels=_int(options, "channels", 8),
        sample_rate_hz=_num(options, "rate_hz", 100.0),
        seed=_int(options, "seed", 0),
        characteristic=characteristic,
        pneumatics=PneumaticParams(supply_pa=supply_pa),
        sensor=SensorParams() if noise == "1" else SensorParams.ideal(),
        initial_pressure_pa=_num(options, "inflated_kpa", 0.0) * 1e3,
        realtime=realtime == "1",
        disturbances=DisturbanceParams() if disturb == "1" else None,
    )
    for text in filter(None, (s.strip() for s in options.get("faults", "").split(","))):
        box.inject_fault(Fault.parse(text))
    return box
