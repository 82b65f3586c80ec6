"""The installation file: one TOML file describing a SoftPad installation.

Read with the standard library (:mod:`tomllib`) and validated into frozen dataclasses; every
error names the key (``box.channel.3.inflate_line``) and the offending value. Units are in the
key names (``offset_pa``, ``pitch_mm``); the settings hold SI values.
"""

from __future__ import annotations

import ipaddress
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from softpad import thesis
from softpad.errors import KPA_AS_PA, MM_AS_M, MS_AS_S, InputError, check_count, check_range

#: Thesis defaults (thesis, Section 6.2, from :mod:`softpad.thesis`), pascals / samples / metres.
DEFAULT_P0_PA = thesis.P0_PA
DEFAULT_ADJUST_TOLERANCE_PA = thesis.ADJUST_TOLERANCE_PA
DEFAULT_OBJECT_THRESHOLD_PA = thesis.OBJECT_THRESHOLD_PA
DEFAULT_CONTACT_THRESHOLD_PA = thesis.CONTACT_THRESHOLD_PA
DEFAULT_FILTER_WINDOW = thesis.FILTER_WINDOW
DEFAULT_MAX_PRESSURE_PA = thesis.MAX_PRESSURE_PA
DEFAULT_PITCH_M = thesis.MODULE_PITCH_M

WATCHDOG_ACTIONS = ("hold", "vent")

# Limits of the settings, SI. The installation file and the Python records check the same ones.
#: Rows or columns of a pad: 1 to 16.
MAX_PAD_SIDE = 16
#: Module pitch, m: 5 mm to 0.5 m.
PITCH_RANGE_M = (0.005, 0.5)
#: The pad's position in the robot base frame, at most this far from the origin, m.
POSE_LIMIT_M = 10.0
#: Tolerance of the initial adjustment t_adj, Pa (the thesis's is 30 Pa).
TOLERANCE_RANGE_PA = (1.0, 1000.0)
#: Object and contact thresholds t_o, t_g, Pa (the thesis's are 50 and 90 Pa).
THRESHOLD_RANGE_PA = (1.0, 5000.0)
#: Running-average window, samples (the thesis's is 10).
MAX_FILTER_WINDOW = 1000
#: Configured maximum pressure, Pa: from 0.2 kPa to the thesis's ceiling.
MAX_PRESSURE_RANGE_PA = (200.0, thesis.MAX_PRESSURE_PA)
#: Sample rate of a hardware box, Hz; ambient (absolute) pressure of a site, Pa; the
#: daemon's watchdog, s (the installation file's limits). The watchdog: from 50 ms (its
#: heartbeats every 10 ms) to 5 s (a controller that vanished leaves its valves that long).
SAMPLE_RATE_RANGE_HZ = (1.0, 10_000.0)
AMBIENT_RANGE_PA = (50e3, 110e3)
WATCHDOG_RANGE_S = (0.05, 5.0)


class ConfigError(InputError):
    """The installation file is unreadable or a value in it is wrong (the message names it)."""


@dataclass(frozen=True, slots=True)
class ChannelWiring:
    """Wiring and calibration of one pneumatic channel.

    ``pressure_pa = offset_pa + gain * pa_per_count * raw_count`` (raw_count read from IIO).
    """

    channel: int
    gpiochip: str
    inflate_line: int
    deflate_line: int
    iio_device: int
    iio_channel: int
    offset_pa: float = 0.0
    gain: float = 1.0
    pa_per_count: float = 1.0

    def pressure_pa(self, raw_count: float) -> float:
        """Calibrated gauge pressure, pascals, of one raw ADC count."""
        return self.offset_pa + self.gain * self.pa_per_count * raw_count


@dataclass(frozen=True, slots=True)
class BoxSettings:
    """The box's wiring: channels (1-based, in order), the supply sensor, the sampling rate,
    and the ambient pressure of the site (added to gauge readings where a message is absolute,
    ``sensor_msgs/FluidPressure``), Pa; how the valves are built (what they do unpowered)."""

    channels: tuple[ChannelWiring, ...] = ()
    supply: ChannelWiring | None = None
    sample_rate_hz: float = 1000.0
    iio_root: str = "/sys/bus/iio/devices"
    ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA
    #: How the valves are built: ``"normally_closed"`` (closed unpowered, open with the GPIO
    #: line active) or ``"normally_open"``. Inflation valves must be normally closed.
    inflate_valves: str = "normally_closed"
    deflate_valves: str = "normally_closed"

    def __post_init__(self) -> None:
        check_range("box sample_rate_hz", self.sample_rate_hz, *SAMPLE_RATE_RANGE_HZ, "Hz")
        for name in ("inflate_valves", "deflate_valves"):
            if getattr(self, name) not in VALVE_KINDS:
                raise InputError(
                    f"box {name} must be one of {', '.join(VALVE_KINDS)}, got {getattr(self, name)!r}"
                )
        if self.inflate_valves != "normally_closed":
            raise InputError("box inflate_valves must be normally_closed (a power loss fills)")
        check_range(
            "box ambient_pressure_pa",
            self.ambient_pressure_pa,
            *AMBIENT_RANGE_PA,
            "Pa",
            low_hint=KPA_AS_PA,
        )


