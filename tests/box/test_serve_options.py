"""softpad.box's serving policy (ServeOptions: URL with the simulator's rate, endpoints, the
real-time priority's range) and the watcher's pieces (Pacer, monitor periods, stats text),
tested without the command line."""

from __future__ import annotations

import pytest

from softpad.box import (
    SERVE_SIM_RATE_HZ,
    MonitorPeriod,
    Pacer,
    ServeOptions,
    describe_box,
    monitor_header,
    monitor_periods,
    open_box,
    stats_lines,
)
from softpad.errors import InputError


@pytest.mark.parametrize(
    ("options", "url"),
    [
        (ServeOptions(), f"sim://?rate_hz={SERVE_SIM_RATE_HZ:g}"),
        (ServeOptions("sim://?seed=2", rate_hz=250.0), "sim://?seed=2&rate_hz=250"),
        (ServeOptions("sim://?rate_hz=200"), "sim://?rate_hz=200"),
        (ServeOptions(hardware="site.toml"), "hw://site.toml"),
        (ServeOptions("zenoh://127.0.0.1:7447"), "zenoh://127.0.0.1:7447"),
    ],
    ids=["default-rate", "rate-given", "url-rate", "hardware", "other-backend"],
)
def test_the_served_url_carries_one_rate(options: ServeOptions, url: str) -> None:
    assert options.url == url


def test_a_rate_given_twice_is_refused() -> None:
    with pytest.raises(InputError, match="give the rate once"):
        _ = ServeOptions("sim://?rate_hz=200", rate_hz=100.0).url


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (ServeOptions(rt_priority=0), "--rt-priority must be from 1 to 99, got 0"),
        (ServeOptions(rt_priority=100), "--rt-priority must be from 1 to 99, got 100"),
        (ServeOptions(port=70000), "--port must be within 1..65535, got 70000"),
    ],
    ids=["priority-low", "priority-high", "port"],
)
def test_bad_serving_options_name_the_value_and_limit(options: ServeOptions, message: str) -> None:
    with pytest.raises(InputError, match=message):
        options.daemon()


def test_a_port_becomes_a_loopback_endpoint() -> None:
    opts = ServeOptions(port=7460)
    link = opts.link(opts.installation())
    assert link.listen == ("tcp/127.0.0.1:7460",)
    assert opts.served == f"the simulated box sim://?rate_hz={SERVE_SIM_RATE_HZ:g}"


def test_only_a_simulated_box_opened_here_is_paced() -> None:
    assert Pacer("sim://").on and not Pacer("sim://?realtime=0").on
    assert not Pacer("zenoh://127.0.0.1:7447").on
    assert describe_box("zenoh://127.0.0.1:7447") == "the served box at zenoh://127.0.0.1:7447"
    assert describe_box("sim://", paced=False) == "the simulated box sim:// (unpaced)"


def test_monitor_periods_count_frames_and_show_the_pads_modules() -> None:
    with open_box("sim://?rate_hz=100&realtime=0") as box:
        periods = list(monitor_periods(box, Pacer("sim://?realtime=0"), 4, 0.05, count=12))
    assert [p.seq for p in periods] == [5, 10, 12]  # every 5 frames, and the last
    assert all(p.lost == 0 and p.latency_ms == (None, None) for p in periods)
    d = periods[0].to_dict()
    assert len(d["pressures_kpa"]) == 4 and d["latency_p50_ms"] is None
    assert len(periods[0].line().split()) == len(monitor_header(4).split())


def test_a_period_line_shows_the_latency_in_ms() -> None:
    with open_box("sim://?realtime=0") as box:
        frame = box.read()
    line = MonitorPeriod(7, frame, 2, 1000.0, (0.25, 1.5), 3).line().split()
    assert line[0] == "7" and line[-3:] == ["0.25", "1.50", "3"]


def test_stats_read_as_text() -> None:
    d = {
        "achieved_rate_hz": 999.5, "target_rate_hz": 1000.0, "period_p99_s": 0.0011,
        "jitter_std_s": 2e-5, "dropped_samples": 0, "malformed_payloads": 1,
        "safety_vents": 0, "watchdog_trips": 2, "refused_commands": 0, "controller": None,
        "frames": 10, "seq": 10,
    }  # fmt: skip
    lines = stats_lines(d)
    assert lines[0] == "rate      999.5 Hz achieved of 1000 Hz"
    assert "p99 1.100 ms" in lines[1] and "p50 -" in lines[1]
    assert lines[-2].startswith("safety    0 vents, 2 watchdog trips")
    assert lines[-1] == "control   nobody; frames 10, seq 10"
