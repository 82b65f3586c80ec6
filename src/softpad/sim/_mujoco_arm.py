"""The kinematic arm of the MuJoCo world: hand pose and jaw setpoint moving towards a goal.

The robot is position-controlled: the hand follows a straight line towards its goal with a
trapezoidal speed profile, whatever pushes on it; the jaws are servoed towards a setpoint that
moves at the commanded speed (see :meth:`KinematicArm.servo_ctrl`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.sim._mujoco_model import MujocoGripper

#: Acceleration and braking of the kinematic arm, m/s^2 (a collaborative arm such as the
#: Sawyer reaches 0.2 m/s in about 0.1 s).
ARM_ACCELERATION_M_S2 = 2.0

#: A commanded width this close to the measured one means "leave the jaws as they are", metres.
SAME_WIDTH_M = 0.5e-3


class KinematicArm:
    """Hand pose (x, y, z of the hand, yaw) and jaw setpoint of the gripper, pad frame.

    Parameters
    ----------
    hand
        Start pose of the hand: x, y, z (the hand, ``finger_length_m`` above the tips), yaw.
    open_width_m
        Start opening of the jaws, metres.

    Attributes
    ----------
    hand
        Current hand pose [x, y, z, yaw], metres and radians.
    goal
        Goal [x, y, z, yaw, width], metres and radians.
    speed_m_s
        Commanded linear speed, m/s (``inf`` for streamed setpoints).
    width_setpoint
        Current jaw-opening setpoint, metres.
    closing
        True while closing fully (force-limited, see :meth:`servo_ctrl`).
    """

    def __init__(self, hand: NDArray[np.float64], open_width_m: float) -> None:
        self.hand = hand
        self.goal = np.append(hand.copy(), open_width_m)
        self.speed_m_s = 0.0
        self.width_setpoint = open_width_m
        self.closing = False
        self._hand_speed = 0.0

    def stop(self) -> None:
        """Hold the hand where it is; the jaws keep their setpoint (and grip)."""
        self.goal = np.append(self.hand.copy(), self.width_setpoint)
        self.speed_m_s = 0.0
        self._hand_speed = 0.0

    def command(
        self,
        pose: tuple[float, float, float, float],
        width_m: float,
        measured_width_m: float,
        speed_m_s: float,
        gripper: MujocoGripper,
    ) -> None:
        """Aim at tip pose ``pose`` (x, y, z, yaw) and opening ``width_m`` at ``speed_m_s``.

        A width within :data:`SAME_WIDTH_M` of ``measured_width_m`` keeps the jaws' goal (a
        squeezed object stays squeezed); other widths are clamped to the mounting's range
        (1 m opens fully, 0 m closes fully, force-limited).
        """
        g = gripper
        w = width_m
        if abs(w - measured_width_m) < SAME_WIDTH_M:
            w = float(self.goal[4])
        else:
            w = min(max(w, g.min_width_m), g.max_width_m)
            self.closing = w <= g.min_width_m + SAME_WIDTH_M
            if self.closing:  # the setpoint runs on past the stops by the squeeze (servo_ctrl)
                w = g.min_width_m - 2 * g.squeeze_offset_m
        x, y, z, yaw = pose
        self.goal = np.array([x, y, z + g.finger_length_m, _unwrap(yaw, self.hand[3]), w])
        self.speed_m_s = speed_m_s

    def servo_ctrl(self) -> float:
        """Setpoint of each jaw's servo, metres from the centre: half the opening setpoint.

        Closing fully is speed- and force-limited, like the Sawyer gripper closing on an
        object: the setpoint moves at the commanded speed towards the closed stops and on past
        them by ``MujocoGripper.squeeze_offset_m``, so a jaw meets an object at the commanded speed, and
        once blocked its force grows with the setpoint (servo gain times speed, 100 N/s at the
        thesis's 0.05 m/s) up to the grip force, which it then holds (an unblocked jaw stops
        at its joint limit). Before, the setpoint jumped ahead by the whole offset as closing
        began, and the jaws hit objects at up to the force limit over the joint damping
        (0.5 m/s), ten times the commanded speed.
        """
        return self.width_setpoint / 2

    def at_rest(self) -> bool:
        """True when the hand stands at its goal and the jaw setpoint at its goal (bit for bit:
        :meth:`move` would change nothing)."""
        g = self.goal
        return (
            self._hand_speed == 0.0
            and self.width_setpoint == g[4]
            and self.hand.tobytes() == g[:4].tobytes()
        )

    def snapshot(self) -> tuple[NDArray[np.float64], float, float]:
        """What :meth:`move` changes (hand pose, hand speed, jaw setpoint), for :meth:`restore`."""
        return self.hand.copy(), self._hand_speed, self.width_setpoint

    def restore(self, state: tuple[NDArray[np.float64], float, float]) -> None:
        """Put back what :meth:`move` changed since ``state`` (:meth:`snapshot`); the hand's
        array is written in place."""
        hand, self._hand_speed, self.width_setpoint = state
        self.hand[:] = hand

    def jaws_at_rest(self) -> bool:
        """True when the jaw setpoint stands at its goal (the hand may move)."""
        return self.width_setpoint == self.goal[4]

    def move(self, dt: float) -> bool:
        """Advance the hand along its straight line, and the yaw and jaw setpoint, by ``dt`` s;
        True when the arm stands at rest afterwards (:meth:`at_rest`, asked once here)."""
        if self.at_rest():  # nothing to advance (the hold, the waits: half of a trial's steps)
            return True
        delta = self.goal[:3] - self.hand[:3]
        # np.linalg.norm's own computation of a 1-D vector's norm, without its Python wrapper
        dist = math.sqrt(float(delta.dot(delta)))
        # the arm accelerates and brakes at ARM_ACCELERATION_M_S2 (a kinematic jump to the
        # lift speed would ask friction for 100 m/s^2 on the object)
        a = ARM_ACCELERATION_M_S2
        if math.isinf(self.speed_m_s):  # streamed setpoints: no profile
            v = math.inf
        else:
            v = min(self.speed_m_s, self._hand_speed + a * dt, math.sqrt(2 * a * dist))
        self._hand_speed = v
        step = v * dt if math.isfinite(v) else math.inf
        if dist <= step or dist < 1e-9:
            self.hand[:3] = self.goal[:3]
            if dist < 1e-9:
                self._hand_speed = 0.0
        else:
            self.hand[:3] = self.hand[:3] + delta * (step / dist)
        step = self.speed_m_s * dt
        dyaw = self.goal[3] - self.hand[3]
        ystep = self.speed_m_s / thesis.APPROACH_SPEED_M_S * dt
        self.hand[3] = (
            self.goal[3] if abs(dyaw) <= ystep else self.hand[3] + math.copysign(ystep, dyaw)
        )
        dw = self.goal[4] - self.width_setpoint
        self.width_setpoint = (
            self.goal[4] if abs(dw) <= step else self.width_setpoint + math.copysign(step, dw)
        )
        return self.at_rest()


def _unwrap(angle: float, reference: float) -> float:
    """``angle`` plus a multiple of 2 pi, closest to ``reference`` (no jumps in the yaw joint)."""
    return reference + math.remainder(angle - reference, 2 * math.pi)