@dataclass(frozen=True, slots=True)
class LinkSettings:
    """The zenoh link: endpoints, authentication, watchdog.

    Listening beyond 127.0.0.1 needs ``allow_remote = true``, a ``tls/`` endpoint (plain
    ``tcp/`` beyond loopback is refused whatever else is set) and authentication: user and
    password file, or mutual TLS (certificate, key and the root CA that verifies the other
    side's certificate). Each side reads its own end of these keys
    (:mod:`softpad.box._credentials`).
    """

    listen: tuple[str, ...] = ("tcp/127.0.0.1:7447",)
    connect: tuple[str, ...] = ()
    key_prefix: str = "softpad/box"
    allow_remote: bool = False
    user: str | None = None
    password_file: str | None = None
    tls_certificate: str | None = None
    tls_private_key: str | None = None
    tls_root_ca: str | None = None
    watchdog_s: float = 0.5
    watchdog_action: str = "hold"

    def __post_init__(self) -> None:
        check_range("link watchdog_s", self.watchdog_s, *WATCHDOG_RANGE_S, "s", MS_AS_S)

    @property
    def has_auth(self) -> bool:
        """True when user/password or mutual TLS (certificate, key and a root CA to verify
        the other side's certificate) is configured; TLS without a root CA authenticates
        nobody."""
        return (self.user is not None and self.password_file is not None) or (
            self.tls_certificate is not None
            and self.tls_private_key is not None
            and self.tls_root_ca is not None
        )


@dataclass(frozen=True, slots=True)
class PadSettings:
    """Pad layout (rows x cols), module pitch (m) and pose in the robot base frame (m, rad)."""

    rows: int = 2
    cols: int = 3
    pitch_m: float = DEFAULT_PITCH_M
    x_m: float = 0.0
    y_m: float = 0.0
    z_m: float = 0.0
    yaw_rad: float = 0.0

    def __post_init__(self) -> None:
        check_count("pad rows", self.rows, 1, MAX_PAD_SIDE)
        check_count("pad cols", self.cols, 1, MAX_PAD_SIDE)
        check_range("pad pitch_m", self.pitch_m, *PITCH_RANGE_M, "m", MM_AS_M)
        for name in ("x_m", "y_m", "z_m"):
            check_range(
                f"pad pose {name}", getattr(self, name), -POSE_LIMIT_M, POSE_LIMIT_M, "m", MM_AS_M
            )
        check_range(
            "pad pose yaw_rad",
            self.yaw_rad,
            -2 * math.pi,
            2 * math.pi,
            "rad",
            "degrees given as radians?",
        )


@dataclass(frozen=True, slots=True)
class Thresholds:
    """Thesis thresholds (Section 6.2), pascals: p0, t_adj, t_o, t_g; filter window; maximum."""

    p0_pa: float = DEFAULT_P0_PA
    adjust_tolerance_pa: float = DEFAULT_ADJUST_TOLERANCE_PA
    object_threshold_pa: float = DEFAULT_OBJECT_THRESHOLD_PA
    contact_threshold_pa: float = DEFAULT_CONTACT_THRESHOLD_PA
    filter_window: int = DEFAULT_FILTER_WINDOW
    max_pressure_pa: float = DEFAULT_MAX_PRESSURE_PA

    def __post_init__(self) -> None:
        p0 = check_range("thresholds p0_pa", self.p0_pa, *thesis.P0_RANGE_PA, "Pa")
        tol = check_range(
            "thresholds adjust_tolerance_pa", self.adjust_tolerance_pa, *TOLERANCE_RANGE_PA, "Pa"
        )
        for name in ("object_threshold_pa", "contact_threshold_pa"):
            check_range(f"thresholds {name}", getattr(self, name), *THRESHOLD_RANGE_PA, "Pa")
        check_count("thresholds filter_window", self.filter_window, 1, MAX_FILTER_WINDOW)
        top = check_range(
            "thresholds max_pressure_pa", self.max_pressure_pa, *MAX_PRESSURE_RANGE_PA, "Pa"
        )
        if p0 + tol >= top:
            raise InputError(
                f"thresholds p0 + adjustment tolerance ({(p0 + tol) / 1e3:g} kPa) must stay "
                f"below the maximum pressure ({top / 1e3:g} kPa)"
            )


