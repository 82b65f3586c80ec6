"""Sweeps on a local Dask cluster (loopback), the on-disk cache, resuming."""

from __future__ import annotations

from pathlib import Path

import pytest

from softpad.design import (
    THESIS_DESIGN,
    PadDesign,
    ResultCache,
    TrialOptions,
    check_scheduler_address,
    design_sweep,
    object_set_from_dict,
)
from softpad.design import _cache as cache_module
from softpad.errors import InputError

pytestmark = pytest.mark.fem

BANANA = object_set_from_dict(
    {
        "schema": "softpad-object-set/1",
        "name": "b",
        "object": [{"name": "banana", "catalogue": "banana"}],
    }
)
OPTIONS = TrialOptions(hold_s=0.5)


def test_cache_key_follows_inputs_and_code(monkeypatch: pytest.MonkeyPatch) -> None:
    k = ResultCache.key("fem", {"a": 1})
    assert k == ResultCache.key("fem", {"a": 1})
    assert k != ResultCache.key("fem", {"a": 2})
    assert k != ResultCache.key("trials", {"a": 1})
    monkeypatch.setattr(cache_module, "code_version", lambda: "another version")
    assert k != ResultCache.key("fem", {"a": 1})


def test_cache_round_trip_and_unreadable_entries(tmp_path: Path) -> None:
    c = ResultCache(tmp_path)
    assert c.get("fem", "k") is None
    c.put("fem", "k", {"x": [1, 2]})
    assert c.get("fem", "k") == {"x": [1, 2]} and c.count("fem") == 1
    (tmp_path / "fem" / "k.json").write_text("{broken")
    assert c.get("fem", "k") is None  # recomputed, not an error


def test_sweep_resumes_from_the_cache(tmp_path: Path) -> None:
    """An interrupted sweep (one result lost) recomputes only that task, and gives the same
    table; the thesis's pad is added as the baseline."""
    thin = PadDesign(thickness_m=0.001)
    seen: list[tuple[int, int]] = []
    kwargs = dict(quick=True, workers=1, cache=ResultCache(tmp_path))
    first = design_sweep(
        [thin], BANANA, OPTIONS, (0,), progress=lambda d, t, w: seen.append((d, t)), **kwargs
    )
    assert first.meta["computed"] == 4 and first.meta["cached"] == 0  # 2 FEM + 2 trial tasks
    assert seen[-1] == (4, 4)
    assert {r.design.name for r in first.rows} == {THESIS_DESIGN.name, thin.name}
    lost = sorted((tmp_path / "trials").glob("*.json"))[0]
    lost.unlink()
    again = design_sweep([thin], BANANA, OPTIONS, (0,), **kwargs)
    assert again.meta["computed"] == 1 and again.meta["cached"] == 3
    assert again.to_dict()["designs"] == first.to_dict()["designs"]
    third = design_sweep([thin], BANANA, OPTIONS, (0,), **kwargs)
    assert third.meta["computed"] == 0 and third.meta["workers"] == 0  # no cluster started


@pytest.mark.parametrize(
    "address",
    [
        "tcp://10.0.0.1:8786",
        "tcp://0.0.0.0:8786",
        "tls://127.0.0.1:8786",
        "127.0.0.1:8786",
        "tcp://127.0.0.1:0",
    ],
    ids=["lan", "any", "tls", "no-scheme", "port-0"],
)
def test_only_loopback_schedulers(address: str) -> None:
    with pytest.raises(InputError, match=r"127\.0\.0\.1"):
        check_scheduler_address(address)


def test_loopback_scheduler_address_is_normalised() -> None:
    assert check_scheduler_address("tcp://localhost:8786") == "tcp://127.0.0.1:8786"
