"""The pneumatic box: interface, back-ends chosen by URL, conformance check.

``open_box("sim://?seed=1")`` returns a :class:`Box`; frames are :class:`PressureFrame`
(gauge pressures in pascals per channel plus the supply pressure); each channel's valves take
a :class:`ValveCommand`. The simulated box (``sim://``, :class:`SimBox`) is the default.
Every back-end must pass :func:`check_conformance`.
"""

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._conformance import ConformanceError, check_conformance
from softpad.box._registry import DEFAULT_URL, backends, open_box, parse_url, register_backend
from softpad.box._sim import FAULT_KINDS, Fault, SimBox, open_sim_url

__all__ = [
    "DEFAULT_URL",
    "FAULT_KINDS",
    "Box",
    "ConformanceError",
    "ConnectionLost",
    "Fault",
    "PressureFrame",
    "SimBox",
    "ValveCommand",
    "backends",
    "check_conformance",
    "open_box",
    "open_sim_url",
    "parse_url",
    "register_backend",
]
