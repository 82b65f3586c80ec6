"""The MuJoCo world's steps between two box frames in compiled code, when it is built.

:class:`FastSteps` runs a run of :meth:`softpad.sim.MujocoWorld.step`'s real MuJoCo steps in one
call of :mod:`softpad.sim._fastworld` (src/softpad/sim/_fastworld.c; ``make ext`` or ``pip
install``): the module springs following the box's heights, the hand and jaw servos put where
the kinematic arm has them (the arm itself moves here, in Python, for each step ahead), MuJoCo's
``mj_step`` through its C API, the module contacts read as :class:`~softpad.sim._mujoco_contacts.
ContactSensing` records them and the hold's coasting watching the velocities
(:class:`~softpad.sim._mujoco_coast.HoldCoast`). The same operations in the same order as the
Python path, so the world's state is the same bits (tests/sim/test_fast_steps.py). Without the
extension (:data:`AVAILABLE` False) the world steps in Python only.

The compiled loop hands back to Python after the step where a first-touch record may change
(a sole's or a finger's contact while they are watched) and where a coasting window opens; the
world does the rest of such a frame in Python.
"""

from __future__ import annotations

import ctypes
import glob
import os
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad.sim._mujoco_arm import KinematicArm
from softpad.sim._mujoco_coast import HoldCoast
from softpad.sim._mujoco_contacts import ContactSensing
from softpad.sim._mujoco_scene import MujocoScene

try:  # src/softpad/sim/_fastworld.c (make ext / pip install)
    import softpad.sim._fastworld as _fastworld
except ImportError:  # pragma: no cover - depends on the build
    _fastworld = None  # type: ignore[assignment]

#: True when the compiled steps are built.
AVAILABLE = _fastworld is not None

_MJ_FUNCTIONS: tuple[int, int] | None = None


def mujoco_functions() -> tuple[int, int]:
    """Addresses of MuJoCo's ``mj_step`` and ``mj_integratePos`` in the library the
    ``mujoco`` module runs on (the wheel's ``libmujoco.so``, loaded once per process)."""
    global _MJ_FUNCTIONS
    if _MJ_FUNCTIONS is None:
        import mujoco

        libs = sorted(glob.glob(os.path.join(os.path.dirname(mujoco.__file__), "libmujoco.so*")))
        if not libs:
            raise ImportError("the mujoco package has no libmujoco.so next to it")
        lib = ctypes.CDLL(libs[0])
        step, integrate = (
            int(ctypes.cast(f, ctypes.c_void_p).value or 0)
            for f in (lib.mj_step, lib.mj_integratePos)
        )
        _MJ_FUNCTIONS = (step, integrate)
    return _MJ_FUNCTIONS


def _addr(a: NDArray[Any]) -> int:
    return int(a.ctypes.data)


