"""A run's recording (``--record FILE.mcap``): its metadata record and the recorder that
watches its box."""

from __future__ import annotations

from typing import Any


def open_recorder(
    path: str | None, box: Any, metadata: dict[str, Any], force: bool, pad: Any = None
) -> Any:
    """A :class:`softpad.record.McapRecorder` for ``path`` watching ``box`` (None without a
    path).

    Valve and robot commands come from the execution's events; on a simulated box the
    gripper's measured pose is recorded too (from the simulator's world).

    Parameters
    ----------
    path
        The recording's file (.mcap), or None.
    box
        The box the run reads.
    metadata
        The metadata record (:func:`run_metadata`).
    force
        Overwrite an existing file.
    pad
        Where the pad stands in the base frame (a :class:`~softpad.layout.PadPose`; None:
        the origin).
    """
    if not path:
        return None
    from softpad.box import simulator_of
    from softpad.record._mcap import McapRecorder

    sim = simulator_of(box)
    robot_state = sim.world.gripper_state if sim is not None else None
    return McapRecorder(path, metadata, force=force, robot_state=robot_state, pad=pad)


def run_metadata(
    command: str, box: Any, url: str, objects: list[str], params: Any, **extra: Any
) -> dict[str, Any]:
    """The metadata record of a recording.

    Parameters
    ----------
    command
        The command that recorded (``run``).
    box
        The box (its sample rate, channels and simulated pad).
    url
        The box's URL (its seed recorded where it has one).
    objects
        The run's objects.
    params
        The execution's parameters (a dataclass, SI).
    extra
        Further facts (gripper, planner, trial...).
    """
    from dataclasses import asdict

    from softpad.box import parse_url, simulator_of

    sim = simulator_of(box)
    layout = sim.world.layout.name if sim is not None else "2x3"
    options = parse_url(url)[2]
    meta: dict[str, Any] = {"command": command, "box": url, "objects": objects, "layout": layout}
    meta.update(seed=int(options["seed"]) if options.get("seed", "").isdigit() else None)
    meta.update(params=asdict(params), sample_rate_hz=box.sample_rate_hz, channels=box.channels)
    meta.update(extra)
    return meta


__all__ = ["open_recorder", "run_metadata"]
