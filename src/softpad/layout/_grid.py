"""R x C grid of pneumatic modules."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import MM_AS_M, InputError, LayoutError, check_finite

#: Module pitch of the thesis prototype: 45 mm square modules (thesis, Section 6.1.1).
DEFAULT_PITCH_M = thesis.MODULE_PITCH_M

_LAYOUT_RE = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")


@dataclass(frozen=True)
class PadLayout:
    """Geometry of an R x C SoftPad.

    Parameters
    ----------
    rows, cols
        Number of module rows and columns (thesis prototype: 2 x 3).
    pitch_m
        Side of one module in metres (module unit -> metres factor), 0.045 m by default.
    """

    rows: int = 2
    cols: int = 3
    pitch_m: float = DEFAULT_PITCH_M

    def __post_init__(self) -> None:
        for name, v in (("rows", self.rows), ("cols", self.cols)):
            if not isinstance(v, int | np.integer) or v < 1 or v > 64:
                raise LayoutError(f"{name} must be an integer from 1 to 64, got {v!r}")
        try:
            pitch = check_finite("module pitch_m", self.pitch_m)
        except InputError as exc:
            raise LayoutError(str(exc)) from None
        if not (1e-3 <= pitch <= 1.0):
            raise LayoutError(
                f"module pitch must be between 1 mm and 1000 mm, got {pitch * 1e3:g} mm"
                + (f" ({MM_AS_M})" if pitch > 1.0 else "")
            )

    def __hash__(self) -> int:
        # the planner's caches key on the layout several times a plan: hash the fields once
        h: int | None = self.__dict__.get("_hash")
        if h is None:
            h = hash((self.rows, self.cols, self.pitch_m))
            self.__dict__["_hash"] = h
        return h

    @property
    def n_modules(self) -> int:
        """Number of modules R*C."""
        return self.rows * self.cols

    @property
    def name(self) -> str:
        """Layout string such as ``"2x3"``."""
        return f"{self.rows}x{self.cols}"

    @property
    def size(self) -> tuple[float, float]:
        """Pad extent (width along x, height along y) in module units."""
        return float(self.cols), float(self.rows)

    @property
    def modules(self) -> range:
        """The module numbers 1..N."""
        return range(1, self.n_modules + 1)

    def check_module(self, module: int) -> int:
        """Return ``module`` if it is a valid 1-based module number, else raise LayoutError."""
        if type(module) is int and 0 < module <= self.rows * self.cols:
            return module
        if not isinstance(module, int | np.integer) or not 1 <= module <= self.n_modules:
            raise LayoutError(
                f"module number must be from 1 to {self.n_modules} on a {self.name} pad, "
                f"got {module!r}"
            )
        return int(module)

    @cached_property
    def _row_col_table(self) -> tuple[tuple[int, int], ...]:
        return tuple((k // self.cols, k % self.cols) for k in range(self.n_modules))

    @cached_property
    def center_table(self) -> tuple[tuple[float, float], ...]:
        """Centre (x, y) of every module in module units, index = module - 1 (plain floats:
        the planner's hot path reads them without a check per module)."""
        return tuple((c + 0.5, (self.rows - 1 - r) + 0.5) for r, c in self._row_col_table)

    @cached_property
    def _neighbour_table(self) -> tuple[tuple[int, ...], ...]:
        table = []
        for r, c in self._row_col_table:
            table.append(
                tuple(
                    sorted(
                        (r + dr) * self.cols + (c + dc) + 1
                        for dr in (-1, 0, 1)
                        for dc in (-1, 0, 1)
                        if (dr or dc) and 0 <= r + dr < self.rows and 0 <= c + dc < self.cols
                    )
                )
            )
        return tuple(table)

    def row_col(self, module: int) -> tuple[int, int]:
        """Row (0 = top) and column (0 = left) of a 1-based module number."""
        return self._row_col_table[self.check_module(module) - 1]

    def module_at(self, row: int, col: int) -> int:
        """1-based module number at (row, col), row 0 at the top."""
        if not (0 <= row < self.rows and 0 <= col < self.cols):
            raise LayoutError(f"(row, col) = ({row}, {col}) is outside the {self.name} pad")
        return row * self.cols + col + 1

    def center(self, module: int) -> tuple[float, float]:
        """Centre (x, y) of a module in module units."""
        return self.center_table[self.check_module(module) - 1]

    @cached_property
    def centers(self) -> NDArray[np.float64]:
        """Centres of all modules, shape (N, 2), row i = module i+1, module units."""
        k = np.arange(self.n_modules)
        return np.column_stack([k % self.cols + 0.5, (self.rows - 1 - k // self.cols) + 0.5])

    def module_containing(self, x: float, y: float) -> int | None:
        """Module whose square contains point (x, y) in module units, or None off the pad.

        Points on a shared edge belong to the module to the right / below.
        """
        if not (0.0 <= x <= self.cols and 0.0 <= y <= self.rows):
            return None
        c = min(int(np.floor(x)), self.cols - 1)
        r_from_bottom = min(int(np.floor(y)), self.rows - 1)
        return self.module_at(self.rows - 1 - r_from_bottom, c)

    def neighbours(self, module: int) -> tuple[int, ...]:
        """8-neighbours of a module, sorted."""
        return self._neighbour_table[self.check_module(module) - 1]

    def connected_groups(
        self, modules: set[int] | list[int] | tuple[int, ...]
    ) -> list[tuple[int, ...]]:
        """Split modules into 8-connected groups, each sorted, groups ordered by first module."""
        remaining = {self.check_module(m) for m in modules}
        groups: list[tuple[int, ...]] = []
        while remaining:
            seed = min(remaining)
            stack, group = [seed], {seed}
            remaining.discard(seed)
            while stack:
                m = stack.pop()
                for n in self._neighbour_table[m - 1]:
                    if n in remaining:
                        remaining.discard(n)
                        group.add(n)
                        stack.append(n)
            groups.append(tuple(sorted(group)))
        return sorted(groups)

    def to_metres(self, xy_units: tuple[float, float] | NDArray[np.float64]) -> NDArray[np.float64]:
        """Module units -> metres in the pad frame (multiply by the pitch)."""
        return np.asarray(xy_units, dtype=float) * self.pitch_m

    def to_units(self, xy_m: tuple[float, float] | NDArray[np.float64]) -> NDArray[np.float64]:
        """Metres in the pad frame -> module units."""
        return np.asarray(xy_m, dtype=float) / self.pitch_m


def parse_layout(text: str, pitch_m: float = DEFAULT_PITCH_M) -> PadLayout:
    """Parse ``"RxC"`` (e.g. ``"2x3"``) into a :class:`PadLayout`.

    Raises
    ------
    LayoutError
        When the string is not of the form ``RxC`` with positive integers.
    """
    m = _LAYOUT_RE.match(str(text))
    if not m:
        raise LayoutError(f"layout must look like ROWSxCOLS, e.g. 2x3, got {text!r}")
    return PadLayout(int(m.group(1)), int(m.group(2)), pitch_m)
