"""The example plug-in outside ``src/`` (examples/plugin): installed, its planner and contact
detector are found by name through their entry points, in the library and on the command line.

"Installed" is what ``pip install ./examples/plugin`` leaves behind: the package on the path and
a ``.dist-info`` whose ``entry_points.txt`` carries the groups of its ``pyproject.toml``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib
from collections.abc import Iterator
from pathlib import Path

import pytest

from softpad.planning import PLANNER_REGISTRY, available_planners, make_planner
from softpad.sensing import (
    CONTACT_DETECTOR_REGISTRY,
    available_contact_detectors,
    make_contact_detector,
)

PLUGIN = Path(__file__).resolve().parents[1] / "examples" / "plugin"
SRC = Path(__file__).resolve().parents[1] / "src"


def _install(site: Path) -> list[str]:
    """The plug-in's distribution metadata on ``site``, entry points from its pyproject."""
    project = tomllib.loads((PLUGIN / "pyproject.toml").read_text())["project"]
    info = site / f"{project['name'].replace('-', '_')}-{project['version']}.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(
        f"Metadata-Version: 2.1\nName: {project['name']}\nVersion: {project['version']}\n"
    )
    text = "".join(
        f"[{group}]\n" + "".join(f"{k} = {v}\n" for k, v in eps.items()) + "\n"
        for group, eps in project["entry-points"].items()
    )
    (info / "entry_points.txt").write_text(text)
    return [str(site), str(PLUGIN / "src")]


@pytest.fixture
def plugin_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    paths = _install(tmp_path)
    for p in reversed(paths):
        monkeypatch.syspath_prepend(p)
    yield paths
    PLANNER_REGISTRY.unregister("pcom-centre")
    CONTACT_DETECTOR_REGISTRY.unregister("median-rise")
    for name in [m for m in sys.modules if m.startswith("softpad_example_plugin")]:
        del sys.modules[name]


def test_not_installed_not_listed() -> None:
    assert "pcom-centre" not in available_planners()
    assert "median-rise" not in available_contact_detectors()


def test_plugin_parts_are_made_by_name(plugin_path: list[str]) -> None:
    from softpad.layout import PadLayout
    from softpad.planning import plan_grasps
    from softpad.sensing import detect_objects

    assert "pcom-centre" in available_planners()
    assert "median-rise" in available_contact_detectors()
    detector = make_contact_detector("median-rise", 100.0, contact_threshold_pa=70.0)
    assert type(detector).__name__ == "MedianRiseDetector" and detector.threshold_pa == 70.0
    banana = [0.0, 124.0, 78.0, 109.0, 0.0, 0.0]  # seed, Table 6.1 (Pa)
    layout = PadLayout()
    (plan,) = make_planner("pcom-centre").plan(banana, detect_objects(banana, layout), layout)
    (thesis,) = plan_grasps(banana, layout)
    assert plan.cog == plan.pcom == thesis.pcom and plan.theta == thesis.theta
    assert plan.rule == f"pcom-centre ({thesis.rule})"


def test_median_rise_ignores_one_spike(plugin_path: list[str]) -> None:
    detector = make_contact_detector("median-rise", contact_threshold_pa=90.0)
    detector.reset([1100.0] * 6)
    assert not detector.update([1100.0 + 500.0] + [1100.0] * 5)  # one spike: median 0
    rises = [detector.update([1100.0] * 5 + [1100.0 + 100.0]) for _ in range(5)]
    assert rises == [False, False, True, True, True]  # the 3rd of 5 samples above t_g
    assert detector.triggered_modules == (6,)


def test_cli_lists_and_runs_the_plugin(plugin_path: list[str]) -> None:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([*plugin_path, str(SRC)])}
    cmd = [sys.executable, "-m", "softpad"]
    helps = subprocess.run([*cmd, "run", "--help"], env=env, capture_output=True, text=True)
    assert "pcom-centre" in helps.stdout and "median-rise" in helps.stdout, helps.stderr
    args = ["run", "--planner", "pcom-centre", "--detector", "median-rise"]
    args += ["--objects", "object-5", "--hold-s", "0", "--json"]
    out = subprocess.run([*cmd, *args], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert report["outcome"] == "held"
    assert report["objects"][0]["rule"].startswith("pcom-centre")
