"""Release hygiene: one version source, the licence file, ``python -m softpad``, the changelog."""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

import softpad

ROOT = Path(__file__).resolve().parents[1]


def test_the_version_has_one_source() -> None:
    """pyproject.toml reads ``softpad.__version__``; it states no version of its own."""
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in pyproject["project"]
    assert "version" in pyproject["project"]["dynamic"]
    attr = pyproject["tool"]["setuptools"]["dynamic"]["version"]["attr"]
    assert attr == "softpad.__version__"
    assert re.fullmatch(r"\d+\.\d+\.\d+", softpad.__version__)


def test_the_licence_is_shipped() -> None:
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert pyproject["project"]["license"] == "MIT"
    assert pyproject["project"]["license-files"] == ["LICENSE"]
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License") and "SoftPad developers" in text


def test_python_m_softpad_runs_the_command() -> None:
    out = subprocess.run(
        [sys.executable, "-W", "error", "-m", "softpad", "--version"],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == f"softpad {softpad.__version__}" and not out.stderr


def test_the_changelog_has_the_version() -> None:
    """CHANGELOG.md (Keep a Changelog) has a dated section for ``softpad.__version__``, an
    Unreleased section above it, and its versions newest first."""
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert "keepachangelog.com" in text
    versions = re.findall(r"^## \[(\d+\.\d+\.\d+)\] - (\d{4}-\d{2}-\d{2})$", text, flags=re.M)
    assert versions, "no '## [X.Y.Z] - YYYY-MM-DD' sections"
    assert versions[0][0] == softpad.__version__, (versions[0], softpad.__version__)
    numbers = [tuple(int(n) for n in v.split(".")) for v, _ in versions]
    assert numbers == sorted(numbers, reverse=True)
    assert [d for _, d in versions] == sorted((d for _, d in versions), reverse=True)
    assert text.index("## [Unreleased]") < text.index(f"## [{softpad.__version__}]")
