"""MJCF model of the SoftPad, a parallel-jaw gripper and the objects, generated from Python.

The model is a string of MuJoCo XML (MJCF) built from frozen parameter records, so a user can
change the pad, the gripper or the objects without touching a file. Everything is in the pad
frame of DESIGN.md (origin at the bottom-left corner of the pad on the rigid base surface, x to
the right, y up the columns, z up), SI units.

What is modelled (thesis, Sections 6.1-6.3)
-----------------------------------------
* **Pad.** A rigid base; on it one *module top* per module: a thin box whose side is the
  module's chamber, carried by a body on a vertical slide joint whose spring holds it at the
  inflated height. Around the pad (and between the tops where a seam is set) the base shows as
  a rigid, lower rim. How much a contact squeezes a chamber is the FEM response at the contact
  point (small near the clamped edges: a fingertip between two modules is barely sensed, the
  failure mode of Section 6.3).
* **Compliance.** Two stiffnesses, because a sealed pneumatic module is stiff for a load spread
  over its whole top (the gas carries it) and soft for a small indenter (the membrane bends
  locally): the slide joint of a top has the *distributed* stiffness, the sole of each fingertip
  sits on a vertical spring of the *local* (indentation) stiffness, so the force a fingertip puts
  on a module grows with its travel like on the real membrane (Fig. 6.3c). See
  :class:`PadPhysics` for the numbers and their derivation.
* **Gripper.** A kinematic hand (four joints whose positions and velocities the world
  overwrites every step) that the simulated robot moves; two
  fingers on slide joints along the closing direction driven by position servos with a force
  limit (the grip force); fingers 9.5 cm long, small tips (Section 6.3). Each finger ends in a
  *sole*, the tip's lower face, the only part of the gripper that touches the pad.
* **Objects.** Rigid bodies made of box / cylinder / sphere parts with their own masses, so the
  mass distribution (e.g. the cylinder's heavy insert) follows from the parts.

Collision classes (MuJoCo ``contype``/``conaffinity`` bits): the pad collides with objects and
soles; objects with the pad, the fingers and the palm; the soles only with the pad; the fingers
and palm only with objects.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol

from softpad import thesis
from softpad.errors import MM_AS_M, CheckedFields, InputError, Positive, check_range
from softpad.layout import GripperSpec, PadLayout
from softpad.sim._contact_nominals import FINGERTIP_FRICTION, PAD_TIP_STIFFNESS_N_M
from softpad.sim._objects import PartSpec

# Collision bits.
_PAD, _OBJ, _FINGER, _SOLE = 1, 2, 4, 8

#: Standard gravity, m/s^2.
GRAVITY_M_S2 = 9.81


@dataclass(frozen=True)
class PadPhysics(CheckedFields, what="pad"):
    """Physical parameters of the pad in the rigid-body world."""

    #: Height of an unloaded module top above the base at the inflating pressure, metres
    #: (8.3 mm at p0 = 1.1 kPa from the FEM of the 45 x 45 x 1.5 mm layer; the thesis measures
    #: about 9 mm, Section 6.3). The box replaces it with its own characteristic at run time
    #: (see :meth:`MujocoWorld.step`).
    free_height_m: Positive = 8.3e-3
    #: Side of the square base of a module's dome, metres: the chamber under it
    #: (:data:`softpad.thesis.CHAMBER_SIDE_M`, the 45 mm acetate of Section 6.1.1), so
    #: neighbouring domes meet at the seam (:data:`softpad.thesis.SEAM_WIDTH_M`). What a
    #: contact on a dome squeezes is not set here: the world weights each contact force by
    #: the FEM module response at its point (:class:`~softpad.sim.PadResponse`), which falls
    #: to zero at the clamped edge.
    sensitive_side_m: Positive = thesis.CHAMBER_SIDE_M
    #: Height of the non-sensitive lines and rim (the bonded silicone over the grid walls),
    #: metres: one 1.5 mm layer over the base.
    line_height_m: Positive = 1.5e-3
    #: Width of the non-sensitive silicone frame around the modules, metres.
    rim_m: float = 15e-3
    #: Vertical stiffness of a module top's slide joint under a load spread over it, N/m:
    #: 400 N/m, soft enough that an object sinks about 1 mm and rests on all the modules it
    #: spans. The sealed chamber's own stiffness (with the FEM characteristic at 1.1 kPa a
    #: newton on the central 30 x 30 mm patch lowers the top centre by 0.88 mm: about
    #: 1.1 kN/m) reaches MuJoCo through the box's module heights (see
    #: :meth:`MujocoWorld.step`), not through this spring.
    distributed_stiffness_n_m: Positive = 400.0
    #: Damping of that joint, N s/m: 20 N s/m, about twice the critical
    #: 2 sqrt(k (m + armature)) = 9.3 N s/m, so a load put on a module does not overshoot.
    distributed_damping_n_s_m: float = 20.0
    #: Moving mass of a module top, kg: the 1.5 mm EcoFlex layer over 45 x 45 mm at
    #: 1070 kg/m^3 (3.3 g) plus the carried air and a margin, 4.5 g.
    top_mass_kg: Positive = 4.5e-3
    #: Extra inertia of the top's slide joint (MuJoCo ``armature``), kg. Joint springs are
    #: integrated explicitly; with the light top alone, a heavy object on it makes the
    #: 2 ms step unstable (a 300 g block bounces). 50 g brings sqrt(k/m) * dt to
    #: 0.33 and only slows the top's free response (period 37 ms).
    top_armature_kg: float = 0.05
    #: Height of the dome of a module top above its rim, metres. An inflated module is a
    #: spherical cap (Section 6.1.2), so the top is a half-ellipsoid of semi-axes
    #: (side/2, side/2, dome height): an object rests on the apexes, near the module centres
    #: where the PCOM of Eq. 6.1 puts each module's share, and a fingertip that lands near
    #: a line slides off a flank into the gap. 4 mm (about half the 8.3 mm height).
    dome_height_m: float = 4e-3
    #: Stiffness of the membrane under a small indenter (a fingertip), N/m. The thesis's FEM
    #: (Fig. 6.3c) computes an equivalent stiffness k = F / (h_free - h_load) for a load on a
    #: 1 cm disc; the project's FEM gives 96-187 N/m around p0 and 114 N/m at p0 under 0.5 N
    #: (docs/fem.md; :data:`softpad.sim._contact_nominals.PAD_TIP_STIFFNESS_N_M`).
    local_stiffness_n_m: Positive = PAD_TIP_STIFFNESS_N_M
    #: Sliding friction coefficient of the silicone against objects (EcoFlex is grippy), -.
    friction: Positive = 1.0

    def __post_init__(self) -> None:
        super().__post_init__()
        for name in ("free_height_m", "sensitive_side_m", "line_height_m", "rim_m"):
            check_range(f"pad {name}", getattr(self, name), 0.0, 1.0, "m", MM_AS_M)
        if self.line_height_m >= self.free_height_m:
            raise InputError(
                f"line height ({self.line_height_m * 1e3:g} mm) must be below the module "
                f"height ({self.free_height_m * 1e3:g} mm)"
            )

    @property
    def top_thickness_m(self) -> float:
        """Thickness of the module-top box, metres (the 1.5 mm layer)."""
        return 1.5e-3


#: Convergence tolerance of MuJoCo's convex collider (``ccd_tolerance``), which finds the
#: contacts of the domes (ellipsoids) with boxes. At MuJoCo's default (1e-6) the depth of a
#: toy's hand resting on a dome changed by up to 7 um from one 2 ms step to the next with the
#: toy at rest; through the contacts' 1 mm impedance width that is a 0.5 N spike, one step in
#: five, and the module's sample load jumped by up to 0.6 N, which the detectors sensed as
#: contacts 80 to 120 mm above the pad (development seeds 102 and 103 of the toy). At 1e-9 the
#: depth is steady and a trial runs no slower (tests/trials/test_trials.py runs that toy).
CCD_TOLERANCE = 1e-9


#: The three mountings of the thesis's gripper: (maximum, minimum) width, metres (Section 6.3).
GRIPPER_MOUNTINGS = thesis.GRIPPER_MOUNTINGS_M


def parse_mounting(text: str) -> tuple[float, float]:
    """(max, min) opening in metres of a mounting ``"MAX/MIN"`` in centimetres.

    The thesis's three are ``"10/4"``, ``"6/2"`` and ``"4/0"``; others (e.g. ``"10/2"``, the
    wider gripper the thesis says would have grasped its cylinder) are accepted for studies.
    """
    if text in GRIPPER_MOUNTINGS:
        return GRIPPER_MOUNTINGS[text]
    try:
        hi, lo = (float(v) for v in str(text).split("/"))
    except ValueError:
        raise InputError(
            f"gripper mounting must be MAX/MIN in cm such as {', '.join(GRIPPER_MOUNTINGS)}, "
            f"got {text!r}"
        ) from None
    if not (0 <= lo < hi <= 30):
        raise InputError(f"gripper mounting {text!r}: need 0 <= MIN < MAX <= 30 cm")
    return hi / 100, lo / 100


@dataclass(frozen=True)
class MujocoGripper(CheckedFields, what="gripper"):
    """Parallel-jaw gripper (Sawyer electric gripper of Section 6.3)."""

    #: ``"10/4"``, ``"6/2"`` or ``"4/0"`` (Section 6.3), or any ``"MAX/MIN"``: maximum /
    #: minimum opening in cm.
    mounting: str = "10/4"
    #: From the palm to the lower face of the tips, metres (9.5 cm).
    finger_length_m: Positive = thesis.FINGER_LENGTH_M
    #: Tip size along and across the closing direction, metres: the planner's
    #: :class:`softpad.layout.GripperSpec` (6.5 x 16 mm, the Sawyer gripper's basic hard tip;
    #: sources in :mod:`softpad.thesis`), one set of figures for the planner, the analytic
    #: world and this model (:meth:`from_spec`, :attr:`geometry`). Never changed to make a
    #: trial pass: whether a tip over the seam between modules is sensed follows from
    #: the pad's FEM response (:mod:`softpad.sim._response`), not from the tip size.
    tip_thickness_m: Positive = thesis.FINGERTIP_THICKNESS_M
    #: Tip size across the closing direction, metres (16 mm; see ``tip_thickness_m``).
    tip_width_m: Positive = thesis.FINGERTIP_WIDTH_M
    #: Force limit of each jaw's servo, newtons (squeeze force once closed on an object).
    grip_force_n: Positive = 20.0
    #: Gain of the jaw position servo, N/m.
    servo_stiffness_n_m: Positive = 4000.0
    #: Friction of the finger pads on objects, -: hard plastic tips (Section 6.3), the
    #: finger's value governs its contacts (:data:`softpad.sim._contact_nominals.FINGERTIP_FRICTION`).
    friction: Positive = FINGERTIP_FRICTION
    #: Travel of the tip's compliant sole before it bottoms out on the finger, metres.
    sole_stroke_m: Positive = 25e-3

    def __post_init__(self) -> None:
        parse_mounting(self.mounting)
        super().__post_init__()

    @classmethod
    def from_spec(cls, spec: GripperSpec, **physics: Any) -> MujocoGripper:
        """The MuJoCo gripper of a :class:`softpad.layout.GripperSpec`: its mounting (max/min
        width), finger length and tips; ``physics`` sets the contact fields (grip force...)."""
        mounting = f"{spec.max_width_m * 100:g}/{spec.min_width_m * 100:g}"
        return cls(
            mounting=mounting,
            finger_length_m=spec.finger_length_m,
            tip_thickness_m=spec.tip_thickness_m,
            tip_width_m=spec.tip_width_m,
            **physics,
        )

    @property
    def geometry(self) -> GripperSpec:
        """The geometry alone, as the planner's :class:`softpad.layout.GripperSpec`."""
        return GripperSpec(
            self.max_width_m,
            self.min_width_m,
            self.finger_length_m,
            self.tip_width_m,
            self.tip_thickness_m,
        )

    @property
    def max_width_m(self) -> float:
        """Largest opening between the tips' inner faces, metres."""
        return parse_mounting(self.mounting)[0]

    @property
    def min_width_m(self) -> float:
        """Smallest opening between the tips' inner faces, metres."""
        return parse_mounting(self.mounting)[1]

    @property
    def squeeze_offset_m(self) -> float:
        """How far past the closed stops each jaw's servo setpoint goes when closing fully,
        metres: twice the servo's deflection at the grip force, so a blocked jaw reaches the
        full force with the setpoint half-way there (the lower end of the servo's range)."""
        return 2 * self.grip_force_n / self.servo_stiffness_n_m

    @property
    def sole_thickness_m(self) -> float:
        """Height of the compliant sole at the bottom of each tip (a capsule across the tip
        whose diameter is the tip thickness), metres."""
        return self.tip_thickness_m


