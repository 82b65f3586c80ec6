"""Slow disturbances of a sealed pad: room temperature, membrane creep, a small leak, and the
sensors' thermal zero shift (docs/box-and-simulator.md, section "Disturbances", gives the figures
and where each comes from).

They act on the gas state of :class:`~softpad.sim.ChamberBank` once every ``update_s`` of
simulated time (each is far slower than that):

* **temperature**: the room's air temperature swings by ``temperature_amplitude_k`` with a
  period ``temperature_period_s`` (a thermostat's cycle; one random phase per box, the same for
  every channel: the whole pad drifts together). At a fixed amount of air ``(p_atm + p)(V +
  V_t) = n R T``, so the state ``n R T`` scales with ``T``; the membrane takes most of the
  expansion (its compliance is 35 times the gas's), a sealed module at 1.1 kPa moves by about
  10 Pa/K;
* **creep**: the stretched silicone slowly gives, adding a volume that relaxes towards
  ``creep_fraction`` of the membrane's stretched volume ``V(p, F) - V_gap`` with the time
  constant ``creep_time_s`` (a first-order Kelvin-Voigt element); a sealed module's pressure
  falls as it does, and recovers after a deflation;
* **leak**: every module leaks through a tiny orifice (the glued tube inlet) sized so that a
  sealed module at p0 loses ``leak_pa_per_min``;
* **sensor thermal shift**: each sensor's zero moves by its own coefficient (uniform within
  +-``sensor_tempco_pa_k``) times the temperature swing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import CheckedFields, InputError, NonNegative, Positive


@dataclass(frozen=True)
class DisturbanceParams(CheckedFields, what="disturbance"):
    """Figures of the slow disturbances (sources in docs/box-and-simulator.md)."""

    #: Amplitude of the room temperature swing, K (0.5 K: a thermostat's +-0.5 K band).
    temperature_amplitude_k: NonNegative = 0.5
    #: Period of the swing, s (20 min).
    temperature_period_s: Positive = 1200.0
    #: Extra volume the membrane creeps to, as a fraction of its stretched volume (1 %).
    creep_fraction: NonNegative = 0.01
    #: Time constant of the creep, s (10 min).
    creep_time_s: Positive = 600.0
    #: Pressure loss of a sealed module at p0 through its leak, Pa/min (1 Pa/min).
    leak_pa_per_min: NonNegative = 1.0
    #: Largest thermal zero shift of a sensor, Pa/K (2 Pa/K: a total error band of 1 % of a
    #: 10 kPa span over 0..50 degC).
    sensor_tempco_pa_k: NonNegative = 2.0
    #: Simulated time between two updates, s (1 s).
    update_s: Positive = 1.0

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.creep_fraction >= 0.5:
            raise InputError(f"creep fraction must be below 0.5, got {self.creep_fraction!r}")


class Disturbances:
    """The disturbance state of one simulated box.

    Parameters
    ----------
    params
        Figures of the disturbances.
    n_channels
        Channels of the box (sensor shifts for every one).
    rng
        The box's random generator (phase of the temperature swing, sensor coefficients).
    room_temperature_k
        Mean room temperature, K (20 degC).
    """

    def __init__(
        self,
        params: DisturbanceParams,
        n_channels: int,
        rng: np.random.Generator,
        room_temperature_k: float = 293.15,
    ) -> None:
        self.params = params
        self.room_k = room_temperature_k
        self.phase = float(rng.uniform(0.0, 2 * math.pi))
        self.tempco_pa_k = rng.uniform(-1.0, 1.0, n_channels) * params.sensor_tempco_pa_k
        self.next_s = 0.0
        self.last_s = 0.0
        self.temperature_k = self.temperature_at(0.0)

    def temperature_at(self, t_s: float) -> float:
        """Room temperature at ``t_s``, K."""
        p = self.params
        w = 2 * math.pi * t_s / p.temperature_period_s + self.phase
        return self.room_k + p.temperature_amplitude_k * math.sin(w)

    def sensor_shift_pa(self) -> NDArray[np.float64]:
        """Thermal zero shift of every sensor now, Pa."""
        return self.tempco_pa_k * (self.temperature_k - self.room_k)

    def leak_area_m2(self, dn_dp: float, k_orifice: float, laminar_pa: float) -> float:
        """Orifice area ``Cd A`` that loses ``leak_pa_per_min`` at p0 from a sealed module whose
        amount changes by ``dn_dp`` per pascal, m^2 (``k_orifice``: the bank's orifice gain)."""
        p0 = thesis.P0_PA
        flow = self.params.leak_pa_per_min / 60.0 * dn_dp
        return flow * math.sqrt(p0 + laminar_pa) / (k_orifice * p0)

    def advance(self, t_s: float) -> tuple[float, float]:
        """Move to ``t_s``; returns (temperature ratio T_new / T_old, elapsed seconds)."""
        t_old = self.temperature_k
        self.temperature_k = self.temperature_at(t_s)
        elapsed = t_s - self.last_s
        self.last_s = t_s
        self.next_s = t_s + self.params.update_s
        return self.temperature_k / t_old, elapsed
