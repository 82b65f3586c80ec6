"""The ``--record FILE.mcap`` option shared by ``run``, ``trials`` and ``demo``."""

from __future__ import annotations

from typing import Any


def add_record_option(p: Any, per_trial: bool = False) -> None:
    """Add ``--record FILE.mcap`` and ``--force`` to a sub-command's parser."""
    what = "every frame, valve command, robot pose, plan and event as MCAP (ROS 2 types)"
    if per_trial:
        what = f"record every trial: {what}, one file per trial, FILE-OBJECT-tK.mcap"
    p.add_argument("--record", metavar="FILE.mcap", help=what if per_trial else f"record {what}")
    p.add_argument("--force", action="store_true", help="overwrite an existing --record file")


def open_recorder(
    path: str | None, box: Any, metadata: dict[str, Any], force: bool, pad: Any = None
) -> Any:
    """A :class:`softpad.record.McapRecorder` for ``path`` watching ``box`` (None without a path),
    the pad at ``pad`` in the base frame (a :class:`~softpad.layout.PadPose`; None: the origin).

    Valve and robot commands come from the execution's events; on a simulated box the
    gripper's measured pose is recorded too (from the simulator's world).
    """
    if not path:
        return None
    from softpad.box import simulator_of
    from softpad.record import McapRecorder

    sim = simulator_of(box)
    robot_state = sim.world.gripper_state if sim is not None else None
    return McapRecorder(path, metadata, force=force, robot_state=robot_state, pad=pad)


def run_metadata(
    command: str, box: Any, url: str, objects: list[str], params: Any, **extra: Any
) -> dict[str, Any]:
    """The metadata record of a recording: command, box URL, objects, layout, parameters
    (the execution's, SI), seed of the box and extra facts (gripper, trial...)."""
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


def check_trial_recordings(base: str | None, specs: Any, trials: int, force: bool) -> None:
    """Refuse, before any trial runs, a ``--record`` base whose trial files exist (unless
    ``force``) or that is not a ``.mcap`` name."""
    if not base:
        return
    from softpad.record import check_output
    from softpad.trials import trial_recording_path

    check_output(base, force=True)  # the name itself: .mcap, existing folder
    for spec in specs:
        for k in range(trials):
            check_output(trial_recording_path(base, spec.name, k), force)
