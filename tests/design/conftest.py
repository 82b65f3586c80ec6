"""Fixtures of the design tests."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def design_keys() -> frozenset[str]:
    """Keys every design of a sweep's JSON (``SweepResult.to_dict()["designs"]``) carries."""
    return frozenset(
        {
            "name",
            "baseline",
            "rows",
            "cols",
            "pitch_mm",
            "success",
            "success_interval",
            "min_detectable_mass_g",
            "detection_delay_ms",
        }
    )
