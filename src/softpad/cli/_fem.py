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


def _numbers(text: str, flag: str, scale: float = 1.0, positive: bool = False) -> list[float]:
    """Parse ``"1,1.5,2"`` times ``scale`` (see :func:`softpad.cli._args.number_list`)."""
    return number_list(text, flag, scale, positive)


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


def _check_outputs(args: argparse.Namespace) -> None:
    """Check every output file named on the command line before the study starts."""
    seen: dict[Any, str] = {}
    for flag, suffix in (("csv", ".csv"), ("png", ".png"), ("vtu", ".vtu"), ("out", ".npz")):
        if not hasattr(args, flag):
            continue
        path = check_output(getattr(args, flag), f"--{flag}", force=args.force, suffix=suffix)
        if path is not None and path.resolve() in seen:
            raise InputError(f"--{flag} and --{seen[path.resolve()]} name the same file {path}")
        if path is not None:
            seen[path.resolve()] = flag
        setattr(args, flag, path)


def _save_figure(fig: Any, path: Any) -> None:
    from softpad.fem import save_figure

    with atomic_path(path) as tmp:
        save_figure(fig, tmp)


# ---------------------------------------------------------------------------- helpers
def _geometry(args: argparse.Namespace) -> Any:
    from softpad.fem import ModuleGeometry

    if args.thickness_mm <= 0:
        raise InputError(f"--thickness-mm must be > 0 mm, got {args.thickness_mm:g} mm")
    if args.width_mm <= 0:
        raise InputError(f"--width-mm must be > 0 mm, got {args.width_mm:g} mm")
    try:
        return ModuleGeometry(args.width_mm * 1e-3, args.thickness_mm * 1e-3)
    except InputError as exc:
        raise InputError(
            f"--thickness-mm {args.thickness_mm:g} / --width-mm {args.width_mm:g}: {exc}"
        ) from None


def _mesh(args: argparse.Namespace) -> Any:
    from softpad.fem import MeshOptions

    return {
        "coarse": MeshOptions(6, 1),
        "default": MeshOptions(),
        "fine": MeshOptions(16, 2),
    }[args.mesh]


def _material(args: argparse.Namespace) -> Any:
    """The preset named by ``--model`` with the ``--param NAME=VALUE`` overrides applied."""
    from softpad.fem import get_material

    material = get_material(args.model)
    overrides = {}
    for item in args.param:
        name, sep, value = str(item).partition("=")
        if not sep:
            raise InputError(f"--param needs NAME=VALUE, got {item!r}")
        try:
            number = float(value)
        except ValueError:
            raise InputError(f"--param {name.strip()}: {value!r} is not a number") from None
        overrides[name.strip()] = number
    return material.with_parameters(**overrides) if overrides else material


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


def _outputs(args: argparse.Namespace, result: Any) -> None:
    if args.csv:
        with atomic_path(args.csv) as tmp:
            result.to_csv(tmp)
    if args.png:
        _save_figure(result.plot(), args.png)


def _setup(args: argparse.Namespace) -> Any:
    """The command's module: ``--model`` with its ``--param`` overrides, geometry and mesh."""
    from softpad.fem import ModuleSetup

    return ModuleSetup(_material(args), _geometry(args), _mesh(args))


def _run_study(
    args: argparse.Namespace, label: str, study: Callable[..., Any], *a: Any, **kw: Any
) -> Any:
    """``study(*a, **kw)`` (a :mod:`softpad.fem` study) with a progress bar named ``label``."""
    with _progress(args, label) as progress:
        return study(*a, progress=progress, **kw)


def _written_or_emitted(args: argparse.Namespace, result: Any) -> bool:
    """Write ``--csv``/``--png``; with ``--json`` print the result's dict and return True
    (nothing more to print)."""
    _outputs(args, result)
    if args.json:
        emit(result.to_dict())
    return bool(args.json)


