"""Finite-element design model of a SoftPad module on FElupe (thesis chapter 7, Section 6.1.2).

The upper silicone layer of one module (default 45 x 45 x 1.5 mm, EcoFlex 00-30) is modelled
as a nearly incompressible hyperelastic block with fixed lateral faces and a follower
pressure on its lower face; a quarter model uses both symmetry planes. On top of the model:
material presets of thesis Table 7.1, inflation / design / stiffness / sensitive-area /
sealed-chamber studies, parameter fitting to measured (pressure, height) pairs, and the
module characteristic (volume and height against pressure and load) and the module response
(chamber squeeze per newton at every point of the top face) used by ``softpad.sim``.

FElupe, tensortrax, scipy and matplotlib are imported lazily inside the functions.
"""

from softpad.fem._cast import (
    DEFAULT_CAST_MESH,
    DEFAULT_WALL_WIDTH_M,
    CastPadGeometry,
    CastPadModel,
    cast_convergence,
    cast_pad_response,
    cast_sensitivities,
    sealed_rises_pa,
)
from softpad.fem._cast_table import (
    CAST_RESPONSE_VERSION,
    PACKAGED_CAST_RESPONSE,
    CastPadResponse,
)
from softpad.fem._chamber import (
    ATMOSPHERIC_PRESSURE_PA,
    DEFAULT_DEAD_VOLUME_M3,
    ChamberResult,
    sealed_chamber_study,
)
from softpad.fem._characteristic import (
    CHARACTERISTIC_PATH,
    ModuleCharacteristic,
    load_characteristic,
    module_characteristic,
)
from softpad.fem._fitting import (
    ComparisonResult,
    FitResult,
    compare_models,
    fit_material,
    read_measurements,
)
from softpad.fem._geometry import (
    DEFAULT_MESH,
    DEFAULT_THICKNESS_M,
    DEFAULT_WIDTH_M,
    LoadPatch,
    MeshOptions,
    ModuleGeometry,
)
from softpad.fem._inputs import (
    MASS_RANGE_KG,
    MIN_FOOTPRINT_M,
    THICKNESS_RANGE_M,
    WIDTH_RANGE_M,
    check_design_values,
    check_masses,
    check_study_pressures,
    detection_threshold_pa,
    parse_footprint,
)
from softpad.fem._materials import (
    BULK_TO_SHEAR,
    MATERIAL_PRESETS,
    MODEL_NAMES,
    MaterialModel,
    get_material,
)
from softpad.fem._model import (
    ConvergenceError,
    ModuleModel,
    ModuleSetup,
    ModuleState,
    ProgressCallback,
    SolverOptions,
)
from softpad.fem._response import (
    DEFAULT_RESPONSE_PRESSURES_PA,
    module_response,
    response_convergence,
)
from softpad.fem._response_table import (
    PACKAGED_RESPONSE,
    PRESSURE_STEP_PA,
    RESPONSE_STEP_M,
    RESPONSE_VERSION,
    ModuleResponse,
    rect_points,
)
from softpad.fem._results import save_figure, write_csv
from softpad.fem._runs import (
    StudyFiles,
    StudyModule,
    StudyReport,
    run_cast_response,
    run_chamber,
    run_characteristic,
    run_compare,
    run_design,
    run_fit,
    run_response,
    run_sensitivity,
    run_stiffness,
    run_sweep,
)
from softpad.fem._studies import (
    DesignResult,
    InflationResult,
    SensitivityResult,
    StiffnessResult,
    design_sweep,
    inflation_sweep,
    sensitive_area_study,
    stiffness_study,
)
from softpad.fem._verification import plate_center_deflection_m

__all__ = [
    "ATMOSPHERIC_PRESSURE_PA",
    "BULK_TO_SHEAR",
    "CAST_RESPONSE_VERSION",
    "CHARACTERISTIC_PATH",
    "DEFAULT_CAST_MESH",
    "DEFAULT_DEAD_VOLUME_M3",
    "DEFAULT_MESH",
    "DEFAULT_RESPONSE_PRESSURES_PA",
    "DEFAULT_THICKNESS_M",
    "DEFAULT_WALL_WIDTH_M",
    "DEFAULT_WIDTH_M",
    "MASS_RANGE_KG",
    "MATERIAL_PRESETS",
    "MIN_FOOTPRINT_M",
    "MODEL_NAMES",
    "PACKAGED_CAST_RESPONSE",
    "PACKAGED_RESPONSE",
    "PRESSURE_STEP_PA",
    "RESPONSE_STEP_M",
    "RESPONSE_VERSION",
    "THICKNESS_RANGE_M",
    "WIDTH_RANGE_M",
    "CastPadGeometry",
    "CastPadModel",
    "CastPadResponse",
    "ChamberResult",
    "ComparisonResult",
    "ConvergenceError",
    "DesignResult",
    "FitResult",
    "InflationResult",
    "LoadPatch",
    "MaterialModel",
    "MeshOptions",
    "ModuleCharacteristic",
    "ModuleGeometry",
    "ModuleModel",
    "ModuleResponse",
    "ModuleSetup",
    "ModuleState",
    "ProgressCallback",
    "SensitivityResult",
    "SolverOptions",
    "StiffnessResult",
    "StudyFiles",
    "StudyModule",
    "StudyReport",
    "cast_convergence",
    "cast_pad_response",
    "cast_sensitivities",
    "check_design_values",
    "check_masses",
    "check_study_pressures",
    "compare_models",
    "design_sweep",
    "detection_threshold_pa",
    "fit_material",
    "get_material",
    "inflation_sweep",
    "load_characteristic",
    "module_characteristic",
    "module_response",
    "parse_footprint",
    "plate_center_deflection_m",
    "read_measurements",
    "rect_points",
    "response_convergence",
    "run_cast_response",
    "run_chamber",
    "run_characteristic",
    "run_compare",
    "run_design",
    "run_fit",
    "run_response",
    "run_sensitivity",
    "run_stiffness",
    "run_sweep",
    "save_figure",
    "sealed_chamber_study",
    "sealed_rises_pa",
    "sensitive_area_study",
    "stiffness_study",
    "write_csv",
]
