"""Object sets for design sweeps: what the pad must grasp, read from TOML.

Schema ``softpad-object-set/1`` (units in the key names, converted to SI on reading):

.. code-block:: toml

    schema = "softpad-object-set/1"
    name = "my-set"
    gripper = "10/4"            # optional: one mounting for every object

    [[object]]
    name = "banana"
    catalogue = "banana"        # shape and mass from the packaged catalogue (Table 6.1)
    placement = "as-thesis"     # default for catalogue objects

    [[object]]
    name = "brick"
    mass_g = 12.6
    shape = "box"               # "box": size_mm = [lx, ly, lz]
    size_mm = [42, 31, 23]      # "cylinder": diameter_mm, length_mm (lying along x;
                                # standing = true: on an end face); "sphere": diameter_mm
    placement = { dx_mm = 0, dy_mm = 0, yaw_deg = 0 }   # centre's offset from the pad's centre
    gripper = "6/2"

Placements: ``"as-thesis"`` keeps the catalogue's placement relative to the pad's centre (on
the thesis's 2 x 3 pad it is the catalogue's own), ``"centre"`` puts the object's footprint
centre on the pad's centre, a table offsets it from there, ``"anywhere"`` draws a pose per
trial from the trial's seed anywhere on the pad the object fits, its centre at least 10 mm
from the pad's centre (held-out trials as a lab runs them; issue 45). Meshes are not read (the
simulated worlds take primitive parts).
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.errors import InputError

#: Schema tag of an object-set file.
OBJECT_SET_SCHEMA = "softpad-object-set/1"
#: Object sets shipped with the package (``--example NAME``).
EXAMPLE_SETS = ("thesis-set", "blocks", "ycb-dev", "ycb-eval", "datasheet-eval")
_MOUNTINGS = ("10/4", "6/2", "4/0")
_THESIS_PAD_M = (
    thesis.PROTOTYPE_COLS * thesis.MODULE_PITCH_M,
    thesis.PROTOTYPE_ROWS * thesis.MODULE_PITCH_M,
)


@dataclass(frozen=True)
class SetObject:
    """One object of a set: its catalogue-style spec and how it is placed on any pad."""

    #: The object (:class:`softpad.sim.ObjectSpec`); its placement is the one on the thesis's
    #: pad (``as-thesis``) or ignored.
    spec: Any
    #: ``"as-thesis"``, ``"centre"``, ``"offset"`` or ``"anywhere"``.
    placement: str = "as-thesis"
    #: (dx_m, dy_m, yaw_rad) of the footprint centre from the pad centre (``offset``).
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def name(self) -> str:
        """The object's name."""
        return str(self.spec.name)

    def placed_on(self, pad_size_m: tuple[float, float]) -> Any:
        """The spec with its placement for a pad of ``pad_size_m`` (width, height), metres."""
        from softpad.sim import Placement

        w, h = pad_size_m
        p = self.spec.placement
        if self.placement == "anywhere":
            return replace(self.spec, placement=Placement(w / 2, h / 2, 0.0, (w, h)))
        if self.placement == "as-thesis":
            dx, dy = (w - _THESIS_PAD_M[0]) / 2, (h - _THESIS_PAD_M[1]) / 2
            return replace(self.spec, placement=Placement(p.x_m + dx, p.y_m + dy, p.yaw_rad))
        yaw = self.offset[2] if self.placement == "offset" else p.yaw_rad
        cx, cy = footprint_centre_m(self.spec.parts, yaw)
        x = w / 2 + self.offset[0] - cx
        y = h / 2 + self.offset[1] - cy
        return replace(self.spec, placement=Placement(x, y, yaw))


