"""The pad read once with an object on it: what a lab sees before it grasps.

:func:`pad_reading` puts an object down on the analytic world behind a noisy simulated box at
p0 and reads the modules' increments as the controller reads them (mean of 10 reads after a
second, minus the reference). ``softpad validate``'s static rows plan from it, and
``--mounting auto`` chooses the gripper's mounting from it before a trial
(:func:`surveyed_mounting`): the readings only, never the object's true size.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.trials._config import TrialConfig


def static_lab(seed: int, config: TrialConfig, lab: Any | None) -> tuple[Any, Any]:
    """The analytic world and the box of one reading (nominal, or ``lab``'s values)."""
    from softpad.box import SimBox
    from softpad.sim import AnalyticWorld

    if lab is None:
        world = AnalyticWorld()
        return world, SimBox(world, seed=seed % 2**31, initial_pressure_pa=thesis.P0_PA)
    world = AnalyticWorld(response=lab.pad_response())
    box = SimBox(
        world,
        sample_rate_hz=config.sample_rate_hz,
        seed=seed % 2**31,
        sensor=lab.sensor(),
        pneumatics=lab.pneumatics(),
        initial_pressure_pa=thesis.P0_PA,
    )
    return world, box


def pad_reading(
    obj: Any, placement: tuple[float, float, float], seed: int, config: TrialConfig, lab: Any | None
) -> NDArray[np.float64]:
    """Increment of every module, pascals, with ``obj`` put down at ``placement``.

    The box is sealed at p0 (1 s to settle), the reference is the mean of 10 reads, the
    increments the mean of 10 reads 1 s after the object is put down.
    """
    world, box = static_lab(seed, config, lab)
    return read_increments(world, box, obj, placement)


def read_increments(
    world: Any, box: Any, obj: Any, placement: tuple[float, float, float]
) -> NDArray[np.float64]:
    """:func:`pad_reading` on a given world and box (the box at its start pressure)."""
    from softpad.sim import Placement

    n = world.layout.n_modules
    box.read_many(int(box.sample_rate_hz))
    reads = thesis.REFERENCE_READS
    ref = np.mean([f.pressures_pa[:n] for f in box.read_many(reads)], axis=0)
    world.place_object(obj, Placement(*placement))
    box.read_many(int(box.sample_rate_hz))
    return np.asarray(
        np.mean([f.pressures_pa[:n] for f in box.read_many(reads)], axis=0) - ref, dtype=float
    )


def surveyed_mounting(
    obj: Any, placement: tuple[float, float, float], seed: int, config: TrialConfig, lab: Any | None
) -> str:
    """The mounting ``--mounting auto`` installs for a trial: chosen from the pad's reading of
    the placed object (:func:`softpad.planning.choose_mounting`, every mounting installed);
    a planner that predicts its grasps' success (the model-based planner) decides it: the
    mounting under which its grasp is the most likely to hold."""
    from softpad.planning import choose_mounting

    reading = pad_reading(obj, placement, seed, config, lab)
    return choose_mounting(reading, planner=trial_planner(config))


def trial_planner(config: TrialConfig) -> Any:
    """The trial's planner as the loop makes it (its detector's sensing ratio at the
    configured sample rate), with the thesis's 10/4 gripper until the mounting is chosen."""
    from softpad.layout import PadLayout
    from softpad.planning import planner_for
    from softpad.sensing import make_contact_detector

    layout, rate = PadLayout(), config.sample_rate_hz
    detector = make_contact_detector(config.detector, rate, layout)
    return planner_for(
        config.planner, None, config.execution.planner, detector, rate, layout, config.catalogue
    )
