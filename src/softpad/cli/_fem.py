"""``softpad fem ...``: finite-element design studies of one module (thesis chapter 7)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from softpad import thesis
from softpad.cli._args import (
    add_command,
    add_group,
    add_integer,
    add_number,
    number_list,
)
from softpad.cli._output import emit
from softpad.cli._paths import atomic_path, check_output
from softpad.errors import InputError

_MODELS = ("neo-hookean", "mooney-rivlin", "ogden-1", "ogden-2", "varga", "yeoh")

_EPILOG = """examples:
  softpad fem sweep --model yeoh --json
  softpad fem sweep --model neo-hookean --thickness-mm 2 --csv h.csv --png h.png --vtu module.vtu
  softpad fem design --parameter thickness --values-mm 1,1.5,2,2.5,3
  softpad fem stiffness --forces-n 0.2,0.5,0.8 --radius-mm 10
  softpad fem sensitivity --pressures-kpa 0.5,1.1,2,2.8
  softpad fem chamber --pressure-kpa 1.1 --footprint-mm 42x31 --masses-g 6,12.6,50
  softpad fem fit --data measurements.csv --model yeoh
  softpad fem compare --data measurements.csv
  softpad fem characteristic --out module_characteristic.npz

models: neo-hookean, mooney-rivlin, ogden-1, ogden-2, varga, yeoh (thesis Table 7.1).
measurement CSV: header pressure_kpa,height_mm; one row per measured point.
"""


def _model_name(text: str) -> str:
    name = str(text).strip().lower()
    if name not in _MODELS:
        raise argparse.ArgumentTypeError(
            f"unknown model {text!r}; choose from {', '.join(_MODELS)}"
        )
    return name


_DESCRIPTION = """\
Finite-element model of one SoftPad module: the upper silicone layer (quarter model, lateral
faces fixed, follower pressure on the lower face, nearly incompressible hyperelastic material
of thesis Table 7.1)."""

_PRESSURES_KPA = "0.5,0.96,1.42,1.88,2.34,2.8"
#: The options' limits of the module's layer thickness and width and of a mass, in their
#: units: :mod:`softpad.fem`'s ranges (THICKNESS_RANGE_M, ...; a test keeps them alike), not
#: imported here so that building the parser loads no FEM.
THICKNESS_RANGE_MM = (0.1, 20.0)
WIDTH_RANGE_MM = (5.0, 500.0)
MASS_RANGE_G = (0.1, 10_000.0)


def _add_study(fem_sub: Any, name: str, help: str, model: bool = True) -> argparse.ArgumentParser:
    """A study's parser with the options every study has (``--model``/``--param`` unless not
    ``model``, geometry, mesh, outputs, progress)."""
    p = add_command(fem_sub, name, help, force=True)
    if model:
        p.add_argument(
            "--model",
            type=_model_name,
            default="neo-hookean",
            help="material preset (default neo-hookean): " + ", ".join(_MODELS),
        )
        p.add_argument(
            "--param",
            action="append",
            default=[],
            metavar="NAME=VALUE",
            help="override a preset parameter (moduli in Pa), e.g. --param mu=30000; repeatable",
        )
    add_number(
        p,
        "--thickness-mm",
        "upper-layer thickness in mm, 0.1..20 (default 1.5)",
        1.5,
        lo=THICKNESS_RANGE_MM[0],
        hi=THICKNESS_RANGE_MM[1],
        unit="mm",
    )
    add_number(
        p,
        "--width-mm",
        "module width in mm, 5..500 (default 45)",
        45.0,
        lo=WIDTH_RANGE_MM[0],
        hi=WIDTH_RANGE_MM[1],
        unit="mm",
    )
    p.add_argument(
        "--mesh",
        choices=("coarse", "default", "fine"),
        default="default",
        help="discretisation: coarse (6x6x1), default (12x12x2), fine (16x16x2) quarter cells",
    )
    p.add_argument("--csv", metavar="FILE.csv", help="write the results as CSV")
    p.add_argument("--png", metavar="FILE.png", help="write a plot as PNG")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    return p


def _add_pressure(p: argparse.ArgumentParser, help: str, default: float) -> None:
    """``--pressure-kpa``: one pressure of the study, 0..10 kPa."""
    add_number(p, "--pressure-kpa", help, default, lo=0.0, hi=10.0, unit="kPa")


def _add_object_threshold(p: argparse.ArgumentParser, help: str) -> None:
    """``--threshold-kpa``: the object-detection threshold t_o the sensitivity is judged by."""
    add_number(
        p, "--threshold-kpa", help, thesis.OBJECT_THRESHOLD_PA / 1e3, lo=0.0, hi=10.0, unit="kPa"
    )


def _table_study(fem_sub: Any, name: str, help: str, default: str, shipped: str) -> Any:
    """A study that writes a table (``--out FILE.npz``, default ``default``) of the kind
    shipped as ``softpad/data/<shipped>``."""
    p = _add_study(fem_sub, name, help)
    p.add_argument(
        "--out",
        metavar="FILE.npz",
        default=default,
        help=f"output file (default ./{default}); developers regenerate the shipped table with "
        f"--out src/softpad/data/{shipped} --force",
    )
    return p


def register(sub: Any) -> None:
    fem_sub = add_group(
        sub,
        "fem",
        "finite-element design studies of one module (FElupe)",
        _DESCRIPTION,
        _EPILOG,
        metavar="STUDY",
    )
    for add in (_sweep_study, _design_study, _stiffness_study, _sensitivity_study):
        add(fem_sub)
    for add in (_chamber_study, _fit_studies, _table_studies):
        add(fem_sub)
    from softpad.cli._fem_cast import register as register_cast

    register_cast(fem_sub)


def _sweep_study(fem_sub: Any) -> None:
    s = _add_study(fem_sub, "sweep", "centre height against pressure (Fig. 7.2b)")
    add_number(
        s,
        "--max-pressure-kpa",
        "highest pressure in kPa (default 3)",
        3.0,
        lo=0.0,
        hi=10.0,
        unit="kPa",
    )
    add_integer(s, "--points", "number of pressures, 2..200 (default 13)", 13, 2, 200)
    s.add_argument(
        "--vtu", metavar="FILE.vtu", help="write the deformed module at the last pressure"
    )
    s.set_defaults(handler=_sweep)


def _design_study(fem_sub: Any) -> None:
    d = _add_study(
        fem_sub, "design", "height at 1 kPa against thickness or width (Fig. 7.3)", model=False
    )
    d.add_argument("--parameter", choices=("thickness", "width"), default="thickness")
    d.add_argument(
        "--values-mm",
        metavar="V1,...",
        help="parameter values in mm (default thickness 1..3, width 35..55)",
    )
    d.add_argument(
        "--models",
        default="neo-hookean,yeoh",
        help="comma-separated presets (default neo-hookean,yeoh)",
    )
    _add_pressure(d, "inflating pressure in kPa (default 1)", 1.0)
    d.set_defaults(handler=_design)


def _stiffness_study(fem_sub: Any) -> None:
    k = _add_study(fem_sub, "stiffness", "equivalent stiffness under a central load (Fig. 6.3c)")
    k.add_argument("--pressures-kpa", default=_PRESSURES_KPA, help="pressures in kPa")
    k.add_argument("--forces-n", default="0.2,0.5,0.8", help="loads in N (default 0.2,0.5,0.8)")
    add_number(
        k,
        "--radius-mm",
        "radius of the loaded central disc in mm, >= 0.5 (default 10)",
        10.0,
        lo=0.5,
        unit="mm",
    )
    k.set_defaults(handler=_stiffness)


def _sensitivity_study(fem_sub: Any) -> None:
    a = _add_study(fem_sub, "sensitivity", "sensitive area against pressure (Section 6.1.2)")
    a.add_argument("--pressures-kpa", default=_PRESSURES_KPA, help="pressures in kPa")
    add_number(
        a,
        "--fraction",
        "response threshold relative to the centre (default 0.5)",
        0.5,
        lo=0.0,
        hi=1.0,
    )
    add_number(
        a,
        "--probe-g",
        "probe mass of the absolute (sealed-chamber) definition in g, 0.1..10000 (default 12.6)",
        12.6,
        lo=MASS_RANGE_G[0],
        hi=MASS_RANGE_G[1],
        unit="g",
    )
    _add_object_threshold(
        a, "detection threshold of the absolute definition in kPa (default %(default)g, t_o)"
    )
    a.set_defaults(handler=_sensitivity)


def _chamber_study(fem_sub: Any) -> None:
    c = _add_study(fem_sub, "chamber", "sealed chamber: pressure rise of a load, minimum mass")
    _add_pressure(c, "pressure when the valves close, kPa (default 1.1)", 1.1)
    c.add_argument(
        "--footprint-mm",
        default="42x31",
        help="object footprint WxH in mm, or a disc diameter as dD (default 42x31: Duplo brick)",
    )
    c.add_argument(
        "--masses-g", default="6,12.6,50,100", help="masses in g (default 6,12.6,50,100)"
    )
    add_number(
        c,
        "--dead-volume-ml",
        "dead volume in mL: tubing (1 m of 2 mm bore) plus the 0.2 mL gap under the flat "
        "layer, as in the simulator (default %(default)g)",
        round((thesis.TUBING_VOLUME_M3 + thesis.CHAMBER_GAP_VOLUME_M3) * 1e6, 4),
        lo=0.0,
        hi=1000.0,
        unit="mL",
    )
    _add_object_threshold(c, "detection threshold in kPa (default %(default)g, thesis t_o)")
    add_number(
        c,
        "--noise-kpa",
        "sensor noise (rms) in kPa, 0..1; if given the threshold is N_SIGMA times it",
        lo=0.0,
        hi=1.0,
        unit="kPa",
    )
    add_number(
        c,
        "--n-sigma",
        "threshold in noise rms units with --noise-kpa (default 3)",
        3.0,
        lo=0.0,
        hi=100.0,
    )
    c.set_defaults(handler=_chamber)


def _fit_studies(fem_sub: Any) -> None:
    data_help = "pressure_kpa,height_mm file"
    f = _add_study(fem_sub, "fit", "fit a model's parameters to measured heights")
    f.add_argument("--data", required=True, metavar="CSV", help=data_help)
    f.add_argument("--free", metavar="NAMES", help="parameters to fit (default: all moduli)")
    add_integer(f, "--max-evals", "budget of sweeps, 1..100000 (default 60)", 60, 1, 100_000)
    f.set_defaults(handler=_fit)
    m = _add_study(fem_sub, "compare", "rank the presets by RMSE on measured heights", model=False)
    m.add_argument("--data", required=True, metavar="CSV", help=data_help)
    m.add_argument("--models", default=",".join(_MODELS), help="presets to compare (default all)")
    m.set_defaults(handler=_compare)


def _table_studies(fem_sub: Any) -> None:
    t = _table_study(
        fem_sub,
        "characteristic",
        "tabulate volume and height against pressure and load (.npz)",
        "characteristic.npz",
        "module_characteristic.npz",
    )
    t.add_argument("--loads-n", help="loads in N starting at 0 (default 0..6 N, 18 values)")
    t.add_argument(
        "--pressures-kpa", help="pressures in kPa starting at 0 (default 0..5 every 0.1)"
    )
    add_number(
        t,
        "--gap-volume-ml",
        "residual air under the flat layer added to every volume, mL (default 0.2)",
        0.2,
        lo=0.0,
        unit="mL",
    )
    t.set_defaults(handler=_characteristic)
    r = _table_study(
        fem_sub,
        "response",
        "chamber response to a load at every point of the module, 0.5..2.8 kPa (.npz)",
        "module_response.npz",
        "module_response.npz",
    )
    r.add_argument(
        "--pressures-kpa", help="increasing pressures in kPa (default 0.5..2.8, 9 values)"
    )
    r.add_argument(
        "--no-convergence",
        action="store_true",
        help="skip the mesh-convergence check (a refined mesh at 1.1 kPa, about 10 s)",
    )
    r.set_defaults(handler=_response)


def _files(args: argparse.Namespace) -> Any:
    """Check every output file named on the command line before the study starts."""
    from softpad.fem import StudyFiles

    seen: dict[Any, str] = {}
    paths: dict[str, Any] = {}
    for flag, suffix in (("csv", ".csv"), ("png", ".png"), ("vtu", ".vtu"), ("out", ".npz")):
        if not hasattr(args, flag):
            continue
        path = check_output(getattr(args, flag), f"--{flag}", force=args.force, suffix=suffix)
        if path is not None and path.resolve() in seen:
            raise InputError(f"--{flag} and --{seen[path.resolve()]} name the same file {path}")
        if path is not None:
            seen[path.resolve()] = flag
        paths[flag] = path
    return StudyFiles(**paths, atomic=atomic_path)


def _models(text: str, flag: str = "--models") -> list[str]:
    from softpad.cli._args import name_list

    names = name_list(text, flag)
    for n in names:
        if n.lower() not in _MODELS:
            raise InputError(f"{flag}: unknown model {n!r}; choose from {', '.join(_MODELS)}")
    return [n.lower() for n in names]


@contextmanager
def _progress(args: argparse.Namespace, label: str) -> Iterator[Callable[[int, int], None] | None]:
    """A tqdm bar on stderr driven by the studies' ``progress(done, total)`` callback."""
    if args.no_progress or not sys.stderr.isatty():
        yield None
        return
    import shutil

    from tqdm import tqdm

    # some pseudo-terminals report a zero width, which would make tqdm print nothing
    columns = shutil.get_terminal_size((80, 20)).columns
    bar = tqdm(
        desc=label,
        unit="step",
        file=sys.stderr,
        leave=False,
        ncols=columns if columns > 20 else 80,
    )

    def update(done: int, total: int) -> None:
        bar.total = total
        bar.n = done
        bar.refresh()

    try:
        yield update
    finally:
        bar.close()


