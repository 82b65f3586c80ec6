"""How far the hand is from everything else in a MuJoCo scene: a lower bound from the geoms'
axis-aligned boxes, for coasting the world while the hand moves through free air.

While the hand approaches and descends towards a settled object, nothing but the hand moves:
the object rests on the inflated pad and no contact is made or broken until a fingertip or a
finger reaches the object or a module top. :func:`hand_clearance_m` bounds the distance from
every collidable geom of the hand (palm, fingers, soles) to every other collidable geom from
below (the largest gap along one axis between two world-aligned boxes that contain the geoms;
the table plane by height), so that a world that coasts only while the clearance, less the
hand's travel since it was computed, exceeds a margin cannot miss a contact.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["CLEARANCE_MARGIN_M", "HandClearance"]

#: Coasting with a moving hand stops this far from any geom, metres (the hand moves at most
#: 0.1 mm a 2 ms step at the trials' 0.05 m/s; MuJoCo's contact margin is zero).
CLEARANCE_MARGIN_M = 3e-3
#: Lever arm for the hand's yaw: no collidable geom of the hand lies farther than this from the
#: hand's axis, metres (the mountings' jaws open to at most about 0.15 m).
_YAW_REACH_M = 0.25


class HandClearance:
    """The hand's clearance to every other geom, computed after a real step, and the hand pose
    it was computed at.

    Parameters
    ----------
    model
        The compiled ``mujoco.MjModel``.
    hand_body
        Body id of the hand (its subtree: fingers and soles, is the hand).
    """

    def __init__(self, model: object, hand_body: int) -> None:
        m = model
        collidable = (np.asarray(m.geom_contype) | np.asarray(m.geom_conaffinity)) != 0  # type: ignore[attr-defined]
        root = np.asarray(m.body_rootid)[np.asarray(m.geom_bodyid)]  # type: ignore[attr-defined]
        plane = np.asarray(m.geom_type) == 0  # type: ignore[attr-defined]  # mjGEOM_PLANE
        self._hand = np.flatnonzero(collidable & (root == hand_body))
        self._other = np.flatnonzero(collidable & (root != hand_body) & ~plane)
        self._plane = np.flatnonzero(collidable & plane)
        self._aabb = np.asarray(m.geom_aabb).reshape(-1, 2, 3)  # type: ignore[attr-defined]
        #: Clearance at the last :meth:`update`, metres (0: not known).
        self.clearance_m = 0.0
        #: True when the world has stepped since the last :meth:`update`.
        self.stale = True
        self._at = np.zeros(4)

    def _boxes(self, data: object, geoms: NDArray[np.intp]) -> tuple[NDArray[np.float64], ...]:
        """World-aligned boxes (centres, half sizes) around ``geoms``."""
        xpos = np.asarray(data.geom_xpos)[geoms]  # type: ignore[attr-defined]
        xmat = np.asarray(data.geom_xmat)[geoms].reshape(-1, 3, 3)  # type: ignore[attr-defined]
        box = self._aabb[geoms]
        centre = xpos + np.einsum("gij,gj->gi", xmat, box[:, 0])
        half = np.einsum("gij,gj->gi", np.abs(xmat), box[:, 1])
        return centre, half

    def update(self, data: object, hand: NDArray[np.float64]) -> None:
        """Compute the clearance from ``data``'s geom poses (the hand at ``hand``: x, y, z,
        yaw)."""
        ch, hh = self._boxes(data, self._hand)
        co, ho = self._boxes(data, self._other)
        gap = np.abs(ch[:, None, :] - co[None, :, :]) - hh[:, None, :] - ho[None, :, :]
        clearance = float(np.min(np.max(gap, axis=2), initial=np.inf))
        if self._plane.size:
            floor = float(np.max(np.asarray(data.geom_xpos)[self._plane, 2]))  # type: ignore[attr-defined]
            clearance = min(clearance, float(np.min(ch[:, 2] - hh[:, 2])) - floor)
        self.clearance_m = clearance
        self._at = np.array(hand, dtype=float)
        self.stale = False

    def clear(self, hand: NDArray[np.float64]) -> bool:
        """True when the hand at ``hand`` is still farther than :data:`CLEARANCE_MARGIN_M`
        from every other geom (the clearance less its travel since :meth:`update`)."""
        a = self._at
        dx, dy, dz = hand[0] - a[0], hand[1] - a[1], hand[2] - a[2]
        travel = (dx * dx + dy * dy + dz * dz) ** 0.5 + abs(hand[3] - a[3]) * _YAW_REACH_M
        return self.clearance_m - travel > CLEARANCE_MARGIN_M