class PartLike(Protocol):
    """A rigid primitive of an object in the catalogue schema ``softpad-objects/1``
    (``softpad.sim`` object catalogue): shape, mass, centre ``pos_m`` in the object frame
    (z up from the plane it rests on), ``yaw_rad`` about the object's z axis, and its size
    (``size_m`` full box edges; ``radius_m``; cylinder ``length_m`` along ``axis``). Metres, kg."""

    shape: str
    mass_kg: float
    pos_m: tuple[float, float, float]
    yaw_rad: float
    size_m: tuple[float, float, float] | None
    radius_m: float | None
    length_m: float | None
    axis: str


#: A part built in code (tests, user scripts): the catalogue's :class:`PartSpec`.
ObjectPart = PartSpec


def _quat_mul(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float, float]:
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    )


def part_geom_xml(
    part: PartLike, name: str, rgba: str, friction: float, at_origin: bool = False
) -> str:
    """The MJCF ``<geom>`` of one part (a cylinder's z axis turned onto ``axis``, then yawed);
    at its body's origin when ``at_origin`` (a loose part is a body of its own)."""
    c, s = math.cos(part.yaw_rad / 2), math.sin(part.yaw_rad / 2)
    q_yaw = (c, 0.0, 0.0, s)
    r = math.sqrt(0.5)
    q_axis = {"x": (r, 0.0, r, 0.0), "y": (r, -r, 0.0, 0.0)}.get(
        part.axis if part.shape == "cylinder" else "z", (1.0, 0.0, 0.0, 0.0)
    )
    quat = _quat_mul(q_yaw, q_axis)
    common = (
        f'name="{name}" pos="{_v((0.0, 0.0, 0.0) if at_origin else part.pos_m)}" '
        f'quat="{_v(quat)}" mass="{part.mass_kg:.9g}" '
        f'rgba="{rgba}" friction="{friction:g} 0.005 0.0001" contype="{_OBJ}" '
        f'conaffinity="{_PAD | _OBJ | _FINGER}" condim="4"'
    )
    if part.shape == "box":
        assert part.size_m is not None
        return f'<geom type="box" size="{_v(v / 2 for v in part.size_m)}" {common}/>'
    assert part.radius_m is not None
    if part.shape == "sphere":
        return f'<geom type="sphere" size="{part.radius_m:.9g}" {common}/>'
    assert part.length_m is not None
    # (module tops are domes, so a lying cylinder touches each in a point: no degenerate line
    # contact on a flat face)
    return f'<geom type="cylinder" size="{part.radius_m:.9g} {part.length_m / 2:.9g}" {common}/>'


