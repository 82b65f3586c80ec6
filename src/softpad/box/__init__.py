"""The pneumatic box: interface, back-ends chosen by URL, conformance check.

``open_box("sim://?seed=1")`` returns a :class:`Box`; frames are :class:`PressureFrame`
(gauge pressures in pascals per channel plus the supply pressure); each channel's valves take
a :class:`ValveCommand`. The simulated box (``sim://``: the plain :class:`SimBox` in the
layers of :func:`compose_sim_box`, found behind them by :func:`simulator_of`) is the default;
``zenoh://host:port[/prefix]`` (:class:`ZenohBox`) reaches a box served over zenoh by
:class:`BoxDaemon` (``softpad box serve``) with the same interface; ``hw://FILE.toml``
(:class:`HardwareBox`) drives the real Pneumaticbox (GPIO valves, IIO sensors) wired as the
installation file says. Back-ends are registered in :data:`BOX_BACKENDS`
(:func:`available_box_backends`, entry-point group ``softpad.box_backends``). The
simulated box is imported only when used
(``sim://`` or one of its names below): ``import softpad.box`` on the box computer loads
neither :mod:`softpad.sim` nor :mod:`softpad.fem`.
The link's wire format is :mod:`softpad.box.wire` (for tools that speak it directly).
Every back-end must pass :func:`check_conformance`; :class:`BoxWrapper` is the base of views
that add something around a box (a hook around reads, an event per valve command).
"""

from typing import TYPE_CHECKING, Any

from softpad.box._base import Box, ConnectionLost, PressureFrame, ValveCommand
from softpad.box._conformance import ConformanceError, check_conformance
from softpad.box._credentials import daemon_auth
from softpad.box._daemon import BoxDaemon, guard_box
from softpad.box._hardware import (
    FakeValveLines,
    FileValveLines,
    GpiodValveLines,
    HardwareBox,
    IIOReader,
    ValveLines,
)
from softpad.box._link import StampedFrame
from softpad.box._registry import (
    BOX_BACKENDS,
    BOX_SERVICES,
    DEFAULT_URL,
    available_box_backends,
    open_box,
    parse_url,
    register_backend,
    served_services,
)
from softpad.box._safety import RATED_MAX_PRESSURE_PA, SafetyGuard, SafetyLimits, SafetyTrip
from softpad.box._serve import SERVE_SIM_RATE_HZ, ServeOptions
from softpad.box._watch import (
    LINK_DEFAULT,
    MonitorPeriod,
    Pacer,
    describe_box,
    monitor_header,
    monitor_periods,
    open_watched,
    stamped_frames,
    stats_lines,
)
from softpad.box._wrapper import BoxWrapper
from softpad.box._zenoh import ControlRefused, ZenohBox, open_zenoh_url

if TYPE_CHECKING:
    from softpad.box._sim import FAULT_KINDS, Fault, SimBox
    from softpad.box._sim_layers import (
        SensorFaults,
        SensorZeroShift,
        SimLayer,
        Unreachable,
        WallClock,
        compose_sim_box,
        simulator_of,
    )
    from softpad.box._sim_url import open_sim_url

#: Names of the simulated box (the plain box, its layers, ``sim://``) and their modules,
#: imported on first use.
_SIMULATED = {
    "FAULT_KINDS": "_sim",
    "Fault": "_sim",
    "SimBox": "_sim",
    "SensorFaults": "_sim_layers",
    "SensorZeroShift": "_sim_layers",
    "SimLayer": "_sim_layers",
    "Unreachable": "_sim_layers",
    "WallClock": "_sim_layers",
    "compose_sim_box": "_sim_layers",
    "simulator_of": "_sim_layers",
    "open_sim_url": "_sim_url",
}


def __getattr__(name: str) -> Any:
    if name in _SIMULATED:
        import importlib

        value = getattr(importlib.import_module(f"softpad.box.{_SIMULATED[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'softpad.box' has no attribute {name!r}")


__all__ = [
    "BOX_BACKENDS",
    "BOX_SERVICES",
    "DEFAULT_URL",
    "FAULT_KINDS",
    "LINK_DEFAULT",
    "RATED_MAX_PRESSURE_PA",
    "SERVE_SIM_RATE_HZ",
    "Box",
    "BoxDaemon",
    "BoxWrapper",
    "ConformanceError",
    "ConnectionLost",
    "ControlRefused",
    "FakeValveLines",
    "Fault",
    "FileValveLines",
    "GpiodValveLines",
    "HardwareBox",
    "IIOReader",
    "MonitorPeriod",
    "Pacer",
    "PressureFrame",
    "SafetyGuard",
    "SafetyLimits",
    "SafetyTrip",
    "SensorFaults",
    "SensorZeroShift",
    "ServeOptions",
    "SimBox",
    "SimLayer",
    "StampedFrame",
    "Unreachable",
    "ValveCommand",
    "ValveLines",
    "WallClock",
    "ZenohBox",
    "available_box_backends",
    "check_conformance",
    "compose_sim_box",
    "daemon_auth",
    "describe_box",
    "guard_box",
    "monitor_header",
    "monitor_periods",
    "open_box",
    "open_sim_url",
    "open_watched",
    "open_zenoh_url",
    "parse_url",
    "register_backend",
    "served_services",
    "simulator_of",
    "stamped_frames",
    "stats_lines",
]
