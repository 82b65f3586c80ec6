"""Known objects as a mode (issue 47 item 3): learning, recognition, planning, files."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.planning import (
    TABLE_6_1,
    Catalogue,
    CatalogueParams,
    CataloguePlanner,
    GraspPlan,
    KnownObject,
    LearnedTrial,
    grasp_rule,
    known_name,
    learn_catalogue,
    load_catalogue,
    load_centre,
    make_planner,
)

LAYOUT = PadLayout()
VAR = 30.0  # Pa^2: a planning increment's variance under about 12 Pa of per-frame noise


def _trials(rng: np.random.Generator) -> list[LearnedTrial]:
    """A banana-like reading on modules 1-3 and a box on 4-6, eight trials each, spread by
    placement; the box held in five of them, the can never."""
    out = []
    for k in range(8):
        a = np.array([250, 180, 130, 0, 0, 0]) + rng.normal(0, 15, 6) * [1, 1, 1, 0, 0, 0]
        out.append(LearnedTrial("banana", tuple(a), (1.3 + 0.01 * k, 1.5, 1.57), True))
        b = np.array([0, 0, 0, 120, 300, 120]) + rng.normal(0, 15, 6) * [0, 0, 0, 1, 1, 1]
        out.append(LearnedTrial("box", tuple(b), (1.5, 0.5 + 0.01 * k, 0.0), k < 5))
        c = np.array([0, 400, 0, 0, 400, 0]) + rng.normal(0, 15, 6) * [0, 1, 0, 0, 1, 0]
        out.append(LearnedTrial("can", tuple(c), (1.5, 1.0, 1.57), False))
    return out


@pytest.fixture(scope="module")
def catalogue() -> Catalogue:
    return learn_catalogue(_trials(np.random.default_rng(1)), VAR)


def test_objects_never_held_stay_unknown_and_grasps_follow_their_readings(
    catalogue: Catalogue,
) -> None:
    assert [o.name for o in catalogue.objects] == ["banana", "box"]
    box = catalogue.objects[1]
    assert len(box.readings_pa) == 5 and box.grasps[4] == (1.5, 0.54, 0.0)


def _shares_and_log(r: np.ndarray) -> tuple[np.ndarray, float]:
    p = np.maximum(np.asarray(r, dtype=float), 0.0)
    return p / p.sum(), float(np.log(p.sum()))


def test_every_object_gets_the_stated_tolerances_and_the_file_keeps_them(
    tmp_path: Path,
) -> None:
    cat = learn_catalogue(_trials(np.random.default_rng(1)), VAR, CatalogueParams(0.2, 0.1))
    assert {(o.share_tolerance, o.load_tolerance) for o in cat.objects} == {(0.2, 0.1)}
    path = tmp_path / "c.toml"
    path.write_text(cat.to_toml())
    assert load_catalogue(path) == cat
    default = learn_catalogue(_trials(np.random.default_rng(1)), VAR)
    assert {(o.share_tolerance, o.load_tolerance) for o in default.objects} == {(0.25, 0.30)}


def test_the_distances_are_scipys_cityblock_of_the_shares_and_of_the_log_loads(
    catalogue: Catalogue,
) -> None:
    """Against scipy.spatial.distance.cityblock on shares and log totals computed here."""
    from scipy.spatial.distance import cityblock

    r = np.array([240.0, 200, 120, 5, -3, 2])
    s, log_total = _shares_and_log(r)
    banana = catalogue.objects[0]
    expected = [
        cityblock(s, _shares_and_log(np.array(x))[0])
        + abs(log_total - _shares_and_log(np.array(x))[1])
        for x in banana.readings_pa
    ]
    d, k, within = banana.distance(r)
    assert d == pytest.approx(min(expected), rel=1e-12) and within
    assert k == int(np.argmin(expected))


def test_a_reading_is_known_within_the_tolerances_and_unknown_beyond() -> None:
    """One object, two held readings far apart, tolerances 0.2 (pattern) and 0.1 (load):
    a reading's total load 0.9 / 1.1 tolerances (log) from the first's is known / unknown;
    so is load share moved between modules (L1 of the shares 0.9 / 1.1 tolerances) and the
    grasp is the matching reading's."""
    first, second = (250.0, 180.0, 130.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 90.0, 300.0, 90.0)
    obj = KnownObject("banana", (first, second), ((1.0, 1.5, 0.0), (1.5, 0.5, 1.57)), 0.2, 0.1)
    cat = Catalogue(6, VAR, (obj,))
    r = np.array(first)
    for factor, known in ((0.9, True), (1.1, False), (-0.9, True), (-1.1, False)):
        got, _, k = cat.recognise(r * np.exp(factor * 0.1))
        assert (got is obj and k == 0) is known, factor
    for fraction, known in ((0.9, True), (1.1, False)):
        moved = fraction * 0.2 / 2 * r.sum()  # the L1 distance of the shares: 2 x moved
        got, _, k = cat.recognise(r + np.array([-moved, 0, 0, moved, 0, 0]))
        assert (got is obj and k == 0) is known, fraction
    assert cat.recognise(np.array(second) * 1.05)[::2] == (obj, 1)


