"""Object catalogue: the thesis's object set (Table 6.1) as data.

The catalogue lives in ``softpad/data/objects.json`` (schema ``softpad-objects/1``) so that users
can add their own objects and both worlds (the analytic one here, the MuJoCo one) read the same
shapes. Each object is a rigid assembly of primitive parts in its own frame, plus the pose at
which it is placed on the pad.

Schema (SI units throughout; see docs/box-and-simulator.md):

.. code-block:: text

    {"schema": "softpad-objects/1",
     "objects": [
       {"name": "banana",                 # unique, lower case
        "description": "...",
        "mass_kg": 0.0598,                # Table 6.1 weight; equals the sum of the parts' masses
        "gripper": "6/2",                 # gripper mounting of Section 6.3 (max/min width, cm)
        "expected_modules": [2, 3, 4],    # modules the thesis reports the object on
        "table_6_1": {"cog": [1.0, 1.0], "theta": -0.785398},   # planned grasp, module units, rad
        "placement": {"x_m": ..., "y_m": ..., "yaw_rad": ...},   # object frame in the pad frame
        "loose_parts": false,             # optional: parts loosely tied (a net of limes)
        "parts": [
          {"name": "...", "shape": "box", "size_m": [lx, ly, lz],
           "pos_m": [x, y, z], "yaw_rad": 0.0, "mass_kg": ...},
          {"shape": "cylinder", "radius_m": r, "length_m": l, "axis": "x" | "y" | "z", ...},
          {"shape": "sphere", "radius_m": r, ...}]}]}

``pos_m`` is the part's centre in the object frame, whose origin lies on the pad surface
(``z = 0`` is the plane the object rests on) and whose yaw is given by the placement. A part's
``yaw_rad`` turns it about the object's z axis. A cylinder's ``axis`` is its axis in the part
frame before the yaw.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

from softpad.errors import MM_AS_M, InputError, check_finite, check_range

#: Schema tag written in every catalogue file.
CATALOGUE_SCHEMA = "softpad-objects/1"

_SHAPES = ("box", "cylinder", "sphere")
_AXES = ("x", "y", "z")


@dataclass(frozen=True)
class PartSpec:
    """One rigid primitive of an object, in the object frame."""

    #: ``"box"``, ``"cylinder"`` or ``"sphere"``.
    shape: str
    #: Mass of the part, kilograms.
    mass_kg: float
    #: Centre of the part in the object frame (x, y, z), metres; z measured up from the plane
    #: the object rests on.
    pos_m: tuple[float, float, float]
    #: Rotation of the part about the object's z axis, radians.
    yaw_rad: float = 0.0
    #: Box only: full edge lengths (lx, ly, lz), metres.
    size_m: tuple[float, float, float] | None = None
    #: Cylinder and sphere: radius, metres.
    radius_m: float | None = None
    #: Cylinder only: length along its axis, metres.
    length_m: float | None = None
    #: Cylinder only: axis in the part frame, ``"x"``, ``"y"`` or ``"z"``.
    axis: str = "z"
    #: Free label.
    name: str = ""

    def __post_init__(self) -> None:
        where = f"part {self.name or self.shape!r}"
        if self.shape not in _SHAPES:
            raise InputError(f"{where}: shape must be one of {_SHAPES}, got {self.shape!r}")
        _positive(self.mass_kg, f"{where}: mass_kg")
        if len(self.pos_m) != 3 or not all(math.isfinite(v) for v in self.pos_m):
            raise InputError(f"{where}: pos_m must be 3 finite numbers, got {self.pos_m!r}")
        if not math.isfinite(self.yaw_rad):
            raise InputError(f"{where}: yaw_rad must be finite, got {self.yaw_rad!r}")
        if self.shape == "box":
            if self.size_m is None or len(self.size_m) != 3:
                raise InputError(f"{where}: a box needs size_m = [lx, ly, lz] in metres")
            for v in self.size_m:
                _positive(v, f"{where}: size_m")
        else:
            _positive(self.radius_m, f"{where}: radius_m")
        if self.shape == "cylinder":
            _positive(self.length_m, f"{where}: length_m")
            if self.axis not in _AXES:
                raise InputError(f"{where}: axis must be one of {_AXES}, got {self.axis!r}")

    @property
    def half_height_m(self) -> float:
        """Half the part's vertical extent, metres."""
        if self.shape == "box":
            assert self.size_m is not None
            return self.size_m[2] / 2
        assert self.radius_m is not None
        if self.shape == "cylinder" and self.axis == "z":
            assert self.length_m is not None
            return self.length_m / 2
        return self.radius_m

    @property
    def bottom_m(self) -> float:
        """Height of the part's lowest point above the resting plane, metres."""
        return self.pos_m[2] - self.half_height_m

    @property
    def top_m(self) -> float:
        """Height of the part's highest point above the resting plane, metres."""
        return self.pos_m[2] + self.half_height_m

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict in the catalogue schema."""
        d: dict[str, Any] = {"name": self.name, "shape": self.shape}
        if self.shape == "box":
            d["size_m"] = list(self.size_m or ())
        else:
            d["radius_m"] = self.radius_m
        if self.shape == "cylinder":
            d["length_m"] = self.length_m
            d["axis"] = self.axis
        d.update(pos_m=list(self.pos_m), yaw_rad=self.yaw_rad, mass_kg=self.mass_kg)
        return d


@dataclass(frozen=True)
class Placement:
    """Pose of an object frame on the pad (pad frame, DESIGN.md)."""

    #: Position of the object frame's origin, metres from the pad's bottom-left corner.
    x_m: float
    #: Position of the object frame's origin, metres from the pad's bottom-left corner.
    y_m: float
    #: Rotation about the pad's z axis, radians.
    yaw_rad: float = 0.0
    #: (width, height) of the pad, metres, when the object goes anywhere on it that it fits,
    #: drawn per trial from the trial's seed (held-out trials; issue 45); None: at the pose
    #: above (which then only marks the pad's centre).
    anywhere_on_m: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        from softpad.layout import POSE_LIMIT_M

        for n in ("x_m", "y_m"):
            check_range(
                f"placement {n}", getattr(self, n), -POSE_LIMIT_M, POSE_LIMIT_M, "m", MM_AS_M
            )
        check_finite("placement yaw_rad", self.yaw_rad)
        if self.anywhere_on_m is not None:
            for v in self.anywhere_on_m:
                check_range("placement anywhere_on_m", v, 1e-3, POSE_LIMIT_M, "m", MM_AS_M)


@dataclass(frozen=True)
class ObjectSpec:
    """An object of the catalogue."""

    #: Unique name (``object-1`` .. ``object-6``, ``banana``, ...).
    name: str
    #: Total mass, kilograms (Table 6.1); equals the sum of the parts' masses.
    mass_kg: float
    #: Rigid primitives in the object frame.
    parts: tuple[PartSpec, ...]
    #: Where the object is put on the pad.
    placement: Placement
    #: Modules the thesis reports the object lying on (1-based).
    expected_modules: tuple[int, ...] = ()
    #: Gripper mounting of Section 6.3, ``"10/4"``, ``"6/2"`` or ``"4/0"`` (max/min width, cm).
    gripper: str = "10/4"
    #: Planned grasp of Table 6.1 (module units, radians), or None.
    table_cog: tuple[float, float] | None = None
    #: Planned grasp of Table 6.1 (module units, radians), or None.
    table_theta: float | None = None
    #: Free text: what the object is and why its parts are as they are.
    description: str = ""
    #: Keys of the catalogue entry that are none of the fields above, kept as read.
    extra: dict[str, Any] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        if not self.parts:
            raise InputError(f"object {self.name!r} needs at least one part")
        _positive(self.mass_kg, f"object {self.name!r}: mass_kg")
        total = sum(p.mass_kg for p in self.parts)
        if abs(total - self.mass_kg) > 1e-6 + 1e-3 * self.mass_kg:
            raise InputError(
                f"object {self.name!r}: parts weigh {total * 1e3:.2f} g but mass_kg is "
                f"{self.mass_kg * 1e3:.2f} g"
            )
        if min(p.bottom_m for p in self.parts) > 1e-3:
            raise InputError(
                f"object {self.name!r}: no part rests on the pad (lowest part above z = 1 mm)"
            )

    @property
    def com_m(self) -> tuple[float, float, float]:
        """Centre of mass in the object frame, metres."""
        m = sum(p.mass_kg for p in self.parts)
        return (
            sum(p.mass_kg * p.pos_m[0] for p in self.parts) / m,
            sum(p.mass_kg * p.pos_m[1] for p in self.parts) / m,
            sum(p.mass_kg * p.pos_m[2] for p in self.parts) / m,
        )

    @property
    def height_m(self) -> float:
        """Height of the object's top above the resting plane, metres."""
        return max(p.top_m for p in self.parts)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict in the catalogue schema."""
        d: dict[str, Any] = {
            "name": self.name,
            "description": self.description,
            "mass_kg": self.mass_kg,
            "gripper": self.gripper,
            "expected_modules": list(self.expected_modules),
        }
        if self.table_cog is not None:
            d["table_6_1"] = {"cog": list(self.table_cog), "theta": self.table_theta}
        d["placement"] = {
            "x_m": self.placement.x_m,
            "y_m": self.placement.y_m,
            "yaw_rad": self.placement.yaw_rad,
        }
        if self.placement.anywhere_on_m is not None:
            d["placement"]["anywhere_on_m"] = list(self.placement.anywhere_on_m)
        d["parts"] = [p.to_dict() for p in self.parts]
        d.update(self.extra)
        return d


def _positive(v: object, name: str) -> float:
    try:
        f = float(v)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a positive number, got {v!r}") from None
    if not math.isfinite(f) or f <= 0:
        raise InputError(f"{name} must be a positive finite number, got {v!r}")
    return f


def _tuple3(v: Any, name: str) -> tuple[float, float, float]:
    if not isinstance(v, list | tuple) or len(v) != 3:
        raise InputError(f"{name} must be a list of 3 numbers, got {v!r}")
    try:
        a, b, c = (float(x) for x in v)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a list of 3 numbers, got {v!r}") from None
    return a, b, c


def part_from_dict(d: dict[str, Any], where: str = "part") -> PartSpec:
    """Build a :class:`PartSpec` from its catalogue dict, raising InputError on bad fields."""
    if not isinstance(d, dict):
        raise InputError(f"{where} must be an object, got {d!r}")
    known = {
        "name",
        "shape",
        "size_m",
        "radius_m",
        "length_m",
        "axis",
        "pos_m",
        "yaw_rad",
        "mass_kg",
    }
    unknown = set(d) - known
    if unknown:
        raise InputError(f"{where}: unknown field(s) {sorted(unknown)}; allowed {sorted(known)}")
    try:
        return PartSpec(
            shape=str(d.get("shape")),
            mass_kg=_positive(d.get("mass_kg"), f"{where}: mass_kg"),
            pos_m=_tuple3(d.get("pos_m"), f"{where}: pos_m"),
            yaw_rad=float(d.get("yaw_rad", 0.0)),
            size_m=_tuple3(d["size_m"], f"{where}: size_m") if "size_m" in d else None,
            radius_m=float(d["radius_m"]) if "radius_m" in d else None,
            length_m=float(d["length_m"]) if "length_m" in d else None,
            axis=str(d.get("axis", "z")),
            name=str(d.get("name", "")),
        )
    except (TypeError, ValueError) as exc:
        if isinstance(exc, InputError):
            raise
        raise InputError(f"{where}: {exc}") from None


def object_from_dict(d: dict[str, Any]) -> ObjectSpec:
    """Build an :class:`ObjectSpec` from its catalogue dict, raising InputError on bad fields."""
    if not isinstance(d, dict) or "name" not in d:
        raise InputError(f"every catalogue object needs a 'name', got {str(d)[:60]!r}")
    name = str(d["name"])
    parts_raw = d.get("parts")
    if not isinstance(parts_raw, list):
        raise InputError(f"object {name!r}: 'parts' must be a list")
    parts = tuple(
        part_from_dict(p, f"object {name!r} part {i + 1}") for i, p in enumerate(parts_raw)
    )
    pl = d.get("placement", {"x_m": 0.0, "y_m": 0.0})
    if not isinstance(pl, dict):
        raise InputError(f"object {name!r}: 'placement' must be an object")
    try:
        placement = Placement(float(pl["x_m"]), float(pl["y_m"]), float(pl.get("yaw_rad", 0.0)))
    except (KeyError, TypeError, ValueError) as exc:
        if isinstance(exc, InputError):
            raise
        raise InputError(f"object {name!r}: placement needs numbers x_m, y_m (yaw_rad)") from None
    table = d.get("table_6_1")
    cog = theta = None
    if isinstance(table, dict):
        cog = (float(table["cog"][0]), float(table["cog"][1]))
        theta = float(table["theta"])
    known = {
        "name",
        "description",
        "mass_kg",
        "gripper",
        "expected_modules",
        "table_6_1",
        "placement",
        "parts",
    }
    return ObjectSpec(
        name=name,
        mass_kg=_positive(d.get("mass_kg"), f"object {name!r}: mass_kg"),
        parts=parts,
        placement=placement,
        expected_modules=tuple(int(m) for m in d.get("expected_modules", ())),
        gripper=str(d.get("gripper", "10/4")),
        table_cog=cog,
        table_theta=theta,
        description=str(d.get("description", "")),
        extra={k: v for k, v in d.items() if k not in known},
    )


def load_catalogue(path: str | Path | None = None) -> dict[str, ObjectSpec]:
    """Read an object catalogue (JSON, schema ``softpad-objects/1``).

    Parameters
    ----------
    path
        Catalogue file; None reads the packaged thesis set (``softpad/data/objects.json``).

    Returns
    -------
    dict
        Objects by name, in file order.
    """
    if path is None:
        return dict(_packaged_catalogue())
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot read object catalogue {str(p)!r}: {exc.strerror}") from None
    return _parse(text, str(p))


@cache
def _packaged_catalogue() -> tuple[tuple[str, ObjectSpec], ...]:
    text = resources.files("softpad").joinpath("data", "objects.json").read_text(encoding="utf-8")
    return tuple(_parse(text, "softpad/data/objects.json").items())


def _parse(text: str, source: str) -> dict[str, ObjectSpec]:
    try:
        raw = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(
            f"object catalogue {source!r} is not valid JSON: {exc.msg} at line {exc.lineno}"
        ) from None
    if not isinstance(raw, dict) or raw.get("schema") != CATALOGUE_SCHEMA:
        raise InputError(f'object catalogue {source!r} must have "schema": "{CATALOGUE_SCHEMA}"')
    objs = raw.get("objects")
    if not isinstance(objs, list):
        raise InputError(f"object catalogue {source!r} needs a list 'objects'")
    out: dict[str, ObjectSpec] = {}
    for d in objs:
        spec = object_from_dict(d)
        if spec.name in out:
            raise InputError(f"object catalogue {source!r} defines {spec.name!r} twice")
        out[spec.name] = spec
    return out


def object_names() -> tuple[str, ...]:
    """Names of the packaged thesis objects, in Table 6.1 order."""
    return tuple(name for name, _ in _packaged_catalogue())


def get_object(name: str, catalogue: dict[str, ObjectSpec] | None = None) -> ObjectSpec:
    """The object called ``name`` (packaged catalogue by default); InputError lists the names."""
    cat = catalogue if catalogue is not None else dict(_packaged_catalogue())
    try:
        return cat[name]
    except KeyError:
        raise InputError(f"unknown object {name!r}; known objects: {', '.join(cat)}") from None


def catalogue_to_json(objects: list[ObjectSpec] | tuple[ObjectSpec, ...]) -> str:
    """Serialise objects as a catalogue file (schema ``softpad-objects/1``)."""
    return json.dumps(
        {"schema": CATALOGUE_SCHEMA, "objects": [o.to_dict() for o in objects]}, indent=1
    )