# ---------------------------------------------------------------------------- handlers
def _sweep(args: argparse.Namespace) -> int:
    import numpy as np

    from softpad.fem import inflation_sweep

    _check_outputs(args)
    if args.points < 2:
        raise InputError(f"--points must be >= 2, got {args.points}")
    if args.max_pressure_kpa <= 0:
        raise InputError(f"--max-pressure-kpa must be > 0 kPa, got {args.max_pressure_kpa:g}")
    pressures = np.linspace(0.0, args.max_pressure_kpa * 1e3, args.points)
    model = _setup(args).model(contact=False)
    with _progress(args, f"sweep {args.model}") as progress:
        result = inflation_sweep(model, pressures, progress)
    _outputs(args, result)
    if args.vtu:
        with atomic_path(args.vtu) as tmp:
            model.write_vtu(str(tmp))
    if args.json:
        emit(result.to_json_dict())
        return 0
    print(f"model {result.model}: centre height against pressure")
    print("pressure_kpa  height_mm  volume_ml")
    for p, h, v in zip(result.pressure_pa, result.height_m, result.volume_m3, strict=True):
        print(f"{p * 1e-3:12.3f}  {h * 1e3:9.3f}  {v * 1e6:9.3f}")
    return 0


def _design(args: argparse.Namespace) -> int:
    from softpad.fem import ModuleSetup, check_design_values, design_sweep

    _check_outputs(args)
    defaults = {"thickness": "1,1.5,2,2.5,3", "width": "35,40,45,50,55"}
    values = _numbers(
        args.values_mm or defaults[args.parameter], "--values-mm", 1e-3, positive=True
    )
    check_design_values(args.parameter, values, "--values-mm")
    geometry, mesh = _geometry(args), _mesh(args)
    result = _run_study(
        args,
        f"design {args.parameter}",
        design_sweep,
        args.parameter,
        values,
        setups=[ModuleSetup(m, geometry, mesh) for m in _models(args.models)],
        pressure_pa=args.pressure_kpa * 1e3,
    )
    if _written_or_emitted(args, result):
        return 0
    print(f"centre height (mm) at {args.pressure_kpa:g} kPa against {args.parameter}")
    print(f"{args.parameter}_mm  " + "  ".join(f"{m:>13}" for m in result.models))
    for j, v in enumerate(result.values_m):
        print(f"{v * 1e3:12.3f}  " + "  ".join(f"{h * 1e3:13.3f}" for h in result.height_m[:, j]))
    return 0


def _stiffness(args: argparse.Namespace) -> int:
    from softpad.fem import check_study_pressures, stiffness_study

    _check_outputs(args)
    pressures = _numbers(args.pressures_kpa, "--pressures-kpa", 1e3, positive=True)
    check_study_pressures(pressures, "--pressures-kpa")
    forces = _numbers(args.forces_n, "--forces-n", positive=True)
    if not 0 < args.radius_mm < args.width_mm / 2:
        raise InputError(
            f"--radius-mm must be > 0 and below half the module width ({args.width_mm / 2:g} mm), "
            f"got {args.radius_mm:g}"
        )
    result = _run_study(
        args,
        "stiffness",
        stiffness_study,
        _setup(args),
        pressures,
        forces,
        args.radius_mm * 1e-3,
    )
    if _written_or_emitted(args, result):
        return 0
    k = result.stiffness_n_per_m * 1e-3
    print(f"model {result.model}: equivalent stiffness (N/mm); * = layer touches the base")
    print("pressure_kpa  " + "  ".join(f"F={f:g}N".rjust(10) for f in result.force_n))
    for i, p in enumerate(result.pressure_pa):
        cells = [
            f"{k[i, j]:9.4f}{'*' if result.touches_base[i, j] else ' '}"
            for j in range(len(result.force_n))
        ]
        print(f"{p * 1e-3:12.3f}  " + "  ".join(cells))
    return 0


