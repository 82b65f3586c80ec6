"""The pneumatic box: interface, back-ends chosen by URL, conformance check.

``open_box("sim://?seed=1")`` returns a :class:`Box`; frames are :class:`PressureFrame`
(gauge pressures in pascals per channel plus the supply pressure); each channel's valves take
a :class:`ValveCommand`. The simulated box (``sim://``, :class:`SimBox`) is the default;
``tcp://host:port`` (:class:`TcpBox`) reaches a box served over the network by
:class:`BoxServer` (``softpad box serve``) with the same interface.
Every back-end must pass :func:`check_conformance`.
"""

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._conformance import ConformanceError, check_conformance
from softpad.box._hardware import (
    FakeValveLines,
    GpiodValveLines,
    HardwareBox,
    IIOReader,
    ValveLines,
)
from softpad.box._protocol import PROTOCOL_VERSION, ProtocolError
from softpad.box._registry import DEFAULT_URL, backends, open_box, parse_url, register_backend
from softpad.box._server import BoxServer
from softpad.box._sim import FAULT_KINDS, Fault, SimBox, open_sim_url
from softpad.box._tcp import TcpBox, open_tcp_url

__all__ = [
    "DEFAULT_URL",
    "FAULT_KINDS",
    "PROTOCOL_VERSION",
    "Box",
    "BoxServer",
    "ConformanceError",
    "ConnectionLost",
    "FakeValveLines",
    "Fault",
    "GpiodValveLines",
    "HardwareBox",
    "IIOReader",
    "PressureFrame",
    "ProtocolError",
    "SimBox",
    "TcpBox",
    "ValveCommand",
    "ValveLines",
    "backends",
    "check_conformance",
    "open_box",
    "open_sim_url",
    "open_tcp_url",
    "parse_url",
    "register_backend",
]
