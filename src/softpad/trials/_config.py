"""Parameters of a simulated grasp trial."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar

from softpad.control import ExecutionParams, InflationParams
from softpad.errors import MM_AS_M, InputError, check_range

if TYPE_CHECKING:
    from _typeshed import DataclassInstance


@dataclass(frozen=True)
class TrialConfig:
    """Parameters of a trial: the loop's :class:`~softpad.control.ExecutionParams` and what
    the simulated lab adds (placement noise, box settings).
    """

    #: The loop's parameters (:func:`trial_execution_params` by default: the thesis's, with the
    #: trial's travel motions and a fault limit near the sensor's full scale).
    execution: ExecutionParams = field(default_factory=lambda: trial_execution_params())
    #: Standard deviation of the random shift of the object's placement in x and y, metres:
    #: 3 mm. The thesis says the objects were placed by hand, "randomly ... similarly to
    #: Fig. 6.10" (Section 6.3), and gives no spread; 3 mm is about what placing an object by
    #: eye on a marked spot achieves, a tenth of a Duplo brick's width. With 3 mm and 3 deg,
    #: 95 % of placements lie within 7 mm and 6 deg of the nominal one.
    position_sigma_m: float = 3e-3
    #: Standard deviation of the random rotation of the placement, radians (3 degrees: an
    #: object laid along a module edge by eye).
    yaw_sigma_rad: float = math.radians(3.0)
    #: Start with the modules already near p0 (as between trials of a session) instead of
    #: deflated; the adjustment to p0 within t_adj and the reference capture always run.
    inflated_start: bool = True
    #: Box sample rate, hertz.
    sample_rate_hz: float = 100.0
    #: Sensor noise on (the box's defaults, like Fig. 6.8) or off.
    noise: bool = True
    #: Keep every frame and event in a :class:`softpad.record.RunLog`.
    record_trace: bool = False
    #: Record the trial as MCAP into this file (:class:`softpad.record.McapRecorder`;
    #: overwritten: the caller checks it first, see :func:`softpad.trials.trial_recording_path`).
    record_path: str | None = None
    #: Planner by name (:func:`softpad.planning.available_planners`), given the trial's gripper.
    planner: str = "thesis"
    #: Contact detector by name (:func:`softpad.sensing.available_contact_detectors`).
    detector: str = "thesis"
    #: Catalogue of known objects (``softpad learn``) for the ``catalogue`` planner; None: no
    #: object is known (every one goes to its model-based fallback).
    catalogue: str | None = None
    #: Draw every uncertain input of the simulated lab (:data:`softpad.sim.UNCERTAIN_PARAMETERS`:
    #: pad and fingertip physics, grip force, seam, sample rate, sensor noise, tubing,
    #: placement noise, the charger's size and the can's mass distribution) from its range,
    #: per trial, seeded by the trial's seed; False: every one at its nominal value.
    randomize: bool = False
    #: Let the MuJoCo world coast through the hold once everything in it moves at steady
    #: velocities (the object settled in the jaws or on the pad): positions advance without
    #: solving contacts, re-checked with real steps every 0.5 s, the hold's last second always
    #: stepped (:mod:`softpad.sim._mujoco_coast`; docs/trials.md). False: every step of the
    #: hold solved (the reference the equivalence tests compare with).
    coast_settled_hold: bool = True
    #: Hold the MuJoCo world still through the valve check that ends a trial
    #: (:meth:`softpad.sim.MujocoWorld.rest_while_still`): the grasp has been scored by then
    #: and nothing the result holds is read from the world after it; the box's valves, gas and
    #: sensors and the fault monitor run on the object's last loads (a check's fault can only
    #: end the trial's simulated time earlier). False: every step solved.
    still_valve_check: bool = True
    #: Let the MuJoCo world coast also through the approach and the descent while the hand
    #: moves through free air (:meth:`softpad.sim.MujocoWorld.coast_free_hand`): the object has
    #: settled on the pad, the hand's geoms stay more than 3 mm from every other geom, so no
    #: contact is made or broken; re-checked with real steps every 0.5 s as in the hold. It
    #: changes results within a stated tolerance, not bit for bit (docs/trials.md). False:
    #: every step of those phases solved.
    coast_free_hand: bool = True
    #: MuJoCo's time step, seconds (2 ms: every campaign before issue 50's fourth round). The
    #: contacts' time constant is twice the step (:func:`softpad.sim.build_mjcf`), so a
    #: coarser step also softens every contact; docs/benchmarks.md gives the tolerance it
    #: was measured against.
    mujoco_timestep_s: float = 2e-3
    #: The gripper's mounting: None, each object's own (the thesis's per-object choice,
    #: Section 6.3, for Table 6.1); ``"auto"``, chosen from the pad's reading of the placed
    #: object among every installed mounting (:func:`softpad.planning.choose_mounting`; issue
    #: 45: no width oracle on held-out objects); or one of ``"10/4"``, ``"6/2"``, ``"4/0"``
    #: for every object.
    mounting: str | None = None

    def __post_init__(self) -> None:
        for name in ("position_sigma_m", "yaw_sigma_rad", "sample_rate_hz"):
            v = getattr(self, name)
            if not isinstance(v, int | float) or not math.isfinite(v) or v < 0:
                raise InputError(f"trial parameter {name} must be a finite number >= 0, got {v!r}")
        # a placement spread beyond a module pitch is a unit mix-up, not a hand placement
        check_range("trial position_sigma_m", self.position_sigma_m, 0.0, 0.05, "m", MM_AS_M)
        check_range(
            "trial yaw_sigma_rad",
            self.yaw_sigma_rad,
            0.0,
            math.pi,
            "rad",
            "degrees given as radians?",
        )
        from softpad.planning import PLANNER_REGISTRY
        from softpad.sensing import CONTACT_DETECTOR_REGISTRY

        PLANNER_REGISTRY.factory(self.planner)  # InputError naming the known ones
        CONTACT_DETECTOR_REGISTRY.factory(self.detector)
        if self.sample_rate_hz <= 0:
            raise InputError("trial sample_rate_hz must be > 0 Hz")
        check_range("trial mujoco_timestep_s", self.mujoco_timestep_s, 5e-4, 5e-3, "s")
        check_mounting_choice(self.mounting, "trial mounting")


def check_counts(trials: int, workers: int | None) -> None:
    """Refuse a trial count outside 1..1000 or a worker count outside 1..256.

    Parameters
    ----------
    trials
        Trials per object (``--trials``).
    workers
        Worker processes (``--workers``), or None (all CPUs).
    """
    if not 1 <= trials <= 1000:
        raise InputError(f"--trials must be from 1 to 1000, got {trials}")
    if workers is not None and not 1 <= workers <= 256:
        raise InputError(f"--workers must be from 1 to 256, got {workers}")


def check_campaign(
    seeds: Sequence[int], seeds_text: str, hold_s: float, record: str | None = None
) -> None:
    """Refuse a trial campaign of more than 100 seeds, a hold outside 0..600 s, or
    recordings (named by object and trial) over several seeds.

    Parameters
    ----------
    seeds
        The experiment seeds.
    seeds_text
        How they were given (``--seeds``), for the message.
    hold_s
        Hold time after the lift, s.
    record
        The recordings' base name, or None.
    """
    if len(seeds) > 100:
        raise InputError(f"--seeds {seeds_text!r} names {len(seeds)} seeds; at most 100")
    if not math.isfinite(hold_s) or not 0 <= hold_s <= 600:
        raise InputError(f"--hold-s must be from 0 to 600 s, got {hold_s!r}")
    if record and len(seeds) > 1:
        raise InputError(
            "--record takes one seed at a time (trial files are named by object and trial)"
        )


def trial_errors_text(errored: list[dict[str, Any]], prog: str) -> str | None:
    """The message of a command whose trials raised, naming them (None when none did).

    Parameters
    ----------
    errored
        The raising trials' ``to_dict()`` records (cause ``trial_error``, the traceback in
        ``detail``).
    prog
        The command, for the message (``trials``, ``demo``).
    """
    if not errored:
        return None
    named = ", ".join(f"{t['object']} trial {t['trial']} (seed {t['seed']})" for t in errored[:5])
    more = f" and {len(errored) - 5} more" if len(errored) > 5 else ""
    last = (errored[0].get("detail") or "").strip().splitlines()[-1:] or [""]
    return (
        f"softpad {prog}: error: {len(errored)} trial(s) raised and count as failed: {named}"
        f"{more}; first: {last[0]}. This is a bug; the tracebacks are in the trials' 'detail' "
        "(--json)"
    )


def check_mounting_choice(mounting: str | None, what: str) -> None:
    """InputError unless ``mounting`` is None, ``"auto"`` or a thesis mounting."""
    from softpad import thesis

    if mounting is not None and mounting != "auto" and mounting not in thesis.GRIPPER_MOUNTINGS_M:
        raise InputError(
            f"{what} must be 'auto' or one of {', '.join(thesis.GRIPPER_MOUNTINGS_M)}, "
            f"got {mounting!r}"
        )


def trial_execution_params(**changes: Any) -> ExecutionParams:
    """The loop's parameters in a trial: the thesis's, with these simulated-lab choices.

    Travel speed 0.2 m/s, lift 0.10 m, settle 1.5 s (the thesis gives none of them); a fault
    limit of 9.5 kPa instead of the 3 kPa inflation maximum, because a gripper pressing an
    object into the pad legitimately reads above it (the sensor's full scale is 10 kPa).
    ``changes`` override any field (e.g. ``hold_s=1.0``).
    """
    base: dict[str, Any] = dict(
        inflation=InflationParams(max_pressure_pa=9.5e3),
        travel_speed_m_s=0.2,
        lift_m=0.10,
        object_settle_s=1.5,
    )
    base.update(changes)
    return ExecutionParams(**base)


_Options = TypeVar("_Options", bound="DataclassInstance")


def drawn_placement(options: _Options, seed: int) -> tuple[_Options, Any]:
    """``options`` (a dataclass with ``position_sigma_m``, ``yaw_sigma_rad`` and
    ``sample_rate_hz``, such as :class:`TrialConfig`) with the placement noise and sample rate
    of the :class:`softpad.sim.LabVariation` drawn from ``seed``, and that variation."""
    from dataclasses import replace

    from softpad.sim import LabVariation, draw_uncertain

    lab = LabVariation.of(draw_uncertain(seed))
    v = lab.values
    options = replace(
        options,
        position_sigma_m=v["placement_sigma_m"],
        yaw_sigma_rad=v["placement_yaw_sigma_rad"],
        sample_rate_hz=v["sample_rate_hz"],
    )
    return options, lab
