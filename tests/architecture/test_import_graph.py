"""The layering of ``softpad.layering`` (docs/architecture.md's picture), read from the source's
import statements."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import softpad
from softpad.layering import ALLOWED_IMPORTS, EVERY_LAYER

SRC = Path(softpad.__file__).parent

#: The layering's one table (docs/architecture.md draws it from there).
ALLOWED = ALLOWED_IMPORTS


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


def _private_imports(path: Path, package: str) -> list[str]:
    """``softpad.X._y`` modules of another sub-package X that a module of ``package`` imports
    (lazy imports included): what it needs must come from ``softpad.X`` itself."""
    found: list[str] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        for n in names:
            parts = n.split(".")
            if parts[0] == "softpad" and len(parts) > 2 and parts[1] != package:
                if any(p.startswith("_") for p in parts[2:]):
                    found.append(n)
    return found


def _packages() -> list[str]:
    return sorted(p.name for p in SRC.iterdir() if (p / "__init__.py").is_file())


@pytest.mark.parametrize("package", _packages())
def test_no_private_module_of_another_package_is_imported(package: str) -> None:
    bad = {
        path.name: found
        for path in sorted((SRC / package).glob("*.py"))
        if (found := _private_imports(path, package))
    }
    assert not bad, f"softpad.{package} imports private modules of other packages: {bad}"


def test_the_checker_sees_a_private_import(tmp_path: Path) -> None:
    f = tmp_path / "m.py"
    f.write_text(
        "from softpad.sensing._objects import x\ndef f():\n    import softpad.sim._sensor\n"
        "from softpad.planning import y\nfrom softpad.box._sim import z\n"
    )
    assert _private_imports(f, "box") == ["softpad.sensing._objects", "softpad.sim._sensor"]


#: What the controller side and the box computer never load: the simulator, the FEM, the lab.
SIMULATOR_MODULES = ("softpad.sim", "softpad.fem", "softpad.harness", "softpad.trials")
_LOADED = (
    "bad = sorted(m for m in sys.modules if m.startswith({mods!r}) or m in ('mujoco', 'felupe'));"
    "print(bad, file=sys.stderr); sys.exit(5 if bad else 0)"
)


@pytest.mark.parametrize(
    "modules", ["softpad.control, softpad.planning, softpad.sensing", "softpad.box"]
)
def test_importing_the_controller_loads_no_simulator(modules: str) -> None:
    code = f"import sys, {modules};" + _LOADED.format(mods=SIMULATOR_MODULES)
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


def test_the_box_daemon_on_hardware_loads_no_simulator() -> None:
    """``softpad box serve --hardware FILE`` up to opening the GPIO lines (absent here: exit
    3) imports neither the simulator nor the FEM (the box computer installs neither)."""
    site = Path(__file__).resolve().parents[2] / "examples" / "site.toml"
    code = (
        "import sys; from softpad.cli.main import main;"
        f"rc = main(['box', 'serve', '--hardware', {str(site)!r}]); print('rc', rc);"
        + _LOADED.format(mods=SIMULATOR_MODULES)
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "rc 3" in out.stdout and "GPIO" in out.stderr, out.stdout + out.stderr
    assert out.returncode == 0, out.stderr
