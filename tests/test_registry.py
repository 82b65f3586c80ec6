"""Parts by name: the registries of planners, detectors and robots, their entry points, and
the pad's size reaching the contact detector from every command."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from softpad.control import ROBOT_REGISTRY, available_robots, make_robot
from softpad.errors import InputError
from softpad.layout import GripperSpec, PadLayout
from softpad.planning import (
    PLANNER_REGISTRY,
    GripperAwarePlanner,
    Planner,
    PlannerContext,
    ThesisPlanner,
    available_planners,
    make_planner,
    register_planner,
)
from softpad.registry import Registry
from softpad.sensing import (
    CONTACT_DETECTOR_REGISTRY,
    CusumContactDetector,
    DetectorContext,
    ThesisContactDetector,
    ThesisObjectDetector,
    available_contact_detectors,
    available_object_detectors,
    cusum_for_rate,
    make_contact_detector,
    make_object_detector,
)


def _dist_info(root: Path, name: str, entry_points: str) -> Path:
    """A minimal installed distribution on ``root`` declaring ``entry_points`` (the text of an
    ``entry_points.txt``): what ``pip install`` leaves in site-packages."""
    info = root / f"{name}-0.1.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(entry_points)
    return root


def test_builtin_parts_are_registered() -> None:
    assert available_planners()[:2] == ("thesis", "gripper-aware")
    assert available_contact_detectors()[:3] == ("thesis", "cusum", "adaptive")
    assert available_object_detectors()[0] == "thesis"
    assert available_robots()[:2] == ("sim", "ros1")


@pytest.mark.parametrize(
    ("make", "kind"),
    [(make_planner, "planner"), (make_contact_detector, "contact detector"),
     (make_object_detector, "object detector")],
    ids=["planner", "contact", "object"],
)  # fmt: skip
def test_unknown_name_is_refused_naming_the_known_ones(make: object, kind: str) -> None:
    with pytest.raises(InputError, match=rf"unknown {kind} 'magic'; available: thesis"):
        make("magic")  # type: ignore[operator]


def test_unknown_robot_scheme_names_the_known_ones() -> None:
    with pytest.raises(InputError, match=r"unknown robot URL scheme 'tcp'.*sim://, ros1://"):
        make_robot("tcp://arm:1")


def test_factories_get_the_context() -> None:
    spec = GripperSpec.from_mounting("6/2")
    ctx = DetectorContext(PadLayout(3, 4), 250.0, spec, 123.0, 45.0, 4)
    thesis = make_contact_detector("thesis", 250.0, PadLayout(3, 4), contact_threshold_pa=123.0)
    assert isinstance(thesis, ThesisContactDetector) and thesis.threshold_pa == 123.0
    objects = make_object_detector("thesis", object_threshold_pa=45.0)
    assert isinstance(objects, ThesisObjectDetector) and objects.threshold_pa == 45.0
    assert ctx.modules == 12
    aware = make_planner("gripper-aware", PlannerContext(gripper=spec))
    assert isinstance(aware, GripperAwarePlanner) and aware.gripper == spec
    assert isinstance(make_planner("thesis"), ThesisPlanner)


def test_a_new_planner_registers_and_is_made_by_name() -> None:
    seen: list[PlannerContext] = []

    def factory(context: PlannerContext) -> Planner:
        seen.append(context)
        return ThesisPlanner(context.params)

    register_planner("test-recorder", factory, "records its context")
    try:
        assert "test-recorder" in available_planners()
        assert PLANNER_REGISTRY.summary("test-recorder") == "records its context"
        make_planner("test-recorder", layout=PadLayout(4, 4), sample_rate_hz=500.0)
        assert seen[0].layout == PadLayout(4, 4) and seen[0].sample_rate_hz == 500.0
        assert "test-recorder: records its context" in PLANNER_REGISTRY.help()
    finally:
        PLANNER_REGISTRY.unregister("test-recorder")
    assert "test-recorder" not in available_planners()


def test_lazy_parts_are_imported_only_when_made() -> None:
    reg: Registry[object] = Registry("widget", "softpad.test_widgets")
    reg.register_lazy("pad", "softpad.layout:PadLayout", "a pad")
    assert reg.names() == ("pad",) and reg.summary("pad") == "a pad"
    assert reg.factory("pad") is PadLayout
    reg.register_lazy("gone", "softpad.no_such_module:x", "never imported")
    with pytest.raises(ModuleNotFoundError):
        reg.factory("gone")
    with pytest.raises(InputError, match="module:attribute"):
        reg.register_lazy("bad", "no-colon", "")
    with pytest.raises(InputError, match="non-empty word"):
        reg.register(" x", PadLayout)


def test_entry_points_of_an_installed_package_are_found(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A distribution declaring ``softpad.contact_detectors`` is listed and loaded by name."""
    text = "[softpad.contact_detectors]\nfrom-entry-point = softpad.sensing:ThesisContactDetector\n"
    monkeypatch.syspath_prepend(str(_dist_info(tmp_path, "softpad_test_ep", text)))
    try:
        assert "from-entry-point" in available_contact_detectors()
        factory = CONTACT_DETECTOR_REGISTRY.factory("from-entry-point")
        assert factory is ThesisContactDetector
    finally:
        CONTACT_DETECTOR_REGISTRY.unregister("from-entry-point")


