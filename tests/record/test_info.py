"""softpad.record's recording info (what ``softpad log info`` prints) as lines."""

from __future__ import annotations

from softpad.record import info_lines


def test_info_lines_show_the_summary() -> None:
    s = {
        "path": "run.mcap", "frames": 1500, "channels": 7, "duration_s": 15.0,
        "wall_clock_start": "2026-01-01T00:00:00", "software_version": "1.0",
        "sample_rate_hz": 100.0, "complete": False, "objects": ["banana"],
        "plans": [{"modules": [1, 2], "cog": [1.0, 1.5], "theta": 0.0, "rule": "n2"}],
        "contact": [{"t_s": 3.25, "modules": [2]}], "events": 9, "valve_commands": 12,
        "robot_poses": 40, "outcome": "held",
        "topics": [{"topic": "/softpad/pressures", "type": "softpad.Pressures", "messages": 5}],
    }  # fmt: skip
    lines = info_lines(s)
    assert lines[0] == "run.mcap: 1500 frames of 7 channels over 15.00 s"
    assert lines[2].startswith("  cut short (crash?)")
    assert "  plan: modules 1,2  COG (1.00, 1.50)  theta +0.000 rad  [n2]" in lines
    assert "  contact: t = 3.250 s on module(s) 2" in lines
    assert lines[-2] == "  outcome: held" and lines[-1].split() == [
        "/softpad/pressures", "softpad.Pressures", "5",
    ]  # fmt: skip
