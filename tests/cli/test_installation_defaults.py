"""``--config FILE.toml`` on every command: the installation file's values are the defaults."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from softpad.cli._installation import OWN_CONFIG, leaf_parsers
from softpad.cli.main import build_parser, main

BANANA = "0,0.124,0.078,0.109,0,0"  # kPa; module 3 rises 0.078 kPa


def _plan(capsys: pytest.CaptureFixture[str], *extra: str) -> list[list[int]]:
    assert main(["plan", "--delta", BANANA, "--json", *extra]) == 0
    return [o["modules"] for o in json.loads(capsys.readouterr().out)["objects"]]


def test_every_command_takes_an_installation_file() -> None:
    missing = [
        p.prog
        for p in leaf_parsers(build_parser())
        if p.prog != "softpad" and "--config" not in p._option_string_actions
    ]
    assert missing == []


def test_the_file_sets_the_default_and_the_command_line_wins(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    site = tmp_path / "site.toml"
    site.write_text("[thresholds]\nt_o_kpa = 0.1\nt_g_kpa = 0.15\n")  # t_g never below t_o
    assert _plan(capsys) == [[2, 3, 4]]  # the seed's t_o = 0.05 kPa
    assert _plan(capsys, "--config", str(site)) == [[2, 4]]  # 0.078 < 0.1: module 3 is out
    assert _plan(capsys, "--config", str(site), "--threshold-kpa", "0.05") == [[2, 3, 4]]


def test_the_box_link_of_the_file_is_the_default_box(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], free_port
) -> None:
    port = free_port()
    site = tmp_path / "site.toml"
    site.write_text(f'[link]\nconnect = ["tcp/127.0.0.1:{port}"]\n')
    code = main(["box", "read", "--count", "1", "--config", str(site)])  # zenoh://...:port
    assert code == 3 and f"127.0.0.1:{port}" in capsys.readouterr().err  # nobody serves there


def test_a_wrong_file_is_named_with_exit_2(tmp_path: Path, capsys) -> None:
    site = tmp_path / "site.toml"
    site.write_text("[thresholds]\nt_o_kpa = -1\n")
    assert main(["plan", "--delta", BANANA, "--config", str(site)]) == 2
    err = capsys.readouterr().err
    assert "t_o_kpa" in err and "-1" in err and err.count("\n") == 1


def test_commands_with_their_own_configuration_are_left_alone() -> None:
    progs = {p.prog for p in leaf_parsers(build_parser())}
    assert set(OWN_CONFIG) <= progs
