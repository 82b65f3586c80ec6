"""The installation file (TOML) into typed, validated settings.

``load_installation("site.toml")`` returns an :class:`Installation`: box wiring and calibration
(:class:`BoxSettings`), the zenoh link (:class:`LinkSettings`), the pad (:class:`PadSettings`),
the thesis thresholds (:class:`Thresholds`) and the gripper mounting. ``softpad config check
FILE`` prints the resolved values with units. See ``examples/site.toml``.
"""

from softpad.config._audit import audit_link, check_installation_file
from softpad.config._settings import (
    WATCHDOG_RANGE_S,
    BoxSettings,
    ChannelWiring,
    ConfigError,
    Installation,
    LinkSettings,
    PadSettings,
    Thresholds,
    check_endpoint,
    check_remote_policy,
    describe,
    is_loopback_endpoint,
    load_installation,
    parse_installation,
    remote_policy_errors,
)

__all__ = [
    "WATCHDOG_RANGE_S",
    "BoxSettings",
    "ChannelWiring",
    "ConfigError",
    "Installation",
    "LinkSettings",
    "PadSettings",
    "Thresholds",
    "audit_link",
    "check_endpoint",
    "check_installation_file",
    "check_remote_policy",
    "describe",
    "is_loopback_endpoint",
    "load_installation",
    "parse_installation",
    "remote_policy_errors",
]
