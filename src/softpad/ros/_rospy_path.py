"""Find Debian's ROS 1 Python packages from any Python 3.11 without mixing in the rest.

Debian's ``python3-rospy`` and the message packages install into the system Python's
``dist-packages`` (``/usr/lib/python3/dist-packages``), which the project's virtual
environment (often made from another Python 3.11 build) does not see. Appending that whole
directory to ``sys.path`` would also expose the system's other packages (numpy, matplotlib,
... when installed) wherever the environment lacks them. Instead :func:`ensure_rospy` appends
one import finder to ``sys.meta_path`` that resolves only the top-level names of
:data:`ROS_MODULES` (rospy, its pure-Python dependencies and the message packages) from that
directory, and only when the environment does not provide them itself (the finder is last).
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import os
import sys
from collections.abc import Sequence
from types import ModuleType

from softpad.errors import InputError

#: Where Debian installs ROS 1 Python packages (override with SOFTPAD_ROS_DIST_PACKAGES).
DIST_PACKAGES = "/usr/lib/python3/dist-packages"

#: Top-level modules taken from :data:`DIST_PACKAGES`: rospy, its dependencies, the messages.
ROS_MODULES = frozenset(
    {
        "rospy", "rosgraph", "roslib", "rospkg", "genpy", "genmsg", "catkin", "catkin_pkg",
        "rosgraph_msgs", "std_msgs", "std_srvs", "geometry_msgs", "sensor_msgs",
        "diagnostic_msgs", "tf2_msgs", "actionlib_msgs", "roscpp", "rostopic", "rosmsg",
        "rosservice", "rosnode", "rosbag", "roslz4", "rosparam", "rosmaster",
        "yaml", "_yaml", "netifaces", "distro", "dateutil", "docutils", "pyparsing",
        "defusedxml", "six", "gnupg", "Cryptodome",
    }
)  # fmt: skip

INSTALL_HINT = (
    "ROS 1 is not installed: run (as root) 'apt-get install -y ros-core python3-rospy "
    "python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-diagnostic-msgs "
    "python3-std-srvs python3-tf2-msgs python3-rostopic' or 'make ros-deps'"
)


class _RosFinder(importlib.abc.MetaPathFinder):
    """Import finder that resolves only :data:`ROS_MODULES` from one directory."""

    def __init__(self, directory: str) -> None:
        self.directory = directory

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if path is not None or fullname not in ROS_MODULES:
            return None  # sub-modules are found through their package's __path__
        return importlib.machinery.PathFinder.find_spec(fullname, [self.directory])


def _installed_finder() -> _RosFinder | None:
    return next((f for f in sys.meta_path if isinstance(f, _RosFinder)), None)


def ensure_rospy() -> ModuleType:
    """Import and return ``rospy``, adding the ROS finder first when needed.

    Raises
    ------
    InputError
        When rospy cannot be imported, with the command that installs it.
    """
    directory = os.environ.get("SOFTPAD_ROS_DIST_PACKAGES", DIST_PACKAGES)
    if _installed_finder() is None and os.path.isdir(directory):
        sys.meta_path.append(_RosFinder(directory))
    try:
        import rospy
    except ImportError as exc:
        raise InputError(f"{INSTALL_HINT} ({exc})") from None
    return rospy


def rospy_available() -> bool:
    """True when :func:`ensure_rospy` can import rospy."""
    try:
        ensure_rospy()
    except InputError:
        return False
    return True


def require_master() -> ModuleType:
    """:func:`ensure_rospy`, then check that the ROS master answers (no endless retrying).

    Raises
    ------
    InputError
        When no master answers at ``ROS_MASTER_URI``, naming it and how to start one.
    """
    rospy = ensure_rospy()
    import rosgraph

    uri = rosgraph.get_master_uri()
    if not rosgraph.is_master_online(uri):
        raise InputError(
            f"no ROS master answers at {uri}: start 'roscore' (loopback: "
            "ROS_MASTER_URI=http://127.0.0.1:11311 ROS_IP=127.0.0.1 ROS_HOSTNAME=localhost)"
        )
    return rospy
