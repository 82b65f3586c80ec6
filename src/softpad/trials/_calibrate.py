"""Calibration from recordings of known loads: the uncertain pad parameters fitted to a real pad.

A calibration session (protocol in docs/validation.md) is an MCAP recording of the inflated,
sealed pad: a minute idle, then known masses put down one at a time at known places for
``hold_s`` and lifted for as long. Every placement is an event ``calibration_load`` (mass_g,
x_mm, y_mm, size_mm: the footprint's sides along x and y) and every removal
``calibration_unload``; :func:`record_calibration` writes such a file from any box, with a
callback that puts the loads (the simulated world's probe block; an operator on a real pad).

:func:`calibrate` fits, from one or more such recordings:

* **sensor noise**: the rms of every channel's idle samples about their straight-line trend,
  also as a factor on the simulator's nominal sample rms (``sensor_noise_scale`` of
  :data:`softpad.sim.UNCERTAIN_PARAMETERS`);
* **leak**: the idle trend of every channel (Pa/s) and the leak area Cd A that gives it in the
  simulator's gas physics (the rate is proportional to the area for small leaks; the factor
  is measured on a simulated sealed module);
* **response scale and seam width**: ``scipy.optimize.least_squares`` on every module's
  measured increment of every load (mean of the last 3 s loaded minus the unloaded level
  interpolated from before and after) against the simulator's sealed rise of the same block
  (:func:`softpad.sim._probe.sealed_rise_map`: FEM response, module characteristic, gas law),
  with the FEM influence scaled by ``response_scale`` and the chambers shrunk by the seam.

The response scale absorbs what a static load cannot tell apart from the membrane's
sensitivity: the tubing volume and the material's stiffness scale the rise alike. The seam
width is identifiable only when loads lie on and near the lines between modules (the
protocol's loads do); with loads at module centres only it is reported as not identified.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import InputError

GRAVITY_M_S2 = 9.80665
#: Seconds at the end of a loaded or unloaded stretch that are averaged (the gas settles in
#: milliseconds, the silicone's creep in about a second).
WINDOW_S = 3.0
#: Seam widths the fit may return, metres (the sourced range of the uncertain parameter is
#: 0-3 mm; the fit allows twice that).
SEAM_BOUNDS_M = (0.0, 6e-3)
#: Response scales the fit may return.
SCALE_BOUNDS = (0.2, 5.0)
#: Events of a calibration recording.
LOAD_EVENT, UNLOAD_EVENT = "calibration_load", "calibration_unload"


@dataclass(frozen=True)
class CalibrationLoad:
    """A known mass put on the pad: a flat block, pad frame, SI units."""

    mass_kg: float
    x_m: float
    y_m: float
    size_m: tuple[float, float] = (0.02, 0.02)

    def to_event(self) -> dict[str, Any]:
        """The ``calibration_load`` event's data (units in the names)."""
        return {
            "mass_g": self.mass_kg * 1e3,
            "x_mm": self.x_m * 1e3,
            "y_mm": self.y_m * 1e3,
            "size_mm": [v * 1e3 for v in self.size_m],
        }

    @classmethod
    def from_event(cls, data: dict[str, Any]) -> CalibrationLoad:
        """Inverse of :meth:`to_event`; InputError naming a missing or bad field."""
        try:
            size = tuple(float(v) * 1e-3 for v in data.get("size_mm", (20.0, 20.0)))
            load = cls(
                float(data["mass_g"]) * 1e-3,
                float(data["x_mm"]) * 1e-3,
                float(data["y_mm"]) * 1e-3,
                (size[0], size[1]),
            )
        except (KeyError, TypeError, ValueError, IndexError) as exc:
            raise InputError(
                f"calibration_load event needs mass_g, x_mm, y_mm and size_mm, got {data!r}"
            ) from exc
        if not (load.mass_kg > 0 and min(load.size_m) > 0):
            raise InputError(f"calibration load must have mass and size > 0, got {data!r}")
        return load


