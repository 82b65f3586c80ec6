"""softpad.record.replay_lines: a replay's comparison as text (what ``softpad replay``
prints)."""

from __future__ import annotations

from softpad.record import replay_lines


def test_a_changed_contact_reads_different() -> None:
    plan = {"modules": [1, 4], "cog": [0.5, 1.0], "theta": 1.5707963, "rule": "n2-col"}
    d = {
        "path": "run.mcap", "outcome": "held", "same": False,
        "plan": {"recorded": [plan], "now": [plan], "same": True},
        "contacts": [{"recorded": {"t_s": 2.5, "modules": [2]}, "now": None, "same": False}],
    }  # fmt: skip
    lines = replay_lines(d)
    assert lines[0] == "softpad replay: run.mcap (recorded outcome: held)"
    assert (
        lines[1]
        == "  plan recorded modules 1,4  COG (0.500, 1.000)  theta +1.5708 rad (+90 deg)  [n2-col]"
    )
    assert lines[3] == "  plan: same"
    assert lines[4:7] == [
        "  descent 1: recorded contact t = 2.500 s on module(s) 2",
        "  descent 1: now      contact none",
        "  descent 1: DIFFERENT",
    ]
    assert lines[-1] == "verdict: DIFFERENT"
