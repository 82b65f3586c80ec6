"""Find Debian's ROS 1 Python packages from any Python 3.11 without mixing in the rest.

Debian's ``python3-rospy`` and the message packages install into the system Python's
``dist-packages`` (``/usr/lib/python3/dist-packages``), which the project's virtual
environment (often made from another Python 3.11 build) does not see. Appending that whole
directory to ``sys.path`` would also expose the system's other packages (numpy, matplotlib,
... when installed) wherever the environment lacks them. Instead :func:`ensure_rospy` adds
import finders to ``sys.meta_path`` that resolve only named top-level modules from that
directory: ROS 1's own (:data:`ROS1_OWN_MODULES`: rospy and the message packages) before
anything else, since ROS 2's wheels install message packages of the same names that rospy
cannot use; rospy's pure-Python dependencies (``yaml``, ...) only when the environment does
not provide them itself (that finder is last). One process speaks ROS 1 or ROS 2, not both.
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

#: ROS 1's own top-level modules, always taken from :data:`DIST_PACKAGES`: rospy and the
#: message packages. ROS 2's wheels (``softpad[ros2]``) install packages of the same names
#: (``std_msgs``, ``geometry_msgs``, ...) that rospy cannot use, so these come first.
ROS1_OWN_MODULES = frozenset(
    {
        "rospy", "rosgraph", "roslib", "rospkg", "genpy", "genmsg", "catkin", "catkin_pkg",
        "rosgraph_msgs", "std_msgs", "std_srvs", "geometry_msgs", "sensor_msgs",
        "diagnostic_msgs", "tf2_msgs", "actionlib", "actionlib_msgs", "roscpp", "rostopic",
        "rosmsg", "rosservice", "rosnode", "rosbag", "roslz4", "rosparam", "rosmaster",
    }
)  # fmt: skip

#: Top-level modules taken from :data:`DIST_PACKAGES`: rospy, its dependencies, the messages.
#: The dependencies (``yaml``, ...) only when the environment lacks them.
ROS_MODULES = ROS1_OWN_MODULES | frozenset(
    {
        "yaml", "_yaml", "netifaces", "distro", "dateutil", "docutils", "pyparsing",
        "defusedxml", "six", "gnupg", "Cryptodome",
    }
)  # fmt: skip

INSTALL_HINT = (
    "ROS 1 is not installed: run (as root) 'apt-get install -y ros-core python3-rospy "
    "python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-diagnostic-msgs "
    "python3-std-srvs python3-tf2-msgs python3-rostopic python3-actionlib' or 'make ros-deps'"
)


class _RosFinder(importlib.abc.MetaPathFinder):
    """Import finder that resolves only :data:`ROS_MODULES` from one directory."""

    def __init__(self, directory: str, names: frozenset[str] = ROS_MODULES) -> None:
        self.directory, self.names = directory, names

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if path is not None or fullname not in self.names:
            return None  # sub-modules are found through their package's __path__
        return importlib.machinery.PathFinder.find_spec(fullname, [self.directory])


def _installed_finder(directory: str | None = None) -> _RosFinder | None:
    """The ROS finder of ``directory`` (any, when None) on ``sys.meta_path``."""
    return next(
        (
            f
            for f in sys.meta_path
            if isinstance(f, _RosFinder) and directory in (None, f.directory)
        ),
        None,
    )


def prefer_modules(directory: str, names: frozenset[str]) -> None:
    """Resolve the top-level modules ``names`` from ``directory`` before anything else in this
    process (e.g. the generated ROS 1 ``softpad_msgs`` before ROS 2's package of that name).

    Raises
    ------
    InputError
        When one of them was already imported from elsewhere.
    """
    if not any(
        isinstance(f, _RosFinder) and f.directory == directory and f.names == names
        for f in sys.meta_path
    ):
        sys.meta_path.insert(0, _RosFinder(directory, names))
    _refuse_ros2_messages(directory, names)


def ensure_rospy() -> ModuleType:
    """Import and return ``rospy``, adding the ROS finder first when needed.

    Raises
    ------
    InputError
        When rospy cannot be imported, with the command that installs it.
    """
    directory = os.environ.get("SOFTPAD_ROS_DIST_PACKAGES", DIST_PACKAGES)
    if _installed_finder(directory) is None and os.path.isdir(directory):
        sys.meta_path.insert(0, _RosFinder(directory, ROS1_OWN_MODULES))  # before ROS 2's
        sys.meta_path.append(_RosFinder(directory, ROS_MODULES))
    _refuse_ros2_messages(directory)
    try:
        import rospy
    except ImportError as exc:
        raise InputError(f"{INSTALL_HINT} ({exc})") from None
    return rospy


def _refuse_ros2_messages(directory: str, names: frozenset[str] = ROS1_OWN_MODULES) -> None:
    """InputError when this process already imported a ROS 2 namesake of a ROS 1 module."""
    for name in sorted(names):
        module = sys.modules.get(name)
        origin = getattr(module, "__file__", None) or ""
        if module is not None and not os.path.abspath(origin).startswith(directory):
            raise InputError(
                f"this process already imported {name} from {origin!r} (ROS 2?); ROS 1 and "
                "ROS 2 cannot share one process: run the ROS 1 command in its own"
            )


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
