"""The ``softpad_msgs`` ROS 1 message package: its Python classes generated from its definitions.

The package's definitions ship with SoftPad (``softpad/data/ros/softpad_msgs``: ``Event.msg``,
``ValveCommands.msg``, ``Grasp.action``, a ``package.xml`` and a ``CMakeLists.txt`` a catkin
workspace builds as usual). Without a catkin build, :func:`generate_messages` writes the Python
modules a catkin build would (Debian's ``genpy``, the generator catkin runs) into a directory
(:func:`messages_dir`) and :func:`ensure_messages` imports them from there, so the node
publishes the typed messages and any other process that has the directory on its
``PYTHONPATH`` (``eval "$(softpad ros env)"``) decodes them: ``rostopic echo /softpad/events``,
an actionlib client of the grasp action.

An action is expanded into its seven messages the way ``actionlib_msgs``' ``genaction.py``
does (``GraspGoal``, ``GraspActionGoal`` with a header and a goal id, ...), so their MD5 sums
are those of a catkin build of the same files.
"""

from __future__ import annotations

import os
import re
from importlib import resources
from pathlib import Path
from types import ModuleType

#: Name of the message package.
PACKAGE = "softpad_msgs"

#: Separator of the definitions of a message's dependencies (ROS 1's ``gendeps --cat``).
_SEPARATOR = "\n" + "=" * 80 + "\n"


def ros_packages_dir() -> Path:
    """The directory holding SoftPad's ROS 1 packages (``softpad_msgs``, ``softpad_ros``): the
    one to put on ``ROS_PACKAGE_PATH``."""
    return Path(str(resources.files("softpad") / "data" / "ros"))


def messages_dir() -> Path:
    """Where the generated Python package ``softpad_msgs`` is written: ``SOFTPAD_ROS1_MSGS``,
    else ``$XDG_CACHE_HOME/softpad/ros1`` (default ``~/.cache/softpad/ros1``)."""
    own = os.environ.get("SOFTPAD_ROS1_MSGS")
    if own:
        return Path(own)
    cache = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(cache) / "softpad" / "ros1"


def _action_messages(name: str, text: str) -> dict[str, str]:
    """The seven messages of action ``name`` (``genaction.py``'s expansion of ``.action``)."""
    parts = re.split(r"^---[ \t]*$\n?", text, flags=re.M)
    if len(parts) != 3:
        raise ValueError(f"{name}.action must have goal, result and feedback parts")
    goal, result, feedback = parts
    status = "Header header\nactionlib_msgs/GoalStatus status\n"
    return {
        f"{name}Goal": goal,
        f"{name}Result": result,
        f"{name}Feedback": feedback,
        f"{name}ActionGoal": f"Header header\nactionlib_msgs/GoalID goal_id\n{name}Goal goal\n",
        f"{name}ActionResult": f"{status}{name}Result result\n",
        f"{name}ActionFeedback": f"{status}{name}Feedback feedback\n",
        f"{name}Action": (
            f"{name}ActionGoal action_goal\n{name}ActionResult action_result\n"
            f"{name}ActionFeedback action_feedback\n"
        ),
    }


def message_definitions() -> dict[str, str]:
    """``{"softpad_msgs/Event": text, ...}``: every message of the package, actions expanded."""
    root = ros_packages_dir() / PACKAGE
    out: dict[str, str] = {}
    for path in sorted((root / "msg").glob("*.msg")):
        out[f"{PACKAGE}/{path.stem}"] = path.read_text()
    for path in sorted((root / "action").glob("*.action")):
        for name, text in _action_messages(path.stem, path.read_text()).items():
            out[f"{PACKAGE}/{name}"] = text
    return out