@dataclass(frozen=True)
class ObjectModel:
    """An object for the rigid-body world: a name and its parts (:class:`PartLike`)."""

    #: Unique name.
    name: str
    #: Rigid primitives in the object frame.
    parts: tuple[PartLike, ...]
    #: Sliding friction of the object's surface, -.
    friction: float = 0.8
    #: Parts loosely tied together (the catalogue's ``loose_parts``, e.g. limes in a net):
    #: each part after the first is a body of its own held to the first by a soft weld (a
    #: net: about 3 mm of sag under a lime's weight), so a jaw can push it aside.
    loose: bool = False

    def __post_init__(self) -> None:
        if not self.parts:
            raise InputError(f"object {self.name!r} has no parts")

    @property
    def mass_kg(self) -> float:
        """Total mass, kg."""
        return sum(p.mass_kg for p in self.parts)

    @classmethod
    def from_spec(cls, spec: Any, friction: float = 0.8) -> ObjectModel:
        """From a catalogue object (anything with ``name`` and ``parts``)."""
        extra = getattr(spec, "extra", {}) or {}
        return cls(
            name=str(spec.name),
            parts=tuple(spec.parts),
            friction=friction,
            loose=bool(extra.get("loose_parts", False)),
        )


def _v(values: object) -> str:
    return " ".join(f"{float(v):.9g}" for v in values)  # type: ignore[attr-defined]