class FastSteps:
    """The compiled steps of one scene (its model, data and index tables).

    Parameters
    ----------
    scene
        The world's compiled model and data (the cone must be elliptic).
    coast
        The world's hold coasting (its watched dofs and windows).
    finger_length_m
        Hand-to-tip length, metres (the tips' height for the first-touch records).
    """

    def __init__(self, scene: MujocoScene, coast: HoldCoast, finger_length_m: float) -> None:
        assert _fastworld is not None
        m = scene.model
        self.scene = scene
        self._fn, self._integrate = mujoco_functions()
        self._m, self._d = int(m._address), int(scene.data._address)
        self._hq = np.ascontiguousarray(np.arange(m.nq)[scene.hand_q], dtype=np.int64)
        self._hv = np.ascontiguousarray(np.arange(m.nv)[scene.hand_v], dtype=np.int64)
        self._gm = np.ascontiguousarray(scene.geom_module, dtype=np.int64)
        self._grip = np.zeros(m.ngeom, dtype=np.uint8)
        self._grip[[*scene.sole, *scene.finger]] = 1
        spring = scene.module_spring
        assert spring.flags.c_contiguous and spring.dtype == np.float64
        self._spring = spring
        self._dofs = np.ascontiguousarray(coast._dofs, dtype=np.int64)
        nd = self._dofs.size
        self._v0, self._anchor = np.zeros(nd), np.zeros(nd)
        self._state = np.zeros(6, dtype=np.int64)
        self._coast_qvel = np.zeros(m.nv)
        self._fl = finger_length_m
        self._adr_spring, self._adr_gm, self._adr_grip = (
            _addr(a) for a in (spring, self._gm, self._grip)
        )
        self._adr_qvel = _addr(self._coast_qvel)
        self._plans: dict[tuple[float, float, float], tuple[list[float], list[float]]] = {}
        self._grow(8)

    def _grow(self, n: int) -> None:
        self._hands = np.zeros((n, 4))
        self._ctrl = np.zeros(n)
        self._still = np.zeros(n, dtype=np.uint8)
        self._ok = np.zeros(n, dtype=np.uint8)
        self._watch = np.zeros(n, dtype=np.uint8)
        self._cap = n
        arrays = (self._hands, self._ctrl, self._still, self._ok, self._watch, self._hq, self._hv)
        self._adr_steps = tuple(_addr(a) for a in arrays)
        v0, anchor, state = (_addr(a) for a in (self._v0, self._anchor, self._state))
        self._adr_coast = (_addr(self._dofs), self._dofs.size, v0, anchor, state)

    def run(
        self,
        world: Any,
        arm: KinematicArm,
        sensing: ContactSensing,
        coast: HoldCoast,
        ts: float,
        remaining: float,
        alpha: float,
        clamp: NDArray[np.int64],
    ) -> tuple[float, bool]:
        """Run the world's steps of this frame that are left, compiled, up to where Python must
        take over; returns the time left of the frame, as the world's step loop counts it, and
        whether the next step is Python's (the arm moves in a coasting window).

        ``world``: the :class:`~softpad.sim.MujocoWorld` (its pending time, heights, time and
        free-hand coasting); ``alpha``: the springs' low-pass factor a step (``ts / (filter
        time + ts)``, as the Python path computes it); ``clamp``: the vertical velocities of
        the objects being lowered onto the pad."""
        start = arm.snapshot()
        until = coast.until_s
        time_ok = until is not None and world._time_s < until
        resting = arm.at_rest()  # then every move of the frame leaves the arm as it is
        chunks, left = self._chunks(world._pending_s, remaining, ts)
        n = len(chunks)
        if n > self._cap:
            self._grow(max(n, 2 * self._cap))
        if resting:
            self._hands[:n] = arm.hand
            self._ctrl[:n] = arm.servo_ctrl()
            self._still[:n] = 1
            self._ok[:n] = time_ok
            self._watch[:n] = sensing.watching(arm.width_setpoint)
            widths = [arm.width_setpoint] * n
        else:
            widths = self._moves(arm, sensing, chunks, time_ok and world._free_hand is not None)
            self._ok[:n] &= time_ok
        if clamp.size:  # while an object is lowered, neither coasting nor resting
            self._still[:n] = 0
            self._ok[:n] = 0
        self._clamp = clamp
        return self._call(
            world, arm, sensing, coast, (ts, alpha, time_ok), (start, chunks, left, widths)
        )

    def _chunks(
        self, pending: float, remaining: float, ts: float
    ) -> tuple[list[float], list[float]]:
        """The frame's steps as the world's step loop counts them: each step's arm move and
        the time left of the frame before the first and after each (the same arithmetic;
        cached, as most frames start alike)."""
        key = (pending, remaining, ts)
        plan = self._plans.get(key)
        if plan is None:
            chunks: list[float] = []
            left = [remaining]
            while pending + remaining >= ts * (1 - 1e-9):
                chunk = max(ts - pending, 0.0)
                remaining -= chunk
                pending = 0.0
                chunks.append(chunk)
                left.append(remaining)
            if len(self._plans) < 64:
                self._plans[key] = (chunks, left)
            plan = (chunks, left)
        return plan

    def _moves(
        self, arm: KinematicArm, sensing: ContactSensing, chunks: list[float], free: bool
    ) -> list[float]:
        """Move the arm through the frame's steps, writing each step's hand, servo setpoint,
        rest and watch flags; returns the jaw setpoints. ``free``: coasting with a moving hand
        is allowed (only the jaws must stand)."""
        widths = []
        for j, chunk in enumerate(chunks):
            still = arm.move(chunk)
            w = arm.width_setpoint
            widths.append(w)
            self._hands[j] = arm.hand
            self._ctrl[j] = w / 2
            self._still[j] = still
            self._ok[j] = still or (free and arm.jaws_at_rest())
            self._watch[j] = sensing.watching(w)
        return widths

    def _call(
        self,
        world: Any,
        arm: KinematicArm,
        sensing: ContactSensing,
        coast: HoldCoast,
        step: tuple[float, float, bool],
        plan: tuple[Any, list[float], list[float], list[float]],
    ) -> tuple[float, bool]:
        start, chunks, left, widths = plan
        ts, alpha, time_ok = step
        n = len(chunks)
        observe = coast.until_s is not None
        if observe:
            coast.save_state(self._v0, self._anchor, self._state, self._coast_qvel)
        records: list[tuple[list[int], list[float], list[list[float]]]] = []
        clamp_address = _addr(self._clamp) if self._clamp.size else 0  # none read when empty
        done, real, stop, last, rested = _fastworld.steps(
            self._m, self._d, self._fn, self._integrate, n, *self._adr_steps, ts,
            self._adr_spring, world._heights_address, self._spring.size, world._heights_given,
            self._adr_gm, self._adr_grip, alpha, observe, time_ok,
            world._resting, *self._adr_coast, coast.verify_steps, coast.coast_steps,
            self._adr_qvel, clamp_address, self._clamp.size, world._LOWER_M_S, records,
        )  # fmt: skip
        world.rested_steps += rested
        if observe:
            coast.load_state(self._v0, self._anchor, self._state, self._coast_qvel)
            if real and world._free_hand is not None:
                world._free_hand.stale = True
        if real:
            sensing.add_steps(records, real, last)
        if done < n:  # the arm as it stood after the last step taken
            arm.restore(start)
            for chunk in chunks[:done]:
                arm.move(chunk)
        if not done:
            return left[0], True
        world._pending_s = 0.0
        if stop == 1:
            hand_z = float(self._hands[done - 1, 2])
            sensing.record_touches(self.scene, world._time_s, hand_z - self._fl, widths[done - 1])
        return left[done], done < n and stop == 0
