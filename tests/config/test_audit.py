"""``softpad config check`` and ``box serve`` on the files and wiring of a lab installation
(issue 49): what passed before and must not, every error of a file in one pass."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from softpad.cli.main import main
from softpad.config import ConfigError, load_installation, parse_installation

_CERT = "-----BEGIN CERTIFICATE-----\nMIIB\n-----END CERTIFICATE-----\n"
_KEY = "-----BEGIN PRIVATE KEY-----\nMIIE\n-----END PRIVATE KEY-----\n"


def _site(path: Path, **link: Any) -> Path:
    lines = ["[link]"] + [f"{k} = {json.dumps(v)}" for k, v in link.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


def _pki(tmp_path: Path) -> dict[str, str]:
    (tmp_path / "box.pem").write_text(_CERT)
    (tmp_path / "box.key").write_text(_KEY)
    (tmp_path / "box.key").chmod(0o600)
    (tmp_path / "ca.pem").write_text(_CERT)
    return {
        k: str(tmp_path / v) for k, v in (("cert", "box.pem"), ("key", "box.key"), ("ca", "ca.pem"))
    }


def _password(tmp_path: Path, text: str, mode: int = 0o600) -> str:
    p = tmp_path / "users"
    p.write_text(text)
    p.chmod(mode)
    return str(p)


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("", "is empty"),
        ("  \n\t\n", "is empty"),
        ("just-a-password-here\n", "no user:password line"),
        ("robot:\n", "no user:password line"),
        ("other:a-long-password-1\n", "no line for link.user 'robot'"),
    ],
    ids=["empty", "whitespace", "bare-line", "no-password", "other-user"],
)
def test_a_password_file_that_would_turn_auth_off_is_refused(
    tmp_path: Path, text: str, named: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """Before: ``config check`` printed ok and ``box serve`` started; zenoh took an empty
    dictionary as no authentication (a client with only the CA certificate took control)."""
    from softpad.box._credentials import daemon_auth

    site = _site(
        tmp_path / "site.toml",
        listen=["tcp/127.0.0.1:7447"],
        user="robot",
        password_file=_password(tmp_path, text),
    )
    assert main(["config", "check", str(site)]) == 2
    assert named in capsys.readouterr().err
    with pytest.raises(ConfigError, match=named):
        daemon_auth(load_installation(site).link)


def test_a_missing_password_file_is_refused(tmp_path: Path, capsys) -> None:
    site = _site(tmp_path / "s.toml", user="robot", password_file=str(tmp_path / "nope"))
    assert main(["config", "check", str(site)]) == 2
    assert "cannot be read" in capsys.readouterr().err


def test_a_readable_password_file_and_a_short_password_are_warned_about(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    site = _site(
        tmp_path / "s.toml", user="robot", password_file=_password(tmp_path, "robot:pw\n", 0o644)
    )
    assert main(["config", "check", str(site)]) == 0
    err = capsys.readouterr().err
    assert "readable by other users" in err and "mode 644" in err
    assert "shorter than 12 characters" in err


@pytest.mark.parametrize(
    ("keys", "named"),
    [
        (lambda p: {"tls_certificate": p["key"], "tls_private_key": p["cert"]}, "swapped"),
        (lambda p: {"tls_certificate": p["cert"], "tls_private_key": p["ca"]}, "not a PEM private key"),
        (lambda p: {"tls_certificate": p["cert"] + ".gone", "tls_private_key": p["key"]}, "cannot be read"),
        (lambda p: {}, "tls_certificate is not set"),
    ],
    ids=["swapped", "key-is-a-certificate", "missing-certificate", "tls-without-certificate"],
)  # fmt: skip
def test_tls_files_that_cannot_work_are_refused(
    tmp_path: Path, keys: Any, named: str, capsys: pytest.CaptureFixture[str]
) -> None:
    site = _site(tmp_path / "s.toml", listen=["tls/127.0.0.1:7447"], **keys(_pki(tmp_path)))
    assert main(["config", "check", str(site)]) == 2
    assert named in capsys.readouterr().err


def test_a_plain_tcp_endpoint_beside_mutual_tls_is_refused(tmp_path: Path) -> None:
    p = _pki(tmp_path)
    link = {
        "tls_certificate": p["cert"],
        "tls_private_key": p["key"],
        "tls_root_ca": p["ca"],
    }
    with pytest.raises(ConfigError, match="plain tcp/ beside mutual TLS"):
        parse_installation(
            {"link": {"listen": ["tls/127.0.0.1:7447", "tcp/127.0.0.1:7448"], **link}}
        )
    assert parse_installation({"link": {"listen": ["tls/127.0.0.1:7447"], **link}})


@pytest.mark.parametrize("watchdog_s", [60.0, 0.0, 0.01, 5.5], ids=["60s", "0s", "10ms", "5.5s"])
def test_a_watchdog_out_of_its_sane_range_is_refused(watchdog_s: float) -> None:
    with pytest.raises(ConfigError, match=r"link\.watchdog_s must be within 0\.05\.\.5"):
        parse_installation({"link": {"watchdog_s": watchdog_s}})


def _channel(k: int, **over: Any) -> dict[str, Any]:
    return {
        "gpiochip": "/dev/gpiochip1",
        "inflate_line": 2 * k,
        "deflate_line": 2 * k + 1,
        "iio_device": 0,
        "iio_channel": k,
        **over,
    }


_KINDS = {"inflate_valves": "normally_closed", "deflate_valves": "normally_open"}


@pytest.mark.parametrize(
    ("channels", "named"),
    [
        ([_channel(0), _channel(1, inflate_line=0), *map(_channel, range(2, 6))], "drive two valves"),
        ([_channel(0), _channel(1, iio_channel=0), *map(_channel, range(2, 6))], "two sensors"),
        ([_channel(k) for k in range(4)], "4 channels wired for a 2 x 3 pad"),
        ([_channel(0, gain=-1.0), *map(_channel, range(1, 6))], "box.channel.1.gain must be > 0"),
        ([_channel(0, gpiochip="gpiochip1"), *map(_channel, range(1, 6))], "/dev/gpiochipN"),
    ],
    ids=["gpio-line-twice", "adc-input-twice", "four-for-six", "negative-gain", "chip-not-dev"],
)  # fmt: skip
def test_wiring_that_passed_before_is_refused(channels: list[dict], named: str) -> None:
    with pytest.raises(ConfigError, match=named):
        parse_installation({"box": {"channel": channels, **_KINDS}})


def test_one_gpio_line_named_two_ways_is_one_line() -> None:
    """``/dev/gpiochip1`` and ``/dev/./gpiochip1`` are the same chip: its line 0 on two
    valves."""
    chans = [_channel(0), _channel(1, gpiochip="/dev/./gpiochip1", inflate_line=0)]
    chans += [_channel(k) for k in range(2, 6)]
    with pytest.raises(ConfigError, match="drive two valves"):
        parse_installation({"box": {"channel": chans, **_KINDS}})


def test_contact_threshold_below_the_object_threshold_is_refused() -> None:
    with pytest.raises(ConfigError, match=r"t_g_kpa .* must not be below t_o_kpa"):
        parse_installation({"thresholds": {"t_o_kpa": 0.09, "t_g_kpa": 0.05}})


def test_ten_mistakes_in_three_tables_are_listed_in_one_pass(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Before: three passes (watchdog_s = 0 on the second, listen 0.0.0.0 on the third) and
    the wiring conflicts never."""
    users = _password(tmp_path, "")
    text = f"""
[box]
inflate_valves = "normally_closed"
deflate_valves = "normally_open"
ambient_pressure_kpa = 5000
[[box.channel]]
gpiochip = "/dev/gpiochip1"
inflate_line = 1
deflate_line = 2
iio_device = 0
iio_channel = 0
gain = -1.0
[[box.channel]]
gpiochip = "/dev/gpiochip1"
inflate_line = 2
deflate_line = 3
iio_device = 0
iio_channel = 0
[link]
listen = ["tcp/0.0.0.0:7447"]
watchdog_s = 0
user = "robot"
password_file = "{users}"
[thresholds]
t_o_kpa = 0.09
t_g_kpa = 0.05
window = 0
"""
    site = tmp_path / "site.toml"
    site.write_text(text)
    assert main(["config", "check", str(site)]) == 2
    err = capsys.readouterr().err
    named = [
        "box.ambient_pressure_kpa",
        "box.channel.1.gain must be > 0",
        "box.channel.2.inflate_line = 2 on /dev/gpiochip1 is already used by "
        "box.channel.1.deflate_line",
        "box.channel.2: iio:device0/in_voltage0 is already read by box.channel.1",
        "2 channels wired for a 2 x 3 pad",
        "link.watchdog_s",
        "'tcp/0.0.0.0:7447' is not on 127.0.0.1",
        "is empty: zenoh would then turn",
        "t_g_kpa (0.05 kPa) must not be below",
        "thresholds.window",
    ]
    assert "10 errors" in err, err
    for what in named:
        assert what in err, what
