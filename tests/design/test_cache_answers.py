"""A design run answered from the cache says so on its first line, with the cache's folder and
how to bypass it; ``--scheduler`` is asked whether or not the cache answers (issue 51)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import softpad.design
from softpad.cli.main import main
from softpad.design import TrialOptions, object_set_from_dict
from softpad.design import _dask as dask_module
from softpad.design import _sweep as sweep_module
from softpad.errors import InputError

BANANA = object_set_from_dict(
    {
        "schema": "softpad-object-set/1",
        "name": "b",
        "object": [{"name": "banana", "catalogue": "banana"}],
    }
)


class _Answered:
    """What :func:`softpad.design.design_sweep` returns, with ``cached`` tasks from the cache."""

    def __init__(self, cached: int, computed: int) -> None:
        self.meta: dict[str, Any] = {"cached": cached, "computed": computed, "wall_time_s": 0.1}

    def to_text(self) -> str:
        return " # design   (the ranked table)"

    def to_dict(self) -> dict[str, Any]:
        return {"designs": [], **self.meta}


@pytest.mark.parametrize(
    ("cached", "computed", "share"),
    [pytest.param(16, 0, "all tasks", id="all"), pytest.param(3, 13, "3 of 16 tasks", id="some")],
)
def test_a_run_answered_from_the_cache_says_so_first(
    monkeypatch: pytest.MonkeyPatch, capsys, tmp_path: Path, cached: int, computed: int, share: str
) -> None:
    monkeypatch.setattr(softpad.design, "design_sweep", lambda *a, **k: _Answered(cached, computed))
    cache = tmp_path / "cache"
    assert main(["design", "--example", "thesis-set", "--quick", "--cache", str(cache)]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith(f"softpad design: {share} answered from the cache {cache}"), first
    assert "--no-cache" in first
    assert (
        main(["design", "--example", "thesis-set", "--quick", "--cache", str(cache), "--json"]) == 0
    )
    out = capsys.readouterr()
    assert out.err.startswith(f"softpad design: {share} answered from the cache")  # JSON: stderr
    assert json.loads(out.out)["cache_dir"] == str(cache)


def test_a_run_computed_now_says_nothing_of_the_cache(monkeypatch, capsys, tmp_path) -> None:
    monkeypatch.setattr(softpad.design, "design_sweep", lambda *a, **k: _Answered(0, 16))
    assert main(["design", "--example", "thesis-set", "--quick", "--cache", str(tmp_path)]) == 0
    assert "cache" not in capsys.readouterr().out.splitlines()[0]


def test_the_scheduler_is_asked_when_the_cache_answers_everything(
    monkeypatch: pytest.MonkeyPatch, free_port
) -> None:
    """Every task in the cache, and nothing serves at the scheduler's address: the run fails
    naming it (before the fix it answered from the cache, exit 0, the scheduler never asked)."""
    monkeypatch.setattr(
        sweep_module, "_cached_results", lambda cache, tasks: {t.key: {} for t in tasks}
    )
    # nothing listens there: a 1 s connection timeout says so as well as the default 20 s
    # (the test idled 20 s; issue 50)
    client = dask_module.dask_client
    monkeypatch.setattr(
        dask_module, "dask_client", lambda s, w, timeout_s=1.0: client(s, w, timeout_s)
    )
    address = f"tcp://127.0.0.1:{free_port()}"
    with pytest.raises(InputError, match=f"no Dask scheduler answers at {address}"):
        sweep_module.run_sweep([], BANANA, TrialOptions(hold_s=0.5), (0,), scheduler=address)