def _register_dependencies(context: object, specs: dict[str, object]) -> None:
    """Register in ``context`` every message of another package that ``specs`` use, from the
    definitions the installed message classes carry (``_full_text``, dependencies included)."""
    import genmsg.msg_loader
    import genmsg.msgs
    import genpy.message

    todo = [t for s in specs.values() for t in s.types]  # type: ignore[attr-defined]
    while todo:
        t = genmsg.msgs.bare_msg_type(todo.pop())
        full = genmsg.msgs.resolve_type(t, PACKAGE)
        if genmsg.msgs.is_builtin(t) or full.startswith(PACKAGE + "/"):
            continue
        if context.is_registered(full):  # type: ignore[attr-defined]
            continue
        cls = genpy.message.get_message_class(full)
        if cls is None:
            raise ImportError(f"message {full} of {PACKAGE}'s dependencies is not installed")
        first, *deps = cls._full_text.split(_SEPARATOR)
        blocks = [(full, first)] + [tuple(d.split("\n", 1)) for d in deps]
        for name, text in blocks:
            name = name.removeprefix("MSG: ").strip()
            if not context.is_registered(name):  # type: ignore[attr-defined]
                spec = genmsg.msg_loader.load_msg_from_string(context, text, name)
                context.register(name, spec)  # type: ignore[attr-defined]
                todo.extend(spec.types)


def message_sources() -> dict[str, str]:
    """``{"_Event": python source, ...}``: each message's module as genpy writes it."""
    from softpad.ros._rospy_path import ensure_rospy

    ensure_rospy()  # genpy, genmsg and the dependencies' classes come with ROS
    import genmsg.msg_loader
    from genpy.generator import msg_generator

    context = genmsg.msg_loader.MsgContext.create_default()
    specs = {}
    for full, text in message_definitions().items():
        specs[full] = genmsg.msg_loader.load_msg_from_string(context, text, full)
        context.register(full, specs[full])
    _register_dependencies(context, specs)
    return {
        "_" + full.split("/")[1]: "\n".join(msg_generator(context, spec, {})) + "\n"
        for full, spec in specs.items()
    }


def _write_if_changed(path: Path, text: str) -> None:
    if path.exists() and path.read_text() == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)  # atomic: another process generating at once reads a whole file


def generate_messages(out_dir: str | Path | None = None) -> Path:
    """Write the Python package ``softpad_msgs`` (``softpad_msgs/msg/_Event.py``, ...) under
    ``out_dir`` (default :func:`messages_dir`); files already up to date are left alone.

    Returns
    -------
    Path
        ``out_dir``: the directory to put on ``PYTHONPATH``.
    """
    import hashlib

    out = Path(out_dir) if out_dir is not None else messages_dir()
    pkg = out / PACKAGE
    # generating takes a second or two on a busy machine: skipped when the definitions (and
    # the genpy that wrote the files) are those of the last generation
    from softpad.ros._rospy_path import ensure_rospy

    ensure_rospy()
    import genpy

    key = repr((sorted(message_definitions().items()), getattr(genpy, "__file__", "")))
    digest = hashlib.sha256(key.encode()).hexdigest()
    stamp = pkg / ".definitions.sha256"
    if stamp.exists() and stamp.read_text() == digest and (pkg / "msg" / "__init__.py").exists():
        return out
    sources = message_sources()
    _write_if_changed(pkg / "__init__.py", "")
    for module, text in sources.items():
        _write_if_changed(pkg / "msg" / f"{module}.py", text)
    init = "".join(f"from .{m} import *\n" for m in sorted(sources))
    _write_if_changed(pkg / "msg" / "__init__.py", init)
    _write_if_changed(stamp, digest)
    return out


def ensure_messages() -> ModuleType:
    """Generate the package's Python modules (when out of date), have ``softpad_msgs`` imported
    from their directory (before any other package of that name: ROS 2's) and return
    ``softpad_msgs.msg``."""
    from softpad.ros._rospy_path import prefer_modules

    out = str(generate_messages())
    # before ROS 2's package of the same name (softpad[ros2] installs one)
    prefer_modules(out, frozenset({PACKAGE}))
    import softpad_msgs.msg  # type: ignore[import-not-found]

    return softpad_msgs.msg  # type: ignore[no-any-return]


def shell_environment() -> str:
    """Shell lines that let other ROS 1 processes use the package (``softpad ros env``): the
    generated modules on ``PYTHONPATH`` and SoftPad's ROS packages on ``ROS_PACKAGE_PATH``
    (``rosmsg show softpad_msgs/Event``, ``roslaunch softpad_ros pad.launch``)."""
    msgs, pkgs = generate_messages(), ros_packages_dir()
    return (
        f'export PYTHONPATH="{msgs}${{PYTHONPATH:+:$PYTHONPATH}}"\n'
        f'export ROS_PACKAGE_PATH="{pkgs}${{ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}}"\n'
    )
