"""``hw://FILE.toml``: the real Pneumaticbox as a back-end chosen by URL.

The URL's location is the installation file (:func:`softpad.config.load_installation`) whose
``[box]`` tables wire the valves and sensors: ``hw:///etc/softpad/site.toml`` (an absolute
path: three slashes) or ``hw://site.toml`` (relative to the working directory). The URL takes
no options: everything about the box is in the file.
"""

from __future__ import annotations

from softpad.box._hardware import HardwareBox
from softpad.errors import InputError


def open_hardware_url(location: str, options: dict[str, str]) -> HardwareBox:
    """The :class:`HardwareBox` wired in the installation file ``location``.

    Parameters
    ----------
    location
        Path of the installation file (TOML).
    options
        URL options: none are taken.

    Returns
    -------
    HardwareBox
        The box, its valve lines requested and its sensors open.

    Raises
    ------
    InputError
        No file named, an option given, or the file unreadable or invalid (named).
    """
    from softpad.config import load_installation

    if options:
        raise InputError(
            f"hw:// takes no options (the installation file says everything), got "
            f"{', '.join(sorted(options))}"
        )
    if not location:
        raise InputError("hw:// needs the installation file: hw:///etc/softpad/site.toml")
    return HardwareBox(load_installation(location).box)


__all__ = ["open_hardware_url"]
