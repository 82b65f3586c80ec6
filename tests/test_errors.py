"""CheckedFields: limits stated by the field annotations."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from softpad.errors import CheckedFields, Count, InputError, NonNegative, Positive


@dataclass(frozen=True)
class _Params(CheckedFields, what="demo"):
    rate_hz: Positive = 1.0
    offset: float = -1.0
    margin: NonNegative = 0.0
    reads: Count = 1


@dataclass(frozen=True)
class _MoreParams(_Params):
    limit: Positive = 2.0

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.limit < self.rate_hz:
            raise InputError("limit below rate")


def test_valid_and_unchecked_fields() -> None:
    assert _Params(offset=-5.0).offset == -5.0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"rate_hz": 0.0}, "demo rate_hz must be a positive number, got 0.0"),
        ({"rate_hz": float("nan")}, "demo rate_hz must be a positive number"),
        ({"margin": -1.0}, "demo margin must be a number >= 0, got -1.0"),
        ({"reads": 0}, "demo reads must be an integer >= 1, got 0"),
        ({"reads": 1.5}, "demo reads must be an integer >= 1, got 1.5"),
    ],
)
def test_limits(kwargs: dict[str, float], message: str) -> None:
    with pytest.raises(InputError, match=message.replace("(", r"\(")):
        _Params(**kwargs)


def test_subclass_inherits_what_and_adds_checks() -> None:
    with pytest.raises(InputError, match="demo limit must be a positive number"):
        _MoreParams(limit=-1.0)
    with pytest.raises(InputError, match="limit below rate"):
        _MoreParams(rate_hz=3.0)