@dataclass(frozen=True, slots=True)
class Installation:
    """Every setting of one installation (see :func:`load_installation`).

    Attributes
    ----------
    box
        The box: channels and their wiring, supply, sample rate (Hz), ambient pressure (Pa).
    link
        The zenoh link: endpoints, key prefix, credentials, watchdog (s).
    pad
        The pad: rows, columns, pitch (m) and its pose in the robot's base frame (m, rad).
    thresholds
        p0, the adjustment tolerance, t_o, t_g and the maximum pressure (Pa), the window
        (samples).
    gripper_mounting
        The gripper's mounting (``"10/4"``, ``"6/2"``, ``"4/0"``), or None.
    source
        The file read, ``"<defaults>"`` without one.
    """

    box: BoxSettings = field(default_factory=BoxSettings)
    link: LinkSettings = field(default_factory=LinkSettings)
    pad: PadSettings = field(default_factory=PadSettings)
    thresholds: Thresholds = field(default_factory=Thresholds)
    gripper_mounting: str | None = None
    source: str = "<defaults>"

    @property
    def box_url(self) -> str | None:
        """The URL of the box daemon the link connects to (``zenoh://HOST:PORT/PREFIX``, with
        ``?config=`` this file where the link has credentials), None without ``link.connect``."""
        link = self.link
        if not link.connect:
            return None
        host_port = link.connect[0].split("/", 1)[1]
        url = f"zenoh://{host_port}/{link.key_prefix}"
        if link.user is not None or link.tls_root_ca is not None:  # the link's credentials
            url += f"?config={self.source}"
        return url


# --- typed getters that name the key --------------------------------------------------
def _get(table: dict[str, Any], key: str, where: str, kind: type, default: Any) -> Any:
    if key not in table:
        return default
    v = table[key]
    name = f"{where}.{key}" if where else key
    if kind is float:
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise ConfigError(f"{name} must be a finite number, got {v!r}")
        return float(v)
    if kind is int and (isinstance(v, bool) or not isinstance(v, int)):
        raise ConfigError(f"{name} must be an integer, got {v!r}")
    if kind is bool and not isinstance(v, bool):
        raise ConfigError(f"{name} must be true or false, got {v!r}")
    if kind is str and not isinstance(v, str):
        raise ConfigError(f"{name} must be a string, got {v!r}")
    if kind is list and not (isinstance(v, list) and all(isinstance(s, str) for s in v)):
        raise ConfigError(f"{name} must be a list of strings, got {v!r}")
    return v


def _range(name: str, v: float, lo: float, hi: float, unit: str = "") -> float:
    if not lo <= v <= hi:
        raise ConfigError(f"{name} must be within {lo:g}..{hi:g}{unit}, got {v!r}")
    return v


def _table(raw: dict[str, Any], key: str, where: str = "") -> dict[str, Any]:
    v = raw.get(key, {})
    if not isinstance(v, dict):
        raise ConfigError(f"{where + '.' if where else ''}{key} must be a table, got {v!r}")
    return v


def _unknown(table: dict[str, Any], allowed: set[str], where: str) -> None:
    extra = sorted(set(table) - allowed)
    _raise_all(
        [
            f"unknown key {where + '.' if where else ''}{key}; allowed: {', '.join(sorted(allowed))}"
            for key in extra
        ]
    )


def _raise_all(errors: list[str]) -> None:
    """Raise one ConfigError carrying every message of ``errors`` (none: nothing)."""
    if errors:
        exc = ConfigError(errors[0])
        exc.errors = list(errors)  # type: ignore[attr-defined]
        raise exc


def _try(errors: list[str], fallback: Any, parse: Any, *args: Any) -> Any:
    """``parse(*args)``, or ``fallback`` with its error message(s) appended to ``errors`` (so
    one table's later keys are still checked)."""
    n = len(errors)
    value = _collect(errors, parse, *args)
    return fallback if len(errors) > n else value


def _number(
    errors: list[str], t: dict[str, Any], key: str, where: str, kind: type, default: Any,
    lo: float, hi: float, unit: str = "",
) -> Any:  # fmt: skip
    """``t[key]`` of ``kind`` within ``lo..hi`` (``default`` when absent), or ``default`` with
    the error appended to ``errors``."""

    def get() -> Any:
        return _range(f"{where}.{key}", _get(t, key, where, kind, default), lo, hi, unit)

    return _try(errors, default, get)


_WIRING_KEYS = {
    "gpiochip",
    "inflate_line",
    "deflate_line",
    "iio_device",
    "iio_channel",
    "offset_pa",
    "gain",
    "pa_per_count",
}


