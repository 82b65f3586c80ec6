"""softpad.fem's study runs (what ``softpad fem STUDY`` calls): input checks naming the value
and the limit, the files written through the writer hook, the report's lines and dict."""

from __future__ import annotations

from contextlib import contextmanager

import pytest

from softpad.errors import InputError
from softpad.fem import StudyFiles, StudyModule, run_characteristic, run_sweep


@pytest.mark.parametrize(
    ("module", "message"),
    [
        (StudyModule(thickness_mm=0.0), "--thickness-mm must be > 0 mm, got 0 mm"),
        (StudyModule(width_mm=-3.0), "--width-mm must be > 0 mm, got -3 mm"),
        (StudyModule(thickness_mm=30.0), "--thickness-mm 30 / --width-mm 45:"),
        (StudyModule(params=("mu",)), "--param needs NAME=VALUE, got 'mu'"),
        (StudyModule(params=("mu=soft",)), "--param mu: 'soft' is not a number"),
        (StudyModule(mesh="huge"), "mesh must be one of coarse, default, fine, got 'huge'"),
    ],
    ids=["thickness", "width", "thickness-range", "param-form", "param-number", "mesh"],
)
def test_a_module_refuses_bad_inputs_naming_them(module: StudyModule, message: str) -> None:
    with pytest.raises(InputError) as err:
        module.setup()
    assert message in str(err.value)


def test_a_module_applies_its_overrides_in_si() -> None:
    setup = StudyModule("yeoh", ("c1=12000",), thickness_mm=2.0, width_mm=40.0).setup()
    assert setup.material.parameters["c1"] == 12000.0
    assert setup.geometry.thickness_m == pytest.approx(2e-3)
    assert setup.geometry.width_m == pytest.approx(40e-3)


@pytest.mark.parametrize(
    ("points", "max_kpa", "message"),
    [(1, 1.0, "--points must be >= 2, got 1"), (3, 0.0, "--max-pressure-kpa must be > 0 kPa")],
    ids=["points", "pressure"],
)
def test_a_sweep_checks_its_range_before_solving(points: int, max_kpa: float, message: str) -> None:
    with pytest.raises(InputError, match=message):
        run_sweep(StudyModule(mesh="coarse"), max_kpa, points)


def test_a_sweep_reports_each_pressure_and_writes_through_the_hook(tmp_path) -> None:
    written = []

    @contextmanager
    def atomic(path):
        written.append(path.name)
        yield path

    files = StudyFiles(csv=tmp_path / "h.csv", atomic=atomic)
    report = run_sweep(StudyModule(mesh="coarse"), 1.0, 3, files)
    assert written == ["h.csv"]
    assert report.data["pressure_kpa"] == [0.0, 0.5, 1.0]
    assert report.lines[1] == "pressure_kpa  height_mm  volume_ml"
    rows = [line.split() for line in report.lines[2:]]
    assert [float(r[0]) for r in rows] == [0.0, 0.5, 1.0]
    assert [float(r[1]) for r in rows] == pytest.approx(report.data["height_mm"], abs=1e-3)
    assert len((tmp_path / "h.csv").read_text().splitlines()) == 4


def test_a_table_study_needs_its_file() -> None:
    with pytest.raises(InputError, match=r"--out FILE\.npz"):
        run_characteristic(StudyModule(mesh="coarse"), [0.0, 500.0], [0.0], 0.2, StudyFiles())


def test_the_cast_response_needs_its_file_before_solving() -> None:
    from softpad.fem import run_cast_response

    with pytest.raises(InputError, match=r"--out FILE\.npz"):
        run_cast_response("neo-hookean", 1.0, None, (4, 1), [], StudyFiles())
