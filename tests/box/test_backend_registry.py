"""Box back-ends on softpad.registry.Registry: listed, opened by URL (hw:// the real box among
them), served by 'softpad box serve --box URL' with the services registered for the scheme."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from softpad.box import (
    BOX_BACKENDS,
    FakeValveLines,
    HardwareBox,
    available_box_backends,
    open_box,
    register_backend,
    served_services,
)
from softpad.errors import InputError
from softpad.harness import SIMULATION_OPS
from softpad.registry import Registry

SITE = """
[pad]
rows = 1
cols = 2
[box]
iio_root = "{root}"
sample_rate_hz = 1000.0
inflate_valves = "normally_closed"
deflate_valves = "normally_closed"
[[box.channel]]
gpiochip = "/dev/gpiochip9"
inflate_line = 0
deflate_line = 1
iio_device = 0
iio_channel = 0
[[box.channel]]
gpiochip = "/dev/gpiochip9"
inflate_line = 2
deflate_line = 3
iio_device = 0
iio_channel = 1
"""


def _site(tmp_path: Path) -> Path:
    dev = tmp_path / "iio" / "iio:device0"
    dev.mkdir(parents=True)
    for k, count in enumerate([1100, 1200]):
        (dev / f"in_voltage{k}_raw").write_text(f"{count}\n")
    (dev / "in_voltage_scale").write_text("0.439453125\n")
    site = tmp_path / "site.toml"
    site.write_text(SITE.format(root=tmp_path / "iio"))
    return site


def test_backends_are_one_registry_like_the_other_parts() -> None:
    assert isinstance(BOX_BACKENDS, Registry) and BOX_BACKENDS.group == "softpad.box_backends"
    assert available_box_backends() == BOX_BACKENDS.names()
    assert {"sim", "zenoh", "hw", "replay"} <= set(available_box_backends())


def test_a_registered_backend_is_listed_and_opened_by_url() -> None:
    seen = []

    def open_loop(location: str, options: dict[str, str]):
        seen.append((location, options))
        return open_box("sim://?seed=2")

    register_backend("Loop", open_loop, "a test back-end")
    try:
        assert "loop" in available_box_backends()
        with open_box("loop://here?x=1") as box:
            assert box.channels == 8
        assert seen == [("here", {"x": "1"})]
    finally:
        BOX_BACKENDS.unregister("loop")
    with pytest.raises(InputError, match=r"unknown box URL scheme 'loop'.*available: sim://"):
        open_box("loop://here")


def test_the_real_box_is_a_backend_chosen_by_its_installation_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    site = _site(tmp_path)
    # the GPIO lines in memory (the box computer's libgpiod is not here)
    monkeypatch.setattr("softpad.box._hardware.GpiodValveLines", FakeValveLines)
    with open_box(f"hw://{site}") as box:
        assert isinstance(box, HardwareBox) and box.channels == 2
        assert box.simulated is False
        np.testing.assert_allclose(box.read().pressures_pa, [1100.0, 1200.0])
        assert served_services(f"hw://{site}", box) == {}


@pytest.mark.parametrize(
    ("url", "match"),
    [
        ("hw://", "hw:// needs the installation file"),
        ("hw:///site.toml?rate=1", "hw:// takes no options"),
        ("hw:///no/such/site.toml", "/no/such/site.toml"),
    ],
    ids=["no-file", "options", "missing-file"],
)
def test_a_bad_hw_url_is_an_input_error(url: str, match: str) -> None:
    with pytest.raises(InputError, match=match):
        open_box(url)


def test_the_simulator_serves_its_world_and_robot_and_nothing_else_does() -> None:
    with open_box("sim://?seed=1") as box:
        assert set(served_services("sim://?seed=1", box)) == set(SIMULATION_OPS)


def test_box_serve_serves_any_backend_by_url(free_port, tmp_path: Path) -> None:
    from softpad.cli._box import _daemon_for
    from softpad.cli.main import build_parser

    port = free_port()
    args = build_parser().parse_args(
        ["box", "serve", "--box", "sim://?seed=1", "--port", f"{port}"]
    )
    with _daemon_for(args) as daemon:
        assert set(daemon.services) == set(SIMULATION_OPS)
    site = _site(tmp_path)
    args = build_parser().parse_args(["box", "serve", "--box", f"hw://{site}", "--port", f"{port}"])
    with pytest.raises(Exception, match=r"(?i)gpio"):
        _daemon_for(args)  # the real lines are asked for (none on this machine)
