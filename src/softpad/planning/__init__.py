"""Grasp planning from pressure increments (thesis, Section 6.2.1).

``plan_grasps`` finds the objects (modules above t_o, 8-connected groups), computes each one's
pressure-based centre of mass (PCOM, Eq. 6.1) and a top grasp (centre of grasp COG and
direction theta) with the thesis's rules, generalised to R x C pads (docs/planner.md).
"""

from softpad.planning._cases import FIG_6_7, RULE_CASES, TABLE_6_1, PlanCase
from softpad.planning._catalogue import (
    KNOWN_RULE,
    UNKNOWN_RULE,
    Catalogue,
    CatalogueParams,
    CataloguePlanner,
    GraspRule,
    KnownObject,
    LearnedTrial,
    features,
    grasp_rule,
    known_name,
    learn_catalogue,
    load_catalogue,
    load_centre,
)
from softpad.planning._detection import (
    NoiseDetectionParams,
    NoiseObjectDetector,
    planner_detector,
    reading_spread_pa,
)
from softpad.planning._gripper_aware import (
    DEFAULT_SEAM_WIDTH_M,
    GripperAwarePlanner,
    across_pairs,
    along_load_axis,
    bridge_pairs,
    centred_on_load,
    landing_side,
    load_axis,
    object_extent_m,
    pressed_share,
    sensed_share,
)
from softpad.planning._model_based import (
    ModelBasedParams,
    ModelBasedPlanner,
    PadModel,
    table_bytes,
)
from softpad.planning._mounting import ALL_MOUNTINGS, choose_mounting
from softpad.planning._params import DEFAULT_SAFETY_SHIFT, PlannerParams
from softpad.planning._pcom import pcom
from softpad.planning._plan import (
    MountingChooser,
    Planner,
    RetryPlanner,
    ThesisPlanner,
    plan_grasps,
)
from softpad.planning._records import GraspPlan
from softpad.planning._registry import (
    PLANNER_REGISTRY,
    PlannerContext,
    PlannerFactory,
    available_planners,
    check_planner_choice,
    make_planner,
    plan_by_name,
    planner_for,
    register_planner,
)
from softpad.planning._render import (
    COLUMN_FONT_PT,
    COLUMN_WIDTH_IN,
    ascii_pad,
    format_plans,
    plan_legend_handles,
    plot_plan_columns,
    plot_plans,
)

__all__ = [
    "ALL_MOUNTINGS",
    "COLUMN_FONT_PT",
    "COLUMN_WIDTH_IN",
    "DEFAULT_SAFETY_SHIFT",
    "DEFAULT_SEAM_WIDTH_M",
    "FIG_6_7",
    "KNOWN_RULE",
    "PLANNER_REGISTRY",
    "RULE_CASES",
    "TABLE_6_1",
    "UNKNOWN_RULE",
    "Catalogue",
    "CatalogueParams",
    "CataloguePlanner",
    "GraspPlan",
    "GraspRule",
    "GripperAwarePlanner",
    "KnownObject",
    "LearnedTrial",
    "ModelBasedParams",
    "ModelBasedPlanner",
    "MountingChooser",
    "NoiseDetectionParams",
    "NoiseObjectDetector",
    "PadModel",
    "PlanCase",
    "Planner",
    "PlannerContext",
    "PlannerFactory",
    "PlannerParams",
    "RetryPlanner",
    "ThesisPlanner",
    "across_pairs",
    "along_load_axis",
    "ascii_pad",
    "available_planners",
    "bridge_pairs",
    "centred_on_load",
    "check_planner_choice",
    "choose_mounting",
    "features",
    "format_plans",
    "grasp_rule",
    "known_name",
    "landing_side",
    "learn_catalogue",
    "load_axis",
    "load_catalogue",
    "load_centre",
    "make_planner",
    "object_extent_m",
    "pcom",
    "plan_by_name",
    "plan_grasps",
    "plan_legend_handles",
    "planner_detector",
    "planner_for",
    "plot_plan_columns",
    "plot_plans",
    "pressed_share",
    "reading_spread_pa",
    "register_planner",
    "sensed_share",
    "table_bytes",
]
