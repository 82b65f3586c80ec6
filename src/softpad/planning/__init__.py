"""Grasp planning from pressure increments (seed, Section 6.2.1).

``plan_grasps`` finds the objects (modules above t_o, 8-connected groups), computes each one's
pressure-based centre of mass (PCOM, Eq. 6.1) and a top grasp (centre of grasp COG and
direction theta) with the thesis's 2 x 3 rules or the general R x C planner.
"""

from softpad.planning._pcom import pcom
from softpad.planning._plan import PlannerParams, plan_grasps, plan_object
from softpad.planning._records import GraspPlan

__all__ = ["GraspPlan", "PlannerParams", "pcom", "plan_grasps", "plan_object"]
