"""A zenoh client's connect timeout follows the timeout its caller asked for."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from typing import Any

import pytest

from softpad.box import ConnectionLost, open_box
from softpad.box import _zenoh as zenoh_box
from softpad.box._link import DEFAULT_CONNECT_TIMEOUT_S, session_config
from softpad.errors import InputError

pytest.importorskip("zenoh")


def _connect_ms(config: Any) -> int:
    return int(json.loads(config.get_json("connect/timeout_ms")))


def test_session_config_writes_the_asked_connect_timeout() -> None:
    assert _connect_ms(session_config("client", connect=("tcp/127.0.0.1:1",))) == 3000
    assert DEFAULT_CONNECT_TIMEOUT_S == 3.0
    for asked_s, ms in ((0.25, 250), (1.5, 1500), (0.0004, 1), (3600.0, 3_600_000)):
        config = session_config("client", connect=("tcp/127.0.0.1:1",), connect_timeout_s=asked_s)
        assert _connect_ms(config) == ms, asked_s


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, -math.inf, 3601.0, True, "1"])
def test_a_connect_timeout_out_of_range_is_refused_naming_it_and_the_limit(bad: Any) -> None:
    with pytest.raises(InputError) as info:
        session_config("client", connect=("tcp/127.0.0.1:1",), connect_timeout_s=bad)
    message = str(info.value)
    assert repr(bad) in message and "more than 0 s" in message and "3600 s" in message


def _recorded(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Connect timeouts (ms) of the configs that ZenohBox builds from now on."""
    seen: list[int] = []

    def record(*args: Any, **kwargs: Any) -> Any:
        config = session_config(*args, **kwargs)
        seen.append(_connect_ms(config))
        return config

    monkeypatch.setattr(zenoh_box, "session_config", record)
    return seen


@pytest.mark.parametrize(("query", "ms"), [("?timeout_s=0.2", 200), ("?timeout_s=0.5", 500)])
def test_a_zenoh_url_s_timeout_bounds_its_connect(
    monkeypatch: pytest.MonkeyPatch, free_port: Callable[[], int], query: str, ms: int
) -> None:
    """Nobody listens at the port: the client gives up with the URL's timeout as its
    connect timeout (checked on the zenoh config it opened, not on the clock)."""
    seen = _recorded(monkeypatch)
    with pytest.raises(ConnectionLost, match="cannot connect"):
        open_box(f"zenoh://127.0.0.1:{free_port()}{query}")
    assert seen == [ms]


def test_a_long_timeout_keeps_the_three_second_connect(
    monkeypatch: pytest.MonkeyPatch, free_port: Callable[[], int]
) -> None:
    """The default (5 s) and longer timeouts connect within today's 3 s, as before."""
    seen = _recorded(monkeypatch)
    monkeypatch.setattr(zenoh_box, "DEFAULT_CONNECT_TIMEOUT_S", 0.2)  # fail fast, same path
    with pytest.raises(ConnectionLost):
        zenoh_box.ZenohBox("127.0.0.1", free_port(), timeout_s=60.0)
    assert seen == [200]
    assert zenoh_box.DEFAULT_TIMEOUT_S > DEFAULT_CONNECT_TIMEOUT_S
