"""Pad geometry: module numbering, centres, 8-neighbour adjacency, units and frames.

Conventions (DESIGN.md, thesis Fig. 6.4a): modules are numbered 1..R*C row-major from the
top-left seen from above; module ``k`` sits in row ``r = (k-1)//C`` (0 = top) and column
``c = (k-1)%C`` with centre ``(c + 0.5, (R-1-r) + 0.5)`` in module units. The pad frame has
its origin at the bottom-left corner, x to the right, y up the columns, z out of the pad.
The gripper's geometry (Section 6.3) lives here too, since plans become fingertip positions.
"""

from softpad.layout._grid import DEFAULT_PITCH_M, PadLayout, parse_layout
from softpad.layout._gripper import GRIPPER_CONFIGS_M, GripperSpec
from softpad.layout._pose import POSE_LIMIT_M, PadPose

__all__ = [
    "DEFAULT_PITCH_M",
    "GRIPPER_CONFIGS_M",
    "POSE_LIMIT_M",
    "GripperSpec",
    "PadLayout",
    "PadPose",
    "parse_layout",
]