def protocol_loads(pitch_m: float = thesis.MODULE_PITCH_M) -> tuple[CalibrationLoad, ...]:
    """The protocol's loads on the 2 x 3 pad (docs/validation.md): 20 g and 50 g blocks of
    20 x 20 mm at module centres (sensitivity), 50 g 10 mm and 17 mm off a centre (the
    response's shape), 50 g straddling the line between modules 1 and 2 and between 2 and 5
    (the seam) and a 100 g 31 x 31 mm block on module 6 (linearity)."""
    p = pitch_m
    c = {k: ((k - 1) % 3 + 0.5, 1.5 if k <= 3 else 0.5) for k in range(1, 7)}

    def at(k: int, dx: float = 0.0, dy: float = 0.0, g: float = 50.0, side: float = 0.02):
        return CalibrationLoad(g * 1e-3, c[k][0] * p + dx, c[k][1] * p + dy, (side, side))

    return (
        at(1, g=20.0),
        at(2),
        at(4, g=20.0),
        at(5),
        at(3, dx=0.010),
        at(5, dx=0.017),
        CalibrationLoad(0.05, p, 1.5 * p, (0.02, 0.02)),
        CalibrationLoad(0.05, 1.5 * p, p, (0.02, 0.02)),
        at(6, g=100.0, side=0.031),
    )


def record_calibration(
    box: Any,
    path: str | Path,
    loads: Sequence[CalibrationLoad],
    put: Callable[[CalibrationLoad | None], None],
    idle_s: float = 60.0,
    hold_s: float = 10.0,
    metadata: dict[str, Any] | None = None,
    force: bool = False,
) -> Path:
    """Record a calibration session of ``box`` (inflated and sealed) into ``path``.

    ``put(load)`` puts a load on the pad and ``put(None)`` lifts it (the simulated world's
    :meth:`press`; on a real pad a prompt to the operator). Idle ``idle_s``, then every load
    for ``hold_s`` and as long lifted.
    """
    from softpad.record import McapRecorder

    meta = {"command": "calibration", "idle_s": idle_s, "hold_s": hold_s, **(metadata or {})}
    rate = box.sample_rate_hz
    with McapRecorder(path, meta, force=force) as rec:
        for f in box.read_many(round(idle_s * rate)):
            rec.frame(f, "idle")
        for load in loads:
            put(load)
            rec.event(box.time_s, LOAD_EVENT, **load.to_event())
            for f in box.read_many(round(hold_s * rate)):
                rec.frame(f, "loaded")
            put(None)
            rec.event(box.time_s, UNLOAD_EVENT)
            for f in box.read_many(round(hold_s * rate)):
                rec.frame(f, "unloaded")
    return Path(path)


@dataclass(frozen=True)
class LoadStep:
    """One load of a recording: what was put and every module's measured increment."""

    load: CalibrationLoad
    increments_pa: NDArray[np.float64]
    #: Mean pressure of the unloaded pad around it (the operating pressure), Pa.
    reference_pa: float


@dataclass(frozen=True)
class Session:
    """What a calibration recording holds, reduced."""

    path: str
    steps: tuple[LoadStep, ...]
    #: Idle samples about each channel's straight-line trend, rms, Pa.
    noise_rms_pa: NDArray[np.float64]
    #: Each channel's idle trend, Pa/s.
    drift_pa_s: NDArray[np.float64]
    #: Mean idle pressure of each module, Pa.
    idle_pa: NDArray[np.float64]
    sample_rate_hz: float


def _window(t: NDArray[np.float64], p: NDArray[np.float64], end: float) -> NDArray[np.float64]:
    sel = (t >= end - WINDOW_S) & (t < end)
    if sel.sum() < 2:
        raise InputError(
            f"calibration recording has under 2 frames in the {WINDOW_S:g} s "
            f"before t = {end:.2f} s; hold every load longer"
        )
    return np.asarray(p[sel].mean(axis=0))