def test_other_objects_are_unknown(catalogue: Catalogue) -> None:
    """The never-held can, the banana moved by half a module (its load shifted), no load."""
    assert catalogue.recognise([0, 400, 0, 0, 400, 0])[0] is None
    assert catalogue.recognise([100, 250, 250, 0, 0, 0])[0] is None
    assert catalogue.recognise([0, 0, 0, 0, 0, 0])[0] is None
    known, d, _ = catalogue.recognise([250, 180, 130, 0, 0, 0])
    assert known is not None and known.name == "banana" and d < banana_gap(catalogue)


def banana_gap(catalogue: Catalogue) -> float:
    """The distance (pattern plus load) of the mean banana from the box's nearest reading."""
    box = catalogue.objects[1]
    return box.distance([250, 180, 130, 0, 0, 0])[0]


class _Fallback:
    def __init__(self) -> None:
        self.calls: list[str] = []

    def plan(self, increments_pa, objects, layout):
        self.calls.append("plan")
        return [GraspPlan(objects[0], (0.0, 0.0), (9.0, 9.0), 0.0, "fallback", objects[0])]

    def retry(self, plan, *args, **kwargs):
        self.calls.append("retry")
        return plan


def test_a_known_object_is_grasped_where_its_nearest_held_trial_was(
    catalogue: Catalogue,
) -> None:
    """Without a grasp rule (a ``softpad-catalogue/2`` file), the nearest held trial's."""
    fallback = _Fallback()
    catalogue = replace(catalogue, objects=tuple(replace(o, rule=None) for o in catalogue.objects))
    planner = CataloguePlanner(catalogue, fallback)
    box = catalogue.objects[1]
    reading = np.array(box.readings_pa[3]) + 1.0  # nearest: the fourth held trial
    (plan,) = planner.plan(reading, [(4, 5, 6)], LAYOUT)
    assert (plan.cog, plan.theta) == ((1.5, 0.53), 0.0)
    assert plan.rule.startswith("catalogue: box (d=") and planner.last_known == "box"
    assert known_name(plan.rule) == "box"
    # a landing on the known object: the fallback plans again
    assert planner.retry(plan, reading, LAYOUT, reading) == plan and fallback.calls == ["retry"]


