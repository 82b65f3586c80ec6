"""The studies run as a command runs them: the module given in the units of its inputs,
checked; the study; its files written; a report as a dict and as lines of text.

``softpad fem STUDY`` parses its options, calls one ``run_*`` function and prints the
report. Every check raises :class:`~softpad.errors.InputError` naming the value and its
limit and, through the names given (``--thickness-mm``), the input it came from.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from softpad.errors import InputError

#: Progress of a study: ``progress(done, total)`` (see :class:`softpad.fem.ProgressCallback`).
Progress = Callable[[int, int], None] | None


@contextmanager
def _in_place(path: Path) -> Iterator[Path]:
    """Write to ``path`` itself (a command passes an atomic writer instead)."""
    yield path


@dataclass(frozen=True)
class StudyModule:
    """The module a study runs on, as its inputs give it.

    Parameters
    ----------
    model
        Material preset (thesis Table 7.1), e.g. ``"yeoh"``.
    params
        Overrides of the preset's parameters as ``"NAME=VALUE"`` texts (moduli in Pa).
    thickness_mm
        Upper-layer thickness, mm (> 0; :data:`softpad.fem.THICKNESS_RANGE_M`).
    width_mm
        Module width, mm (> 0; :data:`softpad.fem.WIDTH_RANGE_M`).
    mesh
        ``"coarse"`` (6 x 6 x 1), ``"default"`` (12 x 12 x 2) or ``"fine"`` (16 x 16 x 2)
        quarter cells.
    """

    model: str = "neo-hookean"
    params: Sequence[str] = ()
    thickness_mm: float = 1.5
    width_mm: float = 45.0
    mesh: str = "default"

    def geometry(self) -> Any:
        """The :class:`~softpad.fem.ModuleGeometry` (m), its limits checked."""
        from softpad.fem._geometry import ModuleGeometry

        if self.thickness_mm <= 0:
            raise InputError(f"--thickness-mm must be > 0 mm, got {self.thickness_mm:g} mm")
        if self.width_mm <= 0:
            raise InputError(f"--width-mm must be > 0 mm, got {self.width_mm:g} mm")
        try:
            return ModuleGeometry(self.width_mm * 1e-3, self.thickness_mm * 1e-3)
        except InputError as exc:
            raise InputError(
                f"--thickness-mm {self.thickness_mm:g} / --width-mm {self.width_mm:g}: {exc}"
            ) from None

    def mesh_options(self) -> Any:
        """The :class:`~softpad.fem.MeshOptions` named by :attr:`mesh`."""
        from softpad.fem._geometry import MeshOptions

        meshes = {"coarse": MeshOptions(6, 1), "default": MeshOptions(), "fine": MeshOptions(16, 2)}
        if self.mesh not in meshes:
            raise InputError(f"mesh must be one of {', '.join(meshes)}, got {self.mesh!r}")
        return meshes[self.mesh]

    def material(self) -> Any:
        """The preset :attr:`model` with the :attr:`params` overrides applied."""
        from softpad.fem._materials import get_material

        material = get_material(self.model)
        overrides = {}
        for item in self.params:
            name, sep, value = str(item).partition("=")
            if not sep:
                raise InputError(f"--param needs NAME=VALUE, got {item!r}")
            try:
                number = float(value)
            except ValueError:
                raise InputError(f"--param {name.strip()}: {value!r} is not a number") from None
            overrides[name.strip()] = number
        return material.with_parameters(**overrides) if overrides else material

    def setup(self) -> Any:
        """The :class:`~softpad.fem.ModuleSetup`: material, geometry and mesh."""
        from softpad.fem._model import ModuleSetup

        return ModuleSetup(self.material(), self.geometry(), self.mesh_options())


@dataclass(frozen=True)
class StudyFiles:
    """The files a study writes; None writes none.

    Parameters
    ----------
    csv
        The results as CSV.
    png
        A plot.
    vtu
        The deformed module (sweep only).
    out
        The table (``.npz``) of the characteristic and response studies.
    atomic
        ``atomic(path)`` is a context manager yielding the path to write in place of
        ``path`` (a command's writes a temporary file and renames it); default: ``path``.
    """

    csv: Path | None = None
    png: Path | None = None
    vtu: Path | None = None
    out: Path | None = None
    atomic: Callable[[Path], AbstractContextManager[Path]] = field(default=_in_place)

    def write(self, result: Any, figure: Callable[[], Any] | None = None) -> None:
        """Write ``result.to_csv`` to :attr:`csv` and ``figure()`` (default
        ``result.plot()``) to :attr:`png`, those given."""
        if self.csv:
            with self.atomic(self.csv) as tmp:
                result.to_csv(tmp)
        if self.png:
            self.save_figure((figure or result.plot)(), self.png)

    def save_figure(self, ax: Any, path: Path) -> None:
        """Save the figure of ``ax`` to ``path`` and close it."""
        from softpad.fem._results import save_figure

        with self.atomic(path) as tmp:
            save_figure(ax, tmp)


@dataclass(frozen=True)
class StudyReport:
    """What a study run reports.

    Parameters
    ----------
    data
        The JSON-ready dict (``--json``).
    lines
        The report as lines of text.
    """

    data: dict[str, Any]
    lines: tuple[str, ...]


def _check_positive(value: float, name: str, unit: str) -> None:
    if value <= 0:
        raise InputError(f"{name} must be > 0 {unit}, got {value:g}")


def run_sweep(
    module: StudyModule,
    max_pressure_kpa: float,
    points: int,
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Centre height against pressure, 0 to ``max_pressure_kpa`` (Fig. 7.2b); the deformed
    module at the last pressure to ``files.vtu``.

    Parameters
    ----------
    max_pressure_kpa
        Highest pressure, kPa (> 0).
    points
        Number of evenly spaced pressures (>= 2).
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    import numpy as np

    from softpad.fem._studies import inflation_sweep

    if points < 2:
        raise InputError(f"--points must be >= 2, got {points}")
    _check_positive(max_pressure_kpa, "--max-pressure-kpa", "kPa")
    pressures = np.linspace(0.0, max_pressure_kpa * 1e3, points)
    model = module.setup().model(contact=False)
    result = inflation_sweep(model, pressures, progress)
    files.write(result)
    if files.vtu:
        with files.atomic(files.vtu) as tmp:
            model.write_vtu(str(tmp))
    lines = [f"model {result.model}: centre height against pressure"]
    lines.append("pressure_kpa  height_mm  volume_ml")
    for p, h, v in zip(result.pressure_pa, result.height_m, result.volume_m3, strict=True):
        lines.append(f"{p * 1e-3:12.3f}  {h * 1e3:9.3f}  {v * 1e6:9.3f}")
    return StudyReport(result.to_json_dict(), tuple(lines))


def run_design(
    module: StudyModule,
    parameter: str,
    values_m: Sequence[float],
    models: Sequence[str],
    pressure_kpa: float,
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Centre height at ``pressure_kpa`` against the layer's thickness or the module's
    width, for each preset of ``models`` (Fig. 7.3).

    Parameters
    ----------
    parameter
        ``"thickness"`` or ``"width"``.
    values_m
        The parameter's values, m (within :data:`THICKNESS_RANGE_M` / :data:`WIDTH_RANGE_M`).
    models
        Material presets compared.
    pressure_kpa
        Inflating pressure, kPa.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._inputs import check_design_values
    from softpad.fem._model import ModuleSetup
    from softpad.fem._studies import design_sweep

    check_design_values(parameter, values_m, "--values-mm")
    geometry, mesh = module.geometry(), module.mesh_options()
    result = design_sweep(
        parameter,
        values_m,
        setups=[ModuleSetup(m, geometry, mesh) for m in models],
        pressure_pa=pressure_kpa * 1e3,
        progress=progress,
    )
    files.write(result)
    lines = [f"centre height (mm) at {pressure_kpa:g} kPa against {parameter}"]
    lines.append(f"{parameter}_mm  " + "  ".join(f"{m:>13}" for m in result.models))
    for j, v in enumerate(result.values_m):
        heights = "  ".join(f"{h * 1e3:13.3f}" for h in result.height_m[:, j])
        lines.append(f"{v * 1e3:12.3f}  " + heights)
    return StudyReport(result.to_dict(), tuple(lines))


def run_stiffness(
    module: StudyModule,
    pressures_pa: Sequence[float],
    forces_n: Sequence[float],
    radius_mm: float,
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Equivalent stiffness under a central load (Fig. 6.3c); N/mm in the lines.

    Parameters
    ----------
    pressures_pa
        Inflating pressures, Pa (at most the module's maximum).
    forces_n
        Central loads, N.
    radius_mm
        Radius of the loaded disc, mm (> 0, below half the module's width).
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._inputs import check_study_pressures
    from softpad.fem._studies import stiffness_study

    check_study_pressures(pressures_pa, "--pressures-kpa")
    if not 0 < radius_mm < module.width_mm / 2:
        raise InputError(
            f"--radius-mm must be > 0 and below half the module width "
            f"({module.width_mm / 2:g} mm), got {radius_mm:g}"
        )
    result = stiffness_study(
        module.setup(), pressures_pa, forces_n, radius_mm * 1e-3, progress=progress
    )
    files.write(result)
    k = result.stiffness_n_per_m * 1e-3
    lines = [f"model {result.model}: equivalent stiffness (N/mm); * = layer touches the base"]
    lines.append("pressure_kpa  " + "  ".join(f"F={f:g}N".rjust(10) for f in result.force_n))
    for i, p in enumerate(result.pressure_pa):
        cells = [
            f"{k[i, j]:9.4f}{'*' if result.touches_base[i, j] else ' '}"
            for j in range(len(result.force_n))
        ]
        lines.append(f"{p * 1e-3:12.3f}  " + "  ".join(cells))
    return StudyReport(result.to_dict(), tuple(lines))


def run_sensitivity(
    module: StudyModule,
    pressures_pa: Sequence[float],
    fraction: float,
    probe_g: float,
    threshold_kpa: float,
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Sensitive area against pressure (Section 6.1.2): where a small load changes the
    chamber volume by at least ``fraction`` of its effect at the centre, and where a probe
    raises the sealed pressure by at least the threshold.

    Parameters
    ----------
    pressures_pa
        Inflating pressures, Pa (at most the module's maximum).
    fraction
        Response threshold relative to the centre (0..1).
    probe_g
        Probe mass of the absolute definition, g.
    threshold_kpa
        Detection threshold t_o of the absolute definition, kPa.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._inputs import check_study_pressures
    from softpad.fem._studies import sensitive_area_study

    check_study_pressures(pressures_pa, "--pressures-kpa")
    result = sensitive_area_study(
        module.setup(),
        pressures_pa,
        fraction=fraction,
        probe_mass_kg=probe_g * 1e-3,
        threshold_pa=threshold_kpa * 1e3,
        progress=progress,
    )
    files.write(result)
    lines = _sensitivity_lines(result, probe_g, threshold_kpa)
    return StudyReport(result.to_dict(), tuple(lines))


def _sensitivity_lines(result: Any, probe_g: float, threshold_kpa: float) -> list[str]:
    """The sensitivity study's report of ``result`` (probe g, threshold kPa)."""
    lines = [
        f"model {result.model}: sensitive area = top-face region where a small load changes "
        f"the chamber volume by >= {result.fraction:g} x its effect at the centre",
        f"detectable side: where a {probe_g:g} g probe raises the sealed pressure by >= "
        f"{threshold_kpa:g} kPa",
        "pressure_kpa  side_mm  area_mm2  centre_dV/dF_ml_per_n  detectable_side_mm",
    ]
    for p, s, ar, c, d in zip(
        result.pressure_pa,
        result.side_m,
        result.area_m2,
        result.centre_response_m3_per_n,
        result.detectable_area_m2,
        strict=True,
    ):
        lines.append(
            f"{p * 1e-3:12.3f}  {s * 1e3:7.2f}  {ar * 1e6:8.1f}  {c * 1e6:21.3f}  "
            f"{d**0.5 * 1e3:18.2f}"
        )
    return lines


def run_chamber(
    module: StudyModule,
    pressure_kpa: float,
    masses_kg: Sequence[float],
    footprint: str,
    dead_volume_ml: float,
    threshold: tuple[float, float | None, float],
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """The sealed chamber: the pressure rise of each mass on a footprint, and the smallest
    mass the threshold detects.

    Parameters
    ----------
    pressure_kpa
        Pressure when the valves close, kPa (> 0).
    masses_kg
        Masses put on the module, kg (within :data:`MASS_RANGE_KG`).
    footprint
        The load's footprint as text: ``"WxH"`` in mm or ``"dD"`` (a disc's diameter, mm).
    dead_volume_ml
        Dead volume beside the chamber (tubing, gap), mL.
    threshold
        (t_o in kPa, sensor noise rms in kPa or None, n_sigma) as
        :func:`detection_threshold_pa` reads them (n_sigma x noise when noise is given).
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._chamber import sealed_chamber_study
    from softpad.fem._inputs import check_masses, detection_threshold_pa, parse_footprint

    check_masses(masses_kg, "--masses-g")
    _check_positive(pressure_kpa, "--pressure-kpa", "kPa")
    t_o_kpa, noise_kpa, n_sigma = threshold
    noise = None if noise_kpa is None else noise_kpa * 1e3
    names = ("--threshold-kpa", "--n-sigma x --noise-kpa")
    threshold_pa, _ = detection_threshold_pa(t_o_kpa * 1e3, noise, n_sigma, names)
    patch = parse_footprint(footprint, module.width_mm * 1e-3, "--footprint-mm")
    result = sealed_chamber_study(
        module.setup(),
        pressure_kpa * 1e3,
        masses_kg,
        footprint=patch,
        dead_volume_m3=dead_volume_ml * 1e-6,
        progress=progress,
    )
    files.write(result, lambda: result.plot(threshold_pa=threshold_pa))
    info = result.to_dict(threshold_pa)
    return StudyReport(info, tuple(_chamber_lines(result.model, info, threshold_pa)))


def _chamber_lines(model: str, info: dict[str, Any], threshold_pa: float) -> list[str]:
    """The chamber study's report: ``info`` is its result's dict at ``threshold_pa`` (Pa)."""
    lines = [
        f"model {model}: sealed at {info['initial_pressure_kpa']:g} kPa, chamber "
        f"{info['initial_volume_ml']:.3f} mL + dead volume {info['dead_volume_ml']:.3f} mL, "
        f"footprint {info['footprint']}",
        "mass_g  rise_kpa  volume_ml  height_mm",
    ]
    columns = ("mass_g", "delta_pressure_kpa", "volume_ml", "height_mm")
    for m, dp, v, h in zip(*(info[c] for c in columns), strict=True):
        lines.append(f"{m:6.1f}  {dp:8.4f}  {v:9.3f}  {h:9.3f}")
    lines.append(
        f"small-load slope {info['rise_kpa_per_g'] * 1e3:.3f} Pa/g; minimum detectable mass "
        f"{info['min_detectable_mass_g']:.2f} g at threshold {threshold_pa * 1e-3:g} kPa"
    )
    return lines


def run_fit(
    module: StudyModule,
    data: str | Path,
    free: Sequence[str] | None,
    max_evaluations: int,
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Fit the module's material to measured heights.

    Parameters
    ----------
    data
        CSV file with the header ``pressure_kpa,height_mm``.
    free
        Parameters to fit; None: all moduli.
    max_evaluations
        Budget of sweeps.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._fitting import fit_material, read_measurements

    pressure, height = read_measurements(data)
    result = fit_material(
        pressure,
        height,
        module.material(),
        free=free,
        geometry=module.geometry(),
        mesh=module.mesh_options(),
        max_evaluations=max_evaluations,
        progress=progress,
    )
    files.write(result)
    info = result.to_dict()
    lines = [
        f"model {module.model}: RMSE {info['initial_rmse_mm']:.4f} mm -> {info['rmse_mm']:.4f} mm"
    ]
    for name, value in info["parameters"].items():
        lines.append(f"  {name} = {value:.6g} (was {info['initial_parameters'][name]:.6g})")
    return StudyReport(info, tuple(lines))


def run_compare(
    module: StudyModule,
    data: str | Path,
    models: Sequence[str],
    files: StudyFiles = StudyFiles(),
    progress: Progress = None,
) -> StudyReport:
    """Rank the presets ``models`` by their RMSE on measured heights.

    Parameters
    ----------
    data
        CSV file with the header ``pressure_kpa,height_mm``.
    models
        Material presets to compare.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._fitting import compare_models, read_measurements

    pressure, height = read_measurements(data)
    result = compare_models(
        pressure,
        height,
        models,
        geometry=module.geometry(),
        mesh=module.mesh_options(),
        progress=progress,
    )
    files.write(result)
    lines = ["rank  model           RMSE_mm"]
    for i, (name, err) in enumerate(zip(result.models, result.rmse_m, strict=True), 1):
        lines.append(f"{i:4d}  {name:14s}  {err * 1e3:7.4f}")
    return StudyReport(result.to_dict(), tuple(lines))


def run_characteristic(
    module: StudyModule,
    pressures_pa: Sequence[float] | None,
    loads_n: Sequence[float] | None,
    gap_volume_ml: float,
    files: StudyFiles,
    progress: Progress = None,
) -> StudyReport:
    """Tabulate volume and height against pressure and load into ``files.out`` (.npz).

    Parameters
    ----------
    pressures_pa
        Pressures, Pa, starting at 0; None: 0..5 kPa every 0.1 kPa.
    loads_n
        Loads, N, starting at 0; None: 0..6 N.
    gap_volume_ml
        Residual air under the flat layer added to every volume, mL.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._characteristic import module_characteristic

    out = _out(files)
    result = module_characteristic(
        module.setup(),
        pressures_pa=pressures_pa,
        loads_n=loads_n,
        gap_volume_m3=gap_volume_ml * 1e-6,
        progress=progress,
    )
    with files.atomic(out) as tmp:
        result.to_npz(tmp)
    if files.png:
        files.save_figure(result.plot(), files.png)
    if files.csv:
        with files.atomic(files.csv) as tmp:
            result.to_csv(tmp)
    line = (
        f"wrote {out}: {len(result.pressure_pa)} pressures x {len(result.load_n)} loads "
        f"({result.meta['model']}, {result.meta['load_patch'].split(' on ')[0]})"
    )
    return StudyReport({"path": str(out), **result.to_dict()}, (line,))


def _out(files: StudyFiles) -> Path:
    if files.out is None:
        raise InputError("the study writes a table: give its file (--out FILE.npz)")
    return files.out


def run_response(
    module: StudyModule,
    pressures_pa: Sequence[float] | None,
    convergence: bool,
    files: StudyFiles,
    progress: Progress = None,
) -> StudyReport:
    """The chamber's response to a load at every point of the module into ``files.out``
    (.npz).

    Parameters
    ----------
    pressures_pa
        Increasing pressures, Pa; None: :data:`DEFAULT_RESPONSE_PRESSURES_PA`.
    convergence
        Whether to add a refined mesh's difference at 1.1 kPa to the table's meta.
    module
        The module (its model unused where the study names its presets).
    files
        The files to write.
    progress
        ``progress(done, total)`` as the study advances, or None.

    Returns
    -------
    StudyReport
        The result's dict and the report's lines.
    """
    from softpad.fem._inputs import check_study_pressures
    from softpad.fem._response import (
        DEFAULT_RESPONSE_PRESSURES_PA,
        module_response,
        response_convergence,
    )

    pressures = DEFAULT_RESPONSE_PRESSURES_PA if pressures_pa is None else pressures_pa
    check_study_pressures(pressures, "--pressures-kpa")
    out = _out(files)
    setup = module.setup()
    result = module_response(setup, pressures, progress)
    if convergence:
        result.meta["convergence"] = response_convergence(setup)
    with files.atomic(out) as tmp:
        result.to_npz(tmp)
    return StudyReport(*_response_report(result, out))


def _response_report(result: Any, out: Path) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The response study's summary and lines for ``result`` written to ``out``."""
    summary = {
        "path": str(out),
        "pressure_kpa": [p * 1e-3 for p in result.pressure_pa],
        "reference_s_ml_n": [s * 1e6 for s in result.reference_influence_m3_n],
        "compliance_ml_kpa": [c * 1e9 for c in result.compliance_m3_pa],
        "meta": result.meta,
    }
    lines = [
        f"wrote {out}: {len(result.pressure_pa)} pressures x "
        f"{len(result.axis_m)}^2 nodes ({result.meta['model']}, {result.meta['mesh']})"
    ]
    conv = result.meta.get("convergence")
    if conv:
        lines.append(
            f"mesh convergence at {conv['pressure_pa'] / 1e3:g} kPa: largest difference "
            f"{100 * conv['largest_difference']:.2f} % against {conv['reference_mesh']}"
        )
    return summary, tuple(lines)


def run_cast_response(
    model: str,
    wall_mm: float,
    foundation_mpa_per_m: float | None,
    mesh: tuple[int, int],
    pressures_pa: Sequence[float],
    files: StudyFiles,
) -> StudyReport:
    """The cast pad's response table into ``files.out`` (.npz) and its sensitivities at p0
    (1.1 kPa, within the table's pressures).

    Parameters
    ----------
    model
        Material preset (thesis Table 7.1).
    wall_mm
        Width of the walls between the chambers, mm.
    foundation_mpa_per_m
        Stiffness of the foundation under the walls, MPa/m; None: rigid.
    mesh
        (cells, layers) of :class:`~softpad.fem.MeshOptions`.
    pressures_pa
        The table's pressures, Pa; empty: :data:`DEFAULT_RESPONSE_PRESSURES_PA`.
    files
        Where the table goes (``out``).

    Returns
    -------
    StudyReport
        The table's path, meta and sensitivities (Pa/N, g), and the report's lines.
    """
    from softpad.fem._cast import CastPadGeometry, cast_pad_response, cast_sensitivities
    from softpad.fem._geometry import MeshOptions
    from softpad.fem._materials import get_material
    from softpad.fem._response import DEFAULT_RESPONSE_PRESSURES_PA

    out = _out(files)
    k = float("inf") if foundation_mpa_per_m is None else foundation_mpa_per_m * 1e6
    pad = CastPadGeometry(wall_width_m=wall_mm * 1e-3, foundation_pa_per_m=k)
    pressures = list(pressures_pa) or DEFAULT_RESPONSE_PRESSURES_PA
    table = cast_pad_response(get_material(model), pad, MeshOptions(*mesh), pressures)
    with files.atomic(out) as tmp:
        table.to_npz(tmp)
    p0 = min(max(1100.0, float(table.pressure_pa[0])), float(table.pressure_pa[-1]))
    figures = cast_sensitivities(table, p0)
    lines = [f"wrote {out}: {len(table.pressure_pa)} pressures, {table.meta['mesh']}"]
    for name, v in figures["probes"].items():
        rises = ", ".join(f"{r:.0f}" for r in v["rise_pa_n"])
        lines.append(f"  {name}: every module [{rises}] Pa/N")
    for name, g in figures["min_detectable_mass_g"].items():
        lines.append(f"  minimum detectable mass, {name}: {g:.2f} g at t_o = 50 Pa")
    data = {"path": str(out), "meta": table.meta, "sensitivities": figures}
    return StudyReport(data, tuple(lines))
