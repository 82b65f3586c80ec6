"""The compiled MuJoCo model of the pad, the gripper and the objects, with its index tables.

:class:`MujocoScene` turns the MJCF of :func:`~softpad.sim._mujoco_model.build_mjcf` into a
MuJoCo model and data and looks up, once, the addresses that stepping and sensing use every
step (module tops, hand and jaw joints, object bodies). Rebuilding with more objects carries
the state of what existed over to the new model.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad.layout import PadLayout
from softpad.sim._mujoco_model import (
    MujocoGripper,
    ObjectModel,
    PadPhysics,
    body_name,
    build_mjcf,
    loose_body_name,
)


def _slice(index: NDArray[np.int_]) -> slice | NDArray[np.int_]:
    """``index`` as a slice when it is a run of consecutive addresses, else itself."""
    i = np.asarray(index)
    if i.size and np.array_equal(i, np.arange(i[0], i[0] + i.size)):
        return slice(int(i[0]), int(i[0]) + int(i.size))
    return index


#: One body of an object: body id, qpos address, dof address, offset in the object frame (m).
ObjectBody = tuple[int, int, int, tuple[float, float, float]]


class MujocoScene:
    """A MuJoCo model and its data, with the ids and addresses of everything the world moves.

    Parameters
    ----------
    layout, pad, gripper
        Pad geometry, pad physics and gripper geometry of the model.
    objects
        Objects in the model (each a free body, or one per part for a loose object).
    timestep_s
        MuJoCo step, seconds.

    Attributes
    ----------
    model, data, xml
        The MuJoCo model, its data and the MJCF it was compiled from.
    objects
        The objects in the model, by name.
    geom_module
        Per geom: index of the module whose top it is, or -1.
    module_qpos
        qpos address of every module top's slide joint, module order.
    pad_static, pad_geoms
        Geoms of the base and the table; those plus the module tops.
    sole, finger, palm
        Geoms of the tips' soles and of the fingers (right, left), and of the palm.
    hand_qpos, hand_dof, jaw_qpos, jaw_dof
        qpos and dof addresses of the hand's x, y, z, yaw joints and of the jaws (right, left).
    obj_body, obj_qpos, obj_dof
        Per object: its main body and that body's qpos and dof addresses.
    obj_bodies
        Per object: every body (a loose object has one per part), see :data:`ObjectBody`.
    body_object
        Per object body id: the object's name.
    """

    def __init__(
        self,
        layout: PadLayout,
        pad: PadPhysics,
        gripper: MujocoGripper,
        objects: tuple[ObjectModel, ...],
        timestep_s: float,
    ) -> None:
        import mujoco

        self.objects: dict[str, ObjectModel] = {o.name: o for o in objects}
        self.xml = build_mjcf(layout, pad, gripper, objects, timestep_s)
        self.model: Any = mujoco.MjModel.from_xml_string(self.xml)
        self.data: Any = mujoco.MjData(self.model)
        self._index_pad(layout)
        self._index_gripper()
        self._index_objects(objects)
        # what every step touches: MuJoCo's arrays (views, fixed for the data's life) and the
        # module tops' and hand's addresses as slices where contiguous (the same elements)
        self.qpos, self.qvel, self.ctrl = self.data.qpos, self.data.qvel, self.data.ctrl
        self.qpos_spring = self.model.qpos_spring
        self.module_q = _slice(self.module_qpos)
        # the module bodies are built one after another, one slide joint each: a slice, so
        # that this is a view the world's springs are written through
        assert isinstance(self.module_q, slice)
        #: The module tops' spring rest lengths (a view into ``qpos_spring``).
        self.module_spring = self.qpos_spring[self.module_q]
        self.hand_q, self.hand_v = _slice(self.hand_qpos), _slice(self.hand_dof)

    def _id(self, kind: str, name: str) -> int:
        import mujoco

        obj = {"geom": mujoco.mjtObj.mjOBJ_GEOM, "body": mujoco.mjtObj.mjOBJ_BODY}.get(
            kind, mujoco.mjtObj.mjOBJ_JOINT
        )
        return int(mujoco.mj_name2id(self.model, obj, name))

    def _qpos(self, joint: str) -> int:
        return int(self.model.jnt_qposadr[self._id("joint", joint)])

    def _dof(self, joint: str) -> int:
        return int(self.model.jnt_dofadr[self._id("joint", joint)])

    def _index_pad(self, layout: PadLayout) -> None:
        top_geom = np.array([self._id("geom", f"module{k}_top") for k in layout.modules])
        self.geom_module: NDArray[np.int_] = np.full(self.model.ngeom, -1, dtype=int)
        self.geom_module[top_geom] = np.arange(layout.n_modules)
        self.module_qpos: NDArray[np.int64] = np.array(
            [self._qpos(f"module{k}_z") for k in layout.modules]
        )
        self.pad_static = {self._id("geom", "base"), self._id("geom", "table")}
        self.pad_geoms = self.pad_static | {int(g) for g in top_geom}

    def _index_gripper(self) -> None:
        self.sole = (self._id("geom", "sole_right"), self._id("geom", "sole_left"))
        self.finger = (self._id("geom", "finger_right"), self._id("geom", "finger_left"))
        self.palm = self._id("geom", "palm")
        self.hand_body = self._id("body", "hand")
        axes = ("x", "y", "z", "yaw")
        self.hand_qpos = np.array([self._qpos(f"hand_{a}") for a in axes])
        self.hand_dof = np.array([self._dof(f"hand_{a}") for a in axes])
        sides = ("right", "left")
        self.jaw_qpos: NDArray[np.int64] = np.array([self._qpos(f"jaw_{s}") for s in sides])
        self.jaw_dof = np.array([self._dof(f"jaw_{s}") for s in sides])

    def _index_objects(self, objects: tuple[ObjectModel, ...]) -> None:
        self.obj_body = {o.name: self._id("body", body_name(o)) for o in objects}
        self.obj_qpos: dict[str, int] = {o.name: self._qpos(body_name(o)) for o in objects}
        self.obj_dof: dict[str, int] = {o.name: self._dof(body_name(o)) for o in objects}
        self.obj_bodies: dict[str, list[ObjectBody]] = {}
        for o in objects:
            bodies: list[ObjectBody] = [
                (self.obj_body[o.name], self.obj_qpos[o.name], self.obj_dof[o.name], (0.0,) * 3)
            ]
            if o.loose:
                for j, part in enumerate(o.parts[1:], start=1):
                    name = loose_body_name(o, j)
                    px, py, pz = (float(v) for v in part.pos_m)
                    bodies.append(
                        (self._id("body", name), self._qpos(name), self._dof(name), (px, py, pz))
                    )
            self.obj_bodies[o.name] = bodies
        self.body_object = {b[0]: name for name, bs in self.obj_bodies.items() for b in bs}

    def rest(self, free_height_m: float, half_width_m: float) -> None:
        """Start state: every module top at ``free_height_m``, each jaw ``half_width_m`` out."""
        self.data.qpos[self.module_qpos] = free_height_m
        self.data.qpos[self.jaw_qpos] = half_width_m

    def carry_over(self, old: MujocoScene) -> None:
        """Take the module springs and tops, the jaws, the objects and the time from ``old``."""
        m, d, od = self.model, self.data, old.data
        m.qpos_spring[self.module_qpos] = old.model.qpos_spring[old.module_qpos]
        d.qpos[self.module_qpos] = od.qpos[old.module_qpos]
        d.qpos[self.jaw_qpos] = od.qpos[old.jaw_qpos]
        for name, qa in old.obj_qpos.items():
            if name in self.obj_qpos:
                new_q, new_d, da = self.obj_qpos[name], self.obj_dof[name], old.obj_dof[name]
                d.qpos[new_q : new_q + 7] = od.qpos[qa : qa + 7]
                d.qvel[new_d : new_d + 6] = od.qvel[da : da + 6]
        d.time = od.time

    def forward(self) -> None:
        """Recompute positions and contacts from the current state (``mj_forward``)."""
        import mujoco

        mujoco.mj_forward(self.model, self.data)