@pytest.mark.parametrize(
    ("reading", "objects", "split_pads"),
    [
        ([0, 400, 0, 0, 400, 0], [(2, 5)], True),
        ([0, 400, 0, 0, 400, 0], [(2,), (5,)], True),
        ([250, 180, 130, 0, 0, 0], [(1, 2, 3), (5,)], False),
    ],
    ids=["unknown", "unknown-split", "two-objects-not-split"],
)
def test_unknown_objects_and_crowded_pads_go_to_the_fallback(
    catalogue: Catalogue, reading: list[float], objects: list[tuple[int, ...]], split_pads: bool
) -> None:
    fallback = _Fallback()
    planner = CataloguePlanner(catalogue, fallback, split_pads=split_pads)
    (plan,) = planner.plan(reading, objects, LAYOUT)
    assert plan.rule == "unknown -> fallback" and planner.last_known is None
    assert known_name(plan.rule) is None
    # the fallback retries its own plan (its rule without the catalogue's prefix)
    assert planner.retry(plan, reading, LAYOUT, reading) == replace(plan, rule="fallback")
    assert fallback.calls == ["plan", "retry"]


def test_a_split_pad_whose_whole_reading_is_known_gets_that_objects_one_grasp(
    catalogue: Catalogue,
) -> None:
    """The banana's reading split by the detector into two objects (modules 1 and 2-3, as a
    banana on its ends reads): one plan, the banana's grasp over both groups' modules, the
    same grasp as for the unsplit pad; the rule says the pad was split."""
    reading = [250.0, 180.0, 130.0, 0.0, 0.0, 0.0]
    planner = CataloguePlanner(catalogue, _Fallback())
    (whole,) = planner.plan(reading, [(1, 2, 3)], LAYOUT)
    (split,) = planner.plan(reading, [(1,), (2, 3)], LAYOUT)
    assert split.modules == (1, 2, 3) and (split.cog, split.theta) == (whole.cog, whole.theta)
    assert split.rule.endswith(", split pad)") and known_name(split.rule) == "banana"
    assert planner.last_known == "banana"


def test_without_a_catalogue_the_planner_is_the_model_based_one() -> None:
    """``--planner catalogue`` with no file knows no object: Table 6.1's plans are the
    model-based planner's."""
    mine, theirs = make_planner("catalogue"), make_planner("model-based")
    for case in TABLE_6_1:
        objects = [tuple(m for m in range(1, 7) if case.delta_pa[m - 1] > 50)]
        plans = mine.plan(case.delta_pa, objects, LAYOUT)
        assert all(p.rule.startswith("unknown -> ") for p in plans), case.name
        handed = [replace(p, rule=p.rule.removeprefix("unknown -> ")) for p in plans]
        assert handed == theirs.plan(case.delta_pa, objects, LAYOUT), case.name


def test_the_file_round_trips_and_reaches_the_planner(catalogue: Catalogue, tmp_path: Path) -> None:
    path = tmp_path / "catalogue.toml"
    path.write_text(catalogue.to_toml())
    assert load_catalogue(path) == catalogue
    planner = make_planner("catalogue", catalogue=str(path))
    assert planner.catalogue == catalogue  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (None, "not found"),
        ('schema = "other"\n', "schema must be one of .*'softpad-catalogue/3'"),
        ('schema = "softpad-catalogue/3"\nmodules = 6\n', "malformed"),
        ("schema = [", "not valid TOML"),
    ],
    ids=["missing", "schema", "malformed", "not-toml"],
)
def test_bad_catalogue_files_are_named(tmp_path: Path, text: str | None, message: str) -> None:
    path = tmp_path / "c.toml"
    if text is not None:
        path.write_text(text)
    with pytest.raises(InputError, match=message):
        load_catalogue(path)


def test_learning_refuses_what_it_cannot_learn_from() -> None:
    with pytest.raises(InputError, match="at least one"):
        learn_catalogue([], VAR)
    a = LearnedTrial("a", (1.0,) * 6, (0, 0, 0), True)
    b = LearnedTrial("b", (1.0,) * 12, (0, 0, 0), True)
    with pytest.raises(InputError, match="different module counts"):
        learn_catalogue([a, b], VAR)
    with pytest.raises(InputError, match="positive"):
        learn_catalogue([a], 0.0)


def _box(theta: float, x: float, held: bool, load: tuple[float, ...]) -> LearnedTrial:
    return LearnedTrial("box", load, (x, 0.5, theta), held)


BOX_LOAD = (0.0, 0.0, 0.0, 100.0, 300.0, 100.0)


