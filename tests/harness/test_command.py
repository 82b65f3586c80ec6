"""softpad.harness's run report (what ``softpad run`` prints): the timeline of a run's
events, a hardware fault with the safe state reached, and the arm chosen by URL."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from softpad.harness import EVENT_TEXT, fault_report, retry_text, timeline


def test_the_timeline_shows_phases_and_known_events_only() -> None:
    events = [
        (0.0, "phase", {"phase": "inflate"}),  # not a shown phase
        (1.25, "phase", {"phase": "descend"}),
        (2.5, "contact", {"modules": [2, 5]}),
        (3.0, "frame_rate", {"hz": 100}),  # not a shown kind
        (4.0, "outcome", {"outcome": "held"}),
    ]
    grasp = SimpleNamespace(outcome="held")
    run = SimpleNamespace(
        result=SimpleNamespace(grasps=[grasp]),
        contact_delay_s=lambda i: 0.042,
        finger_travel_m=lambda i: 0.0031,
    )
    assert timeline(events, run) == [  # type: ignore[arg-type]
        "t =    1.25 s  descend",
        "t =    2.50 s  contact detected on module(s) 2, 5",
        "t =    4.00 s  held",
        "grasp 1: contact 42 ms after the first fingertip touch, finger travel 3.1 mm; "
        "outcome held",
    ]


def test_a_grasp_without_ground_truth_says_only_its_outcome() -> None:
    run = SimpleNamespace(
        result=SimpleNamespace(grasps=[SimpleNamespace(outcome="slipped")]),
        contact_delay_s=lambda i: None,
        finger_travel_m=lambda i: None,
    )
    assert timeline([], run) == ["grasp 1: outcome slipped"]  # type: ignore[arg-type]


def test_every_event_text_reads_its_event() -> None:
    plan = {"modules": [1], "pcom": [0.5, 1.5], "cog": [0.5, 1.5], "theta": 0.0, "rule": "n1"}
    samples = {
        "adjusted": {"target_pa": 1100.0},
        "reference": {"reference_pa": [1100.0, 1101.0]},
        "object_seen": {"modules": [1]},
        "plan": {"increments_pa": [120.0, 0.0], "objects": [plan]},
        "contact": {"modules": [1]},
        "no_contact": {"z_m": 0.004},
        "retry": {"z_m": 0.02, "cog": [1.0, 1.0], "theta": 0.0, "rule": "r"},
        "carried": {"modules": [4]},
        "outcome": {"outcome": "held"},
    }
    assert set(samples) == set(EVENT_TEXT)
    lines = {kind: EVENT_TEXT[kind](d) for kind, d in samples.items()}
    assert lines["reference"] == ["reference saved (kPa): 1.100 1.101"]
    assert lines["plan"][1].startswith("plan: modules 1  PCOM (0.50, 1.50)")
    assert lines["no_contact"] == ["no contact detected down to 4.0 mm: gripper not closed"]
    assert retry_text(samples["retry"]).endswith("trying COG (1.00, 1.00) theta +0.000 rad [r]")


def test_a_fault_report_names_the_faults_and_the_safe_state() -> None:
    fault = SimpleNamespace(to_dict=lambda: {"t_s": 3.5, "channel": 2, "cause": "leak"})
    safe = SimpleNamespace(
        pressures_pa=[1100.0, float("nan")], verified=False, reason="sensor lost",
        to_dict=lambda: {"verified": False},
    )  # fmt: skip
    exc = RuntimeError("valve stuck")
    exc.faults, exc.safe_state = [fault], safe  # type: ignore[attr-defined]
    events = [(0.5, "phase", {"phase": "descend"}), (1.0, "contact", {"modules": [1]})]
    d, lines = fault_report(exc, ["object-5"], events, 120)
    assert d["outcome"] == "fault" and d["phases"] == [{"phase": "descend", "t_s": 0.5}]
    assert d["error"] == {
        "kind": "hardware", "message": "valve stuck", "frames": 120,
        "events": [[0.5, "phase", {"phase": "descend"}], [1.0, "contact", {"modules": [1]}]],
    }  # fmt: skip
    assert lines == [
        "t =    3.50 s  fault on channel 2 (leak)",
        "safe state NOT verified: sensor lost; pressures 1.100, nan kPa",
    ]


@pytest.mark.parametrize("url", ["sim://", "sim:///"], ids=["plain", "slash"])
def test_the_simulated_arm_keeps_its_ground_truth(url: str) -> None:
    from softpad.box import open_box
    from softpad.control import ExecutionParams
    from softpad.harness import run_objects

    params = ExecutionParams(hold_s=0.5)
    with open_box("sim://?seed=1") as box:
        run = run_objects(["object-5"], box, params, None, None, url, "thesis", "thesis")
    assert run.touches and run.touches[0].first_touch_s is not None
