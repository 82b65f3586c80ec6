"""Every public name in every sub-package's __all__ resolves, and import softpad stays light."""

from __future__ import annotations

import importlib
import pkgutil
import subprocess
import sys

import pytest

import softpad

SUBPACKAGES = sorted(
    m.name for m in pkgutil.iter_modules(softpad.__path__) if m.ispkg and not m.name.startswith("_")
)


@pytest.mark.parametrize("name", SUBPACKAGES)
def test_all_names_resolve(name: str) -> None:
    module = importlib.import_module(f"softpad.{name}")
    exported = getattr(module, "__all__", None)
    if exported is None:
        pytest.skip(f"softpad.{name} has no public API yet")
    missing = [n for n in exported if not hasattr(module, n)]
    assert missing == []


def test_planner_import_does_not_load_heavy_libraries() -> None:
    code = (
        "import sys, softpad.planning, softpad.cli.main;"
        "heavy = [m for m in ('matplotlib', 'felupe', 'mujoco', 'scipy') if m in sys.modules];"
        "print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
