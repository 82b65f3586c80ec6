"""What the MuJoCo world senses from its contacts: module loads, gripper contacts, first touch.

:class:`ContactSensing` reads MuJoCo's contact list of a :class:`~softpad.sim._mujoco_scene.
MujocoScene`: the normal force on every module top weighted by the FEM response where it acts
(what the box's modules measure), where the
gripper touches the pad and the objects, whether an object is carried, and the ground truth of
a descent (the first touch of a tip on a module or of a finger on an object).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.sim._mujoco_scene import MujocoScene
from softpad.sim._response import PadResponse

#: A contact normal with a vertical component above this is "from above" (cosine).
_FROM_ABOVE = 0.7


@dataclass(frozen=True)
class GripperContacts:
    """Where the gripper touches things at one instant (diagnostics of a trial)."""

    #: Per finger (right, left): module numbers the tip's sole presses, empty when none.
    sole_on_modules: tuple[tuple[int, ...], tuple[int, ...]]
    #: Per finger: vertical force of the sole on non-sensitive surfaces (lines, rim, table), N.
    sole_on_lines_n: tuple[float, float]
    #: Per finger: total contact force between the finger and any object, N.
    finger_on_object_n: tuple[float, float]
    #: Per finger: True when the finger touches an object with a mostly vertical contact normal
    #: (the jaw came down on the object instead of beside it).
    finger_on_object_from_above: tuple[bool, bool]
    #: Contact force between the palm and any object, N.
    palm_on_object_n: float


class ContactSensing:
    """Module loads and touch records computed from the contacts of a MuJoCo scene.

    Parameters
    ----------
    n_modules
        Number of modules on the pad.
    open_width_m
        Jaw setpoint counted as "open" for :attr:`tip_hit_object`, metres.
    response
        The FEM response on the pad: each contact's normal force counts as its equivalent
        load ``f s(x) / s_ref`` at the contact point (None: the bare force).

    Attributes
    ----------
    loads
        Equivalent load on every module at the last MuJoCo step, N.
    forces
        Plain normal contact force on every module top at the last step, N.
    pressure_pa
        Chamber pressure at which the response is evaluated, Pa.
    first_touch_s
        Simulated time of the first touch of a sole on a module top or of a finger on an object
        from above since the last :meth:`reset_touch`, seconds, or None.
    first_touch_z_m
        Height of the tips' lower faces at the first touch, metres, or None.
    tip_hit_object
        Name of the object a finger came down on from above with the jaws open, or None.
    """

    def __init__(
        self, n_modules: int, open_width_m: float, response: PadResponse | None = None
    ) -> None:
        import mujoco

        self.response = response
        self.pressure_pa = thesis.P0_PA
        self._centres = response.module_centers_m() if response is not None else None
        self._mj = mujoco
        self._force = np.zeros(6)
        self.loads = np.zeros(n_modules)
        self.forces = np.zeros(n_modules)
        self.first_touch_s: float | None = None
        self.first_touch_z_m: float | None = None
        self.tip_hit_object: str | None = None
        self.open_width_m = open_width_m

    def reset_touch(self, open_width_m: float) -> None:
        """Forget the touch records; ``open_width_m`` is the jaws' opening for the descent."""
        self.first_touch_s = None
        self.first_touch_z_m = None
        self.tip_hit_object = None
        self.open_width_m = open_width_m

    def update(self, s: MujocoScene, time_s: float, tip_z_m: float, width_m: float) -> None:
        """Compute :attr:`loads` after a MuJoCo step and record a first touch at ``time_s``.

        ``tip_z_m`` is the tips' height and ``width_m`` the jaw setpoint at that time.
        """
        d, m = s.data, s.model
        ks: list[int] = []
        forces: list[float] = []
        points: list[NDArray[np.float64]] = []
        gm = s.geom_module
        soles, fingers = s.sole, s.finger
        watch = self.first_touch_s is None or self.tip_hit_object is None
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            k = gm[g1] if gm[g1] >= 0 else gm[g2]
            if k >= 0:
                # the normal force indents the membrane and compresses the chamber; friction
                # shears it along its surface and hardly changes the volume
                self._mj.mj_contactForce(m, d, i, self._force)
                ks.append(int(k))
                forces.append(abs(self._force[0]))
                points.append(c.pos[:2].copy())
            if not watch:
                continue
            if g1 in soles or g2 in soles:
                if k >= 0 and self.first_touch_s is None:
                    self._touched(time_s, tip_z_m)
            elif g1 in fingers or g2 in fingers:
                other = g2 if g1 in fingers else g1
                b = int(m.geom_bodyid[other])
                if b in s.body_object and abs(c.frame[2]) > _FROM_ABOVE:
                    if self.first_touch_s is None:
                        self._touched(time_s, tip_z_m)
                    if self.tip_hit_object is None and width_m >= self.open_width_m:
                        self.tip_hit_object = s.body_object[b]
        self.loads = self._equivalent(ks, forces, points)

    def _equivalent(
        self, ks: list[int], forces: list[float], points: list[NDArray[np.float64]]
    ) -> NDArray[np.float64]:
        """Equivalent load per module of normal forces on module tops at contact points."""
        n = len(self.loads)
        if not ks:
            self.forces = np.zeros(n)
            return np.zeros(n)
        k, f = np.array(ks), np.array(forces)
        self.forces = np.bincount(k, weights=f, minlength=n).astype(float)
        if self.response is not None and self._centres is not None:
            r = self.response.response
            local = (np.array(points) - self._centres[k]) / self.response.scale
            f = f * r.influence(local, self.pressure_pa) / r.reference_influence(self.pressure_pa)
        return np.bincount(k, weights=f, minlength=n).astype(float)

    def _touched(self, time_s: float, tip_z_m: float) -> None:
        self.first_touch_s = time_s
        self.first_touch_z_m = tip_z_m

    def world_force(self, s: MujocoScene, i: int) -> NDArray[np.float64]:
        """Force of contact ``i`` in world coordinates, acting on geom2 (from geom1), N."""
        self._mj.mj_contactForce(s.model, s.data, i, self._force)
        frame = s.data.contact[i].frame.reshape(3, 3)
        return np.asarray(frame.T @ self._force[:3], dtype=float)

    def holding(self, s: MujocoScene) -> bool:
        """True when an object (any of its parts) touches both fingers and none of its parts
        touches the pad: it is carried."""
        d, m = s.data, s.model
        touch: dict[str, set[int]] = {}
        on_pad: set[str] = set()
        fingers = {s.finger[0]: 0, s.finger[1]: 1}
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            for g, other in ((g1, g2), (g2, g1)):
                name = s.body_object.get(int(m.geom_bodyid[g]))
                if name is not None:
                    if other in fingers:
                        touch.setdefault(name, set()).add(fingers[other])
                    elif other in s.pad_geoms:
                        on_pad.add(name)
        return any(len(t) == 2 and name not in on_pad for name, t in touch.items())

    def gripper_contacts(self, s: MujocoScene) -> GripperContacts:
        """Where the gripper touches the pad and the objects now."""
        m, d = s.model, s.data
        on_mod: list[set[int]] = [set(), set()]
        on_line = [0.0, 0.0]
        on_obj = [0.0, 0.0]
        above = [False, False]
        palm = 0.0
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            f = self.world_force(s, i)
            for side in (0, 1):
                sole, finger = s.sole[side], s.finger[side]
                if sole in (g1, g2):
                    other = g2 if g1 == sole else g1
                    if s.geom_module[other] >= 0:
                        on_mod[side].add(int(s.geom_module[other]) + 1)
                    elif other in s.pad_static:
                        on_line[side] += abs(f[2])
                if finger in (g1, g2):
                    other = g2 if g1 == finger else g1
                    if int(m.geom_bodyid[other]) in s.body_object:
                        on_obj[side] += float(np.linalg.norm(f))
                        if abs(c.frame[2]) > _FROM_ABOVE and abs(f[2]) > 1e-3:
                            above[side] = True
            if s.palm in (g1, g2):
                other = g2 if g1 == s.palm else g1
                if int(m.geom_bodyid[other]) in s.body_object:
                    palm += float(np.linalg.norm(f))
        return GripperContacts(
            sole_on_modules=(tuple(sorted(on_mod[0])), tuple(sorted(on_mod[1]))),
            sole_on_lines_n=(on_line[0], on_line[1]),
            finger_on_object_n=(on_obj[0], on_obj[1]),
            finger_on_object_from_above=(above[0], above[1]),
            palm_on_object_n=palm,
        )

    def gripper_vertical_force_n(self, s: MujocoScene) -> float:
        """Upward contact force on the gripper (soles on anything, fingers and palm on objects),
        N: what a force-limited robot would feel while descending."""
        d = s.data
        total = 0.0
        gripper_geoms = {*s.sole, *s.finger, s.palm}
        for i in range(d.ncon):
            c = d.contact[i]
            g1, g2 = int(c.geom1), int(c.geom2)
            if g1 in gripper_geoms or g2 in gripper_geoms:
                f = self.world_force(s, i)
                # force on geom2 is +f (normal from geom1 to geom2); upward on the gripper
                total += f[2] if g2 in gripper_geoms else -f[2]
        return total
