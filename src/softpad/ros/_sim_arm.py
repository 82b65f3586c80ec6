"""``softpad sim arm-node``: a simulated arm honouring the ``ros1://`` contract.

The simulated arm must move the gripper of the same world whose pressures the box reports, so
this one process owns the simulated box and its world: it serves the box over ``zenoh://`` on
127.0.0.1 (the :class:`~softpad.box.BoxDaemon` of ``softpad box serve``, with the simulator's
``sim.setup``/``sim.place`` services so a run can place catalogue objects), and the arm over
ROS (:data:`~softpad.ros.ARM_COMMAND_TOPIC` in, :data:`~softpad.ros.ARM_STATE_TOPIC` out). The
daemon samples the box on the wall clock (no lock-step) so that ROS latencies count as they
would on hardware. Commands are applied between two frames, in the daemon's sampling thread,
so the world is only touched from one thread.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from typing import Any

from softpad.box import Box, BoxWrapper, PressureFrame, simulator_of
from softpad.errors import InputError


class _HookedBox(BoxWrapper):
    """A box that calls ``before`` ahead of every read of ``inner`` and ``after`` with it."""

    def __init__(self, inner: Box, before: Callable[[], None], after: Callable[[], None]) -> None:
        super().__init__(inner)
        self.before, self.after = before, after

    def _read(self) -> PressureFrame:
        self.before()
        frame = super()._read()
        self.after()
        return frame


def _free_loopback_port() -> int:
    """A TCP port free on 127.0.0.1 now (the daemon listens there next)."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class SimArmNode:
    """The simulated arm node (module docstring).

    Parameters
    ----------
    box_url
        A ``sim://`` URL (sampled on the wall clock by the daemon).
    port
        Port of the served box's zenoh endpoint ``tcp/127.0.0.1:PORT`` (0: a free one, see
        :attr:`url`).
    lose_arm_on
        Fault injection: on this command (``move_to``, ``descend``, ``stop``, ``gripper``) the
        arm's ROS side goes silent, as if its driver died, while the box stays served.
    """

    def __init__(
        self, box_url: str = "sim://", port: int = 0, lose_arm_on: str | None = None
    ) -> None:
        from softpad.box import BoxDaemon, open_box
        from softpad.harness import SimulatedRobot, simulation_extensions
        from softpad.ros._rospy_path import require_master

        if not box_url.startswith("sim://"):
            raise InputError(f"the simulated arm drives a sim:// box, got {box_url!r}")
        rospy = require_master()
        from std_msgs.msg import Float64MultiArray

        box = open_box(box_url)
        sim = simulator_of(box)
        assert sim is not None
        self.sim = box
        self.robot = SimulatedRobot(sim.world)
        if lose_arm_on not in (None, "move_to", "descend", "stop", "gripper"):
            raise InputError(
                f"lose_arm_on must be move_to, descend, stop or gripper, got {lose_arm_on!r}"
            )
        self.lose_arm_on = lose_arm_on
        self._commands: queue.Queue[tuple[str, list[float]]] = queue.Queue()
        self._lock = threading.Lock()
        self._current = self._done = 0.0
        self._snapshot = self._take_snapshot()
        ext = simulation_extensions(sim)
        port = port or _free_loopback_port()
        #: URL of the served box.
        self.url = f"zenoh://127.0.0.1:{port}"
        self.server = BoxDaemon(
            _HookedBox(box, self._apply_commands, self._after_read),
            (f"tcp/127.0.0.1:{port}",),
            services={k: ext[k] for k in ("sim.setup", "sim.place")},
        ).start()
        from softpad.ros._arm import ARM_COMMAND_TOPIC, ARM_STATE_TOPIC

        rospy.init_node("softpad_sim_arm", disable_signals=True)
        self._pub = rospy.Publisher(ARM_STATE_TOPIC, Float64MultiArray, queue_size=10)
        self._sub = rospy.Subscriber(ARM_COMMAND_TOPIC, Float64MultiArray, self._on_command)
        self._timer = rospy.Timer(rospy.Duration(0.01), self._publish)

    def _on_command(self, msg: Any) -> None:
        op = msg.layout.dim[0].label if msg.layout.dim else ""
        if op == self.lose_arm_on:
            self._timer.shutdown()  # the arm's driver "dies": no state, no commands
            self._sub.unregister()
            return
        self._commands.put((op, [float(v) for v in msg.data]))

    def _apply_commands(self) -> None:
        """Apply received commands to the simulated robot (box thread, between frames)."""
        from softpad.control import ToolPose

        arity = {"move_to": 6, "descend": 3, "stop": 1, "gripper": 3}
        while not self._commands.empty():
            op, d = self._commands.get()
            if arity.get(op) != len(d):
                continue  # malformed: ignored, never acknowledged
            if op == "move_to":
                self.robot.move_to(ToolPose(*d[1:5]), d[5])
            elif op == "descend":
                self.robot.descend(d[1], d[2])
            elif op == "stop":
                self.robot.stop()
            else:
                self.robot.set_gripper(d[1], d[2])
            self._current = d[0]
            print(f"arm: {op} {' '.join(f'{v:g}' for v in d)}", flush=True)

    def _take_snapshot(self) -> list[float]:
        moving = bool(self.robot.is_moving())
        if not moving:
            self._done = self._current
        s = self.robot.state()
        held = float(self.robot.holding())
        return [s.x_m, s.y_m, s.z_m, s.yaw_rad, s.width_m, float(moving), held, self._done]

    def _after_read(self) -> None:
        snap = self._take_snapshot()
        with self._lock:
            self._snapshot = snap

    def _publish(self, _event: Any) -> None:
        from softpad.ros._messages import labelled_array

        with self._lock:
            snap = list(self._snapshot)
        self._pub.publish(labelled_array(snap, "x_y_z_yaw_width_moving_holding_done_id"))

    def serve(self) -> None:
        """Serve the box until interrupted (the ROS side runs in rospy's threads)."""
        try:
            self.server.wait()
        finally:
            self._timer.shutdown()
            self.server.close()
