"""Every example runs, and pins a value (scikit-fem style)."""

from __future__ import annotations

import math
import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_plan_from_increments_example(capsys: pytest.CaptureFixture[str]) -> None:
    ns = runpy.run_path(str(EXAMPLES / "plan_from_increments.py"))
    result = ns["main"]()
    # COG (1, 1) module units = (0.045, 0.045) m, rotated by 90 deg and shifted.
    assert result["x"] == pytest.approx(0.40 - 0.045)
    assert result["y"] == pytest.approx(-0.10 + 0.045)
    assert result["yaw"] == pytest.approx(math.pi / 4)
    assert "n3-diagonal-corner" in capsys.readouterr().out


def test_custom_contact_detector_example() -> None:
    """A detector written in the example, plugged into the same execution, holds object 5
    and detects sooner than the thesis's running average."""
    result = runpy.run_path(str(EXAMPLES / "custom_contact_detector.py"))["main"]()
    assert result["outcome"] == "held"
    assert result["custom_delay_s"] is not None and result["thesis_delay_s"] is not None
    assert result["custom_delay_s"] < result["thesis_delay_s"]


def test_custom_robot_example() -> None:
    """The logging adapter sees the loop's commands in the seed's order and the grasp holds."""
    result = runpy.run_path(str(EXAMPLES / "custom_robot.py"))["main"]()
    assert result["outcome"] == "held"
    kinds = [c.split()[0] for c in result["commands"]]
    first = {k: kinds.index(k) for k in ("descend", "stop")}
    assert kinds[0] == "gripper" and first["descend"] < first["stop"]
    assert "descend at 0.05 m/s" in result["commands"]


def test_pad_4x4_example() -> None:
    """Object 5 moved one module up and right on a 4 x 4 pad: the 2 x 3 plan, shifted by one
    module in x and y (the 2 x 3 pad's plan of the same object, computed here on the same pad
    model: the packaged cast-pad table is the 2 x 3 pad's, so a 4 x 4 pad has clamped modules)."""
    from softpad.harness import run_simulated

    result = runpy.run_path(str(EXAMPLES / "pad_4x4.py"))["main"]()
    small = run_simulated(["object-5"], "sim://?seed=5&pad=clamped").result.plans[0]
    assert small.modules == (1, 2, 3) and result["modules"] == (6, 7, 8)
    assert result["cog"] == pytest.approx((small.cog[0] + 1, small.cog[1] + 1), abs=0.02)
    assert result["theta"] == pytest.approx(small.theta) == pytest.approx(math.pi / 2)
    assert result["outcome"] == "held"


@pytest.mark.fem
def test_design_sweep_example(capsys: pytest.CaptureFixture[str]) -> None:
    """Four designs ranked on the blocks set; the thesis's pad is the baseline; a 35 mm module
    feels lighter masses than the 45 mm one (FEM)."""
    result = runpy.run_path(str(EXAMPLES / "design_sweep.py"))["main"]()
    designs = {d["name"]: d for d in result["designs"]}
    assert len(designs) == 4 and sum(d["baseline"] for d in designs.values()) == 1
    thesis = next(d for d in designs.values() if d["baseline"])
    assert (
        designs["3x3-35mm-t1.5-neo-hookean-p1.1"]["min_detectable_mass_g"]
        < thesis["min_detectable_mass_g"]
    )
    assert all(d["trials"] == 3 for d in designs.values())
    assert "thesis 2x3 45 mm *" in capsys.readouterr().out


def test_make_objects_example_writes_the_catalogues_sourced_objects(tmp_path: Path) -> None:
    """The generator writes Table 6.1's objects from their sources: the six Duplo objects as
    packaged, field for field (the banana, toy, limes, cylinder and charger were since
    refitted to Table 6.1's plans, issue 45: their packaged geometry is the fit's), and the
    cylinder's heavy part is the seed's 88.9 g less the 37 g tinplate shell."""
    import json

    import softpad

    out = tmp_path / "objects.json"
    main = runpy.run_path(str(EXAMPLES / "make_objects.py"), run_name="example")["main"]
    objects = {o["name"]: o for o in main(str(out))}
    assert json.loads(out.read_text())["objects"] == list(objects.values())
    packaged = Path(softpad.__file__).parent / "data" / "objects.json"
    shipped = {o["name"]: o for o in json.loads(packaged.read_text())["objects"]}
    for k in range(1, 7):
        assert objects[f"object-{k}"] == shipped[f"object-{k}"]
    cylinder = {p["name"]: p["mass_kg"] for p in objects["cylinder"]["parts"]}
    assert cylinder["heavy part"] == pytest.approx(0.0889 - 0.037, abs=1e-9)


