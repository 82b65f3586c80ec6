"""Simulation: module characteristic, chamber gas physics, valves, sensor model, worlds.

The simulated box (``sim://``) is the default back-end of :mod:`softpad.box`; it steps the
gas physics of every channel and a :class:`World` (:class:`AnalyticWorld`, or
:class:`MujocoWorld` for rigid-body contact physics, docs/trials.md) once per sample period.
What a module senses of a load is the FEM module response (:class:`PadResponse`). Objects of the thesis (Table 6.1) are data in
``softpad/data/objects.json``.
"""

from softpad.sim._analytic import GRIPPER_MOUNTINGS, AnalyticWorld, SimGripper
from softpad.sim._characteristic import (
    AnalyticCharacteristic,
    ModuleCharacteristic,
    TabulatedCharacteristic,
    default_characteristic,
    packaged_table_path,
    sealed_sensitivity_pa_n,
)
from softpad.sim._disturbances import DisturbanceParams, Disturbances
from softpad.sim._footprint import (
    DEFAULT_LINE_WIDTH_M,
    GRAVITY_M_S2,
    ObjectFootprint,
    PadSurface,
    fingertip_overlap,
    object_footprint,
)
from softpad.sim._mujoco_model import MujocoGripper, PadPhysics, parse_mounting
from softpad.sim._mujoco_world import GripperContacts, MujocoWorld, ObjectPose
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
from softpad.sim._pad_report import PadMap, pad_map, probe_report, sensitivity_lines
from softpad.sim._pneumatics import ChamberBank, PneumaticParams
from softpad.sim._probe import SENSITIVITY_LOADS, pad_sensitivities, probe_box, sealed_rise_map
from softpad.sim._response import (
    LINE_BAND_M,
    PAD_MODELS,
    ModuleResponse,
    PadResponse,
    default_cast_response,
    default_response,
    operating_pressure,
    packaged_response_path,
)
from softpad.sim._sensor import SensorBank, SensorParams
from softpad.sim._tips import TIP_TRANSITIONS, TipState, TipStateError
from softpad.sim._uncertain import (
    OBJECT_UNKNOWNS,
    UNCERTAIN_PARAMETERS,
    LabVariation,
    UncertainParameter,
    draw_uncertain,
    nominal_uncertain,
)
from softpad.sim._world import GripperState, World

__all__ = [
    "CATALOGUE_SCHEMA",
    "DEFAULT_LINE_WIDTH_M",
    "GRAVITY_M_S2",
    "GRIPPER_MOUNTINGS",
    "LINE_BAND_M",
    "OBJECT_UNKNOWNS",
    "PAD_MODELS",
    "SENSITIVITY_LOADS",
    "TIP_TRANSITIONS",
    "UNCERTAIN_PARAMETERS",
    "AnalyticCharacteristic",
    "AnalyticWorld",
    "ChamberBank",
    "DisturbanceParams",
    "Disturbances",
    "GripperContacts",
    "GripperState",
    "LabVariation",
    "ModuleCharacteristic",
    "ModuleResponse",
    "MujocoGripper",
    "MujocoWorld",
    "ObjectFootprint",
    "ObjectPose",
    "ObjectSpec",
    "PadMap",
    "PadPhysics",
    "PadResponse",
    "PadSurface",
    "PartSpec",
    "Placement",
    "PneumaticParams",
    "SensorBank",
    "SensorParams",
    "SimGripper",
    "TabulatedCharacteristic",
    "TipState",
    "TipStateError",
    "UncertainParameter",
    "World",
    "catalogue_to_json",
    "default_cast_response",
    "default_characteristic",
    "default_response",
    "draw_uncertain",
    "fingertip_overlap",
    "get_object",
    "load_catalogue",
    "nominal_uncertain",
    "object_footprint",
    "object_names",
    "operating_pressure",
    "packaged_response_path",
    "packaged_table_path",
    "pad_map",
    "pad_sensitivities",
    "parse_mounting",
    "probe_box",
    "probe_report",
    "sealed_rise_map",
    "sealed_sensitivity_pa_n",
    "sensitivity_lines",
]