def test_a_distribution_installed_after_a_first_look_is_found(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The entry points are read once per state of the import path (issue 38): installing into
    a folder already on it, after the names were listed, still shows the new part."""
    monkeypatch.syspath_prepend(str(tmp_path))
    assert "late-entry-point" not in available_contact_detectors()
    text = "[softpad.contact_detectors]\nlate-entry-point = softpad.sensing:ThesisContactDetector\n"
    _dist_info(tmp_path, "softpad_test_late", text)
    try:
        assert "late-entry-point" in available_contact_detectors()
    finally:
        CONTACT_DETECTOR_REGISTRY.unregister("late-entry-point")


def test_cusum_is_calibrated_for_the_pads_size() -> None:
    """12 modules raise the per-module threshold over 6 (more statistics, same false-alarm
    rate): the registry passes the layout through."""
    six = make_contact_detector("cusum", 100.0)
    twelve = make_contact_detector("cusum", 100.0, PadLayout(3, 4))
    assert isinstance(six, CusumContactDetector) and isinstance(twelve, CusumContactDetector)
    assert twelve.single.threshold_pa == pytest.approx(
        cusum_for_rate(100.0, 12).single.threshold_pa
    )
    assert twelve.single.threshold_pa > six.single.threshold_pa + 1.0


def test_run_builds_the_detector_for_the_boxs_pad() -> None:
    """``softpad run`` (and ``trials``, ``compare``) make the contact detector for the pad on
    the box: a 3 x 4 simulated pad gets the 12-module CUSUM, not the 6-module one."""
    from softpad.box import open_box
    from softpad.cli._run import execution_params
    from softpad.cli.main import build_parser
    from softpad.harness import box_loop_parts

    args = build_parser().parse_args(["run", "--detector", "cusum", "--planner", "thesis"])
    assert isinstance(args, argparse.Namespace)
    with open_box("sim://?layout=3x4&channels=12&seed=1") as box:
        parts = box_loop_parts(box, execution_params(args), "10/4", args.planner, args.detector)
    twelve = cusum_for_rate(box.sample_rate_hz, 12).single.threshold_pa
    assert parts["contact_detector"].single.threshold_pa == pytest.approx(twelve)


def test_robot_registry_makes_the_simulated_arm() -> None:
    from softpad.box import open_box
    from softpad.harness import SimulatedRobot

    with open_box("sim://?seed=1") as box:
        robot = make_robot("sim://", box=box)
    assert isinstance(robot, SimulatedRobot)
    with pytest.raises(InputError, match="needs a simulated box"):
        make_robot("sim://")
    assert ROBOT_REGISTRY.summary("ros1").startswith("an arm and gripper reached through ROS")
