"""Write loaded_traces.npz: the descents of two MuJoCo grasp trials with a rocking object.

Object 6 (122 g, 58 mm tall) rocks modules 4-6 at about 4 Hz while the fingers come down
(seeds the adaptive CUSUM was checked on, not the compared 0-19): experiment seed 102,
trial index 2 at 100 Hz, and seed 101, trial index 0 at 1 kHz; gripper-aware planner, the thesis's
detector (the slowest: the trace runs on after the first touch). Per trace ``rate`` (Hz):
``t_s``, ``pressures_pa`` (frames of the descent, modules 1-6), ``reference_pa`` (the
detector's reference), ``touch_s`` (ground truth: the first fingertip touch, for scoring).

    python tests/data/make_loaded_traces.py
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from softpad.sim import get_object
from softpad.trials import TrialConfig, run_trial, trial_seed

TRACES = ((100.0, 102, 2), (1000.0, 101, 0))  # (rate, experiment seed, trial index)


def descent(rate: float, seed: int, k: int) -> dict[str, np.ndarray]:
    config = replace(
        TrialConfig(),
        detector="thesis",
        planner="gripper-aware",
        record_trace=True,
        sample_rate_hz=rate,
    )
    result, log = run_trial(get_object("object-6"), k, trial_seed(seed, "object-6", k), config)
    t, p = log.t_s, log.pressures_pa[:, :6]
    phases = np.array(log.phases)
    desc = np.flatnonzero(phases == "descend")
    ((t_contact, _),) = log.events_of("contact")
    return {
        "t_s": t[desc],
        "pressures_pa": p[desc].astype(np.float32),
        "reference_pa": p[desc[0] - 10 : desc[0]].mean(axis=0),
        "touch_s": np.float64(t_contact - result.contact_delay_s),
    }


def main() -> None:
    out = {}
    for rate, seed, k in TRACES:
        for key, value in descent(rate, seed, k).items():
            out[f"{int(rate)}hz_{key}"] = value
    np.savez_compressed(Path(__file__).with_name("loaded_traces.npz"), **out)


if __name__ == "__main__":
    main()