def _wiring(t: dict[str, Any], where: str, channel: int, valves: bool) -> ChannelWiring:
    """One channel's (or the supply's) wiring; every error of the table in one ConfigError."""
    errors: list[str] = []
    _try(errors, None, _unknown, t, _WIRING_KEYS, where)
    lines = []
    for key in ("inflate_line", "deflate_line"):
        v = _try(errors, 0, _get, t, key, where, int, None if valves else -1)
        if v is None:
            errors.append(f"{where}.{key} is missing (GPIO line offset of the valve)")
        elif valves and v < 0:
            errors.append(f"{where}.{key} must be a line offset >= 0, got {v}")
        lines.append(v if v is not None else 0)
    iio = []
    for key in ("iio_device", "iio_channel"):
        v = _try(errors, 0, _get, t, key, where, int, None)
        if v is None:
            errors.append(f"{where}.{key} is missing (IIO device N / in_voltageK of the sensor)")
        elif v < 0:
            errors.append(f"{where}.{key} must be >= 0, got {v}")
        iio.append(v if v is not None else 0)
    gain = _try(errors, 1.0, _get, t, "gain", where, float, 1.0)
    ppc = _try(errors, 1.0, _get, t, "pa_per_count", where, float, 1.0)
    for key, v in (("gain", gain), ("pa_per_count", ppc)):
        if v <= 0:
            errors.append(
                f"{where}.{key} must be > 0, got {v:g} (zero reads nothing; a negative factor "
                "turns a rising pressure into a falling reading and the over-pressure guard "
                "would never trip: wire the sensor the right way round)"
            )
    chip = _try(errors, "/dev/gpiochip0", _get, t, "gpiochip", where, str, "/dev/gpiochip0")
    if valves and not (chip.startswith("/dev/") and len(chip) > 5):
        errors.append(
            f"{where}.gpiochip must be the character device's path (/dev/gpiochipN), got {chip!r}"
        )
    offset = _try(errors, 0.0, _get, t, "offset_pa", where, float, 0.0)
    _raise_all(errors)
    return ChannelWiring(
        channel=channel,
        gpiochip=chip,
        inflate_line=lines[0],
        deflate_line=lines[1],
        iio_device=iio[0],
        iio_channel=iio[1],
        offset_pa=offset,
        gain=gain,
        pa_per_count=ppc,
    )


def _wiring_conflicts(chans: list[dict[str, Any]], supply: Any) -> list[str]:
    """One GPIO line on two valves, or one ADC input read as two sensors, from the tables as
    written (a channel with other errors still counts; paths compared as resolved:
    ``/dev/gpiochip1`` and ``/dev/./gpiochip1`` are one chip)."""
    errors: list[str] = []
    lines: dict[tuple[str, Any], str] = {}
    inputs: dict[tuple[Any, Any], str] = {}
    tables = [(f"box.channel.{i}", c) for i, c in enumerate(chans, 1)]
    if isinstance(supply, dict):
        tables.append(("box.supply", supply))
    for name, t in tables:
        if name != "box.supply":
            chip = t.get("gpiochip", "/dev/gpiochip0")
            for key in ("inflate_line", "deflate_line"):
                line = t.get(key)
                if not isinstance(chip, str) or not _is_int(line):
                    continue
                where, here = (_chip_path(chip), line), f"{name}.{key}"
                if where in lines:
                    errors.append(
                        f"{here} = {line} on {chip} is already used by {lines[where]}"
                        " (one GPIO line would drive two valves)"
                    )
                lines.setdefault(where, here)
        adc = (t.get("iio_device"), t.get("iio_channel"))
        if not (_is_int(adc[0]) and _is_int(adc[1])):
            continue
        if adc in inputs:
            errors.append(
                f"{name}: iio:device{adc[0]}/in_voltage{adc[1]} is already read by "
                f"{inputs[adc]} (one ADC input would be two sensors)"
            )
        inputs.setdefault(adc, name)
    return errors


def _is_int(v: object) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _chip_path(path: str) -> str:
    import os

    return os.path.realpath(path)


#: What a valve does unpowered (its GPIO line inactive): the file must say, for each kind.
VALVE_KINDS = ("normally_closed", "normally_open")


def _valve_kinds(errors: list[str], t: dict[str, Any], wired: bool) -> tuple[str, str]:
    """``(inflate_valves, deflate_valves)``: how the valves are built, which the safe state
    at a final close depends on. Required when channels are wired; an inflation valve that
    opens unpowered is refused (a power loss would fill every module)."""
    out = []
    for key in ("inflate_valves", "deflate_valves"):
        v = _try(errors, None, _get, t, key, "box", str, None)
        if v is None:
            if wired and f"box.{key}" not in " ".join(errors):
                errors.append(
                    f"box.{key} is missing: say how the valves are built, "
                    f"{' or '.join(repr(k) for k in VALVE_KINDS)} (unpowered state); the "
                    "safe state at a final close depends on it"
                )
            v = "normally_closed"
        elif v not in VALVE_KINDS:
            errors.append(f"box.{key} must be one of {', '.join(VALVE_KINDS)}; got {v!r}")
            v = "normally_closed"
        out.append(v)
    if out[0] == "normally_open":
        errors.append(
            "box.inflate_valves = 'normally_open' is refused: an inflation valve that opens "
            "unpowered fills every module on a power loss or a crash, with no guard running"
        )
    return out[0], out[1]


