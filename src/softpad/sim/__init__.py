"""Simulation: module characteristic, chamber gas physics, valves, sensor model, worlds.

The simulated box (``sim://``) is the default back-end of :mod:`softpad.box`; it steps the
gas physics of every channel and a :class:`World` (the analytic one here, a MuJoCo one in
issue 4) once per sample period. Objects of the thesis (Table 6.1) are data in
``softpad/data/objects.json``.
"""

from softpad.sim._analytic import GRIPPER_MOUNTINGS, AnalyticWorld, GripperSpec
from softpad.sim._footprint import (
    DEFAULT_LINE_WIDTH_M,
    GRAVITY_M_S2,
    ObjectFootprint,
    PadSurface,
    fingertip_overlap,
    object_footprint,
)
from softpad.sim._objects import (
    CATALOGUE_SCHEMA,
    ObjectSpec,
    PartSpec,
    Placement,
    catalogue_to_json,
    get_object,
    load_catalogue,
    object_names,
)
from softpad.sim._world import GripperState, World

__all__ = [
    "CATALOGUE_SCHEMA",
    "DEFAULT_LINE_WIDTH_M",
    "GRAVITY_M_S2",
    "GRIPPER_MOUNTINGS",
    "AnalyticWorld",
    "GripperSpec",
    "GripperState",
    "ObjectFootprint",
    "ObjectSpec",
    "PadSurface",
    "PartSpec",
    "Placement",
    "World",
    "catalogue_to_json",
    "fingertip_overlap",
    "get_object",
    "load_catalogue",
    "object_footprint",
    "object_names",
]
