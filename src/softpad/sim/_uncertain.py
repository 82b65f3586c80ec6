"""Every simulator input that neither the thesis nor a datasheet fixes: nominal value, range, source.

This is the one list of the simulated lab's assumptions (issue 33). Each
:class:`UncertainParameter` names the value the simulator uses by default (``nominal``, the
library's default today, so a run without ``--randomize`` is unchanged), the range the value
may really take (``low`` .. ``high``) and where that range comes from (``source``). Every
nominal lies inside its own sourced range (issue 45; ``tests/sim/test_uncertain.py`` fails
when one leaves): the range is the evidence, the nominal a point within it.

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
from softpad.sim._contact_nominals import FINGERTIP_FRICTION, PAD_TIP_STIFFNESS_N_M
from softpad.sim._response import LINE_GAIN_RANGE

__all__ = [
    "OBJECT_UNKNOWNS",
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
        PAD_TIP_STIFFNESS_N_M,
        96.0,
        187.0,
        "the project's FEM, softpad fem stiffness (docs/fem.md, Fig. 6.3c): k = F / (h_free - "
        "h_load) for 0.2-0.8 N on a 10 mm disc at 0.96-1.42 kPa around p0 = 1.1 kPa",
        "MuJoCo PadPhysics.local_stiffness_n_m (the dome under a fingertip)",
        "nominal: the same FEM at p0 = 1.1 kPa and the middle force 0.5 N, interpolated "
        "between 0.096 N/mm (0.96 kPa) and 0.154 N/mm (1.42 kPa); the analytic world's "
        "125 N/m lies inside the range too",
    ),
    _p(
        "fingertip_friction",
        FINGERTIP_FRICTION,
        0.3,
        0.7,
        "the thesis calls the tips rigid, without soft parts (Section 6.3), and names no "
        "material; hard thermoplastics' static friction: cast nylon 6 0.32, polycarbonate "
        "0.52, Noryl 0.67 (Shackelford and Alexander, CRC Materials Science and Engineering "
        "Handbook, 3rd ed., 2001, Table 399, from the CRC Handbook of Materials Science and "
        "ASM's Engineered Materials Handbook vol. 2)",
        "MuJoCo MujocoGripper.friction (finger pads on objects; the finger's friction governs "
        "the contact)",
        "nominal: polycarbonate's 0.52 rounded to 0.5, a hard plastic tip",
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
        -0.01804,
        -0.0515,
        -0.015,
        "the thesis says only 'a heavy small part in one side' of the can (Section 6.3); from "
        "against the end cap to 15 mm left of the middle",
        "catalogue cylinder: position of its heavy part along the can's axis",
        "nominal: fitted to Table 6.1's cylinder plan (softpad calibrate --objects)",
    ),
    _p(
        "charger_brick_mass_share",
        0.875,
        0.6,
        0.9,
        "the thesis gives the charger's total only (312.3 g, Table 6.1); a 300 g laptop "
        "adapter's mains cord and DC cable with their plugs weigh 30-120 g (our reading of "
        "common 45-90 W adapters): the brick carries 0.6-0.9 of the mass",
        "catalogue charger: the brick's share of the mass (the cable coil and the plug keep "
        "their ratio)",
        "nominal: fitted to Table 6.1's charger plan (softpad calibrate --objects)",
    ),
    _p(
        "limes_pair_gap_m",
        0.0,
        0.0,
        0.02,
        "the thesis says only 'limes' on modules 2, 4, 5, 6 (Section 6.3) and gives no "
        "arrangement; three 49 mm limes in a net: the lower two touching (0 mm) to 20 mm "
        "apart in a loose net, the third nested on them",
        "catalogue limes: the gap between the two lower limes (the third rests on both)",
        "nominal: fitted to Table 6.1's limes plan (softpad calibrate --objects)",
    ),
    _p(
        "toy_right_hand_share",
        0.7,
        0.2,
        0.8,
        "the thesis gives the toy's mass only (131.6 g, Table 6.1), not its shape; the hands of "
        "a V-shaped toy carry from a fifth to four fifths of their joint mass on the right",
        "catalogue toy: the right hand's share of the two hands' mass",
        "nominal: fitted to Table 6.1's toy plan (softpad calibrate --objects)",
    ),
    _p(
        "banana_sagitta_m",
        0.0225,
        0.015,
        0.045,
        "the catalogue's banana is one YCB specimen (011, sagitta 27 mm from the chord "
        "through its ends); bananas of 180-200 mm vary in curvature: 15-45 mm",
        "catalogue banana: the largest distance of its spine from the chord through its ends",
        "nominal: fitted to Table 6.1's banana plan (softpad calibrate --objects)",
    ),
    # issue 45: appended last, so the draws of every parameter above stay as they were
    _p(
        "line_response_gain",
        LINE_GAIN_RANGE[2],
        LINE_GAIN_RANGE[0],
        LINE_GAIN_RANGE[1],
        "the cast-pad FEM (gain 1, the nominal: 135 Pa/N astride a line, a 9.8 g Duplo face) "
        "falls short of the thesis; the range reaches what its own observations bracket "
        "(softpad.trials._line.line_gain_bracket): the can seen on six modules (Section 6.3, "
        "line rise >= 269 Pa/N) from 3.26 on, up to a 5 g minimum detectable mass on the Duplo "
        "face ('around 6 g', Section 6.1) at 5.95",
        "PadResponse line_gain: every chamber's response within 12.5 mm of its border",
    ),
)

#: The uncertain inputs that shape one object of the catalogue, by object: only these are
#: fitted to the thesis's plan of that object (``softpad calibrate --objects``).
OBJECT_UNKNOWNS = {
    "cylinder": "cylinder_heavy_x_m",
    "charger": "charger_brick_mass_share",
    "limes": "limes_pair_gap_m",
    "toy": "toy_right_hand_share",
    "banana": "banana_sagitta_m",
}

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
        """Checked: known names, each value within its range (every nominal lies inside its
        own range, so the nominal lab passes too)."""
        merged = nominal_uncertain()
        for name, v in (values or {}).items():
            p = _BY_NAME.get(name)
            if p is None:
                raise InputError(f"unknown uncertain parameter {name!r}")
            ok = math.isfinite(v) and p.low <= v <= p.high
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

    def pad_response(self, layout: Any = None) -> Any:
        """The pad's FEM response with the seam and the line gain."""
        from softpad.sim._response import PadResponse

        v = self.values
        return PadResponse(
            layout, seam_width_m=v["seam_width_m"], line_gain=v["line_response_gain"]
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
        """``spec`` with the size, shape or mass distribution the thesis does not give
        (charger, cylinder, limes, toy, banana); any other object unchanged. Every setting
        but the charger's scale sets an absolute value, so the catalogue's objects, built at
        the nominals, come back unchanged from the nominal lab."""
        v = self.values
        if spec.name == "charger":
            spec = _charger_mass(spec, v["charger_brick_mass_share"])
            return _charger(spec, v["charger_brick_scale"])
        if spec.name == "cylinder":
            return _cylinder(spec, v["cylinder_heavy_x_m"])
        if spec.name == "limes":
            return _limes(spec, v["limes_pair_gap_m"])
        if spec.name == "toy":
            return _toy(spec, v["toy_right_hand_share"])
        if spec.name == "banana":
            return _banana(spec, v["banana_sagitta_m"])
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


def _rescaled(parts: list[Any], names: set[str], total: float) -> list[Any]:
    """``parts`` with the masses of those named ``names`` scaled to sum to ``total``."""
    now = sum(p.mass_kg for p in parts if p.name in names)
    return [replace(p, mass_kg=p.mass_kg * total / now) if p.name in names else p for p in parts]


def _charger_mass(spec: Any, share: float) -> Any:
    """The charger with ``share`` of its mass in the brick (the first part)."""
    parts = list(spec.parts)
    rest = {p.name for p in parts[1:]}
    parts = _rescaled(parts, {parts[0].name}, share * spec.mass_kg)
    return replace(spec, parts=tuple(_rescaled(parts, rest, (1 - share) * spec.mass_kg)))


def _toy(spec: Any, right_share: float) -> Any:
    """The toy with ``right_share`` of its two hands' mass in the right hand."""
    parts = list(spec.parts)
    hands = sum(p.mass_kg for p in parts if p.name in ("left hand", "right hand"))
    parts = _rescaled(parts, {"right hand"}, right_share * hands)
    return replace(spec, parts=tuple(_rescaled(parts, {"left hand"}, (1 - right_share) * hands)))


def _limes(spec: Any, gap_m: float) -> Any:
    """The limes with the lower two ``gap_m`` apart, the third resting on both, the three
    placed about the pair's midpoint as the catalogue's are."""
    parts = list(spec.parts)
    r = parts[0].radius_m
    half = r + gap_m / 2
    rise = math.sqrt(max((2 * r) ** 2 - half**2, 0.0))
    xy = ((-half, 0.0), (half, 0.0), (0.0, rise))
    out = [replace(p, pos_m=(x, y, p.pos_m[2])) for p, (x, y) in zip(parts, xy, strict=True)]
    return replace(spec, parts=tuple(out))


def _banana(spec: Any, sagitta_m: float) -> Any:
    """The banana with its spine's largest distance from the chord through its end
    stretches set to ``sagitta_m``: every stretch's distance from the chord and the tangent
    of its angle to the chord scaled alike (lengths kept)."""
    parts = list(spec.parts)
    a, b = np.array(parts[0].pos_m[:2]), np.array(parts[-1].pos_m[:2])
    u = (b - a) / np.linalg.norm(b - a)
    n = np.array([-u[1], u[0]])
    off = [float(n @ (np.array(p.pos_m[:2]) - a)) for p in parts]
    k = sagitta_m / max(abs(d) for d in off)
    chord = math.atan2(u[1], u[0])
    out = []
    for p, d in zip(parts, off, strict=True):
        x, y = np.array(p.pos_m[:2]) + (k - 1.0) * d * n
        yaw = chord + math.atan(k * math.tan(p.yaw_rad - chord))
        out.append(replace(p, pos_m=(float(x), float(y), p.pos_m[2]), yaw_rad=yaw))
    return replace(spec, parts=tuple(out))
