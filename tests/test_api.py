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


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"lift_m": 0.0}, "execution lift_m must be a positive number, got 0.0"),
        ({"hold_s": float("nan")}, "execution hold_s must be a number >= 0, got nan"),
        ({"filter_length": 2.5}, "execution filter_length must be an integer >= 1, got 2.5"),
    ],
    ids=["positive", "non-negative", "count"],
)
def test_parameter_records_name_the_bad_field(change: dict, message: str) -> None:
    import dataclasses

    from softpad.control import ExecutionParams
    from softpad.errors import InputError

    with pytest.raises(InputError) as info:
        dataclasses.replace(ExecutionParams(), **change)
    assert str(info.value) == message
