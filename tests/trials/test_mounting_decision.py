"""``--mounting auto`` with a planner that predicts its success: the trial's mounting is the
planner's decision (issue 47 item 2), not the width rule."""

from __future__ import annotations

import pytest

from softpad.design import load_object_set
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import choose_mounting, make_planner
from softpad.sensing import detect_objects

DEV = "src/softpad/data/object_sets/ycb-dev.toml"


def _spec(name: str):
    from softpad.cli._trials import select_objects

    (spec,) = select_objects(name, DEV)
    return spec


@pytest.mark.parametrize(
    ("name", "at"),
    [("ycb-058-golf-ball", (0.0675, 0.0675, 0.3)), ("ycb-061-foam-brick", (0.0675, 0.06, 0.0))],
)
def test_model_based_trials_install_the_mounting_it_predicts_best(
    name: str, at: tuple[float, float, float]
) -> None:
    from softpad.trials import TrialConfig
    from softpad.trials._loop import configured_mounting
    from softpad.trials._survey import pad_reading

    assert load_object_set(DEV).objects  # the development half only
    spec = _spec(name)
    cfg = TrialConfig(planner="model-based", detector="thesis", mounting="auto")
    reading = pad_reading(spec, at, 3, cfg, None)
    layout = PadLayout()
    objects = detect_objects(reading, layout)
    p = {
        m: make_planner("model-based", gripper=GripperSpec()).mounting_success(
            reading, objects, layout, GripperSpec.from_mounting(m)
        )
        for m in ("10/4", "6/2", "4/0")
    }
    chosen = configured_mounting(spec, at, 3, cfg, None)
    assert p[chosen] == max(p.values()), (p, chosen)
    # the width rule (the thesis's planner has no prediction) chooses otherwise here
    thesis_cfg = TrialConfig(planner="thesis", detector="thesis", mounting="auto")
    by_width = configured_mounting(spec, at, 3, thesis_cfg, None)
    assert by_width == choose_mounting(reading) != chosen, (by_width, chosen, p)
