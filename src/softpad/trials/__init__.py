"""Grasp trials: the thesis's Experiment 2 (Table 6.1) in rigid-body physics.

A sub-package of its own because a trial drives every layer below it (the MuJoCo world in
``softpad.sim``, the simulated box and robot of ``softpad.harness``, the execution of
``softpad.control``) and so sits above them.
"""

from softpad.trials._calibrate import (
    CalibrationLoad,
    CalibrationResult,
    calibrate,
    protocol_loads,
    record_calibration,
    simulated_session,
)
from softpad.trials._compare import (
    DEFAULT_PAIRS,
    IDLE_BOX,
    compare,
    idle_false_alarms_per_hour,
    merge_comparisons,
    read_comparisons,
    wilson_interval,
)
from softpad.trials._compare_report import comparison_table, parse_pairs, plot_comparison
from softpad.trials._config import (
    TrialConfig,
    check_campaign,
    check_counts,
    check_mounting_choice,
    drawn_placement,
    trial_errors_text,
    trial_execution_params,
)
from softpad.trials._object_fit import ObjectFit, fit_object_unknowns, object_fits_table
from softpad.trials._quoted import (
    RESULTS,
    ResultSpec,
    RunCommand,
    commit_text,
    rerun_results,
    result_argv,
)
from softpad.trials._recordings import check_trial_recordings
from softpad.trials._records import (
    FAILURE_CAUSES,
    THESIS_OVERALL_SUCCESS,
    THESIS_TABLE_6_1,
    ExperimentResult,
    ObjectSummary,
    TrialResult,
    errored_records,
)
from softpad.trials._reference_plans import write_reference_plans
from softpad.trials._report import write_report
from softpad.trials._runner import (
    errored_trial,
    perturbed_placement,
    run_experiment,
    run_experiments,
    run_trial,
    trial_recording_path,
    trial_seed,
)
from softpad.trials._survey import pad_reading, read_increments
from softpad.trials._validate import Observation, ValidationResult, validate

__all__ = [
    "DEFAULT_PAIRS",
    "FAILURE_CAUSES",
    "IDLE_BOX",
    "RESULTS",
    "THESIS_OVERALL_SUCCESS",
    "THESIS_TABLE_6_1",
    "CalibrationLoad",
    "CalibrationResult",
    "ExperimentResult",
    "ObjectFit",
    "ObjectSummary",
    "Observation",
    "ResultSpec",
    "RunCommand",
    "TrialConfig",
    "TrialResult",
    "ValidationResult",
    "calibrate",
    "check_campaign",
    "check_counts",
    "check_mounting_choice",
    "check_trial_recordings",
    "commit_text",
    "compare",
    "comparison_table",
    "drawn_placement",
    "errored_records",
    "errored_trial",
    "fit_object_unknowns",
    "idle_false_alarms_per_hour",
    "merge_comparisons",
    "object_fits_table",
    "pad_reading",
    "parse_pairs",
    "perturbed_placement",
    "plot_comparison",
    "protocol_loads",
    "read_comparisons",
    "read_increments",
    "record_calibration",
    "rerun_results",
    "result_argv",
    "run_experiment",
    "run_experiments",
    "run_trial",
    "simulated_session",
    "trial_errors_text",
    "trial_execution_params",
    "trial_recording_path",
    "trial_seed",
    "validate",
    "wilson_interval",
    "write_reference_plans",
    "write_report",
]
