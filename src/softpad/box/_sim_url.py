"""``sim://`` URLs: the plain simulated box and its layers, built from the URL's options."""

from __future__ import annotations

import math

from softpad.box._sim import SimBox
from softpad.box._sim_faults import Fault
from softpad.box._sim_layers import SimLayer, compose_sim_box
from softpad.errors import InputError
from softpad.layout import PadLayout, parse_layout
from softpad.sim import (
    AnalyticCharacteristic,
    AnalyticWorld,
    DisturbanceParams,
    ModuleCharacteristic,
    PadResponse,
    PneumaticParams,
    SensorParams,
    SimGripper,
    default_characteristic,
    get_object,
)

_SIM_OPTIONS = {
    "seed": "integer seed of the sensor noise (0)",
    "channels": "number of channels (8)",
    "rate_hz": "frames per second (100)",
    "layout": "pad layout RxC (2x3)",
    "pitch_mm": "module pitch in mm (45)",
    "realtime": "1 to pace reads to the wall clock (0)",
    "pad": "the pad's FEM response: cast (the pad as cast, one upper layer; the "
    "default where its table fits the layout) or clamped (independent modules, clamped edges)",
    "inflated_kpa": "start with every module at this pressure (0: deflated)",
    "supply_kpa": "regulated supply pressure (10)",
    "noise": "0 for an ideal noise-free sensor (1)",
    "disturbances": "1 for slow temperature swing, membrane creep, small leaks and sensors' "
    "thermal zero shift (0)",
    "characteristic": "analytic, or default (the FEM table when packaged)",
    "gripper": "gripper mounting 10/4, 6/2 or 4/0 (10/4)",
    "object": "name of a catalogue object placed on the pad at start",
    "faults": "comma-separated KIND[:CHANNEL[:ARG]][@T_S], e.g. leak:2:0.01,stuck:3:inflate@1",
}


def _num(options: dict[str, str], key: str, default: float) -> float:
    if key not in options:
        return default
    try:
        v = float(options[key])
    except ValueError:
        raise InputError(f"sim:// option {key}={options[key]!r} must be a number") from None
    if not math.isfinite(v):
        raise InputError(f"sim:// option {key}={options[key]!r} must be finite")
    return v


def _int(options: dict[str, str], key: str, default: int) -> int:
    if key not in options:
        return default
    try:
        return int(options[key])
    except ValueError:
        raise InputError(f"sim:// option {key}={options[key]!r} must be an integer") from None


def _flag(options: dict[str, str], key: str) -> bool:
    value = options.get(key, "0")
    if value not in ("0", "1"):
        raise InputError(f"sim:// option {key}={value!r} must be 0 or 1")
    return value == "1"


def _world(options: dict[str, str]) -> AnalyticWorld:
    """The analytic world of the URL's layout, pitch and gripper, with its object."""
    layout = parse_layout(options.get("layout", "2x3")) if "layout" in options else PadLayout()
    if "pitch_mm" in options:
        layout = PadLayout(layout.rows, layout.cols, _num(options, "pitch_mm", 45.0) / 1e3)
    gripper = SimGripper.mounting(options.get("gripper", "10/4"))
    pad = options.get("pad")
    if pad not in (None, "cast", "clamped"):
        raise InputError(f"sim:// option pad={pad!r} must be 'cast' or 'clamped'")
    response = None if pad is None else PadResponse(layout, pad_model=pad)
    world = AnalyticWorld(layout, gripper, response=response)
    if "object" in options:
        world.place_object(get_object(options["object"]))
    return world


def _characteristic(options: dict[str, str]) -> ModuleCharacteristic:
    char_name = options.get("characteristic", "default")
    if char_name == "analytic":
        return AnalyticCharacteristic()
    if char_name == "default":
        return default_characteristic()
    raise InputError(f"sim:// option characteristic={char_name!r} must be 'analytic' or 'default'")


def open_sim_url(location: str, options: dict[str, str]) -> SimLayer:
    """Build the simulated box of a ``sim://`` URL's options (see ``_SIM_OPTIONS``): the plain
    :class:`SimBox` in its layers (:func:`~softpad.box.compose_sim_box`), with its faults."""
    if location.strip("/"):
        raise InputError(f"sim:// takes no host or path, got {location!r} (options go after '?')")
    unknown = sorted(set(options) - set(_SIM_OPTIONS))
    if unknown:
        raise InputError(
            f"unknown sim:// option {unknown[0]!r}; known options: {', '.join(_SIM_OPTIONS)}"
        )
    world = _world(options)
    characteristic = _characteristic(options)
    noise = options.get("noise", "1")
    if noise not in ("0", "1"):
        raise InputError(f"sim:// option noise={noise!r} must be 0 or 1")
    disturb, realtime = _flag(options, "disturbances"), _flag(options, "realtime")
    supply_pa = _num(options, "supply_kpa", 10.0) * 1e3
    plain = SimBox(
        world,
        channels=_int(options, "channels", 8),
        sample_rate_hz=_num(options, "rate_hz", 100.0),
        seed=_int(options, "seed", 0),
        characteristic=characteristic,
        pneumatics=PneumaticParams(supply_pa=supply_pa),
        sensor=SensorParams() if noise == "1" else SensorParams.ideal(),
        initial_pressure_pa=_num(options, "inflated_kpa", 0.0) * 1e3,
        disturbances=DisturbanceParams() if disturb else None,
    )
    box = compose_sim_box(plain, realtime=realtime)
    for text in filter(None, (s.strip() for s in options.get("faults", "").split(","))):
        box.inject_fault(Fault.parse(text))
    return box


__all__ = ["open_sim_url"]