def _sensitivity(args: argparse.Namespace) -> int:
    from softpad.fem import check_study_pressures, sensitive_area_study

    _check_outputs(args)
    pressures = _numbers(args.pressures_kpa, "--pressures-kpa", 1e3, positive=True)
    check_study_pressures(pressures, "--pressures-kpa")
    result = _run_study(
        args,
        "sensitivity",
        sensitive_area_study,
        _setup(args),
        pressures,
        fraction=args.fraction,
        probe_mass_kg=args.probe_g * 1e-3,
        threshold_pa=args.threshold_kpa * 1e3,
    )
    if _written_or_emitted(args, result):
        return 0
    print(
        f"model {result.model}: sensitive area = top-face region where a small load changes the "
        f"chamber volume by >= {result.fraction:g} x its effect at the centre"
    )
    print(
        f"detectable side: where a {args.probe_g:g} g probe raises the sealed pressure by >= "
        f"{args.threshold_kpa:g} kPa"
    )
    print("pressure_kpa  side_mm  area_mm2  centre_dV/dF_ml_per_n  detectable_side_mm")
    for p, s, ar, c, d in zip(
        result.pressure_pa,
        result.side_m,
        result.area_m2,
        result.centre_response_m3_per_n,
        result.detectable_area_m2,
        strict=True,
    ):
        print(
            f"{p * 1e-3:12.3f}  {s * 1e3:7.2f}  {ar * 1e6:8.1f}  {c * 1e6:21.3f}  "
            f"{d**0.5 * 1e3:18.2f}"
        )
    return 0


def _chamber(args: argparse.Namespace) -> int:
    from softpad.fem import (
        check_masses,
        detection_threshold_pa,
        parse_footprint,
        sealed_chamber_study,
    )

    _check_outputs(args)
    masses = _numbers(args.masses_g, "--masses-g", 1e-3, positive=True)
    check_masses(masses, "--masses-g")
    if args.pressure_kpa <= 0:
        raise InputError(f"--pressure-kpa must be > 0 kPa, got {args.pressure_kpa:g}")
    noise = None if args.noise_kpa is None else args.noise_kpa * 1e3
    threshold, _ = detection_threshold_pa(
        args.threshold_kpa * 1e3,
        noise,
        args.n_sigma,
        ("--threshold-kpa", "--n-sigma x --noise-kpa"),
    )
    footprint = parse_footprint(args.footprint_mm, args.width_mm * 1e-3, "--footprint-mm")
    result = _run_study(
        args,
        "chamber",
        sealed_chamber_study,
        _setup(args),
        args.pressure_kpa * 1e3,
        masses,
        footprint=footprint,
        dead_volume_m3=args.dead_volume_ml * 1e-6,
    )
    if args.csv:
        with atomic_path(args.csv) as tmp:
            result.to_csv(tmp)
    if args.png:
        _save_figure(result.plot(threshold_pa=threshold), args.png)
    info = result.to_dict(threshold)
    if args.json:
        emit(info)
        return 0
    print(
        f"model {result.model}: sealed at {info['initial_pressure_kpa']:g} kPa, chamber "
        f"{info['initial_volume_ml']:.3f} mL + dead volume {info['dead_volume_ml']:.3f} mL, "
        f"footprint {info['footprint']}"
    )
    print("mass_g  rise_kpa  volume_ml  height_mm")
    for m, dp, v, h in zip(
        info["mass_g"],
        info["delta_pressure_kpa"],
        info["volume_ml"],
        info["height_mm"],
        strict=True,
    ):
        print(f"{m:6.1f}  {dp:8.4f}  {v:9.3f}  {h:9.3f}")
    print(
        f"small-load slope {info['rise_kpa_per_g'] * 1e3:.3f} Pa/g; minimum detectable mass "
        f"{info['min_detectable_mass_g']:.2f} g at threshold {threshold * 1e-3:g} kPa"
    )
    return 0


