"""``softpad box read|monitor|serve``: what --help documents is what --json prints; the
monitor on a served box (latency, lost frames); ``box serve --port --rate-hz``."""

from __future__ import annotations

import itertools
import json
import re
import subprocess
import sys

import pytest

from softpad.cli.main import main


def _help(capsys: pytest.CaptureFixture[str], *argv: str) -> str:
    with pytest.raises(SystemExit):
        main([*argv, "--help"])
    return " ".join(capsys.readouterr().out.split())  # argparse wraps: one line of words


def _documented(help_text: str, lead: str) -> list[str]:
    """The field names listed after ``lead`` in a --json help text, up to the parenthesis."""
    found = re.search(re.escape(lead) + r" ([a-z0-9_, ]+) \(", help_text)
    assert found, help_text
    return [f.strip() for f in found.group(1).split(",")]


def _json_lines(out: str) -> list[dict]:
    return [json.loads(line) for line in out.splitlines() if line.strip()]


def test_box_read_json_prints_the_documented_fields(capsys) -> None:
    fields = _documented(_help(capsys, "box", "read"), "JSON lines, one per frame:")
    assert fields == ["seq", "t_s", "pressures_kpa", "supply_kpa"]
    assert main(["box", "read", "--count", "3", "--json"]) == 0
    lines = _json_lines(capsys.readouterr().out)
    assert len(lines) == 3
    for d in lines:
        assert [k for k in d if k != "schema_version"] == fields


def test_box_monitor_json_prints_the_documented_fields(capsys) -> None:
    fields = _documented(_help(capsys, "box", "monitor"), "JSON lines, one per period:")
    argv = ["box", "monitor", "--box", "sim://", "--count", "30", "--period-s", "0.1", "--json"]
    assert main(argv) == 0
    lines = _json_lines(capsys.readouterr().out)
    assert [d["seq"] for d in lines] == [10, 20, 30]  # one object per period, no text
    for d in lines:
        assert [k for k in d if k != "schema_version"] == fields
        assert len(d["pressures_kpa"]) == 6  # the 2 x 3 pad, not the box's 8 channels
        assert d["lost"] == 0 and d["latency_p50_ms"] is None  # a box opened here: no link


def test_serve_port_rate_and_a_monitor_with_latency(free_port) -> None:
    """``box serve --sim --port P --rate-hz 200`` in its own process; ``box monitor --json``
    on it sees frames 5 ms apart in box time, consecutive sequence numbers (nothing lost) and
    a measured latency (p50 <= p99)."""
    port = free_port()
    cli = [sys.executable, "-c", "import sys; from softpad.cli.main import main; sys.exit(main())"]
    serve = subprocess.Popen(
        [*cli, "box", "serve", "--sim", "--port", str(port), "--rate-hz", "200"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        assert f"tcp/127.0.0.1:{port}" in serve.stdout.readline()  # type: ignore[union-attr]
        monitor = [*cli, "box", "monitor", "--box", f"zenoh://127.0.0.1:{port}", "--json"]
        done = subprocess.run(
            [*monitor, "--count", "400", "--period-s", "0.5"],
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
    finally:
        serve.terminate()
        serve.wait(timeout=30)
    assert done.returncode == 0, done.stderr
    lines = _json_lines(done.stdout)
    assert len(lines) == 4  # 400 frames, 100 per 0.5 s of box time at 200 Hz
    assert [b["t_s"] - a["t_s"] for a, b in itertools.pairwise(lines)] == pytest.approx(
        [0.5] * 3, abs=1e-9
    )
    assert [b["seq"] - a["seq"] for a, b in itertools.pairwise(lines)] == [100] * 3
    assert all(d["lost"] == 0 for d in lines)
    assert all(0 <= d["latency_p50_ms"] <= d["latency_p99_ms"] for d in lines)


def test_serve_rate_given_twice_is_refused(capsys) -> None:
    argv = ["box", "serve", "--sim", "--box", "sim://?rate_hz=100", "--rate-hz", "200"]
    assert main(argv) == 2
    assert "--rate-hz or the URL's rate_hz" in capsys.readouterr().err
