"""Pad designs and design spaces: the variables a design sweep changes.

A design is what one would build: the grid (R x C modules at a pitch), the upper layer
(thickness, material preset of thesis Table 7.1) and the inflating pressure p0. The thesis's
prototype (2 x 3, 45 mm, 1.5 mm neo-Hookean EcoFlex 00-30, 1.1 kPa) is
:data:`THESIS_DESIGN`, evaluated in every sweep as the baseline.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from typing import Any

from softpad import thesis
from softpad.errors import InputError
from softpad.layout import PadLayout

#: Ranges a design variable may take (inclusive), in SI: what the FEM model and the
#: simulator describe sensibly.
LIMITS: dict[str, tuple[float, float]] = {
    "rows": (1, 16),
    "cols": (1, 16),
    "pitch_m": (0.020, 0.080),
    "thickness_m": (0.0005, 0.005),
    "p0_pa": (500.0, 2800.0),
}


@dataclass(frozen=True)
class PadDesign:
    """One SoftPad design."""

    #: Module grid R x C (thesis: 2 x 3).
    rows: int = thesis.PROTOTYPE_ROWS
    #: Module grid R x C (thesis: 2 x 3).
    cols: int = thesis.PROTOTYPE_COLS
    #: Module pitch = side of a module's air channel, metres (thesis: 45 mm).
    pitch_m: float = thesis.MODULE_PITCH_M
    #: Thickness of the upper silicone layer, metres (thesis: 1.5 mm).
    thickness_m: float = thesis.LAYER_THICKNESS_M
    #: Material preset of :data:`softpad.fem.MATERIAL_PRESETS` (thesis fit: neo-Hookean).
    material: str = "neo-hookean"
    #: Initial inflating pressure p0, pascals (thesis: 1.1 kPa; usable 0.5 to 2.8 kPa).
    p0_pa: float = thesis.P0_PA
    #: Label; derived from the variables when empty.
    name: str = ""

    def __post_init__(self) -> None:
        for key in ("rows", "cols"):
            v = getattr(self, key)
            lo, hi = LIMITS[key]
            if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                raise InputError(f"design {key} must be an integer from {lo} to {hi}, got {v!r}")
        for key, unit, scale in (
            ("pitch_m", "mm", 1e3),
            ("thickness_m", "mm", 1e3),
            ("p0_pa", "kPa", 1e-3),
        ):
            v = getattr(self, key)
            lo, hi = LIMITS[key]
            if not isinstance(v, int | float) or not math.isfinite(v) or not lo <= v <= hi:
                raise InputError(
                    f"design {key.rsplit('_', 1)[0]} must be within {lo * scale:g}..{hi * scale:g} "
                    f"{unit}, got {v!r} (SI)"
                )
        from softpad.fem import MODEL_NAMES

        if self.material not in MODEL_NAMES:
            raise InputError(
                f"unknown material {self.material!r}; use one of {', '.join(MODEL_NAMES)}"
            )
        if not self.name:
            object.__setattr__(self, "name", self.label())

    def label(self) -> str:
        """A name from the variables, e.g. ``2x3-45mm-t1.5-neo-hookean-p1.1``."""
        return (
            f"{self.rows}x{self.cols}-{self.pitch_m * 1e3:g}mm-t{self.thickness_m * 1e3:g}"
            f"-{self.material}-p{self.p0_pa * 1e-3:g}"
        )

    @property
    def layout(self) -> PadLayout:
        """The pad's grid of modules."""
        return PadLayout(self.rows, self.cols, self.pitch_m)

    @property
    def n_modules(self) -> int:
        """Number of modules (and box channels): the cost proxy."""
        return self.layout.n_modules

    @property
    def is_thesis(self) -> bool:
        """Whether this is the thesis's prototype (whatever its name)."""
        return self.variables() == THESIS_DESIGN.variables()

    def variables(self) -> dict[str, Any]:
        """The design variables in SI (no name), the identity of a design."""
        d = asdict(self)
        d.pop("name")
        return d

    def fem_variables(self) -> dict[str, Any]:
        """The variables the finite-element response depends on (not the grid)."""
        return {
            "width_m": self.pitch_m,
            "thickness_m": self.thickness_m,
            "material": self.material,
            "p0_pa": self.p0_pa,
        }

    def to_dict(self) -> dict[str, Any]:
        """The design with units in the keys (mm, kPa)."""
        return {
            "name": self.name,
            "baseline": self.is_thesis,
            "rows": self.rows,
            "cols": self.cols,
            "pitch_mm": round(self.pitch_m * 1e3, 6),
            "thickness_mm": round(self.thickness_m * 1e3, 6),
            "material": self.material,
            "p0_kpa": round(self.p0_pa * 1e-3, 6),
            "modules": self.n_modules,
        }


#: The thesis's prototype pad (Sections 6.1 and 6.3): the baseline row of every sweep.
THESIS_DESIGN = PadDesign(name="thesis 2x3 45 mm")


def stable_hash(payload: Any) -> str:
    """SHA-256 (hex, 16 characters) of a JSON-serialisable payload, keys sorted."""
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