def _study(args: argparse.Namespace, files: Any, label: str, run: Any, *a: Any) -> int:
    """``run(module, *a, files, progress)`` (a :mod:`softpad.fem` ``run_*`` study) on the
    command's module with a progress bar named ``label``; print its report (``--json``: its
    dict)."""
    from softpad.fem import StudyModule

    model = getattr(args, "model", "neo-hookean")
    shape = (args.thickness_mm, args.width_mm, args.mesh)
    module = StudyModule(model, getattr(args, "param", ()), *shape)
    with _progress(args, label) as progress:
        report = run(module, *a, files, progress)
    if args.json:
        emit(report.data)
    else:
        print("\n".join(report.lines))
    return 0


# ---------------------------------------------------------------------------- handlers
def _sweep(args: argparse.Namespace) -> int:
    from softpad.fem import run_sweep

    files = _files(args)
    return _study(args, files, f"sweep {args.model}", run_sweep, args.max_pressure_kpa, args.points)


def _design(args: argparse.Namespace) -> int:
    from softpad.fem import run_design

    files = _files(args)
    defaults = {"thickness": "1,1.5,2,2.5,3", "width": "35,40,45,50,55"}
    text = args.values_mm or defaults[args.parameter]
    values = number_list(text, "--values-mm", 1e-3, positive=True)
    models = _models(args.models)
    design = (args.parameter, values, models, args.pressure_kpa)
    return _study(args, files, f"design {args.parameter}", run_design, *design)