def read_session(path: str | Path, n_modules: int = 6) -> Session:
    """Reduce one calibration recording (InputError when it is not one)."""
    from softpad.record import load_recording

    run = load_recording(path)
    t, p = run.t_s, run.pressures_pa[:, :n_modules]
    loads = run.events_of(LOAD_EVENT)
    unloads = [e[0] for e in run.events_of(UNLOAD_EVENT)]
    if not loads or len(unloads) != len(loads):
        raise InputError(
            f"{path}: not a calibration recording: it needs '{LOAD_EVENT}' events, each "
            f"followed by '{UNLOAD_EVENT}' (found {len(loads)} and {len(unloads)})"
        )
    idle = t < loads[0][0]
    if idle.sum() < 10 * n_modules:
        raise InputError(f"{path}: under {10 * n_modules} idle frames before the first load")
    ti, pi = t[idle], p[idle]
    coef = np.polyfit(ti - ti[0], pi, 1)
    resid = pi - (np.outer(ti - ti[0], coef[0]) + coef[1])
    bounds = [lo for lo, _ in loads] + [float(t[-1]) + 1e-9]
    steps = []
    for k, ((t_on, data), t_off) in enumerate(zip(loads, unloads, strict=True)):
        before = _window(t, p, t_on)
        after = _window(t, p, bounds[k + 1])
        loaded = _window(t, p, t_off)
        t_mid = t_off - WINDOW_S / 2
        frac = (t_mid - (t_on - WINDOW_S / 2)) / (bounds[k + 1] - t_on)
        base = before + frac * (after - before)
        steps.append(
            LoadStep(CalibrationLoad.from_event(data), loaded - base, float(np.median(base)))
        )
    return Session(
        path=str(path),
        steps=tuple(steps),
        noise_rms_pa=resid.std(axis=0),
        drift_pa_s=coef[0],
        idle_pa=pi.mean(axis=0),
        sample_rate_hz=run.sample_rate_hz,
    )


