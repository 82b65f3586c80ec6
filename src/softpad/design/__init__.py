"""Design a SoftPad for an object set: sweep the pad's variables on FEM plus simulated trials.

A :class:`PadDesign` is a grid R x C at a module pitch, a layer thickness, a material preset
and an inflating pressure p0; :class:`DesignSpace` spans ranges of them. For every design
:func:`design_sweep` computes the module's finite-element response at p0 (height, sealed-chamber
sensitivity and its map, minimum detectable mass at t_o; :func:`fem_response`) and runs the
object set's grasp trials on the simulated box with that response (:func:`run_design_trials`),
as tasks on a Dask ``distributed`` cluster (a local one on 127.0.0.1 by default), each result
cached on disk by a hash of its inputs and the code version. The ranked :class:`SweepResult`
writes a table (text, CSV, Parquet), a Pareto plot and a short report; the thesis's pad
(:data:`THESIS_DESIGN`) is always the baseline row.

Dask, pyarrow, FElupe and matplotlib are imported lazily inside the functions.
"""

from softpad.design._cache import ResultCache, code_version, default_cache_dir
from softpad.design._dask import available_cpus, check_scheduler_address, dask_client, has_dask
from softpad.design._density import (
    DENSITY_PADS,
    DENSITY_PAIRS,
    DensityStudy,
    density_study,
    pad_convergence,
)
from softpad.design._evaluate import VALVE_CHOICES, TrialOptions, run_design_trials
from softpad.design._inputs import (
    MAX_DESIGNS,
    cache_folder,
    cached_line,
    choose_object_set,
    designs_from_text,
    sweep_trial_options,
    trial_objects,
    write_sweep,
)
from softpad.design._objects import (
    EXAMPLE_SETS,
    OBJECT_SET_SCHEMA,
    ObjectSet,
    SetObject,
    example_object_set,
    footprint_centre_m,
    load_object_set,
    object_set_from_dict,
)
from softpad.design._response import FemResponse, fem_response
from softpad.design._results import COLUMNS, DesignRow, SweepResult, design_row, rank_rows
from softpad.design._space import (
    LIMITS,
    QUICK_DESIGNS,
    THESIS_DESIGN,
    DesignSpace,
    PadDesign,
    parse_grids,
    parse_values,
    stable_hash,
)
from softpad.design._sweep import FEM_CELLS, SweepRaw, design_sweep, run_sweep
from softpad.design._trials import run_experiment_on_dask

__all__ = [
    "COLUMNS",
    "DENSITY_PADS",
    "DENSITY_PAIRS",
    "EXAMPLE_SETS",
    "FEM_CELLS",
    "LIMITS",
    "MAX_DESIGNS",
    "OBJECT_SET_SCHEMA",
    "QUICK_DESIGNS",
    "THESIS_DESIGN",
    "VALVE_CHOICES",
    "DensityStudy",
    "DesignRow",
    "DesignSpace",
    "FemResponse",
    "ObjectSet",
    "PadDesign",
    "ResultCache",
    "SetObject",
    "SweepRaw",
    "SweepResult",
    "TrialOptions",
    "available_cpus",
    "cache_folder",
    "cached_line",
    "check_scheduler_address",
    "choose_object_set",
    "code_version",
    "dask_client",
    "default_cache_dir",
    "density_study",
    "design_row",
    "design_sweep",
    "designs_from_text",
    "example_object_set",
    "fem_response",
    "footprint_centre_m",
    "has_dask",
    "load_object_set",
    "object_set_from_dict",
    "pad_convergence",
    "parse_grids",
    "parse_values",
    "rank_rows",
    "run_design_trials",
    "run_experiment_on_dask",
    "run_sweep",
    "stable_hash",
    "sweep_trial_options",
    "trial_objects",
    "write_sweep",
]
