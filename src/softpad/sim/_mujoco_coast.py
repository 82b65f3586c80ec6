"""Coasting through a settled hold: the MuJoCo world's steady state carried on without solving.

Half of a grasp trial's simulated time is the 15 s hold, in which the hand stands still, the
jaws' servos hold a constant setpoint and, once the lift's swing has died out, the object creeps
in the jaws at a constant rate (MuJoCo's soft friction: 5-50 um/s in the catalogue's trials) or
not at all. :class:`HoldCoast` watches the velocities after every real MuJoCo step; when every
degree of freedom's velocity (the kinematic hand's excepted) has changed by less than
:data:`STEADY_DV` over :data:`VERIFY_STEPS` steps, the world *coasts* for :data:`COAST_STEPS`
steps: positions advance at those constant velocities (``mj_integratePos``), the contacts and the
module loads stay as they were, no constraint is solved. Then it steps for real again and
checks the velocities once more, against the ones it coasted with (:data:`ANCHOR_DV`): a slip
that starts (the object accelerating out of the jaws) ends the coasting within
``COAST_STEPS + VERIFY_STEPS`` steps, and the slip itself is simulated step by step.

The world coasts only when told to (:meth:`softpad.sim.MujocoWorld.coast_settled_until`: the
trial's lab allows it for the hold, up to a margin before its end, so that the outcome is read
from real steps) and only while the hand and the jaw setpoint stand still, or, where allowed
(:meth:`softpad.sim.MujocoWorld.coast_free_hand`), while only the hand moves, clear of
everything else.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: A velocity (m/s for a slide or a translation, rad/s for a rotation) that changes by less
#: than this over the verification window counts as steady: an acceleration below 2e-4 m/s^2
#: (the catalogue's held objects settle to below 1e-5 m/s^2 within 4-8 s of the lift).
STEADY_DV = 1e-5
#: Every velocity stays within this of those coasted with, or the coasting ends (a slow
#: acceleration, too small for one window, adds up over several).
ANCHOR_DV = 3e-5
#: Real MuJoCo steps that must show steady velocities before coasting (0.05 s at 2 ms).
VERIFY_STEPS = 25
#: MuJoCo steps coasted between two verifications (0.5 s at 2 ms).
COAST_STEPS = 250


class HoldCoast:
    """When a world may coast: steady velocities over a verification window, the coasting
    allowed (``until_s``) and the arm standing still.

    Parameters
    ----------
    moving_dofs
        Indices of the velocities to watch and to integrate (every dof but the hand's).
    timestep_s
        MuJoCo's step, seconds: the windows keep their durations (:data:`VERIFY_STEPS` and
        :data:`COAST_STEPS` are counted in 2 ms steps), so a coarser step verifies and coasts
        over the same simulated time.
    """

    def __init__(self, moving_dofs: NDArray[np.intp], timestep_s: float = 2e-3) -> None:
        self._dofs = moving_dofs
        scale = 2e-3 / timestep_s
        #: Real steps that must show steady velocities before coasting.
        self.verify_steps = max(1, round(VERIFY_STEPS * scale))
        #: Steps coasted between two verifications.
        self.coast_steps = max(1, round(COAST_STEPS * scale))
        #: Coasting allowed before this simulated time, seconds (None: not allowed).
        self.until_s: float | None = None
        #: MuJoCo steps coasted so far (diagnostics).
        self.coasted_steps = 0
        self._v0: NDArray[np.float64] | None = None
        self._count = 0
        self._anchor: NDArray[np.float64] | None = None
        self._left = 0
        #: The velocities coasted with (every dof; the hand's at zero, it stands still).
        self.qvel: NDArray[np.float64] | None = None

    def allow(self, until_s: float | None) -> None:
        """Allow coasting before simulated time ``until_s`` (None: stop coasting now)."""
        self.until_s = until_s
        self._reset()

    def _reset(self) -> None:
        self._v0, self._count, self._anchor, self._left = None, 0, None, 0

    def save_state(
        self,
        v0: NDArray[np.float64],
        anchor: NDArray[np.float64],
        state: NDArray[np.int64],
        qvel: NDArray[np.float64],
    ) -> None:
        """Write the window's state into arrays (the compiled steps' copy,
        :mod:`softpad.sim._mujoco_fast`): ``v0`` and ``anchor`` (one per watched dof),
        ``state`` (whether v0 is set, the count, whether the anchor is set, steps left, steps
        coasted there, whether ``qvel`` is new) and ``qvel`` (the velocities coasted with)."""
        state[:] = (self._v0 is not None, self._count, self._anchor is not None, self._left, 0, 0)
        if self._v0 is not None:
            v0[:] = self._v0
        if self._anchor is not None:
            anchor[:] = self._anchor
        if self.qvel is not None:
            qvel[:] = self.qvel

    def load_state(
        self,
        v0: NDArray[np.float64],
        anchor: NDArray[np.float64],
        state: NDArray[np.int64],
        qvel: NDArray[np.float64],
    ) -> None:
        """Take the window's state back from :meth:`save_state`'s arrays, as the compiled steps
        left them."""
        has_v0, count, has_anchor, left, coasted, new = state.tolist()
        self._v0 = v0.copy() if has_v0 else None
        self._anchor = anchor.copy() if has_anchor else None
        self._count, self._left = count, left
        self.coasted_steps += coasted
        if new:
            self.qvel = qvel.copy()

    @property
    def armed(self) -> bool:
        """True when steps are left of a coasting window (:meth:`coasts` may say True): the
        world asks whether the arm stands still only then."""
        return self._left > 0

    def coasts(self, time_s: float, still: bool) -> bool:
        """True when the next step at ``time_s`` is coasted (``still``: the arm stands)."""
        if self._left <= 0:
            return False
        if self.until_s is None or time_s >= self.until_s or not still:
            self._reset()
            return False
        self._left -= 1
        self.coasted_steps += 1
        return True

    def observe(self, qvel: NDArray[np.float64], time_s: float, still: bool) -> None:
        """Look at the velocities after a real step at ``time_s``."""
        if self.until_s is None or time_s >= self.until_s or not still:
            if self._v0 is not None or self._anchor is not None:
                self._reset()
            return
        v = qvel[self._dofs]
        if self._v0 is None:
            self._v0, self._count = v.copy(), 0
            return
        self._count += 1
        if self._count < self.verify_steps:
            return
        steady = float(np.max(np.abs(v - self._v0), initial=0.0)) <= STEADY_DV
        anchor = self._anchor
        if steady and (anchor is None or float(np.max(np.abs(v - anchor))) <= ANCHOR_DV):
            if anchor is None:
                self._anchor = v.copy()
            self.qvel = np.zeros_like(qvel)
            self.qvel[self._dofs] = v
            self._left = self.coast_steps
            self._v0 = None
        else:  # moving: watch a new window from here
            self._anchor = None
            self._v0, self._count = v.copy(), 0
