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
        self._n = n_modules
        self._last: tuple[list[int], list[float]] = ([], [])
        # contacts of the steps not yet weighted: (modules, normal forces, points) per step
        self._pending: list[tuple[list[int], list[float], list[list[float]]]] = []
        self._pending_pressure = self.pressure_pa
        self._flushed = np.zeros(n_modules)
        self._steps = 0
        self._gm: tuple[MujocoScene, list[int]] | None = None
        self._grip: frozenset[int] = frozenset()
        self._elliptic = True
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
        """Read the module contacts after a MuJoCo step and record a first touch at ``time_s``.

        ``tip_z_m`` is the tips' height and ``width_m`` the jaw setpoint at that time. The
        contacts are read from MuJoCo's arrays at once (the normal force of an elliptic-cone
        contact is its first constraint force, what ``mj_contactForce`` returns); their
        equivalent loads are weighted later, all steps of a sample period in one call
        (:meth:`mean_loads`), at the pressure the period ran at.
        """
        d = s.data
        gm = self._geom_modules(s)
        if not d.ncon:  # nothing touches anything (the hand in the air over an empty pad)
            self._last = ([], [])
            self._steps += 1
            return
        con = d.contact
        g1, g2 = con.geom1.tolist(), con.geom2.tolist()
        grip = self._grip
        # _watch can change a record only before the first touch, or, with the jaws open,
        # before a jaw came down on an object (closed jaws: no first-touch work per step)
        watch = self.first_touch_s is None or (
            self.tip_hit_object is None and width_m >= self.open_width_m
        )
        on: list[int] = []
        ks: list[int] = []
        near: list[int] = []  # contacts of a sole or a finger (the first-touch records)
        for i, (a, b) in enumerate(zip(g1, g2, strict=True)):
            k = gm[a] if gm[a] >= 0 else gm[b]
            if k >= 0:
                on.append(i)
                ks.append(k)
            if watch and (a in grip or b in grip):
                near.append(i)
        if on:
            # plain floats, made arrays once a sample period (_flush): a step has 3-4 contacts
            if self._elliptic:
                addr, efc = con.efc_address.tolist(), d.efc_force
                # excluded contacts (address -1) carry no force
                f = [abs(float(efc[a])) if a >= 0 else 0.0 for a in (addr[i] for i in on)]
            else:
                f = [self._normal_force(s, i) for i in on]
            self._flush_if_pressure_changed()
            xy = con.pos.tolist()
            self._pending.append((ks, f, [xy[i][:2] for i in on]))
            self._last = (ks, f)
        else:
            self._last = ([], [])
        self._steps += 1
        for i in near:
            self._watch(s, time_s, tip_z_m, width_m, i, g1[i], g2[i], gm)

    def add_steps(
        self,
        records: list[tuple[list[int], list[float], list[list[float]]]],
        n_steps: int,
        last: int,
    ) -> None:
        """Take ``n_steps`` (> 0) steps' module contacts read elsewhere (the compiled steps,
        :mod:`softpad.sim._mujoco_fast`), as :meth:`update` records them: ``records`` one per
        step with a module contact, in step order; ``last``: the last step had one (1) or
        not (0)."""
        if records:
            # the pressure is the same for every step of a call (the box sets it between)
            self._flush_if_pressure_changed()
            self._pending.extend(records)
        self._last = (records[-1][0], records[-1][1]) if last == 1 else ([], [])
        self._steps += n_steps

    def record_touches(self, s: MujocoScene, time_s: float, tip_z_m: float, width_m: float) -> None:
        """The first-touch records of the step just taken, as :meth:`update` keeps them (for a
        step whose contacts were read elsewhere, with the records watched)."""
        gm = self._geom_modules(s)
        con = s.data.contact
        g1, g2 = con.geom1.tolist(), con.geom2.tolist()
        grip = self._grip
        near = [i for i, (a, b) in enumerate(zip(g1, g2, strict=True)) if a in grip or b in grip]
        for i in near:
            self._watch(s, time_s, tip_z_m, width_m, i, g1[i], g2[i], gm)

    def watching(self, width_m: float) -> bool:
        """Whether a step with jaw setpoint ``width_m`` can change a first-touch record."""
        return self.first_touch_s is None or (
            self.tip_hit_object is None and width_m >= self.open_width_m
        )

    def _geom_modules(self, s: MujocoScene) -> list[int]:
        """The scene's geom -> module table as a list (read per contact), and the gripper's
        sole and finger geoms."""
        if self._gm is None or self._gm[0] is not s:
            self._gm = (s, s.geom_module.tolist())
            self._grip = frozenset((*s.sole, *s.finger))
            self._elliptic = s.model.opt.cone == self._mj.mjtCone.mjCONE_ELLIPTIC
        return self._gm[1]

    def _normal_force(self, s: MujocoScene, i: int) -> float:
        self._mj.mj_contactForce(s.model, s.data, i, self._force)
        return abs(float(self._force[0]))

    def _watch(
        self,
        s: MujocoScene,
        time_s: float,
        tip_z_m: float,
        width_m: float,
        i: int,
        a: int,
        b: int,
        gm: list[int],
    ) -> None:
        """First touch of a sole on a module or of a finger on an object from above."""
        soles, fingers = s.sole, s.finger
        if a in soles or b in soles:
            k = gm[a] if gm[a] >= 0 else gm[b]
            if k >= 0 and self.first_touch_s is None:
                self._touched(time_s, tip_z_m)
        elif a in fingers or b in fingers:
            other = b if a in fingers else a
            body = int(s.model.geom_bodyid[other])
            if body in s.body_object and abs(s.data.contact.frame[i, 2]) > _FROM_ABOVE:
                if self.first_touch_s is None:
                    self._touched(time_s, tip_z_m)
                if self.tip_hit_object is None and width_m >= self.open_width_m:
                    self.tip_hit_object = s.body_object[body]

    @property
    def forces(self) -> NDArray[np.float64]:
        """Plain normal contact force on every module top at the last step, N."""
        k, f = self._last
        ks = np.array(k, dtype=np.intp)
        return np.bincount(ks, weights=np.array(f, dtype=float), minlength=self._n).astype(float)

    def mean_loads(self) -> NDArray[np.float64] | None:
        """Equivalent load per module, averaged over the steps since the last call (None when
        there was none): each step's loads summed in step order, as a per-step sum would."""
        if not self._steps:
            return None
        total = self._flushed
        self._flush()
        self._flushed = np.zeros(self._n)
        out = total / self._steps
        self._steps = 0
        return out

    def _flush_if_pressure_changed(self) -> None:
        if self._pending and self.pressure_pa != self._pending_pressure:
            self._flush()
        if not self._pending:
            self._pending_pressure = self.pressure_pa

    def _flush(self) -> None:
        """Weight the pending steps' forces (one influence call) and add each step's loads."""
        pending, self._pending = self._pending, []
        if not pending:
            return
        response = self.response
        if response is not None and response.weigh_steps(
            pending, self._pending_pressure, self._flushed
        ):
            return  # the cast pad's weighting in compiled code (the same bits)
        ks = np.array([k for p in pending for k in p[0]], dtype=np.intp)
        f = np.array([v for p in pending for v in p[1]], dtype=float)
        total, start = self._flushed, 0
        if self.response is not None and self._centres is not None:
            # every module's share of each contact (the cast pad's layer spreads a load on a
            # module top to its neighbours)
            pts = np.array([xy for p in pending for xy in p[2]], dtype=float)
            shares = self.response.point_factors(ks, pts, self._pending_pressure) * f[:, None]
            for step in pending:
                stop = start + len(step[0])
                total += shares[start:stop].sum(axis=0)
                start = stop
            return
        for step in pending:
            stop = start + len(step[0])
            total += np.bincount(ks[start:stop], weights=f[start:stop], minlength=self._n)
            start = stop

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