def body_name(obj: ObjectModel) -> str:
    """Name of an object's body in the model."""
    return f"obj_{obj.name}"


def loose_body_name(obj: ObjectModel, part_index: int) -> str:
    """Name of the body of part ``part_index`` (>= 1) of a loose object."""
    return f"{body_name(obj)}__{part_index}"


def parking_position(index: int) -> tuple[float, float, float]:
    """Where object ``index`` waits, far from the pad, until it is placed (metres)."""
    return (-1.0 - 0.5 * index, -1.0, 0.1)


def build_mjcf(
    layout: PadLayout,
    pad: PadPhysics,
    gripper: MujocoGripper,
    objects: tuple[ObjectModel, ...] = (),
    timestep_s: float = 2e-3,
) -> str:
    """Return the MJCF text of the pad, the gripper and ``objects`` (parked off the pad).

    Parameters
    ----------
    layout
        Pad geometry (rows, columns, pitch).
    pad
        Pad physics.
    gripper
        Gripper geometry and servo.
    objects
        Objects that may be placed later; each gets a free joint and starts parked.
    timestep_s
        MuJoCo time step, seconds (2 ms is stable with the stiffnesses above; see
        docs/trials.md for the measurement).
    """
    if not math.isfinite(timestep_s) or not 1e-4 <= timestep_s <= 1e-2:
        raise InputError(f"MuJoCo time step must be in [0.1, 10] ms, got {timestep_s * 1e3:g} ms")
    hand = _hand_xml(pad, gripper)
    obj_bodies, welds = _objects_xml(objects)
    return (
        '<mujoco model="softpad">'
        f'<option timestep="{timestep_s:.9g}" gravity="0 0 {-GRAVITY_M_S2:g}" '
        'integrator="implicitfast" cone="elliptic" impratio="10" '
        f'ccd_tolerance="{CCD_TOLERANCE:g}"/>'
        '<compiler angle="radian" inertiafromgeom="true" autolimits="true"/>'
        '<size memory="8M"/>'
        # contacts as stiff as the 2 ms step allows (time constant 2 steps, impedance 0.99):
        # with MuJoCo's default (20 ms, 0.95) the 20 N grip sinks the jaws 5 mm into a 24 g
        # brick, with these about 0.1 mm
        f'<default><geom solref="{2 * timestep_s:.6g} 1" solimp="0.95 0.99 0.001"/>'
        f'<joint solreflimit="{2 * timestep_s:.6g} 1" solimplimit="0.95 0.99 0.001"/></default>'
        f"<worldbody>{_pad_xml(layout, pad)}{hand}"
        f"{''.join(obj_bodies)}</worldbody>"
        f"<equality>{''.join(welds)}</equality>"
        f"<actuator>{_actuators_xml(gripper)}</actuator>"
        "</mujoco>"
    )