def _stiffness(args: argparse.Namespace) -> int:
    from softpad.fem import run_stiffness

    files = _files(args)
    pressures = number_list(args.pressures_kpa, "--pressures-kpa", 1e3, positive=True)
    forces = number_list(args.forces_n, "--forces-n", positive=True)
    return _study(args, files, "stiffness", run_stiffness, pressures, forces, args.radius_mm)


def _sensitivity(args: argparse.Namespace) -> int:
    from softpad.fem import run_sensitivity

    files = _files(args)
    pressures = number_list(args.pressures_kpa, "--pressures-kpa", 1e3, positive=True)
    probe = (args.fraction, args.probe_g, args.threshold_kpa)
    return _study(args, files, "sensitivity", run_sensitivity, pressures, *probe)


def _chamber(args: argparse.Namespace) -> int:
    from softpad.fem import run_chamber

    files = _files(args)
    masses = number_list(args.masses_g, "--masses-g", 1e-3, positive=True)
    threshold = (args.threshold_kpa, args.noise_kpa, args.n_sigma)
    chamber = (args.pressure_kpa, masses, args.footprint_mm, args.dead_volume_ml, threshold)
    return _study(args, files, "chamber", run_chamber, *chamber)


def _fit(args: argparse.Namespace) -> int:
    from softpad.fem import run_fit

    files = _files(args)
    free = [s.strip() for s in args.free.split(",") if s.strip()] if args.free else None
    return _study(args, files, f"fit {args.model}", run_fit, args.data, free, args.max_evals)


def _compare(args: argparse.Namespace) -> int:
    from softpad.fem import run_compare

    files = _files(args)
    return _study(args, files, "compare", run_compare, args.data, _models(args.models))


def _characteristic(args: argparse.Namespace) -> int:
    from softpad.fem import run_characteristic

    files = _files(args)
    text = args.pressures_kpa
    pressures = number_list(text, "--pressures-kpa", 1e3) if text else None
    loads = number_list(args.loads_n, "--loads-n") if args.loads_n else None
    table = (pressures, loads, args.gap_volume_ml)
    return _study(args, files, "characteristic", run_characteristic, *table)


def _response(args: argparse.Namespace) -> int:
    from softpad.fem import run_response

    files = _files(args)
    text = args.pressures_kpa
    pressures = number_list(text, "--pressures-kpa", 1e3, positive=True) if text else None
    return _study(args, files, "response", run_response, pressures, not args.no_convergence)
