"""Learning a catalogue of known objects from recorded trials (``softpad learn``): each
trial's first plan, the grasp tried last and its outcome, and the increments' noise from the
recording's sensor variance."""

from __future__ import annotations

import json
import statistics
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from softpad.errors import InputError


def learned_trial(run: Any) -> tuple[Any, float] | None:
    """The :class:`~softpad.planning.LearnedTrial` of one recorded trial and the variance of
    a planning increment under its sensor noise, Pa^2 (per-frame variance / 5: the mean of 10
    reads minus a reference of 10); None for a trial that teaches nothing (no plan of one
    object or no outcome: the object was not detected, the box faulted).

    Parameters
    ----------
    run
        The :class:`~softpad.record.RecordedRun` of one trial of one object.
    """
    from softpad.planning import LearnedTrial

    name = f"recording {str(run.path)!r}"
    objects = run.metadata.get("objects")
    if not (isinstance(objects, list) and len(objects) == 1):
        raise InputError(f"{name}: not a trial of one object (objects {objects!r})")
    plans = [d for _, kind, d in run.events if kind == "plan"]
    outcomes = [d.get("outcome") for _, kind, d in run.events if kind == "outcome"]
    if not plans or not outcomes or len(plans[0].get("objects", [])) != 1:
        return None
    first = plans[0]["objects"][0]
    grasp = (float(first["cog"][0]), float(first["cog"][1]), float(first["theta"]))
    for _, kind, d in run.events:
        if kind == "retry":  # the grasp tried last
            grasp = (float(d["cog"][0]), float(d["cog"][1]), float(d["theta"]))
    if "increments_pa" not in plans[0]:
        raise InputError(
            f"{name}: its plan carries no increments_pa (recorded by an older SoftPad)"
        )
    increments = tuple(float(v) for v in plans[0]["increments_pa"])
    variance = float(run.metadata.get("pressure_variance_pa2", 0.0)) / 5
    return LearnedTrial(str(objects[0]), increments, grasp, outcomes[-1] == "held"), variance


@dataclass(frozen=True)
class _TrialEvents:
    """What learning reads of a recording: its path, metadata and events (t, kind, data)."""

    path: Path
    metadata: dict[str, Any]
    events: list[tuple[float, str, dict[str, Any]]]


def _trial_events(path: str) -> Any:
    """The metadata and events of a recording, read through its index without decoding its
    frames (a fortieth of :func:`~softpad.record.load_recording`'s time); a file without an
    index (cut short by a crash) or not a SoftPad recording goes through ``load_recording``,
    which reads what it can or names what is wrong."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    from softpad.record import _schemas as S
    from softpad.record._read import _decode_metadata, load_recording

    try:
        with open(path, "rb") as f:
            reader = make_reader(f, decoder_factories=[DecoderFactory()])
            meta: dict[str, Any] = {}
            for m in reader.iter_metadata():
                if m.name == "softpad":
                    meta.update(_decode_metadata(dict(m.metadata)))
            events = [
                (msg.log_time * 1e-9, str(d.kind), dict(json.loads(d.data_json)))
                for _, _, msg, d in reader.iter_decoded_messages(topics=[S.EVENT_TOPIC])
            ]
    except Exception:  # no summary or index, a torn file, not an MCAP: the full reader decides
        return load_recording(path)
    if meta.get("format") not in S.READABLE_FORMATS:
        return load_recording(path)
    events.sort(key=lambda e: e[0])
    return _TrialEvents(Path(path), meta, events)


@dataclass(frozen=True)
class Learned:
    """A catalogue learned from recordings.

    Attributes
    ----------
    catalogue
        The :class:`~softpad.planning.Catalogue` of known objects.
    trials
        The trials it was learned from.
    skipped
        Recordings that taught nothing (no plan of one object or no outcome).
    variance_pa2
        The median variance of a planning increment, Pa^2.
    """

    catalogue: Any
    trials: tuple[Any, ...]
    skipped: int
    variance_pa2: float


def learn_from_recordings(paths: Sequence[str], params: Any = None) -> Learned:
    """Learn the catalogue of known objects from the recorded trials ``paths``
    (:func:`softpad.planning.learn_catalogue`).

    Parameters
    ----------
    paths
        Recordings (.mcap) of trials of one object each.
    params
        The :class:`~softpad.planning.CatalogueParams` (None: the defaults).
    """
    from softpad.planning import learn_catalogue

    learned = [learned_trial(_trial_events(path)) for path in paths]
    pairs = [x for x in learned if x is not None]
    if not pairs:
        raise InputError("no recording holds a plan of one object and its outcome")
    trials = tuple(t for t, _ in pairs)
    variance = statistics.median(v for _, v in pairs)
    if not variance > 0:
        raise InputError("the recordings carry no sensor noise (pressure_variance_pa2)")
    catalogue = learn_catalogue(trials, variance, params)
    return Learned(catalogue, trials, len(learned) - len(pairs), variance)


__all__ = ["Learned", "learn_from_recordings", "learned_trial"]
