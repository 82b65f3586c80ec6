"""Records of runs: MCAP recording (ROS 2 message types), reading back, replay, log tools, plots.

:class:`McapRecorder` is the recorder of :class:`softpad.control.GraspExecution` that writes a
rosbag2-compatible MCAP file (crash-safe, flushed every 100 ms); :func:`load_recording` reads it
back as a :class:`RecordedRun` (summary, plots, CSV/Parquet export); :func:`recover` repairs a
file cut short by a crash; ``replay://run.mcap`` plays it back as a box (:class:`ReplayBox`);
:func:`compare_replay` runs today's sensing and planning on it. :class:`RunLog` is the
in-memory recorder, :class:`Tee` sends a run to several recorders.
"""

from softpad.record._bags import to_rosbag1, to_rosbag2
from softpad.record._export_to import export_recording
from softpad.record._info import info_lines, recording_info
from softpad.record._learn import Learned, learn_from_recordings, learned_trial
from softpad.record._live import FoxgloveLive
from softpad.record._log import RunLog
from softpad.record._mcap import FLUSH_PERIOD_S, McapRecorder, check_output
from softpad.record._read import RecordedRun, load_recording, recover
from softpad.record._relay import relay_frames
from softpad.record._replay import ReplayBox, compare_replay, open_replay_url, replay_lines
from softpad.record._run_record import open_recorder, run_metadata
from softpad.record._schemas import (
    EVENT_TOPIC,
    OWN_TYPES,
    PLAN_TOPIC,
    RECORDING_FORMAT,
    ROBOT_POSE_TOPIC,
    SUPPLY_TOPIC,
    VALVE_TOPIC,
    module_topic,
)
from softpad.record._tee import Tee

__all__ = [
    "EVENT_TOPIC",
    "FLUSH_PERIOD_S",
    "OWN_TYPES",
    "PLAN_TOPIC",
    "RECORDING_FORMAT",
    "ROBOT_POSE_TOPIC",
    "SUPPLY_TOPIC",
    "VALVE_TOPIC",
    "FoxgloveLive",
    "Learned",
    "McapRecorder",
    "RecordedRun",
    "ReplayBox",
    "RunLog",
    "Tee",
    "check_output",
    "compare_replay",
    "export_recording",
    "info_lines",
    "learn_from_recordings",
    "learned_trial",
    "load_recording",
    "module_topic",
    "open_recorder",
    "open_replay_url",
    "recording_info",
    "recover",
    "relay_frames",
    "replay_lines",
    "run_metadata",
    "to_rosbag1",
    "to_rosbag2",
]
