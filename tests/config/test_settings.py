"""The installation file: example resolves, wrong values are named, the network policy holds."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from softpad.cli.main import main
from softpad.config import ConfigError, load_installation, parse_installation

SITE = Path(__file__).resolve().parents[2] / "examples" / "site.toml"

_CH = {"inflate_line": 1, "deflate_line": 2, "iio_device": 0, "iio_channel": 0}


def test_example_site_resolves_to_si() -> None:
    inst = load_installation(SITE)
    assert len(inst.box.channels) == 6
    w = inst.box.channels[0]
    assert (w.gpiochip, w.inflate_line, w.deflate_line) == ("/dev/gpiochip1", 12, 13)
    assert w.pressure_pa(1000) == pytest.approx(-250 + 1221)
    assert inst.pad.pitch_m == pytest.approx(0.045)
    assert inst.pad.x_m == pytest.approx(0.4)
    assert inst.thresholds.p0_pa == pytest.approx(1100)
    assert inst.thresholds.contact_threshold_pa == pytest.approx(90)
    assert inst.thresholds.max_pressure_pa == pytest.approx(3000)
    assert inst.link.listen == ("tcp/127.0.0.1:7447",)


def test_defaults_are_the_thesis_values() -> None:
    inst = parse_installation({})
    th = inst.thresholds
    assert (th.p0_pa, th.adjust_tolerance_pa, th.object_threshold_pa) == (1100, 30, 50)
    assert (th.contact_threshold_pa, th.filter_window, th.max_pressure_pa) == (90, 10, 3000)
    assert inst.pad.yaw_rad == 0 and math.isclose(inst.pad.pitch_m, 0.045)


@pytest.mark.parametrize(
    ("raw", "named"),
    [
        ({"thresholds": {"p0_kpa": "high"}}, "thresholds.p0_kpa"),
        ({"thresholds": {"max_pressure_kpa": 1.0}}, "max_pressure_kpa"),
        ({"thresholds": {"window": 0}}, "thresholds.window"),
        ({"pad": {"pitch_mm": -3.0}}, "pad.pitch_mm"),
        ({"pad": {"colour": "red"}}, "pad.colour"),
        ({"box": {"channel": [{**_CH, "inflate_line": -1}]}}, "box.channel.1.inflate_line"),
        ({"box": {"channel": [_CH, _CH]}}, "box.channel.2.inflate_line"),
        (
            {"box": {"channel": [{"inflate_line": 1, "deflate_line": 2}]}},
            "box.channel.1.iio_device",
        ),
        ({"link": {"watchdog_action": "explode"}}, "link.watchdog_action"),
        ({"link": {"listen": ["udp/1.2.3.4"]}}, "link.listen"),
        ({"gripper": {"mounting": "9/9"}}, "gripper.mounting"),
    ],
    ids=[
        "nan-p0",
        "max-below-p0",
        "window",
        "pitch",
        "unknown",
        "line",
        "dup-line",
        "no-iio",
        "action",
        "endpoint",
        "gripper",
    ],
)
def test_wrong_values_are_named(raw: dict, named: str) -> None:
    with pytest.raises(ConfigError, match=named.replace(".", r"\.")):
        parse_installation(raw)


def test_non_loopback_listen_needs_allow_remote_and_auth() -> None:
    with pytest.raises(ConfigError, match="allow_remote"):
        parse_installation({"link": {"listen": ["tcp/0.0.0.0:7447"]}})
    with pytest.raises(ConfigError, match="plain tcp"):
        parse_installation({"link": {"listen": ["tcp/0.0.0.0:7447"], "allow_remote": True}})
    with pytest.raises(ConfigError, match="no authentication"):
        parse_installation({"link": {"listen": ["tls/0.0.0.0:7447"], "allow_remote": True}})
    ok = parse_installation(
        {
            "link": {
                "listen": ["tls/192.168.7.2:7447"],
                "allow_remote": True,
                "user": "lab",
                "password_file": "/etc/softpad/password",
                "tls_certificate": "/etc/softpad/box.pem",
                "tls_private_key": "/etc/softpad/box.key",
            }
        }
    )
    assert ok.link.has_auth


def test_cli_check_prints_units_and_names_errors(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["config", "check", str(SITE)]) == 0
    out = capsys.readouterr().out
    assert "p0 1.1 kPa" in out and "pitch 45 mm" in out and "ok" in out
    bad = tmp_path / "bad.toml"
    bad.write_text("[thresholds]\nt_g_kpa = -1\n")
    assert main(["config", "check", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "thresholds.t_g_kpa" in err and len(err.strip().splitlines()) == 1
    broken = tmp_path / "broken.toml"
    broken.write_text("[pad\n")
    assert main(["config", "check", str(broken)]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_run_takes_thresholds_from_the_installation_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """t_g from the file reaches the contact detector: 2.9 kPa is never reached, so no contact."""
    import json

    site = tmp_path / "site.toml"
    site.write_text("[thresholds]\nt_g_kpa = 2.9\n")
    assert main(["run", "--objects", "object-5", "--config", str(site), "--json"]) == 1  # not held
    assert json.loads(capsys.readouterr().out)["outcome"] == "contact_not_detected"
    assert (
        main(["run", "--objects", "object-5", "--config", str(SITE), "--json", "--hold-s", "1"])
        == 0
    )
    assert json.loads(capsys.readouterr().out)["outcome"] == "held"


#: Installation files with several errors, and what ``config check`` must name of each.
_BAD_FILES = {
    # errors in two channels, the link, the thresholds and an unknown table: all five named
    "across-tables": (
        "[[box.channel]]\ninflate_line = 1\ndeflate_line = 2\niio_device = 0\niio_channel = -1\n"
        "[[box.channel]]\ninflate_line = 3\niio_device = 0\niio_channel = 1\n"
        "[link]\nwatchdog_action = 'explode'\n"
        "[thresholds]\nt_g_kpa = -1\n"
        "[nonsense]\n",
        (
            "box.channel.1.iio_channel", "box.channel.2.deflate_line", "link.watchdog_action",
            "thresholds.t_g_kpa", "unknown key nonsense", "box.inflate_valves is missing",
            "box.deflate_valves is missing", "2 channels wired for a 2 x 3 pad",
        ),
    ),
    # several bad keys in one table (and two unknown keys): each named, not only the first
    "within-a-table": (
        "[box]\nsample_rate_hz = -5\nambient_pressure_kpa = 5000\n"
        "[pad]\nrows = 0\npitch_mm = 0.045\ncolour = 'red'\nshape = 1\n"
        "[thresholds]\np0_kpa = -1\nt_o_kpa = nan\nt_g_kpa = 99\nwindow = 0\n",
        (
            "box.sample_rate_hz", "box.ambient_pressure_kpa", "pad.rows", "pad.pitch_mm",
            "unknown key pad.colour", "unknown key pad.shape", "thresholds.p0_kpa",
            "thresholds.t_o_kpa", "thresholds.t_g_kpa", "thresholds.window",
        ),
    ),
}  # fmt: skip


@pytest.mark.parametrize("case", sorted(_BAD_FILES))
def test_cli_check_lists_every_error(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Every error of the file named, and their count."""
    text, named = _BAD_FILES[case]
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    assert main(["config", "check", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{len(named)} errors" in err, err
    for key in named:
        assert key in err, err
    assert "Traceback" not in err