def _pad_xml(layout: PadLayout, pad: PadPhysics) -> str:
    """MJCF of the base, the table and the module tops (each on a vertical spring)."""
    pitch = layout.pitch_m
    width, height = layout.cols * pitch, layout.rows * pitch
    base_t = 0.01
    line_h = pad.line_height_m
    # rigid base slab + line/rim layer (non-sensitive) as one slab at line height: the module
    # tops stand above it, so a fingertip between two tops reaches this slab and no module
    rim = pad.rim_m
    pad_geoms = [
        f'<geom name="base" type="box" pos="{width / 2:.9g} {height / 2:.9g} {-base_t / 2 + line_h / 2:.9g}" '
        f'size="{width / 2 + rim:.9g} {height / 2 + rim:.9g} {(base_t + line_h) / 2:.9g}" '
        f'rgba="0.55 0.55 0.6 1" friction="{pad.friction:g} 0.005 0.0001" '
        f'contype="{_PAD}" conaffinity="0" condim="3"/>',
        # the table the pad lies on
        f'<geom name="table" type="plane" pos="0 0 {-base_t:.9g}" size="1 1 0.01" '
        f'rgba="0.8 0.8 0.8 1" contype="{_PAD}" conaffinity="0" condim="3"/>',
    ]
    half = pad.sensitive_side_m / 2
    dome = pad.dome_height_m
    module_bodies = []
    for k in layout.modules:
        cx, cy = layout.to_metres(layout.center(k))
        module_bodies.append(
            f'<body name="module{k}" pos="{cx:.9g} {cy:.9g} 0">'
            f'<joint name="module{k}_z" type="slide" axis="0 0 1" '
            f'stiffness="{pad.distributed_stiffness_n_m:g}" springref="{pad.free_height_m:.9g}" '
            f'damping="{pad.distributed_damping_n_s_m:g}" range="0 0.03" limited="true" armature="{pad.top_armature_kg:g}"/>'
            f'<geom name="module{k}_top" type="ellipsoid" pos="0 0 {-dome:.9g}" '
            f'size="{half:.9g} {half:.9g} {dome:.9g}" mass="{pad.top_mass_kg:.9g}" '
            f'rgba="0.95 0.55 0.7 1" friction="{pad.friction:g} 0.005 0.0001" '
            f'contype="{_PAD}" conaffinity="0" condim="3"/>'
            f"</body>"
        )
    return "".join(pad_geoms) + "".join(module_bodies)


