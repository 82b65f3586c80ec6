"""Simulation: module characteristic, chamber gas physics, valves, sensor model, worlds.

The simulated box (``sim://``) is the default back-end of :mod:`softpad.box`.
"""

from softpad.sim._world import GripperState, World

__all__ = ["GripperState", "World"]
