"""Geometry, mesh and load-patch descriptions of one SoftPad module (thesis Section 7.2)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from softpad import thesis
from softpad.errors import MM_AS_M, InputError, check_finite, check_range

#: Widest module the model accepts, m (the prototype's is 45 mm): wider is a unit mix-up.
MAX_MODULE_WIDTH_M = 0.5

#: Module width of the prototype, m (thesis Section 6.1: 45 x 45 mm air channel).
DEFAULT_WIDTH_M = thesis.MODULE_PITCH_M
#: Upper-layer thickness of the prototype, m (thesis Section 6.1: 1.5 mm).
DEFAULT_THICKNESS_M = thesis.LAYER_THICKNESS_M


@dataclass(frozen=True)
class ModuleGeometry:
    """The upper silicone layer of a module: a ``width x width x thickness`` block.

    Parameters
    ----------
    width_m
        Side of the square air channel, m (thesis: 45 mm).
    thickness_m
        Thickness of the upper layer, m (thesis: 1.5 mm).

    Raises
    ------
    InputError
        When a size is not finite, <= 0, or the layer is thicker than half its width
        (no longer a plate over an air channel).
    """

    width_m: float = DEFAULT_WIDTH_M
    thickness_m: float = DEFAULT_THICKNESS_M

    def __post_init__(self) -> None:
        w = check_finite("width_m", self.width_m)
        t = check_finite("thickness_m", self.thickness_m)
        if w <= 0:
            raise InputError(f"module width must be > 0 m, got {w!r} m")
        if t <= 0:
            raise InputError(f"layer thickness must be > 0 m, got {t!r} m")
        check_range("module width_m", w, 0.0, MAX_MODULE_WIDTH_M, "m", MM_AS_M)
        if t > 0.5 * w:
            raise InputError(
                f"layer thickness {t * 1e3:.4g} mm exceeds half the module width "
                f"{w * 1e3:.4g} mm; the model describes a thin layer over an air channel"
            )
        object.__setattr__(self, "width_m", w)
        object.__setattr__(self, "thickness_m", t)

    @property
    def half_width_m(self) -> float:
        """Half the width: the side of the quarter model, m."""
        return 0.5 * self.width_m

    @property
    def area_m2(self) -> float:
        """Area of the air channel (the pressurised lower face), m^2."""
        return self.width_m**2


@dataclass(frozen=True)
class MeshOptions:
    """Discretisation of the quarter model.

    Parameters
    ----------
    cells_in_plane
        Cells along each in-plane side of the quarter (half width).
    cells_through_thickness
        Cells through the layer thickness.
    element
        ``"hex8"``: trilinear hexahedra with the mean-dilatation u/p/J formulation
        (pressure and volume ratio constant per cell, statically condensed; FElupe
        ``SolidBodyNearlyIncompressible``). ``"hex27"``: triquadratic hexahedra with
        discontinuous trilinear pressure and volume-ratio fields (u/p/J mixed, FElupe
        ``FieldsMixed`` + ``NearlyIncompressible``). Both are free of volumetric locking at
        kappa = 1e5 mu.
    grading
        In-plane grading toward the clamped edges, in [0, 1): a reference coordinate
        ``xi`` in [0, 1] of the quarter maps to ``(1 - g) xi + g sin(pi xi / 2)``, so cells
        shrink toward the clamped edge where the layer bends sharply. 0 is uniform.
    """

    cells_in_plane: int = 12
    cells_through_thickness: int = 2
    element: str = "hex8"
    grading: float = 0.5

    def __post_init__(self) -> None:
        if int(self.cells_in_plane) != self.cells_in_plane or self.cells_in_plane < 1:
            raise InputError(
                f"cells_in_plane must be a positive integer, got {self.cells_in_plane!r}"
            )
        if (
            int(self.cells_through_thickness) != self.cells_through_thickness
            or self.cells_through_thickness < 1
        ):
            raise InputError(
                "cells_through_thickness must be a positive integer, "
                f"got {self.cells_through_thickness!r}"
            )
        if self.element not in ("hex8", "hex27"):
            raise InputError(f"element must be 'hex8' or 'hex27', got {self.element!r}")
        g = check_finite("grading", self.grading)
        if not 0.0 <= g < 1.0:
            raise InputError(f"grading must be in [0, 1), got {g!r}")

    def map_coordinate(self, xi: np.ndarray) -> np.ndarray:
        """Graded position in [0, 1] of the uniform reference coordinate ``xi`` in [0, 1]."""
        xi = np.asarray(xi, dtype=float)
        return (1.0 - self.grading) * xi + self.grading * np.sin(0.5 * np.pi * xi)

    def refined(self, factor: int = 2) -> MeshOptions:
        """The same mesh with every cell split ``factor`` times in each direction."""
        return MeshOptions(
            self.cells_in_plane * factor,
            self.cells_through_thickness * factor,
            self.element,
            self.grading,
        )


#: Default mesh (12 x 12 x 2 graded hex8): centre height within 0.4 % of a 32 x 32 x 4 mesh
#: over 0.25..3 kPa (see docs/fem.md).
DEFAULT_MESH = MeshOptions()


@dataclass(frozen=True)
class LoadPatch:
    """A centred region of the top face that carries a uniform vertical load.

    Parameters
    ----------
    shape
        ``"rectangle"`` or ``"disc"``.
    size_x_m
        Rectangle side along x, or disc diameter, m.
    size_y_m
        Rectangle side along y, m (ignored for a disc; defaults to ``size_x_m``).
    """

    shape: str = "rectangle"
    size_x_m: float = 0.030
    size_y_m: float | None = None

    def __post_init__(self) -> None:
        if self.shape not in ("rectangle", "disc"):
            raise InputError(f"load patch shape must be 'rectangle' or 'disc', got {self.shape!r}")
        sx = check_finite("patch size_x_m", self.size_x_m)
        if sx <= 0:
            raise InputError(f"load patch size must be > 0 m, got {sx!r} m")
        sy = sx if self.size_y_m is None else check_finite("patch size_y_m", self.size_y_m)
        if sy <= 0:
            raise InputError(f"load patch size must be > 0 m, got {sy!r} m")
        for name, v in (("size_x_m", sx), ("size_y_m", sy)):  # a module is 45 mm wide
            check_range(f"load patch {name}", v, 0.0, 1.0, "m", MM_AS_M)
        object.__setattr__(self, "size_x_m", sx)
        object.__setattr__(self, "size_y_m", sy)

    @classmethod
    def square(cls, side_m: float) -> LoadPatch:
        """A centred square of side ``side_m`` (m)."""
        return cls("rectangle", side_m, side_m)

    @classmethod
    def disc(cls, radius_m: float) -> LoadPatch:
        """A centred disc of radius ``radius_m`` (m)."""
        return cls("disc", 2.0 * radius_m, 2.0 * radius_m)

    @property
    def area_m2(self) -> float:
        """Area of the patch, m^2."""
        assert self.size_y_m is not None
        if self.shape == "disc":
            return float(np.pi * (0.5 * self.size_x_m) ** 2)
        return self.size_x_m * self.size_y_m

    def contains(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Whether the points ``(x, y)`` (m, centre at the origin) lie in the patch."""
        assert self.size_y_m is not None
        if self.shape == "disc":
            return np.asarray(x**2 + y**2 <= (0.5 * self.size_x_m) ** 2)
        return np.asarray((np.abs(x) <= 0.5 * self.size_x_m) & (np.abs(y) <= 0.5 * self.size_y_m))

    def describe(self) -> str:
        """Human-readable description, e.g. ``'centred square 30 x 30 mm'``."""
        assert self.size_y_m is not None
        if self.shape == "disc":
            return f"centred disc of radius {0.5e3 * self.size_x_m:g} mm"
        return f"centred rectangle {self.size_x_m * 1e3:g} x {self.size_y_m * 1e3:g} mm"