_BOX_KEYS = {
    "channel",
    "supply",
    "sample_rate_hz",
    "iio_root",
    "ambient_pressure_kpa",
    "inflate_valves",
    "deflate_valves",
}


def _channels(errors: list[str], t: dict[str, Any]) -> list[dict[str, Any]]:
    chans = t.get("channel", [])
    if not isinstance(chans, list) or not all(isinstance(c, dict) for c in chans):
        errors.append(f"box.channel must be an array of tables ([[box.channel]]), got {chans!r}")
        return []
    if len(chans) > 64:
        errors.append(f"box.channel: at most 64 channels, got {len(chans)}")
        return []
    return chans


def _box(raw: dict[str, Any]) -> BoxSettings:
    t = _table(raw, "box")
    errors: list[str] = []
    _try(errors, None, _unknown, t, _BOX_KEYS, "box")
    chans = _channels(errors, t)
    found = [
        _collect(errors, _wiring, c, f"box.channel.{i}", i, True) for i, c in enumerate(chans, 1)
    ]
    rate = _number(errors, t, "sample_rate_hz", "box", float, 1000.0, *SAMPLE_RATE_RANGE_HZ, " Hz")
    # the lowest and highest sea-level pressures on record, with room for a site up a mountain
    lo_kpa, hi_kpa = (v / 1e3 for v in AMBIENT_RANGE_PA)
    default_kpa = thesis.AMBIENT_PRESSURE_PA / 1e3
    ambient = _number(
        errors, t, "ambient_pressure_kpa", "box", float, default_kpa, lo_kpa, hi_kpa, " kPa"
    )
    inflate_kind, deflate_kind = _valve_kinds(errors, t, bool(chans))
    supply = None
    if t.get("supply") is not None:
        supply_table = _try(errors, {}, _table, t, "supply", "box")
        supply = _collect(errors, _wiring, supply_table, "box.supply", 0, False)
    wiring = tuple(w for w in found if w is not None)
    errors.extend(_wiring_conflicts(chans, t.get("supply")))
    iio_root = _try(errors, "", _get, t, "iio_root", "box", str, "/sys/bus/iio/devices")
    _raise_all(errors)  # every channel's and key's error, not only the first
    return BoxSettings(
        channels=wiring,
        supply=supply,
        sample_rate_hz=rate,
        iio_root=iio_root,
        ambient_pressure_pa=ambient * 1e3,
        inflate_valves=inflate_kind,
        deflate_valves=deflate_kind,
    )


def is_loopback_endpoint(endpoint: str) -> bool:
    """True for a zenoh endpoint ``proto/127.x.y.z:port`` or ``proto/[::1]:port``."""
    try:
        _, addr = endpoint.split("/", 1)
        host = addr.split("#", 1)[0].rsplit(":", 1)[0].strip("[]")
        if host == "localhost":
            return True
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


_LINK_KEYS = {
    "listen",
    "connect",
    "key_prefix",
    "allow_remote",
    "user",
    "password_file",
    "tls_certificate",
    "tls_private_key",
    "tls_root_ca",
    "watchdog_s",
    "watchdog_action",
}


def check_endpoint(endpoint: str, name: str) -> str:
    """Return ``endpoint`` when it looks like ``tcp/HOST:PORT`` (or tls/), else ConfigError."""
    proto, _, rest = endpoint.partition("/")
    if proto not in ("tcp", "tls") or ":" not in rest:
        raise ConfigError(f"{name} endpoint must look like tcp/127.0.0.1:7447, got {endpoint!r}")
    port = rest.split("#", 1)[0].rsplit(":", 1)[1]
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise ConfigError(f"{name} endpoint {endpoint!r}: port must be 1..65535")
    return endpoint


