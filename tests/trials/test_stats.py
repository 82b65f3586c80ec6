"""The Wilson interval of a success rate, written out, against scipy's (issue 50)."""

from __future__ import annotations

import subprocess
import sys

from scipy.stats import binomtest

from softpad.trials import wilson_interval
from softpad.trials._plots import wilson_interval as plotted_interval


def test_wilson_interval_is_scipys_to_the_last_bit() -> None:
    """Every count of 1-40 trials and of the campaigns' 55, 110 and 550: the same bits as
    scipy's binomtest interval, rounded."""
    for n in [*range(1, 41), 55, 110, 550]:
        for k in range(n + 1):
            ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
            assert wilson_interval(k, n) == (round(float(ci.low), 4), round(float(ci.high), 4))
            assert plotted_interval(k, n) == (float(ci.low), float(ci.high))
    assert wilson_interval(0, 0) == (0.0, 1.0)


def test_a_trial_table_imports_no_scipy_stats() -> None:
    """Printing an experiment's table (every object's interval) loads no scipy.stats: about a
    second of CPU in every process that prints one (the demo, the CLI's trial commands)."""
    code = (
        "import sys; from softpad.trials import ExperimentResult, TrialResult;"
        "t = [TrialResult(object='banana', trial=k, seed=k, placement=(0.0, 0.0, 0.0),"
        " mounting='10/4', success=k > 0, cause=None if k else 'jaws_hit_object')"
        " for k in range(5)];"
        "e = ExperimentResult(trials=tuple(t), seed=0, masses_g={'banana': 59.8});"
        "print(e.to_text()); print('scipy.stats' in sys.modules)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert "80" in out  # 4 of 5 held
    assert out.strip().splitlines()[-1] == "False", out
