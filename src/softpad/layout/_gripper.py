"""Parallel-jaw gripper geometry (thesis, Section 6.3)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from softpad import thesis
from softpad.errors import MM_AS_M, InputError, check_finite, check_range

#: Largest jaw opening or finger length accepted, m: a parallel-jaw gripper for objects on a pad
#: (the thesis's opens 10 cm at most); a larger value is a unit mix-up.
MAX_GRIPPER_SIZE_M = 0.5

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
        (thesis, Section 6.3: the three mountings 10/4, 6/2 or 4/0 cm).
    finger_length_m
        Finger length, metres (thesis, Section 6.3: 9.5 cm).
    tip_width_m
        Size of a fingertip across the closing direction, metres: 16 mm, the Sawyer electric
        gripper's basic hard tip (:data:`softpad.thesis.FINGERTIP_WIDTH_M` names the source; the
        seed only says the tips were "very small for the chosen gripper").
    tip_thickness_m
        Size of a fingertip along the closing direction, metres: 6.5 mm, the same tip.

    Notes
    -----
    One set of figures for the planner, the analytic world (``softpad.sim.SimGripper``) and the
    MuJoCo world (``softpad.sim.MujocoGripper.from_spec``); they come from the seed and the
    gripper's published description and are never changed to make a trial pass.
    """

    max_width_m: float = 0.06
    min_width_m: float = 0.02
    finger_length_m: float = thesis.FINGER_LENGTH_M
    tip_width_m: float = thesis.FINGERTIP_WIDTH_M
    tip_thickness_m: float = thesis.FINGERTIP_THICKNESS_M

    def __post_init__(self) -> None:
        check_finite("gripper min_width_m", self.min_width_m)
        for name in ("max_width_m", "finger_length_m", "tip_width_m", "tip_thickness_m"):
            v = check_finite(f"gripper {name}", getattr(self, name))
            if v <= 0:
                raise InputError(f"gripper {name} must be a positive length, got {v!r}")
        check_range("gripper max_width_m", self.max_width_m, 0.0, MAX_GRIPPER_SIZE_M, "m", MM_AS_M)
        check_range(
            "gripper finger_length_m", self.finger_length_m, 0.0, MAX_GRIPPER_SIZE_M, "m", MM_AS_M
        )
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

    @classmethod
    def from_mounting(cls, mounting: str) -> GripperSpec:
        """One of the thesis's mountings by its widths in cm: ``"10/4"``, ``"6/2"``, ``"4/0"``."""
        if mounting not in thesis.GRIPPER_MOUNTINGS_M:
            raise InputError(
                f"gripper mounting must be one of {', '.join(thesis.GRIPPER_MOUNTINGS_M)}, "
                f"got {mounting!r}"
            )
        mx, mn = thesis.GRIPPER_MOUNTINGS_M[mounting]
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