def _link(raw: dict[str, Any]) -> LinkSettings:
    t = _table(raw, "link")
    errors: list[str] = []
    _try(errors, None, _unknown, t, _LINK_KEYS, "link")
    ends = {}
    for key, default in (("listen", ["tcp/127.0.0.1:7447"]), ("connect", [])):
        given = _try(errors, [], _get, t, key, "link", list, default)
        ends[key] = tuple(e for e in given if _try(errors, None, check_endpoint, e, f"link.{key}"))
    action = _try(errors, "hold", _get, t, "watchdog_action", "link", str, "hold")
    if action not in WATCHDOG_ACTIONS:
        errors.append(f"link.watchdog_action must be one of hold, vent; got {action!r}")
        action = "hold"
    prefix = _try(errors, "softpad/box", _get, t, "key_prefix", "link", str, "softpad/box")
    if not prefix or any(c in prefix for c in "*$?#") or prefix.startswith("/"):
        errors.append(f"link.key_prefix must be a plain zenoh key like softpad/box, got {prefix!r}")
        prefix = "softpad/box"
    text = {
        key: _try(errors, None, _get, t, key, "link", str, None)
        for key in ("user", "password_file", "tls_certificate", "tls_private_key", "tls_root_ca")
    }
    for key, v in text.items():
        if v is not None and not v.strip():
            errors.append(f"link.{key} is empty: remove the key or give a value")
            text[key] = None
    link = LinkSettings(
        listen=ends["listen"],
        connect=ends["connect"],
        key_prefix=prefix,
        allow_remote=_try(errors, False, _get, t, "allow_remote", "link", bool, False),
        watchdog_s=_number(errors, t, "watchdog_s", "link", float, 0.5, *WATCHDOG_RANGE_S, " s"),
        watchdog_action=action,
        **text,
    )
    errors.extend(remote_policy_errors(link))
    _raise_all(errors)
    return link


def check_remote_policy(link: LinkSettings) -> None:
    """Raise ConfigError with every message of :func:`remote_policy_errors` (none: nothing)."""
    _raise_all(remote_policy_errors(link))


def remote_policy_errors(link: LinkSettings) -> list[str]:
    """What the link's policy refuses: a non-loopback endpoint without ``allow_remote`` and
    authentication, plain tcp beyond loopback, a ``tls/`` listener without a certificate, a
    plain tcp listener beside mutual TLS (it would let clients in without a certificate)."""
    errors = []
    for e in (*link.listen, *link.connect):
        if is_loopback_endpoint(e):
            continue
        if not link.allow_remote:
            errors.append(
                f"link.listen/connect endpoint {e!r} is not on 127.0.0.1; set "
                "link.allow_remote = true (and authentication) to use it"
            )
        elif not e.startswith("tls/"):
            errors.append(
                f"endpoint {e!r} is plain tcp/ beyond loopback: refused whatever else is set "
                "(nothing on it would be encrypted); use tls/HOST:PORT"
            )
        elif not link.has_auth:
            errors.append(
                f"endpoint {e!r} is beyond loopback but no authentication is configured: set "
                "link.user + link.password_file, or link.tls_certificate + "
                "link.tls_private_key + link.tls_root_ca (mutual TLS)"
            )
    if link.tls_certificate is not None and link.tls_private_key is None:
        errors.append("link.tls_certificate needs link.tls_private_key")
    tls_listen = [e for e in link.listen if e.startswith("tls/")]
    if tls_listen and link.tls_certificate is None:
        errors.append(
            f"link.listen {tls_listen[0]!r} is tls/ but link.tls_certificate is not set "
            "(a TLS listener needs its certificate and key)"
        )
    mutual = link.tls_certificate is not None and link.tls_root_ca is not None
    plain = [e for e in link.listen if e.startswith("tcp/")]
    if mutual and tls_listen and plain and link.password_file is None:
        errors.append(
            f"link.listen {plain[0]!r} is plain tcp/ beside mutual TLS: a client would get in "
            "there without a certificate; listen on tls/ endpoints only"
        )
    return errors


def _pad(raw: dict[str, Any]) -> PadSettings:
    t = _table(raw, "pad")
    errors: list[str] = []
    _try(errors, None, _unknown, t, {"rows", "cols", "pitch_mm", "pose"}, "pad")
    pose = _try(errors, {}, _table, t, "pose", "pad")
    _try(errors, None, _unknown, pose, {"x_mm", "y_mm", "z_mm", "yaw_deg"}, "pad.pose")
    rows = _number(errors, t, "rows", "pad", int, 2, 1, MAX_PAD_SIDE)
    cols = _number(errors, t, "cols", "pad", int, 3, 1, MAX_PAD_SIDE)
    lo_mm, hi_mm = (v * 1e3 for v in PITCH_RANGE_M)
    pitch = _number(errors, t, "pitch_mm", "pad", float, 45.0, lo_mm, hi_mm, " mm")
    xyz = [_try(errors, 0.0, _get, pose, k, "pad.pose", float, 0.0) for k in _POSE_KEYS]
    _raise_all(errors)
    return PadSettings(
        rows=rows,
        cols=cols,
        pitch_m=pitch / 1e3,
        x_m=xyz[0] / 1e3,
        y_m=xyz[1] / 1e3,
        z_m=xyz[2] / 1e3,
        yaw_rad=math.radians(xyz[3]),
    )


_POSE_KEYS = ("x_mm", "y_mm", "z_mm", "yaw_deg")


