"""Every simulator input that neither the thesis nor a datasheet fixes: nominal value, range, source.

This is the one list of the simulated lab's assumptions (issue 33). Each
:class:`UncertainParameter` names the value the simulator uses by default (``nominal``, the
library's default today, so a run without ``--randomize`` is unchanged), the range the value
may really take (``low`` .. ``high``) and where that range comes from (``source``). Where the
nominal lies outside its sourced range the entry says so (``note``): the range is the evidence,
the nominal a model choice still to be settled against it.

:func:`draw_uncertain` draws every parameter uniformly within its range from a seed (the trial
seed: reproducible, independent between trials); :class:`LabVariation` turns a set of values
into the simulated lab's pieces (MuJoCo pad and gripper physics, box sample rate, sensor noise,
tubing, placement noise, the objects whose size or mass distribution the thesis does not give).
``softpad trials|compare|design --randomize`` draw them per trial and report them in ``--json``.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from softpad import thesis
from softpad.errors import InputError

__all__ = [
    "UNCERTAIN_PARAMETERS",
    "LabVariation",
    "UncertainParameter",
    "draw_uncertain",
    "nominal_uncertain",
]


@dataclass(frozen=True)
class UncertainParameter:
    """One assumed input of the simulator."""

    #: Key in the drawn values (units in the name).
    name: str
    #: Value used when nothing is drawn (the library's default).
    nominal: float
    #: Lowest value the source supports.
    low: float
    #: Highest value the source supports.
    high: float
    #: Where the range comes from.
    source: str
    #: What the value sets in the simulated lab.
    sets: str
    #: Remarks (a nominal outside its range is named here).
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        return {
            "name": self.name,
            "nominal": self.nominal,
            "low": self.low,
            "high": self.high,
            "source": self.source,
            "sets": self.sets,
            "note": self.note,
        }


def _p(
    name: str, nominal: float, low: float, high: float, source: str, sets: str, note: str = ""
) -> UncertainParameter:
    return UncertainParameter(name, nominal, low, high, source, sets, note)


#: The simulator's assumed inputs, each with nominal value, range and the range's source.
UNCERTAIN_PARAMETERS: tuple[UncertainParameter, ...] = (
    _p(
        "pad_tip_stiffness_n_m",
        80.0,
        96.0,
        187.0,
        "the project's FEM, softpad fem stiffness (docs/fem.md, Fig. 6.3c): k = F / (h_free - "
        "h_load) for 0.2-0.8 N on a 10 mm disc at 0.96-1.42 kPa around p0 = 1.1 kPa",
        "MuJoCo PadPhysics.local_stiffness_n_m (the dome under a fingertip)",
        "nominal 80 N/m (the MuJoCo default) lies below the FEM range; the analytic world "
        "uses 125 N/m",
    ),
    _p(
        "fingertip_friction",
        0.8,
        0.3,
        0.8,
        "the thesis calls the Sawyer's tips hard (Section 6.3); hard plastic on plastic, "
        "fruit skin and tinplate: 0.3-0.5 in friction tables; 0.8 (rubber-like) as the upper end",
        "MuJoCo MujocoGripper.friction (finger pads on objects)",
        "nominal 0.8 is the range's upper end (a rubber-like tip)",
    ),
    _p(
        "pad_friction",
        1.0,
        0.6,
        1.2,
        "silicone elastomer (EcoFlex 00-30, tacky) on plastics and skins: 0.6-1.2 in friction "
        "tables; the thesis gives none",
        "MuJoCo PadPhysics.friction",
    ),
    _p(
        "grip_force_n",
        20.0,
        10.0,
        35.0,
        "the thesis gives no grip force; the Rethink electric parallel gripper's force is set in "
        "software up to its limit (a few tens of newtons); 10 N: set gently for fruit",
        "MuJoCo MujocoGripper.grip_force_n (each jaw's servo force limit)",
    ),
    _p(
        "seam_width_m",
        thesis.SEAM_WIDTH_M,
        0.0,
        3e-3,
        "the mould's grid walls (thesis Fig. 6.2a) whose thickness the thesis does not give; "
        "0 mm: chambers meet (45 mm acetate on a 45 mm pitch); 3 mm: a thick printed wall",
        "the insensitive bonded strip between chambers (PadResponse) and the MuJoCo domes' side",
    ),
    _p(
        "sample_rate_hz",
        100.0,
        50.0,
        200.0,
        "the thesis gives no read rate of the Pneumaticbox; 50-200 Hz spans the rates of "
        "serial-read pressure boxes of its kind",
        "SimBox sample rate (the 10-sample filters follow it)",
    ),
    _p(
        "sensor_noise_scale",
        1.0,
        0.5,
        2.0,
        "noise visible in the thesis's Fig. 6.8 (a few pascals to tens of pascals); factor on "
        "SensorParams' white noise (8 Pa), drift (3 Pa) and offsets (20 Pa)",
        "SimBox sensor noise",
    ),
    _p(
        "tubing_volume_m3",
        thesis.TUBING_VOLUME_M3,
        math.pi * 0.8e-3**2 * 0.5,
        math.pi * 1.6e-3**2 * 1.5,
        "the thesis names the tube (SPX-60 FB Versilon) but not bore or length: 1.6-3.2 mm bore, "
        "0.5-1.5 m",
        "PneumaticParams.tubing_volume_m3 (dead volume of every channel)",
    ),
    _p(
        "placement_sigma_m",
        3e-3,
        1e-3,
        6e-3,
        "objects placed by hand (Section 6.3), spread not given; 1-6 mm: placing by eye on a "
        "marked spot",
        "TrialConfig.position_sigma_m",
    ),
    _p(
        "placement_yaw_sigma_rad",
        math.radians(3.0),
        math.radians(1.0),
        math.radians(6.0),
        "as placement_sigma_m: 1-6 degrees by eye along a module edge",
        "TrialConfig.yaw_sigma_rad",
    ),
    _p(
        "charger_brick_scale",
        1.0,
        0.85,
        1.15,
        "the thesis gives the charger's mass only (312.3 g, Table 6.1); laptop bricks of that "
        "mass measure 65-90 x 45-65 mm: factor on the 75 x 55 mm footprint",
        "catalogue charger: brick length and width (cable and plug move with its end)",
    ),
    _p(
        "cylinder_heavy_x_m",
        -0.0515,
        -0.0515,
        -0.015,
        "the thesis says only 'a heavy small part in one side' of the can (Section 6.3); from "
        "against the end cap to 15 mm left of the middle",
        "catalogue cylinder: position of its heavy part along the can's axis",
    ),
)

_BY_NAME = {p.name: p for p in UNCERTAIN_PARAMETERS}


def nominal_uncertain() -> dict[str, float]:
    """Every parameter at its nominal value."""
    return {p.name: p.nominal for p in UNCERTAIN_PARAMETERS}


def draw_uncertain(seed: int) -> dict[str, float]:
    """Every parameter drawn uniformly within its range from ``seed`` (reproducible)."""
    if not isinstance(seed, int | np.integer) or seed < 0:
        raise InputError(f"the seed of the drawn parameters must be an integer >= 0, got {seed!r}")
    key = zlib.crc32(b"softpad-uncertain")
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), key]))
    u = rng.random(len(UNCERTAIN_PARAMETERS))
    return {
        p.name: float(p.low + x * (p.high - p.low))
        for p, x in zip(UNCERTAIN_PARAMETERS, u, strict=True)
    }


@dataclass(frozen=True)
class LabVariation:
    """The simulated lab built from one set of parameter values (nominal where not given)."""

    values: dict[str, float]

    @classmethod
    def of(cls, values: dict[str, float] | None) -> LabVariation:
        """Checked: known names, each value within its range (or at its nominal)."""
        merged = nominal_uncertain()
        for name, v in (values or {}).items():
            p = _BY_NAME.get(name)
            if p is None:
                raise InputError(f"unknown uncertain parameter {name!r}")
            ok = math.isfinite(v) and (p.low <= v <= p.high or v == p.nominal)
            if not ok:
                raise InputError(
                    f"uncertain parameter {name} must be within {p.low:g}..{p.high:g}, got {v!r}"
                )
            merged[name] = float(v)
        return cls(merged)

    def pad_physics(self, layout_pitch_m: float = thesis.MODULE_PITCH_M) -> Any:
        """MuJoCo pad physics with the tip stiffness, pad friction and seam."""
        from softpad.sim._mujoco_model import PadPhysics

        v = self.values
        return PadPhysics(
            local_stiffness_n_m=v["pad_tip_stiffness_n_m"],
            friction=v["pad_friction"],
            sensitive_side_m=layout_pitch_m - v["seam_width_m"],
        )

    def gripper_physics(self) -> dict[str, float]:
        """The MuJoCo gripper's contact fields (:meth:`MujocoGripper.from_spec` ``physics``)."""
        v = self.values
        return {"friction": v["fingertip_friction"], "grip_force_n": v["grip_force_n"]}

    def sensor(self) -> Any:
        """Sensor parameters with the noise scaled."""
        from softpad.sim._sensor import SensorParams

        base, k = SensorParams(), self.values["sensor_noise_scale"]
        return replace(
            base,
            noise_std_pa=base.noise_std_pa * k,
            drift_std_pa=base.drift_std_pa * k,
            offset_std_pa=base.offset_std_pa * k,
        )

    def pneumatics(self) -> Any:
        """Pneumatic parameters with the tubing volume."""
        from softpad.sim._pneumatics import PneumaticParams

        return PneumaticParams(tubing_volume_m3=self.values["tubing_volume_m3"])

    def object(self, spec: Any) -> Any:
        """``spec`` with the size or mass distribution the thesis does not give (charger,
        cylinder); any other object unchanged."""
        if spec.name == "charger":
            return _charger(spec, self.values["charger_brick_scale"])
        if spec.name == "cylinder":
            return _cylinder(spec, self.values["cylinder_heavy_x_m"])
        return spec

    def to_dict(self) -> dict[str, float]:
        """The values, rounded for JSON."""
        return {k: float(f"{v:.6g}") for k, v in self.values.items()}


def _charger(spec: Any, scale: float) -> Any:
    """The charger with its brick's footprint scaled; the cable and plug keep their distance
    from the brick's end."""
    parts = list(spec.parts)
    brick = parts[0]
    if brick.size_m is None or scale == 1.0:
        return spec
    lx, ly, lz = brick.size_m
    shift = (scale - 1.0) * lx / 2
    out = [replace(brick, size_m=(lx * scale, ly * scale, lz))]
    for p in parts[1:]:
        out.append(replace(p, pos_m=(p.pos_m[0] + shift, p.pos_m[1], p.pos_m[2])))
    return replace(spec, parts=tuple(out))


def _cylinder(spec: Any, heavy_x_m: float) -> Any:
    """The can with its heavy part at ``heavy_x_m`` along the axis."""
    parts = list(spec.parts)
    for i, p in enumerate(parts):
        if p.name == "heavy part":
            parts[i] = replace(p, pos_m=(heavy_x_m, p.pos_m[1], p.pos_m[2]))
    return replace(spec, parts=tuple(parts))