def _fit(args: argparse.Namespace) -> int:
    from softpad.fem import fit_material, read_measurements

    _check_outputs(args)
    pressure, height = read_measurements(args.data)
    free = [s.strip() for s in args.free.split(",") if s.strip()] if args.free else None
    result = _run_study(
        args,
        f"fit {args.model}",
        fit_material,
        pressure,
        height,
        _material(args),
        free=free,
        geometry=_geometry(args),
        mesh=_mesh(args),
        max_evaluations=args.max_evals,
    )
    if _written_or_emitted(args, result):
        return 0
    info = result.to_dict()
    print(f"model {args.model}: RMSE {info['initial_rmse_mm']:.4f} mm -> {info['rmse_mm']:.4f} mm")
    for name, value in info["parameters"].items():
        print(f"  {name} = {value:.6g} (was {info['initial_parameters'][name]:.6g})")
    return 0


def _compare(args: argparse.Namespace) -> int:
    from softpad.fem import compare_models, read_measurements

    _check_outputs(args)
    pressure, height = read_measurements(args.data)
    result = _run_study(
        args,
        "compare",
        compare_models,
        pressure,
        height,
        _models(args.models),
        geometry=_geometry(args),
        mesh=_mesh(args),
    )
    if _written_or_emitted(args, result):
        return 0
    print("rank  model           RMSE_mm")
    for i, (name, err) in enumerate(zip(result.models, result.rmse_m, strict=True), 1):
        print(f"{i:4d}  {name:14s}  {err * 1e3:7.4f}")
    return 0


def _characteristic(args: argparse.Namespace) -> int:
    from softpad.fem import module_characteristic

    _check_outputs(args)
    pressures = _numbers(args.pressures_kpa, "--pressures-kpa", 1e3) if args.pressures_kpa else None
    loads = _numbers(args.loads_n, "--loads-n") if args.loads_n else None
    result = _run_study(
        args,
        "characteristic",
        module_characteristic,
        _setup(args),
        pressures_pa=pressures,
        loads_n=loads,
        gap_volume_m3=args.gap_volume_ml * 1e-6,
    )
    out = args.out
    with atomic_path(out) as tmp:
        result.to_npz(tmp)
    if args.png:
        _save_figure(result.plot(), args.png)
    if args.csv:
        with atomic_path(args.csv) as tmp:
            result.to_csv(tmp)
    if args.json:
        emit({"path": str(out), **result.to_dict()})
        return 0
    print(
        f"wrote {out}: {len(result.pressure_pa)} pressures x {len(result.load_n)} loads "
        f"({result.meta['model']}, {result.meta['load_patch'].split(' on ')[0]})"
    )
    return 0


def _response(args: argparse.Namespace) -> int:
    from softpad.fem import (
        DEFAULT_RESPONSE_PRESSURES_PA,
        check_study_pressures,
        module_response,
        response_convergence,
    )

    _check_outputs(args)
    pressures = (
        _numbers(args.pressures_kpa, "--pressures-kpa", 1e3, positive=True)
        if args.pressures_kpa
        else DEFAULT_RESPONSE_PRESSURES_PA
    )
    check_study_pressures(pressures, "--pressures-kpa")
    setup = _setup(args)
    with _progress(args, "response") as progress:
        result = module_response(setup, pressures, progress)
    if not args.no_convergence:
        result.meta["convergence"] = response_convergence(setup)
    with atomic_path(args.out) as tmp:
        result.to_npz(tmp)
    summary = {
        "path": str(args.out),
        "pressure_kpa": [p * 1e-3 for p in result.pressure_pa],
        "reference_s_ml_n": [s * 1e6 for s in result.reference_influence_m3_n],
        "compliance_ml_kpa": [c * 1e9 for c in result.compliance_m3_pa],
        "meta": result.meta,
    }
    if args.json:
        emit(summary)
        return 0
    conv = result.meta.get("convergence")
    print(
        f"wrote {args.out}: {len(result.pressure_pa)} pressures x "
        f"{len(result.axis_m)}^2 nodes ({result.meta['model']}, {result.meta['mesh']})"
    )
    if conv:
        print(
            f"mesh convergence at {conv['pressure_pa'] / 1e3:g} kPa: largest difference "
            f"{100 * conv['largest_difference']:.2f} % against {conv['reference_mesh']}"
        )
    return 0