def _thresholds(raw: dict[str, Any]) -> Thresholds:
    t = _table(raw, "thresholds")
    keys = {"p0_kpa", "t_adj_kpa", "t_o_kpa", "t_g_kpa", "window", "max_pressure_kpa"}
    errors: list[str] = []
    _try(errors, None, _unknown, t, keys, "thresholds")

    bad: set[str] = set()

    def kpa(key: str, default_pa: float, lo_pa: float, hi_pa: float) -> float:
        where, lo, hi = "thresholds", lo_pa / 1e3, hi_pa / 1e3
        n = len(errors)
        v = float(_number(errors, t, key, where, float, default_pa / 1e3, lo, hi, " kPa")) * 1e3
        if len(errors) > n:
            bad.add(key)
        return v

    values = {
        "p0_pa": kpa("p0_kpa", DEFAULT_P0_PA, *thesis.P0_RANGE_PA),
        "adjust_tolerance_pa": kpa("t_adj_kpa", DEFAULT_ADJUST_TOLERANCE_PA, *TOLERANCE_RANGE_PA),
        "object_threshold_pa": kpa("t_o_kpa", DEFAULT_OBJECT_THRESHOLD_PA, *THRESHOLD_RANGE_PA),
        "contact_threshold_pa": kpa("t_g_kpa", DEFAULT_CONTACT_THRESHOLD_PA, *THRESHOLD_RANGE_PA),
        "max_pressure_pa": kpa("max_pressure_kpa", DEFAULT_MAX_PRESSURE_PA, *MAX_PRESSURE_RANGE_PA),
    }
    window = _number(
        errors, t, "window", "thresholds", int, DEFAULT_FILTER_WINDOW, 1, MAX_FILTER_WINDOW
    )
    errors.extend(_threshold_order(values, bad))
    _raise_all(errors)
    return Thresholds(filter_window=int(window), **values)


def _threshold_order(values: dict[str, float], bad: set[str]) -> list[str]:
    """The order the thesis's thresholds must keep (each pair judged when both parsed):
    p0 + t_adj below the maximum; the gripper's contact threshold t_g at or above the object
    threshold t_o (a contact must be the larger rise: Section 6.2 sets 0.09 over 0.05 kPa)."""
    errors = []
    if not bad & {"p0_kpa", "t_adj_kpa", "max_pressure_kpa"} and (
        values["p0_pa"] + values["adjust_tolerance_pa"] >= values["max_pressure_pa"]
    ):
        errors.append(
            "thresholds.p0_kpa + t_adj_kpa "
            f"({(values['p0_pa'] + values['adjust_tolerance_pa']) / 1e3:g} kPa) "
            f"must stay below max_pressure_kpa ({values['max_pressure_pa'] / 1e3:g} kPa)"
        )
    t_o, t_g = values["object_threshold_pa"], values["contact_threshold_pa"]
    if not bad & {"t_o_kpa", "t_g_kpa"} and t_g < t_o:
        errors.append(
            f"thresholds.t_g_kpa ({t_g / 1e3:g} kPa) must not be below t_o_kpa "
            f"({t_o / 1e3:g} kPa): the gripper's contact is the larger rise (thesis 0.09 "
            "over 0.05 kPa)"
        )
    return errors


def _gripper(raw: dict[str, Any]) -> str | None:
    gripper = _table(raw, "gripper")
    _unknown(gripper, {"mounting"}, "gripper")
    mounting: str | None = _get(gripper, "mounting", "gripper", str, None)
    if mounting is not None and mounting not in thesis.GRIPPER_MOUNTINGS_M:
        raise ConfigError(
            f"gripper.mounting must be one of {', '.join(thesis.GRIPPER_MOUNTINGS_M)}; got {mounting!r}"
        )
    return mounting


def _collect(errors: list[str], parse: Any, *args: Any) -> Any:
    """``parse(*args)``, or None with its ConfigError's message(s) appended to ``errors``."""
    try:
        return parse(*args)
    except InputError as exc:  # ConfigError, or a settings record refusing a value
        errors.extend(getattr(exc, "errors", None) or [str(exc)])
        return None


def _cross_table(raw: dict[str, Any], pad: PadSettings | None) -> list[str]:
    """Errors between tables: fewer channels wired than the pad has modules (counted from
    the file, so a channel with errors of its own still counts)."""
    box = raw.get("box")
    chans = box.get("channel") if isinstance(box, dict) else None
    if pad is None or not isinstance(chans, list) or not chans:
        return []
    modules = pad.rows * pad.cols
    if len(chans) >= modules:
        return []
    return [
        f"box.channel: {len(chans)} channels wired for a {pad.rows} x {pad.cols} pad "
        f"({modules} modules): every module needs its channel"
    ]