@dataclass(frozen=True)
class DesignSpace:
    """Values of each design variable; the designs are their Cartesian product."""

    #: (rows, cols) pairs.
    grids: tuple[tuple[int, int], ...] = ((2, 3),)
    #: Values of the other variables (SI).
    pitches_m: tuple[float, ...] = (thesis.MODULE_PITCH_M,)
    #: Values of the other variables (SI).
    thicknesses_m: tuple[float, ...] = (thesis.LAYER_THICKNESS_M,)
    #: Values of the other variables (SI).
    materials: tuple[str, ...] = ("neo-hookean",)
    #: Values of the other variables (SI).
    p0s_pa: tuple[float, ...] = (thesis.P0_PA,)

    def designs(self, with_baseline: bool = True) -> list[PadDesign]:
        """Every design of the space (the thesis's first when ``with_baseline``), no
        duplicates."""
        out = [THESIS_DESIGN] if with_baseline else []
        seen = {_key(d) for d in out}
        for (r, c), pitch, t, mat, p0 in itertools.product(
            self.grids, self.pitches_m, self.thicknesses_m, self.materials, self.p0s_pa
        ):
            d = PadDesign(int(r), int(c), float(pitch), float(t), str(mat), float(p0))
            if _key(d) not in seen:
                seen.add(_key(d))
                out.append(d)
        return out

    @property
    def size(self) -> int:
        """Number of designs in the product (without the baseline)."""
        return (
            len(self.grids)
            * len(self.pitches_m)
            * len(self.thicknesses_m)
            * len(self.materials)
            * len(self.p0s_pa)
        )


def _key(d: PadDesign) -> str:
    return stable_hash(d.variables())


#: The ``--quick`` sweep: eight designs around the thesis's pad, one variable or two at a time
#: (grid and pitch together keep the pad's size near 90 x 135 mm).
QUICK_DESIGNS: tuple[PadDesign, ...] = (
    THESIS_DESIGN,
    PadDesign(3, 4, 0.034),
    PadDesign(4, 6, 0.023),
    PadDesign(2, 3, 0.045, thickness_m=0.001),
    PadDesign(2, 3, 0.045, thickness_m=0.0025),
    PadDesign(2, 3, 0.045, material="yeoh"),
    PadDesign(2, 3, 0.045, p0_pa=600.0),
    PadDesign(2, 3, 0.045, p0_pa=2000.0),
)


def parse_values(
    text: str, name: str, scale: float, limits: tuple[float, float]
) -> tuple[float, ...]:
    """Numbers of a design option: ``1,1.5,2`` or ``1:2:0.5`` (start:stop:step, inclusive),
    in the option's unit, returned in SI (times ``scale``).

    Parameters
    ----------
    text
        The values as given.
    name
        The option, for messages (``--pitch-mm``).
    scale
        SI per unit of the text (1e-3 for mm, 1e3 for kPa).
    limits
        The lowest and highest value, SI.
    """
    values: list[float] = []
    for part in text.split(","):
        values.extend(_values_of(part.strip(), name))
    si = tuple(round(v * scale, 12) for v in values)
    _once(si, name, lambda v: f"{v / scale:g}")
    lo, hi = limits
    for v in si:
        if not math.isfinite(v) or not lo <= v <= hi:
            raise InputError(f"{name}: {v / scale:g} outside {lo / scale:g}..{hi / scale:g}")
    return si


def parse_grids(text: str) -> tuple[tuple[int, int], ...]:
    """Grids of ``--grid 2x3,3x4``.

    Parameters
    ----------
    text
        ``RxC`` grids, comma-separated (each side within :data:`LIMITS` ``rows``).
    """
    out = []
    lo, hi = LIMITS["rows"]
    for part in text.split(","):
        try:
            r, c = (int(x) for x in part.strip().lower().split("x"))
        except ValueError:
            raise InputError(f"--grid: expected RxC like 2x3, got {part.strip()!r}") from None
        if not (lo <= r <= hi and lo <= c <= hi):
            raise InputError(f"--grid: rows and columns must be {lo:g}..{hi:g}, got {part.strip()}")
        out.append((r, c))
    _once(out, "--grid", lambda g: f"{g[0]}x{g[1]}")
    return tuple(out)


def _once(values: Sequence[Any], name: str, show: Callable[[Any], str]) -> None:
    """InputError when a value of a design option is given twice (it would be computed twice)."""
    for i, v in enumerate(values):
        if v in values[:i]:
            raise InputError(f"{name}: {show(v)} is given twice")


def _values_of(part: str, name: str) -> list[float]:
    """One item of a design option: a number or ``start:stop:step`` (at most 100 values)."""
    try:
        numbers = [float(x) for x in part.split(":")] if part.isascii() and "_" not in part else []
    except ValueError:
        numbers = []
    if len(numbers) == 1:
        return numbers
    if len(numbers) != 3 or not all(math.isfinite(x) for x in numbers):
        raise InputError(f"{name}: expected numbers like 1,1.5 or start:stop:step, got {part!r}")
    a, b, step = numbers
    if step <= 0 or b < a:
        raise InputError(f"{name}: range {part!r} needs start <= stop and a step > 0")
    n = math.floor((b - a) / step + 1e-9) + 1
    if n > 100:
        raise InputError(f"{name}: range {part!r} has {n} values, at most 100")
    return [a + i * step for i in range(n)]
