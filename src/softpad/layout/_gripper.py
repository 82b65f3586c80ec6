"""Parallel-jaw gripper geometry (seed, Section 6.3)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from softpad import thesis
from softpad.errors import InputError

#: The three ways the thesis mounted the Sawyer gripper: (max width, min width) in metres.
GRIPPER_CONFIGS_M: dict[str, tuple[float, float]] = {
    "wide": thesis.GRIPPER_MOUNTINGS_M["10/4"],
    "medium": thesis.GRIPPER_MOUNTINGS_M["6/2"],
    "narrow": thesis.GRIPPER_MOUNTINGS_M["4/0"],
}


@dataclass(frozen=True)
class GripperSpec:
    """A parallel-jaw gripper seen from above.

    Parameters
    ----------
    max_width_m, min_width_m
        Largest and smallest distance between the fingertips' inner faces, metres
        (thesis: 10/4, 6/2 or 4/0 cm).
    finger_length_m
        Finger length, metres (9.5 cm in the thesis).
    tip_width_m
        Size of a fingertip across the closing direction, metres.
    tip_thickness_m
        Size of a fingertip along the closing direction, metres. The thesis notes the tips were
        very small, which let a tip land entirely on a non-sensitive line between modules.
    """

    max_width_m: float = 0.06
    min_width_m: float = 0.02
    finger_length_m: float = thesis.FINGER_LENGTH_M
    tip_width_m: float = thesis.FINGERTIP_WIDTH_M
    tip_thickness_m: float = thesis.FINGERTIP_THICKNESS_M

    def __post_init__(self) -> None:
        for name in ("max_width_m", "finger_length_m", "tip_width_m", "tip_thickness_m"):
            v = getattr(self, name)
            if not math.isfinite(v) or v <= 0:
                raise InputError(f"gripper {name} must be a positive length, got {v!r}")
        if not (0 <= self.min_width_m < self.max_width_m):
            raise InputError(
                f"gripper min width must be in [0, max width = {self.max_width_m} m), "
                f"got {self.min_width_m!r}"
            )

    @classmethod
    def from_config(cls, name: str) -> GripperSpec:
        """One of the thesis's mountings: ``wide`` (10/4 cm), ``medium`` (6/2), ``narrow`` (4/0)."""
        if name not in GRIPPER_CONFIGS_M:
            raise InputError(
                f"gripper config must be one of {sorted(GRIPPER_CONFIGS_M)}, got {name!r}"
            )
        mx, mn = GRIPPER_CONFIGS_M[name]
        return cls(max_width_m=mx, min_width_m=mn)

    def fingertip_centres(
        self, cog_m: tuple[float, float], theta_rad: float, width_m: float | None = None
    ) -> tuple[tuple[float, float], tuple[float, float]]:
        """Centres (pad frame, metres) of the two fingertips for a grasp at ``cog_m``.

        The jaws close along ``theta_rad``; ``width_m`` is the opening (max width by default).
        """
        w = self.max_width_m if width_m is None else width_m
        r = w / 2 + self.tip_thickness_m / 2
        ux, uy = math.cos(theta_rad), math.sin(theta_rad)
        return (cog_m[0] + r * ux, cog_m[1] + r * uy), (cog_m[0] - r * ux, cog_m[1] - r * uy)