def test_make_eval_objects_example_splits_the_ycb_set_in_halves(tmp_path: Path) -> None:
    """The generator writes the two packaged halves (tests/cli/test_model_based_cli.py checks
    them byte for byte): 10 objects each, none in both."""
    import tomllib

    runpy.run_path(str(EXAMPLES / "make_eval_objects.py"), run_name="example")["main"](
        str(tmp_path)
    )
    halves = {
        h: {o["name"] for o in tomllib.loads((tmp_path / f"{h}.toml").read_text())["object"]}
        for h in ("ycb-dev", "ycb-eval")
    }
    assert len(halves["ycb-dev"]) == len(halves["ycb-eval"]) == 10
    assert not halves["ycb-dev"] & halves["ycb-eval"]


def test_make_validation_table_example_sets_before_beside_after(tmp_path: Path) -> None:
    """One row of two validate JSONs: the old verdict, the new one with its interval, and
    the detectable fall in points (0.21 -> 21); the counts of each role below."""
    import json

    name = "Experiment 2 held, all objects"
    before = {
        "counts": {"agree": 0, "disagree": 1, "not_run": 0},
        "observations": [{"name": name, "predicted": "89/110", "agrees": False}],
    }
    counts = {"agree": 0, "disagree": 0, "undecided": 1, "not_run": 0}
    after = {
        "counts": {"validation": counts},
        "observations": [
            {
                "name": name,
                "role": "validation",
                "thesis": "52/55",
                "thesis_interval": [0.852, 0.981],
                "predicted": "91/110",
                "interval": [0.746, 0.886],
                "verdict": "undecided",
                "detectable": [0.21, None],
            }
        ],
    }
    paths = [tmp_path / "before.json", tmp_path / "after.json"]
    for path, doc in zip(paths, (before, after), strict=True):
        path.write_text(json.dumps(doc), encoding="utf-8")
    main = runpy.run_path(str(EXAMPLES / "make_validation_table.py"), run_name="example")["main"]
    out = main(*paths)
    assert (
        f"| validation | {name} | 52/55 (0.852, 0.981) | 89/110 | **no** | "
        "91/110 (0.746, 0.886) | undecided | -21/+none |"
    ) in out.splitlines()
    assert "After, validation: 0 agree, 0 disagree, 1 undecided, 0 not run." in out


def test_planner_dev_draws_example_counts_every_development_draw() -> None:
    """One draw per development object: each ends in exactly one outcome, and the 5.2 g dice
    (below the minimum detectable mass) is the one object never seen."""
    main = runpy.run_path(str(EXAMPLES / "planner_dev_draws.py"), run_name="example")["main"]
    total = main(["--seeds", "1"])
    outcomes = ("hit", "outside", "nothing_between", "narrow", "ok", "none")
    assert sum(total[k] for k in outcomes) == 10
    assert total["none"] == 1


def test_every_example_is_run_here() -> None:
    """A new script in examples/ needs its test in this file (one figure pinned)."""
    source = Path(__file__).read_text(encoding="utf-8")
    missing = [p.name for p in sorted(EXAMPLES.glob("*.py")) if f'"{p.name}"' not in source]
    assert not missing, f"examples without a test in {Path(__file__).name}: {missing}"


@pytest.mark.fem
def test_the_example_runs_at_a_tiny_size_and_draws_the_figure(tmp_path: Path) -> None:
    """One object of each set, 2 of the 4 pads, the three pairs: every row, the convergence of
    each pad, the answer, and a figure 3.5 in wide."""
    from PIL import Image

    png, js = tmp_path / "density.png", tmp_path / "density.json"
    argv = ["--objects", "1", "--pads", "0,3", "--cache", str(tmp_path / "cache"),
            "--png", str(png), "--json", str(js)]  # fmt: skip
    out = runpy.run_path(str(EXAMPLES / "density_study.py"))["main"](argv)
    rows = out["rows"]
    assert len(rows) == 2 * 3 * 2  # sets x pairs x pads
    assert {r["pad"] for r in rows} == {"2x3 45 mm", "4x6 22.5 mm"}
    assert all(r["trials"] == 1 for r in rows)
    by_pad = {r["pad"]: r["fem"] for r in rows}
    # the denser pad's module is stiffer and feels lighter weights (its own FEM response)
    assert (
        by_pad["4x6 22.5 mm"]["centre_stiffness_n_per_mm"]
        > by_pad["2x3 45 mm"]["centre_stiffness_n_per_mm"]
    )
    assert (
        by_pad["4x6 22.5 mm"]["compact_min_detectable_mass_g"]
        < 0.5 * by_pad["2x3 45 mm"]["compact_min_detectable_mass_g"]
    )
    for figures in out["convergence"].values():  # coarse within 5 % of medium for the masses
        assert abs(figures["compact_min_detectable_mass_kg"]["relative_difference"]) < 0.05
    assert out["answer"]["set"] == "ycb-eval" and js.is_file()
    with Image.open(png) as im:
        assert im.size[0] == pytest.approx(3.5 * 200, abs=2)
