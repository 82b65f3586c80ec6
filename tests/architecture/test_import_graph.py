"""The layering of docs/architecture.md, read from the source's import statements."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import softpad

SRC = Path(softpad.__file__).parent

#: Sub-packages each sub-package may import (besides itself and the modules every layer may
#: use: ``errors``, ``thesis`` and ``registry``).
ALLOWED: dict[str, set[str]] = {
    "layout": set(),
    "sensing": {"layout"},
    "planning": {"layout", "sensing"},
    "fem": set(),
    "config": set(),
    "sim": {"layout", "fem"},
    "box": {"sim", "layout", "config"},
    "control": {"box", "layout", "sensing", "planning"},
    # record replays the controller's decisions on recordings (ExecutionParams, detectors)
    "record": {"box", "control", "layout", "planning", "sensing"},
    "harness": {"box", "control", "layout", "sim", "planning", "sensing"},
    "trials": {"box", "control", "harness", "layout", "planning", "record", "sensing", "sim"},
    # the ROS adapters translate; the simulated arm node uses the harness and the catalogue
    "ros": {"box", "control", "harness", "layout", "planning", "sensing", "sim"},
    # design sweeps evaluate pads with the FEM and simulated trials
    "design": {
        "box",
        "control",
        "fem",
        "harness",
        "layout",
        "planning",
        "sensing",
        "sim",
        "trials",
    },
}

#: Modules below every layer: the errors, the thesis's constants, the registries' base.
EVERY_LAYER = ("errors", "thesis", "registry")


def _is_module(name: str) -> bool:
    return not name.startswith("_") and ((SRC / name).is_dir() or (SRC / f"{name}.py").is_file())


def _imports(path: Path) -> set[str]:
    """Top-level softpad sub-packages imported anywhere in a module (lazy imports included)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module]
            if node.module == "softpad":  # ``from softpad import thesis`` names a module
                # only sub-packages and modules count (``SCHEMA_VERSION`` is a constant)
                names = [f"softpad.{a.name}" for a in node.names if _is_module(a.name)]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        found |= {n.split(".")[1] for n in names if n.startswith("softpad.")}
    return found


@pytest.mark.parametrize("package", sorted(ALLOWED))
def test_package_imports_only_lower_layers(package: str) -> None:
    bad = {}
    for path in sorted((SRC / package).glob("*.py")):
        extra = _imports(path) - ALLOWED[package] - {package, *EVERY_LAYER}
        if extra:
            bad[path.name] = sorted(extra)
    assert not bad, f"softpad.{package} imports higher layers: {bad}"


@pytest.mark.parametrize("package", ["control", "planning", "sensing"])
def test_controller_side_never_imports_the_simulator(package: str) -> None:
    for path in sorted((SRC / package).glob("*.py")):
        assert not _imports(path) & {"sim", "harness", "trials"}, path.name


def test_the_checker_sees_a_forbidden_import(tmp_path: Path) -> None:
    """The AST reader finds plain, lazy and from-package imports (so the tests above can fail)."""
    f = tmp_path / "m.py"
    f.write_text(
        "import softpad.sim\ndef f():\n    from softpad.harness import x\n"
        "from softpad import trials, __version__\n"
    )
    assert _imports(f) == {"sim", "harness", "trials"}


def test_importing_the_controller_loads_no_simulator_world() -> None:
    code = (
        "import sys, softpad.control, softpad.planning, softpad.sensing;"
        "bad = [m for m in ('softpad.harness', 'softpad.trials', 'mujoco', 'felupe') "
        "if m in sys.modules]; print(bad); sys.exit(1 if bad else 0)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


def test_planning_has_no_function_over_60_lines() -> None:
    """Issue 34: the planners read as short steps (docstrings count)."""
    long = []
    for path in sorted((SRC / "planning").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                n = (node.end_lineno or node.lineno) - node.lineno + 1
                if n > 60:
                    long.append(f"{path.name}:{node.name} ({n} lines)")
    assert not long, long