def _hand_xml(pad: PadPhysics, gripper: MujocoGripper) -> str:
    """MJCF of the kinematic hand: palm and two fingers, each with a sprung sole."""
    # gripper: hand at the palm; fingers hang finger_length below it
    t, w = gripper.tip_thickness_m, gripper.tip_width_m
    sole_t = gripper.sole_thickness_m
    finger_l = gripper.finger_length_m - sole_t
    open_half = gripper.max_width_m / 2
    sole_mass = 0.002
    # critically damped sole (2 sqrt(k m)): no bouncing on the pad
    sole_damping = 2 * math.sqrt(pad.local_stiffness_n_m * sole_mass)
    fingers = []
    for side, sign in (("right", 1.0), ("left", -1.0)):
        fingers.append(
            f'<body name="finger_{side}" pos="0 0 0" gravcomp="1">'
            f'<joint name="jaw_{side}" type="slide" axis="{sign:g} 0 0" damping="40" '
            f'range="{gripper.min_width_m / 2 - 1e-3:.9g} {open_half + 1e-3:.9g}" limited="true"/>'
            f'<geom name="finger_{side}" type="box" pos="{sign * t / 2:.9g} 0 {-finger_l / 2:.9g}" '
            f'size="{t / 2:.9g} {w / 2:.9g} {finger_l / 2:.9g}" mass="0.05" '
            f'rgba="0.2 0.2 0.25 1" friction="{gripper.friction:g} 0.02 0.001" priority="1" '
            f'contype="{_FINGER}" conaffinity="0" condim="6"/>'
            f'<body name="sole_{side}" pos="{sign * t / 2:.9g} 0 {-finger_l:.9g}">'
            f'<joint name="sole_{side}_z" type="slide" axis="0 0 1" '
            f'stiffness="{pad.local_stiffness_n_m:g}" springref="0" damping="{sole_damping:.6g}" '
            f'range="0 {gripper.sole_stroke_m:.9g}" limited="true"/>'
            # rounded in the closing direction (a capsule across the tip): closing after the
            # contact, the tip rides up a dome's flank on its spring instead of ramming it
            f'<geom name="sole_{side}" type="capsule" pos="0 0 {-t / 2:.9g}" '
            f'size="{t / 2:.9g} {max(w / 2 - t / 2, 1e-4):.9g}" quat="0.70710678 0.70710678 0 0" '
            f'mass="{sole_mass:g}" '
            f'rgba="0.1 0.1 0.1 1" friction="0.3 0.005 0.0001" priority="1" '
            f'contype="{_SOLE}" conaffinity="{_PAD}" condim="3"/>'
            f"</body></body>"
        )
    palm = (
        f'<geom name="palm" type="box" pos="0 0 0.01" size="{open_half + t + 0.005:.9g} 0.02 0.01" '
        f'mass="0.5" rgba="0.3 0.3 0.35 1" contype="{_FINGER}" conaffinity="0" condim="3"/>'
    )
    # the hand is driven kinematically: the world overwrites these four joints' positions and
    # velocities every step (the robot is position-controlled and far stiffer than anything
    # here), so contacts see the true finger velocity
    # a heavy armature makes the solver treat the hand as the immovable robot it stands for,
    # and gravity compensation keeps the weight of hand and fingers off what they touch
    hand_joints = "".join(
        f'<joint name="hand_{a}" type="{kind}" axis="{axis}" armature="1000"/>'
        for a, kind, axis in (
            ("x", "slide", "1 0 0"),
            ("y", "slide", "0 1 0"),
            ("z", "slide", "0 0 1"),
            ("yaw", "hinge", "0 0 1"),
        )
    )
    return (
        f'<body name="hand" pos="0 0 0" gravcomp="1">{hand_joints}{palm}{"".join(fingers)}</body>'
    )


