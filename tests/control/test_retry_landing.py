"""A retried grasp whose jaws land on the object again (issue 47's box faults after retries)."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.design import trial_objects
from softpad.trials import TrialConfig, run_trial, trial_seed
from softpad.trials._config import trial_execution_params


@pytest.mark.slow
def test_a_retry_that_lands_on_the_apple_again_goes_up_without_closing() -> None:
    """A development trial (ycb-dev, seed 1000, model-based planner, adaptive detector,
    randomized): a jaw lands on the lying apple (sensed 51 mm above the pad base), the planner
    retries, and the retry lands on it again (46 mm). With no attempt left the loop used to
    close there anyway: the closing jaw wedged the apple into the pad and modules 1 and 2 read
    the sensor's 10 kPa full scale within 60 ms (a box fault in phase ``close``). Now the
    planner's word that a jaw is on the object stands on the last attempt too: the loop goes
    up without closing, the pad never leaves the range of a grasp's descent (under 3 kPa,
    the inflation maximum) and the trial fails as a jaw landing, not a fault."""
    (spec,) = trial_objects(["ycb-013-apple"], "src/softpad/data/object_sets/ycb-dev.toml")
    config = TrialConfig(
        trial_execution_params(hold_s=1.0),
        planner="model-based",
        detector="adaptive",
        randomize=True,
        record_trace=True,
    )
    result, log = run_trial(spec, 0, trial_seed(1000, spec.name, 0), config)
    assert result.cause == "jaws_hit_object", result.detail
    assert result.attempts == 2
    contacts = [d["z_m"] for _, d in log.events_of("contact")]
    assert len(contacts) == 2 and min(contacts) > config.execution.landing_height_m
    phases = [d["phase"] for _, d in log.events_of("phase")]
    assert "close" not in phases and phases[-1] == "done"
    assert [d["outcome"] for _, d in log.events_of("outcome")] == ["landed"]
    assert log.events_of("fault") == []
    peak = float(np.nanmax(log.pressures_pa))
    assert peak < 3e3