def footprint_centre_m(parts: Any, yaw_rad: float) -> tuple[float, float]:
    """Centre of the parts' bounding box in the pad plane for an object turned by
    ``yaw_rad``, relative to the object's origin, metres (part extents from their
    circumscribed radius in the plane)."""
    c, s = math.cos(yaw_rad), math.sin(yaw_rad)
    xs, ys = [], []
    for part in parts:
        x, y = part.pos_m[0], part.pos_m[1]
        xs.append(c * x - s * y)
        ys.append(s * x + c * y)
    return (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2


@dataclass(frozen=True)
class ObjectSet:
    """A named set of objects to grasp."""

    #: Name of the set.
    name: str
    #: The objects.
    objects: tuple[SetObject, ...]
    #: One gripper mounting for every object (``"10/4"``, ``"6/2"``, ``"4/0"``), or None for
    #: each object's own.
    gripper: str | None = None
    #: Where the set was read from.
    source: str = ""
    _names: tuple[str, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        names = tuple(o.name for o in self.objects)
        if not names:
            raise InputError(f"object set {self.name!r} has no objects")
        if len(set(names)) != len(names):
            raise InputError(f"object set {self.name!r}: object names must be unique, got {names}")
        if self.gripper is not None and self.gripper not in _MOUNTINGS:
            raise InputError(
                f"gripper must be one of {', '.join(_MOUNTINGS)}, got {self.gripper!r}"
            )
        object.__setattr__(self, "_names", names)

    @property
    def names(self) -> tuple[str, ...]:
        """The objects' names, in order."""
        return self._names

    def mounting(self, obj: SetObject) -> str:
        """The gripper mounting used for ``obj``."""
        return self.gripper or str(obj.spec.gripper)

    def with_gripper(self, gripper: str | None) -> ObjectSet:
        """The set with one mounting for every object (None: unchanged)."""
        return self if gripper is None else replace(self, gripper=gripper)

    def check_on_pads(self, designs: Sequence[Any]) -> None:
        """Refuse a sweep where an object would lie off a design's pad: its footprint centre,
        placed as its rule says, outside the pad's outline (checked before any work).

        Parameters
        ----------
        designs
            Pad designs (``rows``, ``cols``, ``pitch_m``), e.g. :class:`PadDesign`.
        """
        for d in designs:
            w, h = d.cols * d.pitch_m, d.rows * d.pitch_m
            pad = f"the {d.rows}x{d.cols} pad of {w * 1e3:.0f} x {h * 1e3:.0f} mm"
            for obj in self.objects:
                try:
                    p = obj.placed_on((w, h)).placement
                except InputError as exc:  # metres away: beyond any placement
                    raise InputError(f"object {obj.name!r} would lie off {pad}: {exc}") from None
                cx, cy = footprint_centre_m(obj.spec.parts, p.yaw_rad)
                x, y = p.x_m + cx, p.y_m + cy
                if not (0.0 <= x <= w and 0.0 <= y <= h):
                    raise InputError(
                        f"object {obj.name!r} would lie at ({x * 1e3:.0f}, {y * 1e3:.0f}) mm, "
                        f"off {pad}"
                    )

    def fingerprint(self) -> dict[str, Any]:
        """What identifies the set in a cache key: every spec and placement rule."""
        return {
            "gripper": self.gripper,
            "objects": [
                {
                    "spec": o.spec.to_dict() if hasattr(o.spec, "to_dict") else repr(o.spec),
                    "placement": o.placement,
                    "offset": list(o.offset),
                }
                for o in self.objects
            ],
        }


def load_object_set(path: str | Path) -> ObjectSet:
    """Read an object set from a TOML file (schema above); InputError names what is wrong."""
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"object set file {str(p)!r} not found") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"object set file {str(p)!r} is not valid TOML: {exc}") from None
    return object_set_from_dict(data, source=str(p))


def example_object_set(name: str) -> ObjectSet:
    """A packaged object set by name (:data:`EXAMPLE_SETS`)."""
    if name not in EXAMPLE_SETS:
        raise InputError(
            f"unknown example object set {name!r}; use one of {', '.join(EXAMPLE_SETS)}"
        )
    res = resources.files("softpad").joinpath("data", "object_sets", f"{name}.toml")
    data = tomllib.loads(res.read_text(encoding="utf-8"))
    return object_set_from_dict(data, source=f"example:{name}")


def object_set_from_dict(data: dict[str, Any], source: str = "") -> ObjectSet:
    """An :class:`ObjectSet` from parsed TOML."""
    if data.get("schema") != OBJECT_SET_SCHEMA:
        raise InputError(
            f"object set {source!r}: schema must be {OBJECT_SET_SCHEMA!r}, got {data.get('schema')!r}"
        )
    entries = data.get("object")
    if not isinstance(entries, list) or not entries:
        raise InputError(f"object set {source!r}: needs at least one [[object]] table")
    objects = tuple(_set_object(e, i) for i, e in enumerate(entries))
    return ObjectSet(str(data.get("name", Path(source).stem)), objects, data.get("gripper"), source)


