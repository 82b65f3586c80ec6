"""Export a recording as a rosbag2 directory or a ROS 1 bag, with ``rosbags``' writers.

Every message of the MCAP file is copied with its recorded clock (``log_time``), so the bag
plays back at the run's real speed: into rosbag2 unchanged (CDR, the embedded ROS 2 message
definitions, ``/tf_static`` offered as transient-local, i.e. latched, as the MCAP's channel
says), into a ROS 1 bag converted to ROS 1 serialisation by ``rosbags``' converter
(``std_msgs/Header`` gains its ``seq``, counting up per topic; ``/tf_static`` latched), readable by ``rosbag play`` and Debian's ``python3-rosbag``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from softpad.errors import InputError
from softpad.record._schemas import TF_STATIC_TOPIC


def _latched_qos() -> Any:
    """The QoS ``/tf_static`` is published with in ROS 2: reliable, transient local, depth 1."""
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    never = QosTime(0x7FFFFFFF, 0xFFFFFFFF)
    return Qos(
        QosHistory.KEEP_LAST, 1, QosReliability.RELIABLE, QosDurability.TRANSIENT_LOCAL,
        never, never, QosLiveliness.AUTOMATIC, never, False,
    )  # fmt: skip


def latched_qos_yaml() -> str:
    """``offered_qos_profiles`` of a latched topic as rosbag2 stores it in a channel's metadata
    (YAML, metadata version 9's names: ``keep_last``, ``transient_local``, ...): what a
    ROS 2 player reads to republish ``/tf_static`` latched."""
    from io import StringIO

    from rosbags.rosbag2.metadata import dump_qos_v9
    from ruamel.yaml import YAML

    stream = StringIO()
    yaml = YAML(typ="safe")
    yaml.default_flow_style = False
    yaml.dump(dump_qos_v9([_latched_qos()]), stream)
    return stream.getvalue().strip()


def _refuse_existing(out: Path, force: bool) -> None:
    if out.exists() and not force:
        raise InputError(f"{str(out)!r} exists; refusing to overwrite it (add --force)")
    if not out.parent.exists():
        raise InputError(f"directory {str(out.parent)!r} of {str(out)!r} does not exist")


def to_rosbag2(recording: str | Path, out: str | Path, force: bool = False) -> Path:
    """Write ``recording`` (a SoftPad MCAP file) as the rosbag2 directory ``out`` (SQLite 3
    storage, ``metadata.yaml`` version 9), which ``ros2 bag info|play`` and ``rosbags`` read.

    An existing ``out`` is refused unless ``force`` (then it is replaced).

    Parameters
    ----------
    recording
        The MCAP file.
    out
        The rosbag2 directory written.
    force
        Replace an existing ``out``.
    """
    import shutil

    from rosbags.highlevel import AnyReader
    from rosbags.rosbag2 import Writer

    src, dst = Path(recording), Path(out)
    _refuse_existing(dst, force)
    if dst.exists():
        shutil.rmtree(dst) if dst.is_dir() else dst.unlink()
    with AnyReader([src]) as reader, Writer(dst, version=9) as writer:
        conns = {}
        for c in reader.connections:
            qos = list(getattr(c.ext, "offered_qos_profiles", []))
            if c.topic == TF_STATIC_TOPIC and not qos:  # recorded before the MCAP carried it
                qos = [_latched_qos()]
            conns[c.id] = writer.add_connection(
                c.topic, c.msgtype, typestore=reader.typestore, offered_qos_profiles=qos
            )
        for c, t_ns, raw in reader.messages():
            writer.write(conns[c.id], t_ns, raw)
    return dst


def to_rosbag1(recording: str | Path, out: str | Path, force: bool = False) -> Path:
    """Write ``recording`` as the ROS 1 bag ``out`` (``.bag``): ``rosbags``' converter turns
    each message into ROS 1 serialisation against ROS Noetic's types (``std_msgs/Header``
    gains ``seq``; the project's two types are carried over), then copied once more to mark
    ``/tf_static`` latched (the converter writes no latching flag) and to number each topic's
    headers 1, 2, 3, ... (it leaves every ``seq`` 0); ``rosbag play`` and
    Debian's ``rosbag`` Python package read it.

    Parameters
    ----------
    recording
        The MCAP file.
    out
        The bag written (``.bag``).
    force
        Replace an existing ``out``.
    """
    import contextlib
    import io

    from rosbags.convert import convert
    from rosbags.typesys import Stores, get_typestore

    src, dst = Path(recording), Path(out)
    if dst.suffix != ".bag":
        raise InputError(f"a ROS 1 bag's name ends in .bag, got {str(dst)!r}")
    _refuse_existing(dst, force)
    dst.unlink(missing_ok=True)
    noetic = get_typestore(Stores.ROS1_NOETIC)
    converted = dst.with_name(dst.stem + ".converting.bag")
    converted.unlink(missing_ok=True)
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # it names the types it carries over
            convert([src], converted, "sqlite3", 9, None, "file", None, noetic, [], [], [], [])
        _latch_tf_static(converted, dst)
    finally:
        converted.unlink(missing_ok=True)
    return dst


def _starts_with_header(msgdef: str) -> bool:
    """Whether a ROS 1 message definition's first field is a ``std_msgs/Header``."""
    for line in msgdef.splitlines():
        words = line.split("#", 1)[0].split()
        if words:
            return words[0] in ("Header", "std_msgs/Header")
    return False


def _latch_tf_static(src: Path, dst: Path) -> None:
    """Copy the ROS 1 bag ``src`` to ``dst`` message for message, ``/tf_static`` latched, and
    the ``seq`` of each topic's headers counting 1, 2, 3, ... as rospy's publisher numbers
    them (the converter leaves every ``seq`` 0). ``seq`` is the first field of a message that
    starts with a header: its first 4 bytes, little-endian."""
    import struct

    from rosbags.rosbag1 import Reader, Writer

    with Reader(src) as reader, Writer(dst) as writer:
        conns, seq = {}, {}
        for c in reader.connections:
            conns[c.id] = writer.add_connection(
                c.topic, c.msgtype, msgdef=c.msgdef.data, md5sum=c.digest, callerid="/softpad",
                latching=1 if c.topic == TF_STATIC_TOPIC else None,
            )  # fmt: skip
            if _starts_with_header(c.msgdef.data):
                seq[c.id] = 0
        for c, t_ns, raw in reader.messages():
            if c.id in seq:
                seq[c.id] += 1
                numbered = bytearray(raw)
                struct.pack_into("<I", numbered, 0, seq[c.id])
                raw = bytes(numbered)
            writer.write(conns[c.id], t_ns, raw)