def parse_installation(raw: dict[str, Any], source: str = "<dict>") -> Installation:
    """Validate a parsed TOML document into :class:`Installation`.

    Every table is checked, and every channel of the box; the ConfigError lists every error
    found (one per line, each naming its key), not only the first.
    """
    if not isinstance(raw, dict):
        raise ConfigError(
            f"an installation is a table of settings (a dict), got {type(raw).__name__}"
        )
    errors: list[str] = []
    _collect(errors, _unknown, raw, {"box", "link", "pad", "thresholds", "gripper"}, "")
    parts = {
        name: _collect(errors, parse, raw)
        for name, parse in (
            ("box", _box), ("link", _link), ("pad", _pad), ("thresholds", _thresholds),
            ("gripper", _gripper),
        )
    }  # fmt: skip
    errors.extend(_cross_table(raw, parts["pad"]))
    if errors:
        if len(errors) == 1:
            raise ConfigError(errors[0])
        exc = ConfigError(f"{len(errors)} errors:\n  " + "\n  ".join(errors))
        exc.errors = errors  # type: ignore[attr-defined]
        raise exc
    return Installation(
        box=parts["box"],
        link=parts["link"],
        pad=parts["pad"],
        thresholds=parts["thresholds"],
        gripper_mounting=parts["gripper"],
        source=source,
    )


def read_toml(path: Path) -> dict[str, Any]:
    """The TOML document of ``path``; ConfigError naming the file when unreadable or invalid."""
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(f"cannot read installation file {str(path)!r}: {exc.strerror}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ConfigError(f"installation file {str(path)!r} is not valid TOML: {exc}") from None


def load_installation(path: str | Path) -> Installation:
    """Read and validate an installation file (TOML).

    Raises
    ------
    ConfigError
        Unreadable file, TOML syntax error, unknown key or wrong value (named in the message).
    """
    p = Path(path)
    raw = read_toml(p)
    try:
        return parse_installation(raw, str(p))
    except ConfigError as exc:  # the file named: it may be one of several
        raise ConfigError(f"installation file {str(p)!r}: {exc}") from None


def describe(inst: Installation) -> list[str]:
    """Resolved settings as ``key = value unit`` lines (for ``softpad config check``)."""
    th, pad, link, box = inst.thresholds, inst.pad, inst.link, inst.box
    out = [f"# {inst.source}"]
    out.append(f"box.sample_rate_hz = {box.sample_rate_hz:g} Hz")
    out.append(f"box.iio_root = {box.iio_root}")
    out.append(f"box.ambient_pressure_kpa = {box.ambient_pressure_pa / 1e3:g} kPa")
    for w in (*box.channels, *([box.supply] if box.supply else [])):
        name = "box.supply" if w.channel == 0 else f"box.channel.{w.channel}"
        valves = (
            ""
            if w.channel == 0
            else f"{w.gpiochip} inflate line {w.inflate_line}, deflate line {w.deflate_line}; "
        )
        out.append(
            f"{name}: {valves}iio:device{w.iio_device}/in_voltage{w.iio_channel}_raw; "
            f"p = {w.offset_pa:g} Pa + {w.gain:g} x {w.pa_per_count:g} Pa/count x raw"
        )
    out.append(f"link.listen = {', '.join(link.listen) or '-'}")
    out.append(f"link.connect = {', '.join(link.connect) or '-'}")
    out.append(f"link.key_prefix = {link.key_prefix}")
    auth = "user/password" if link.user else ("TLS" if link.tls_certificate else "none")
    if link.tls_certificate and link.tls_root_ca:
        auth += " + mutual TLS" if link.user else " (mutual)"
    out.append(f"link.auth = {auth}; allow_remote = {str(link.allow_remote).lower()}")
    out.append(f"link.watchdog = {link.watchdog_s:g} s, then {link.watchdog_action}")
    out.append(f"pad = {pad.rows} x {pad.cols} modules, pitch {pad.pitch_m * 1e3:g} mm")
    out.append(
        f"pad.pose = ({pad.x_m * 1e3:g}, {pad.y_m * 1e3:g}, {pad.z_m * 1e3:g}) mm, "
        f"yaw {math.degrees(pad.yaw_rad):g} deg"
    )
    out.append(
        f"thresholds: p0 {th.p0_pa / 1e3:g} kPa, t_adj {th.adjust_tolerance_pa / 1e3:g} kPa, "
        f"t_o {th.object_threshold_pa / 1e3:g} kPa, t_g {th.contact_threshold_pa / 1e3:g} kPa, "
        f"window {th.filter_window} samples, max {th.max_pressure_pa / 1e3:g} kPa"
    )
    mounting = inst.gripper_mounting or "each object's catalogue mounting (Section 6.3)"
    out.append(f"gripper.mounting = {mounting} (max/min width, cm)")
    return out