def _set_object(entry: Any, index: int) -> SetObject:
    """One ``[[object]]`` table."""
    if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
        raise InputError(f"object {index + 1}: needs a name")
    name = entry["name"]
    gripper = entry.get("gripper")
    if gripper is not None and gripper not in _MOUNTINGS:
        raise InputError(
            f"object {name!r}: gripper must be one of {', '.join(_MOUNTINGS)}, got {gripper!r}"
        )
    if "catalogue" in entry:
        from softpad.sim import get_object

        spec = replace(get_object(str(entry["catalogue"])), name=name)
        default_placement: Any = "as-thesis"
    else:
        spec = _primitive_spec(name, entry)
        default_placement = "centre"
    if gripper is not None:
        spec = replace(spec, gripper=gripper)
    placement = entry.get("placement", default_placement)
    if isinstance(placement, dict):
        offset = (
            _number(placement, "dx_mm", name, 0.0) * 1e-3,
            _number(placement, "dy_mm", name, 0.0) * 1e-3,
            math.radians(_number(placement, "yaw_deg", name, 0.0)),
        )
        return SetObject(spec, "offset", offset)
    if placement not in ("as-thesis", "centre", "anywhere"):
        raise InputError(
            f"object {name!r}: placement must be 'as-thesis', 'centre', 'anywhere' or a table "
            f"{{dx_mm, dy_mm, yaw_deg}}, got {placement!r}"
        )
    return SetObject(spec, str(placement))


def _number(d: dict[str, Any], key: str, name: str, default: float | None = None) -> float:
    v = d.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"object {name!r}: {key} must be a finite number, got {v!r}")
    return float(v)


#: Lightest object and shortest side of an object set, g and mm: below them a mass was given in
#: kilograms or a length in metres (a 0.1 g object would not press a module measurably).
MIN_MASS_G = 0.1
SIZE_RANGE_MM = (1.0, 2000.0)


def _length_m(d: dict[str, Any], key: str, name: str) -> float:
    """A side given in millimetres under ``key``, in metres (mix-ups refused)."""
    v = _number(d, key, name)
    lo, hi = SIZE_RANGE_MM
    if not lo <= v <= hi:
        hint = " (metres given as millimetres?)" if 0 < v < lo else ""
        raise InputError(
            f"object {name!r}: {key} must be within {lo:g}..{hi:g} mm, got {v:g}{hint}"
        )
    return v * 1e-3


def _primitive_spec(name: str, entry: dict[str, Any]) -> Any:
    """An object of one primitive part from mass and dimensions."""
    from softpad.sim import ObjectSpec, PartSpec, Placement

    mass = _number(entry, "mass_g", name) * 1e-3
    if not MIN_MASS_G * 1e-3 <= mass <= 2.0:
        hint = " (kilograms given as grams?)" if 0 < mass < MIN_MASS_G * 1e-3 else ""
        raise InputError(
            f"object {name!r}: mass_g must be within {MIN_MASS_G:g}..2000 g, got "
            f"{mass * 1e3:g}{hint}"
        )
    shape = entry.get("shape", "box")
    if shape == "box":
        size = entry.get("size_mm")
        if not isinstance(size, list) or len(size) != 3:
            raise InputError(f"object {name!r}: a box needs size_mm = [lx, ly, lz]")
        lx, ly, lz = (_length_m({"size_mm": v}, "size_mm", name) for v in size)
        part = PartSpec("box", mass, (0.0, 0.0, lz / 2), size_m=(lx, ly, lz), name=name)
    elif shape == "cylinder":
        r = _length_m(entry, "diameter_mm", name) * 0.5
        length = _length_m(entry, "length_mm", name)
        standing = entry.get("standing", False)
        if not isinstance(standing, bool):
            raise InputError(f"object {name!r}: standing must be true or false, got {standing!r}")
        # lying along x, or standing on an end face (a puck, a can upright)
        axis, z = ("z", length / 2) if standing else ("x", r)
        part = PartSpec(
            "cylinder", mass, (0.0, 0.0, z), radius_m=r, length_m=length, axis=axis, name=name
        )
    elif shape == "sphere":
        r = _length_m(entry, "diameter_mm", name) * 0.5
        part = PartSpec("sphere", mass, (0.0, 0.0, r), radius_m=r, name=name)
    else:
        raise InputError(
            f"object {name!r}: shape must be 'box', 'cylinder' or 'sphere', got {shape!r}"
        )
    return ObjectSpec(
        name, mass, (part,), Placement(0.0, 0.0), gripper=entry.get("gripper", "10/4")
    )
