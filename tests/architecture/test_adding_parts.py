"""docs/architecture.md's three one-file parts, installed from the page and run by name.

The python blocks of "Parts by name" are written as the modules they name
(``my_parts/NAME.py``), their toml blocks become the entry points of an installed
distribution (a ``.dist-info``, as ``pip install`` leaves it), and each part is then found by
name through the registries and the command line.
"""

from __future__ import annotations

import json
import re
import sys
import tomllib
from collections.abc import Iterator
from pathlib import Path

import pytest

from softpad.control import ROBOT_REGISTRY, make_robot
from softpad.layout import PadLayout
from softpad.planning import PLANNER_REGISTRY, make_planner, plan_grasps
from softpad.sensing import CONTACT_DETECTOR_REGISTRY, make_contact_detector

DOC = Path(__file__).resolve().parents[2] / "docs" / "architecture.md"
PARTS = {"max-rise": CONTACT_DETECTOR_REGISTRY, "heaviest-first": PLANNER_REGISTRY}


def _section() -> str:
    text = DOC.read_text(encoding="utf-8")
    return text.split("## Parts by name", 1)[1].split("\n## ", 1)[0]


def _install(root: Path) -> None:
    """The page's files under ``root/my_parts`` and their entry points in a dist-info."""
    section = _section()
    files = re.findall(r"`my_parts/(\w+\.py)`[^\n]*:\n\n```python\n(.*?)```", section, re.S)
    assert [f for f, _ in files] == ["max_rise.py", "heaviest_first.py", "capped.py"]
    package = root / "my_parts"
    package.mkdir()
    (package / "__init__.py").write_text("")
    for name, code in files:
        (package / name).write_text(code)
    groups: dict[str, dict[str, str]] = {}
    for block in re.findall(r"```toml\n(.*?)```", section, re.S):
        for group, eps in tomllib.loads(block)["project"]["entry-points"].items():
            groups.setdefault(group, {}).update(eps)
    info = root / "my_parts-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: my-parts\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(
        "".join(
            f"[{g}]\n" + "".join(f"{k} = {v}\n" for k, v in eps.items())
            for g, eps in groups.items()
        )
    )


@pytest.fixture
def installed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    _install(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    yield
    for name, registry in {**PARTS, "capped": ROBOT_REGISTRY}.items():
        registry.unregister(name)
    for module in [m for m in sys.modules if m.split(".")[0] == "my_parts"]:
        del sys.modules[module]


def test_every_command_lists_the_parts(installed: None) -> None:
    from softpad.cli.main import build_parser

    sub = next(a for a in build_parser()._actions if a.dest == "command").choices
    for command in ("run", "trials", "compare", "design"):
        text = sub[command].format_help()
        assert "max-rise" in text and "heaviest-first" in text, command
    assert "capped://" in sub["run"].format_help()
    assert "heaviest-first" in sub["plan"].format_help()


def test_the_detector_alarms_on_one_frame_over_twice_t_g(installed: None) -> None:
    detector = make_contact_detector("max-rise", 100.0, PadLayout(), contact_threshold_pa=90.0)
    detector.reset([1100.0] * 6)
    assert not detector.update([1100.0 + 179.0] * 6)  # 2 t_g = 180 Pa
    assert detector.update([1100.0, 1100.0 + 181.0, 1100.0, 1100.0, 1100.0, 1100.0])
    assert detector.triggered_modules == (2,)


def test_the_planner_takes_the_heaviest_first(installed: None) -> None:
    two = [100.0, 0.0, 300.0, 0.0, 0.0, 0.0]  # objects on modules 1 and 3, Pa
    layout = PadLayout()
    thesis = plan_grasps(two, layout)
    plans = make_planner("heaviest-first").plan(two, [(1,), (3,)], layout)
    assert [p.modules for p in thesis] == [(1,), (3,)]
    assert [p.modules for p in plans] == [(3,), (1,)] and plans == thesis[::-1]


def test_the_robot_runs_a_grasp_slower(installed: None, capsys: pytest.CaptureFixture[str]) -> None:
    """``run --robot capped://?max_speed_mps=0.03`` holds object 5; the fingers travelled
    after the touch at the capped speed (travel over delay, 3 % for the frame's quantisation)
    where the thesis's approach is 0.05 m/s."""
    from softpad.box import open_box
    from softpad.cli.main import main

    with open_box("sim://") as box:
        assert type(make_robot("capped://?max_speed_mps=0.02", box=box)).__name__ == "CappedRobot"
    args = ["run", "--robot", "capped://?max_speed_mps=0.03", "--objects", "object-5"]
    assert main([*args, "--hold-s", "0", "--json"]) == 0
    grasp = json.loads(capsys.readouterr().out)["grasps"][0]
    assert grasp["outcome"] == "held"
    assert grasp["finger_travel_m"] / grasp["contact_delay_s"] == pytest.approx(0.03, rel=0.03)
    assert main(["run", "--robot", "capped://?max_speed_mps=9", "--objects", "object-5"]) == 2