def test_the_rule_takes_the_direction_that_held_most_often() -> None:
    """Across (theta 0): 3 of 5 held, Laplace 4/7; along (theta near pi/2, either sign): 2 of
    2, Laplace 3/4. The rule closes along, at the mean of its held centres and directions;
    with one more failure along (2 of 3: 3/5 > 4/7 still) and then two (2 of 4: 1/2 < 4/7)
    the choice holds, then turns."""
    across = [_box(0.0, 1.0 + 0.1 * k, k < 3, BOX_LOAD) for k in range(5)]
    along = [_box(1.5, 1.4, True, BOX_LOAD), _box(-1.5, 1.6, True, BOX_LOAD)]
    params = CatalogueParams()
    rule = grasp_rule(across + along, params)
    assert rule is not None and (rule.held, rule.tried) == (2, 2)
    assert rule.grasp[:2] == pytest.approx((1.5, 0.5)) and abs(rule.grasp[2]) == pytest.approx(
        np.pi / 2, abs=1e-12
    )
    miss = _box(1.55, 1.5, False, BOX_LOAD)
    assert grasp_rule([*across, *along, miss], params).tried == 3  # type: ignore[union-attr]
    turned = grasp_rule([*across, *along, miss, miss], params)
    assert turned is not None and (turned.held, turned.tried) == (3, 5)
    assert turned.grasp == pytest.approx((1.1, 0.5, 0.0))
    assert grasp_rule([_box(0.0, 1.0, False, BOX_LOAD)], params) is None


def test_the_rule_centre_follows_the_load_centre_by_the_stated_gain() -> None:
    """Load moved from module 4 to module 6 (one module's share of 0.2 over 2 module units):
    the load centre moves 0.4 module units in x (computed here as a weighted mean of the
    module centres), the grasp centre by gain times that; the direction stays."""
    trials = [_box(0.0, 1.5, True, BOX_LOAD), _box(0.0, 1.5, True, BOX_LOAD)]
    for gain in (0.0, 0.75, 1.0):
        rule = grasp_rule(trials, CatalogueParams(centre_gain=gain))
        assert rule is not None
        moved = np.array([0.0, 0.0, 0.0, 0.0, 300.0, 200.0])
        centres = np.array(LAYOUT.center_table)
        shift = moved @ centres[:, 0] / moved.sum() - np.array(BOX_LOAD) @ centres[:, 0] / 500
        assert shift == pytest.approx(0.4)
        x, y, theta = rule.apply(moved, LAYOUT.center_table)
        assert (x, y, theta) == pytest.approx((1.5 + gain * shift, 0.5, 0.0))
        assert load_centre(moved, centres) == pytest.approx((1.9, 0.5))


def test_a_known_object_is_grasped_by_its_rule_and_the_file_keeps_it(
    catalogue: Catalogue, tmp_path: Path
) -> None:
    box = catalogue.objects[1]
    assert box.rule is not None and (box.rule.held, box.rule.tried) == (5, 8)
    assert box.rule.grasp[0] == pytest.approx(1.5) and box.rule.grasp[1] == pytest.approx(0.52)
    reading = np.array(box.readings_pa[3]) + 1.0
    (plan,) = CataloguePlanner(catalogue, _Fallback()).plan(reading, [(4, 5, 6)], LAYOUT)
    assert (*plan.cog, plan.theta) == pytest.approx(box.rule.apply(reading, LAYOUT.center_table))
    assert (*plan.cog, plan.theta) != pytest.approx(box.grasps[3])
    path = tmp_path / "c.toml"
    path.write_text(catalogue.to_toml())
    assert load_catalogue(path).objects[1].rule == box.rule
    old = catalogue.to_toml().replace("softpad-catalogue/3", "softpad-catalogue/2")
    path.write_text(
        "\n".join(x for x in old.splitlines() if not x.startswith(("rule_", "centre_")))
    )
    assert all(o.rule is None for o in load_catalogue(path).objects)