def scaled_pad_response(response_scale: float = 1.0, seam_width_m: float | None = None) -> Any:
    """The FEM pad response with every equivalent load scaled by ``response_scale`` (the
    membrane squeezes the chamber that much more per newton than the FEM says) and the
    chambers shrunk by a seam: the two pad parameters :func:`calibrate` fits. At (1, None)
    the packaged response."""
    from softpad.sim import PadResponse

    class _Scaled(PadResponse):
        def weights(
            self, points_m: Any, pressure_pa: float
        ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
            idx, w = super().weights(points_m, pressure_pa)
            return idx, w * float(response_scale)

    return _Scaled(seam_width_m=seam_width_m)


def predicted_increments(
    steps: Sequence[LoadStep], response_scale: float, seam_width_m: float
) -> NDArray[np.float64]:
    """The simulator's sealed rise of every module for every step's load, Pa, (steps, 6):
    each load's equivalent loads on the scaled response (as the world's probe block), then
    one gas-law step of sealed chambers on the module characteristic (the probe's
    :func:`softpad.sim._probe.sealed_rise_map`, vectorised over the steps), at the steps'
    median operating pressure."""
    from softpad.sim import ChamberBank, default_characteristic, operating_pressure

    r = scaled_pad_response(response_scale, seam_width_m)
    p = float(np.median([s.reference_pa for s in steps]))
    p_op = operating_pressure(p, r.response)
    eq = np.array(
        [
            r.rect_equivalent_loads(
                (s.load.x_m, s.load.y_m), s.load.size_m, s.load.mass_kg * GRAVITY_M_S2, p_op
            )
            for s in steps
        ]
    )
    flat = eq.ravel()
    bank = ChamberBank(flat.size, flat.size, default_characteristic())
    bank.set_state(np.full(flat.size, p), np.zeros(flat.size))
    closed = np.zeros(flat.size, dtype=bool)
    bank.step(1e-3, closed, closed, flat, 0.0, False, same_load=False)
    return np.asarray((bank.pressure_pa - p).reshape(eq.shape))


@dataclass(frozen=True)
class CalibrationResult:
    """The fitted pad parameters (SI) and how well they explain the recordings."""

    response_scale: float
    #: Seam width, metres; None when the loads cannot tell it (none near a line).
    seam_width_m: float | None
    #: Standard errors from the fit's Jacobian (response_scale, seam_width_m).
    response_scale_se: float
    seam_width_se_m: float | None
    #: Idle sample rms, median over the channels, Pa.
    noise_rms_pa: float
    #: That over the simulator's nominal sample rms (``sensor_noise_scale``).
    sensor_noise_scale: float
    #: Idle trend of every module, Pa/s.
    drift_pa_s: tuple[float, ...]
    #: Leak area Cd A that gives each module's trend in the gas physics, m^2 (0: none seen).
    leak_m2: tuple[float, ...]
    #: Rms of measured minus fitted increments over every module of every load, Pa.
    residual_rms_pa: float
    loads: int
    recordings: tuple[str, ...] = field(default=())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, units in the names."""
        seam = self.seam_width_m
        return {
            "response_scale": round(self.response_scale, 4),
            "response_scale_se": round(self.response_scale_se, 4),
            "seam_width_mm": None if seam is None else round(seam * 1e3, 3),
            "seam_width_se_mm": None
            if self.seam_width_se_m is None
            else round(self.seam_width_se_m * 1e3, 3),
            "noise_rms_pa": round(self.noise_rms_pa, 3),
            "sensor_noise_scale": round(self.sensor_noise_scale, 4),
            "drift_pa_s": [round(v, 4) for v in self.drift_pa_s],
            "leak_mm2": [float(f"{v * 1e6:.4g}") for v in self.leak_m2],
            "leak_mm2_mean": float(f"{np.mean(self.leak_m2) * 1e6:.4g}"),
            "residual_rms_pa": round(self.residual_rms_pa, 3),
            "loads": self.loads,
            "recordings": list(self.recordings),
        }

    def to_text(self) -> str:
        """A few lines for the terminal."""
        d = self.to_dict()
        seam = (
            "not identified (no load near a line)"
            if d["seam_width_mm"] is None
            else (f"{d['seam_width_mm']:.2f} +- {d['seam_width_se_mm']:.2f} mm")
        )
        return "\n".join(
            [
                f"response scale  {d['response_scale']:.3f} +- {d['response_scale_se']:.3f}",
                f"seam width      {seam}",
                f"sensor noise    {d['noise_rms_pa']:.2f} Pa rms (x{d['sensor_noise_scale']:.2f} "
                "the simulator's)",
                f"leak            {', '.join(f'{v:.3g}' for v in d['leak_mm2'])} mm^2 "
                f"(trend {', '.join(f'{v:.3f}' for v in d['drift_pa_s'])} Pa/s)",
                f"fit residual    {d['residual_rms_pa']:.2f} Pa rms over {self.loads} loads",
            ]
        )


def nominal_sample_rms_pa() -> float:
    """Rms of one idle sample of the simulator's nominal sensor about its trend: white
    noise, drift and quantisation, Pa."""
    from softpad.sim import SensorParams

    s = SensorParams()
    return math.sqrt(s.noise_std_pa**2 + s.drift_std_pa**2 + s.quantization_pa**2 / 12)


def leak_rate_per_area(pressure_pa: float = thesis.P0_PA, area_m2: float = 2e-11) -> float:
    """Pressure decay of a sealed, unloaded simulated module per unit leak area at
    ``pressure_pa``, (Pa/s) per m^2 (measured over 20 s without noise)."""
    from softpad.box import Fault, SimBox
    from softpad.sim import AnalyticWorld, SensorParams

    box = SimBox(AnalyticWorld(), sensor=SensorParams.ideal(), initial_pressure_pa=pressure_pa)
    box.inject_fault(Fault("leak", 1, 0.0, area_m2))
    p0 = box.read().pressures_pa[0]
    frames = box.read_many(round(20 * box.sample_rate_hz))
    return float((p0 - frames[-1].pressures_pa[0]) / (frames[-1].t_s - frames[0].t_s) / area_m2)


def _near_a_line(steps: Sequence[LoadStep], pitch_m: float = thesis.MODULE_PITCH_M) -> bool:
    """Some load's footprint reaches within 5 mm of a line between modules."""
    for s in steps:
        for c, half in ((s.load.x_m, s.load.size_m[0] / 2), (s.load.y_m, s.load.size_m[1] / 2)):
            off = abs((c / pitch_m) % 1.0 - 0.5) * pitch_m  # from the module centre
            if off + half > pitch_m / 2 - 0.005:
                return True
    return False


def fit_response(steps: Sequence[LoadStep]) -> tuple[float, float | None, NDArray[np.float64]]:
    """Least squares of the measured increments on the simulator's: (scale, seam or None,
    standard errors)."""
    from scipy.optimize import least_squares

    meas = np.array([s.increments_pa for s in steps])
    seam_free = _near_a_line(steps)

    def resid(x: NDArray[np.float64]) -> NDArray[np.float64]:
        seam = x[1] * 1e-3 if seam_free else 0.0
        return (predicted_increments(steps, x[0], seam) - meas).ravel()

    x0 = np.array([1.0, 1.0]) if seam_free else np.array([1.0])
    lo = [SCALE_BOUNDS[0], SEAM_BOUNDS_M[0] * 1e3][: x0.size]
    hi = [SCALE_BOUNDS[1], SEAM_BOUNDS_M[1] * 1e3][: x0.size]
    fit = least_squares(resid, x0, bounds=(lo, hi), diff_step=1e-3, x_scale=[0.1, 0.5][: x0.size])
    dof = max(fit.fun.size - x0.size, 1)
    s2 = float(fit.fun @ fit.fun) / dof
    try:
        cov = np.linalg.inv(fit.jac.T @ fit.jac) * s2
        se = np.sqrt(np.diag(cov))
    except np.linalg.LinAlgError:
        se = np.full(x0.size, np.inf)
    seam_m = float(fit.x[1]) * 1e-3 if seam_free else None
    return float(fit.x[0]), seam_m, se * np.array([1.0, 1e-3][: x0.size])


def calibrate(paths: Sequence[str | Path]) -> CalibrationResult:
    """Fit the pad parameters to calibration recordings (see the module's docstring)."""
    if not paths:
        raise InputError("calibrate needs at least one recording")
    sessions = [read_session(p) for p in paths]
    steps = [s for ses in sessions for s in ses.steps]
    scale, seam, se = fit_response(steps)
    resid = predicted_increments(steps, scale, seam or 0.0) - np.array(
        [s.increments_pa for s in steps]
    )
    noise = float(np.median(np.concatenate([s.noise_rms_pa for s in sessions])))
    drift = np.mean([s.drift_pa_s for s in sessions], axis=0)
    p_idle = float(np.median(np.concatenate([s.idle_pa for s in sessions])))
    per_area = leak_rate_per_area(p_idle)
    leak = np.clip(-drift / per_area, 0.0, None) if per_area > 0 else np.zeros_like(drift)
    return CalibrationResult(
        response_scale=scale,
        seam_width_m=seam,
        response_scale_se=float(se[0]),
        seam_width_se_m=None if seam is None else float(se[1]),
        noise_rms_pa=noise,
        sensor_noise_scale=noise / nominal_sample_rms_pa(),
        drift_pa_s=tuple(float(v) for v in drift),
        leak_m2=tuple(float(v) for v in leak),
        residual_rms_pa=float(np.sqrt(np.mean(resid**2))),
        loads=len(steps),
        recordings=tuple(str(p) for p in paths),
    )


def simulated_session(
    path: str | Path,
    response_scale: float = 1.0,
    seam_width_m: float = 0.0,
    sensor_noise_scale: float = 1.0,
    leak_m2: float = 0.0,
    seed: int = 0,
    loads: Sequence[CalibrationLoad] | None = None,
    idle_s: float = 60.0,
    hold_s: float = 10.0,
) -> Path:
    """Record the protocol on a simulated pad with the given (hidden) parameters: the
    analytic world behind a box sealed at p0, the loads pressed as flat blocks (the world's
    probe), every module leaking through ``leak_m2``."""
    from softpad.box import Fault, SimBox
    from softpad.sim import AnalyticWorld, LabVariation

    world = AnalyticWorld(response=scaled_pad_response(response_scale, seam_width_m))
    sensor = LabVariation.of({"sensor_noise_scale": sensor_noise_scale}).sensor()
    box = SimBox(world, seed=seed, sensor=sensor, initial_pressure_pa=thesis.P0_PA)
    if leak_m2 > 0:
        for ch in range(world.layout.n_modules):
            box.inject_fault(Fault("leak", ch + 1, 0.0, leak_m2))

    def put(load: CalibrationLoad | None) -> None:
        if load is None:
            world.press((0.0, 0.0), (0.01, 0.01), 0.0)
        else:
            world.press((load.x_m, load.y_m), load.size_m, load.mass_kg * GRAVITY_M_S2)

    hidden = {
        "response_scale": response_scale,
        "seam_width_m": seam_width_m,
        "sensor_noise_scale": sensor_noise_scale,
        "leak_m2": leak_m2,
    }
    box.read_many(round(box.sample_rate_hz))  # settle
    return record_calibration(
        box,
        path,
        loads or protocol_loads(),
        put,
        idle_s,
        hold_s,
        {"simulated": hidden, "seed": seed},
        force=True,
    )
