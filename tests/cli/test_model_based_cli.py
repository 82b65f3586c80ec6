"""``softpad plan --planner`` and ``--objects-file`` of ``trials``/``compare``: choices and
bad input (the trials themselves run in tests/trials)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from softpad import thesis

BANANA = "0,0.124,0.078,0.109,0,0"
DATA = Path(__file__).parents[2] / "src" / "softpad" / "data" / "object_sets"


def test_plan_with_the_model_based_planner(cli) -> None:
    code, out, _ = cli("plan", "--delta", BANANA, "--planner", "model-based", "--json")
    assert code == 0
    (obj,) = json.loads(out)["objects"]
    assert obj["modules"] == [2, 3, 4]
    assert obj["rule"].startswith("model-based")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--planner", "magic"], "--planner must be one of"),
        (["--gripper", "5/5"], "--gripper must be one of"),
    ],
)
def test_plan_refuses_unknown_planner_or_mounting(cli, args, message) -> None:
    code, _, err = cli("plan", "--delta", BANANA, *args)
    assert code == 2 and message in err and "Traceback" not in err


def test_objects_file_gives_the_sets_objects_on_the_pad() -> None:
    from softpad.cli._trials import select_objects
    from softpad.design import load_object_set

    path = DATA / "ycb-eval.toml"
    specs = select_objects(None, str(path))
    objects = load_object_set(path)
    assert [s.name for s in specs] == list(objects.names)
    assert len(specs) >= 10
    pad = (
        thesis.PROTOTYPE_COLS * thesis.MODULE_PITCH_M,
        thesis.PROTOTYPE_ROWS * thesis.MODULE_PITCH_M,
    )
    for spec, obj in zip(specs, objects.objects, strict=True):
        assert spec.gripper == objects.mounting(obj)
        # the file's offsets are at most 10 mm from the pad's centre
        assert abs(spec.placement.x_m - pad[0] / 2) < 0.03
    (one,) = select_objects("ycb-026-sponge", str(path))
    assert one.name == "ycb-026-sponge" and one.mass_kg == pytest.approx(6.2e-3)


def test_dev_and_eval_halves_are_disjoint_and_at_least_twenty() -> None:
    from softpad.design import load_object_set

    dev, ev = (set(load_object_set(DATA / f"ycb-{h}.toml").names) for h in ("dev", "eval"))
    assert not dev & ev and len(dev | ev) >= 20


@pytest.mark.parametrize("command", ["trials", "compare"])
def test_objects_file_errors_are_clear(cli, tmp_path, command) -> None:
    code, _, err = cli(command, "--objects-file", str(tmp_path / "none.toml"), "--seeds", "0")
    assert code == 2 and "not found" in err and "Traceback" not in err
    path = DATA / "ycb-eval.toml"
    code, _, err = cli(command, "--objects-file", str(path), "--objects", "banana", "--seeds", "0")
    assert code == 2 and "not in" in err and "ycb-026-sponge" in err


def test_the_evaluation_set_is_what_its_script_generates(tmp_path) -> None:
    import runpy

    script = Path(__file__).parents[2] / "examples" / "make_eval_objects.py"
    runpy.run_path(str(script), run_name="not_main")["main"](str(tmp_path))
    for half in ("ycb-dev", "ycb-eval"):
        generated = (tmp_path / f"{half}.toml").read_text(encoding="utf-8")
        assert generated == (DATA / f"{half}.toml").read_text(encoding="utf-8")
