"""The node's settings from an installation file (read by :mod:`softpad.config`; this
package takes the object it returns, so that the ROS layer imports no configuration code)."""

from __future__ import annotations

from typing import Any


def installation_settings(installation: Any, pitch: bool = True) -> dict[str, Any]:
    """The node's settings (:data:`softpad.ros.CONFIG_KEYS`, SI) of an installation.

    Parameters
    ----------
    installation
        A :class:`softpad.config.Installation`: its box link, pad and pose, thresholds,
        ambient pressure and gripper.
    pitch
        Whether to give the pad's pitch (``pitch_m``; the ROS 2 node takes none).

    Returns
    -------
    dict
        ``layout``, ``pitch_m``, ``pad_x_m`` .. ``pad_yaw_rad`` (m, rad), the thresholds and
        ambient pressure (Pa), and ``box`` and ``gripper`` where the installation has them.
    """
    pad, th = installation.pad, installation.thresholds
    values: dict[str, Any] = {
        "layout": f"{pad.rows}x{pad.cols}", "pitch_m": pad.pitch_m,
        "pad_x_m": pad.x_m, "pad_y_m": pad.y_m, "pad_z_m": pad.z_m, "pad_yaw_rad": pad.yaw_rad,
        "object_threshold_pa": th.object_threshold_pa,
        "contact_threshold_pa": th.contact_threshold_pa,
        "ambient_pressure_pa": installation.box.ambient_pressure_pa,
    }  # fmt: skip
    if not pitch:
        del values["pitch_m"]
    if installation.box_url is not None:  # the box daemon's link
        values["box"] = installation.box_url
    if installation.gripper_mounting is not None:
        values["gripper"] = installation.gripper_mounting
    return values


def given_settings(hold_s: float | None = None, **names: str | None) -> dict[str, Any]:
    """The node's settings given as options: ``hold_s`` unless None, each of ``names``
    (``box``, ``place``, ``planner``, ``detector``, ``robot``) unless None or empty; they
    override the installation's (:meth:`NodeConfig.updated`).

    Parameters
    ----------
    hold_s
        Hold time of a grasp, s.
    names
        Settings by key (:data:`softpad.ros.CONFIG_KEYS`).
    """
    changes: dict[str, Any] = {} if hold_s is None else {"hold_s": hold_s}
    changes.update({key: value for key, value in names.items() if value})
    return changes


__all__ = ["given_settings", "installation_settings"]