def _objects_xml(objects: tuple[ObjectModel, ...]) -> tuple[list[str], list[str]]:
    """MJCF bodies of ``objects`` at their parking places, and the welds of loose parts."""
    obj_bodies = []
    palette = ("0.9 0.2 0.2 1", "0.2 0.6 0.9 1", "0.95 0.8 0.1 1", "0.3 0.8 0.3 1")
    welds = []
    for i, obj in enumerate(objects):
        park = parking_position(i)
        tied = obj.parts[:1] if obj.loose else obj.parts
        geoms = "".join(
            part_geom_xml(part, f"{body_name(obj)}_{j}", palette[j % len(palette)], obj.friction)
            for j, part in enumerate(tied)
        )
        obj_bodies.append(
            f'<body name="{body_name(obj)}" pos="{_v(park)}">'
            f'<freejoint name="{body_name(obj)}"/>{geoms}</body>'
        )
        if obj.loose:
            for j, part in enumerate(obj.parts[1:], start=1):
                name = loose_body_name(obj, j)
                pos = tuple(a + b for a, b in zip(park, part.pos_m, strict=True))
                geom = part_geom_xml(
                    part, f"{name}_g", palette[j % len(palette)], obj.friction, at_origin=True
                )
                obj_bodies.append(
                    f'<body name="{name}" pos="{_v(pos)}"><freejoint name="{name}"/>{geom}</body>'
                )
                welds.append(
                    f'<weld body1="{body_name(obj)}" body2="{name}" solref="0.02 1" '
                    'solimp="0.9 0.95 0.001"/>'
                )
    return obj_bodies, welds


def _actuators_xml(gripper: MujocoGripper) -> str:
    """MJCF of the jaws' force-limited position servos."""
    open_half = gripper.max_width_m / 2
    kp = gripper.servo_stiffness_n_m
    f_max = gripper.grip_force_n
    closed = gripper.min_width_m / 2 - gripper.squeeze_offset_m
    return "".join(
        f'<position name="jaw_{side}" joint="jaw_{side}" kp="{kp:g}" '
        f'forcelimited="true" forcerange="{-f_max:g} {f_max:g}" '
        f'ctrlrange="{closed:.9g} {open_half + 1e-3:.9g}"/>'
        for side in ("right", "left")
    )
