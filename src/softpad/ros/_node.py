"""``softpad ros node``: the pad as a ROS 1 node (rospy). Translation only.

The node owns the box: it inflates and adjusts every module (:func:`softpad.control.
inflate_and_adjust`), keeps the reference, reads every frame and publishes it, and plans on the
filtered increments once the objects on the pad have settled (and on request). Its parts are the
registered ones ``softpad run`` uses, by name (``planner``, ``detector``: the object detector,
planner and contact detector of :mod:`softpad.sensing` and :mod:`softpad.planning`'s
registries, made for the box's rate and the pad). Topics, services and parameters: docs/ros.md.
"""

from __future__ import annotations

import json
import math
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from softpad import thesis
from softpad.errors import HardwareFault, InputError
from softpad.layout import PadLayout, PadPose

#: Keys of the installation file and ROS parameters (``~name``) of the node.
CONFIG_KEYS = (
    "box", "layout", "pad_x_m", "pad_y_m", "pad_z_m", "pad_yaw_rad", "base_frame",
    "object_threshold_pa", "contact_threshold_pa", "settle_s", "place", "place_after_s",
    "ambient_pressure_pa", "planner", "detector",
)  # fmt: skip


@dataclass(frozen=True)
class NodeConfig:
    """Installation of the pad node (JSON file, then ROS parameters override it).

    Parameters
    ----------
    box
        Box URL (``sim://``, ``zenoh://127.0.0.1:PORT``, ...).
    layout
        Pad layout ``RxC``.
    pad
        Pose of the pad frame in the robot base frame (static transform ``base_frame`` ->
        ``softpad``).
    base_frame
        Name of the robot's base frame.
    object_threshold_pa, contact_threshold_pa
        t_o and t_g, pascals (thesis: 50 and 90).
    settle_s
        A changed set of objects is planned after it has stayed the same this long, seconds.
    place
        Simulation only: catalogue objects put on a ``sim://`` box ``place_after_s`` after the
        reference (for demonstrations and tests; a person places them on a real pad).
    ambient_pressure_pa
        Added to the gauge readings in ``sensor_msgs/FluidPressure`` (absolute), Pa (default
        the standard atmosphere, 101325 Pa).
    planner, detector
        The planner and contact detector by name (:func:`softpad.planning.available_planners`,
        :func:`softpad.sensing.available_contact_detectors`), as ``softpad run --planner
        --detector``.
    """

    box: str = "sim://"
    layout: str = "2x3"
    pad: PadPose = field(default_factory=PadPose)
    base_frame: str = "base"
    object_threshold_pa: float = thesis.OBJECT_THRESHOLD_PA
    contact_threshold_pa: float = thesis.CONTACT_THRESHOLD_PA
    settle_s: float = 0.5
    place: tuple[str, ...] = ()
    place_after_s: float = 1.0
    ambient_pressure_pa: float = thesis.AMBIENT_PRESSURE_PA
    planner: str = "thesis"
    detector: str = "thesis"

    def updated(self, values: dict[str, Any]) -> NodeConfig:
        """This config with ``values`` (keys of :data:`CONFIG_KEYS`) applied, checked."""
        unknown = sorted(set(values) - set(CONFIG_KEYS))
        if unknown:
            raise InputError(
                f"unknown node setting {unknown[0]!r}; known: {', '.join(CONFIG_KEYS)}"
            )
        pad = {k[4:]: _finite(k, values[k]) for k in values if k.startswith("pad_")}
        out = replace(self, pad=replace(self.pad, **pad))
        for k in (
            "object_threshold_pa", "contact_threshold_pa", "settle_s", "place_after_s",
            "ambient_pressure_pa",
        ):  # fmt: skip
            if k in values:
                v = _finite(k, values[k])
                if v < 0:
                    raise InputError(f"{k} must be >= 0, got {v!r}")
                out = replace(out, **{k: v})  # type: ignore[arg-type]
        for k in ("box", "layout", "base_frame", "planner", "detector"):
            if k in values:
                out = replace(out, **{k: str(values[k])})  # type: ignore[arg-type]
        _check_parts(out)
        if "place" in values:
            names = values["place"]
            names = names.split(",") if isinstance(names, str) else names
            out = replace(out, place=tuple(str(n) for n in names if n))
        return out


def _check_parts(config: NodeConfig) -> None:
    """The planner and detector are registered ones (InputError naming the known ones)."""
    from softpad.planning import PLANNER_REGISTRY
    from softpad.sensing import CONTACT_DETECTOR_REGISTRY

    PLANNER_REGISTRY.factory(config.planner)
    CONTACT_DETECTOR_REGISTRY.factory(config.detector)


def _finite(key: str, v: object) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"{key} must be a finite number, got {v!r}")
    return float(v)


def load_config(path: str | Path | None) -> NodeConfig:
    """Read a node installation file (JSON object of :data:`CONFIG_KEYS`); defaults when None."""
    if path is None:
        return NodeConfig()
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as exc:
        raise InputError(f"cannot read node config {str(path)!r}: {exc}") from None
    if not isinstance(data, dict):
        raise InputError(f"node config {str(path)!r} must hold a JSON object")
    return NodeConfig().updated(data)


@dataclass
class _Request:
    """A service call handed to the node's loop (the box is used from one thread only)."""

    name: str
    done: threading.Event = field(default_factory=threading.Event)
    ok: bool = False
    message: str = ""


class PadNode:
    """The ROS 1 node of one pad (see the module docstring and docs/ros.md).

    Parameters
    ----------
    config
        Installation; ROS parameters of the node's private namespace override it.
    name
        ROS node name.
    """

    def __init__(self, config: NodeConfig, name: str = "softpad") -> None:
        from softpad.ros._rospy_path import require_master

        self.rospy = require_master()
        self.rospy.init_node(name, disable_signals=True)
        params = {
            k: self.rospy.get_param("~" + k) for k in CONFIG_KEYS if self.rospy.has_param("~" + k)
        }
        self.config = config.updated(params)
        from softpad.layout import parse_layout

        self.layout: PadLayout = parse_layout(self.config.layout)
        self.n = self.layout.n_modules
        self._requests: queue.Queue[_Request] = queue.Queue()
        self._make_publishers()
        self._make_services()
        self.reference_pa: NDArray[np.float64] | None = None
        self.frames = 0
        self.fault: str | None = None
        self.plans: list[Any] = []

    def _make_publishers(self) -> None:
        from diagnostic_msgs.msg import DiagnosticArray
        from geometry_msgs.msg import PoseArray
        from sensor_msgs.msg import FluidPressure
        from std_msgs.msg import Bool, Float64MultiArray
        from tf2_msgs.msg import TFMessage

        pub = self.rospy.Publisher
        self.pub_module = [
            pub(f"/softpad/module_{k}/pressure", FluidPressure, queue_size=50)
            for k in range(1, self.n + 1)
        ]
        self.pub_all = pub("/softpad/pressures", Float64MultiArray, queue_size=50)
        self.pub_objects = pub("/softpad/objects", PoseArray, queue_size=5, latch=True)
        self.pub_grasps = pub("/softpad/grasps", PoseArray, queue_size=5, latch=True)
        self.pub_contact = pub("/softpad/contact", Bool, queue_size=50)
        self.pub_diag = pub("/diagnostics", DiagnosticArray, queue_size=5)
        self.pub_tf = pub("/tf_static", TFMessage, queue_size=1, latch=True)

    def _make_services(self) -> None:
        from std_srvs.srv import Trigger, TriggerResponse

        def handler(name: str) -> Callable[[Any], Any]:
            def call(_req: Any) -> Any:
                r = _Request(name)
                self._requests.put(r)
                if not r.done.wait(60.0):
                    return TriggerResponse(False, f"{name}: the node did not answer in 60 s")
                return TriggerResponse(r.ok, r.message)

            return call

        self.services = [
            self.rospy.Service("~" + n, Trigger, handler(n))
            for n in ("inflate", "capture_reference", "plan")
        ]

    # --- the loop -------------------------------------------------------------------------
    def run(self, max_frames: int | None = None) -> None:
        """Open the box, adjust, then publish every frame until ROS shuts down.

        On a hardware fault the diagnostics say ERROR, the box is made safe and the fault
        propagates (the command exits non-zero).
        """
        from softpad.box import open_box
        from softpad.control import DEFAULT_MAX_PRESSURE_PA, make_safe
        from softpad.ros import _messages as m

        stamp = self.rospy.Time.now()
        tf = m.static_transform(stamp, self.config.pad, self.config.base_frame)
        tf.transforms.extend(m.module_transforms(stamp, self.layout))
        self.pub_tf.publish(tf)
        with open_box(self.config.box) as box:
            self.box = box
            try:
                self._make_parts()
                self._adjust()
                self._place_later()
                self._loop(max_frames)
            except HardwareFault as exc:
                self.fault = str(exc)
                self._publish_diagnostics()
                make_safe(box, self.n, DEFAULT_MAX_PRESSURE_PA)
                raise

    def _make_parts(self) -> None:
        """The object detector, contact detector and planner from the registries, for the
        box's sample rate and the pad (as ``softpad run`` makes them)."""
        from softpad.planning import PlannerParams, planner_for
        from softpad.sensing import make_contact_detector, make_object_detector

        c, rate = self.config, float(self.box.sample_rate_hz)
        thresholds = {
            "contact_threshold_pa": c.contact_threshold_pa,
            "object_threshold_pa": c.object_threshold_pa,
        }
        self.object_detector = make_object_detector("thesis", rate, self.layout, **thresholds)
        self.contact_detector = make_contact_detector(c.detector, rate, self.layout, **thresholds)
        params = PlannerParams(object_threshold_pa=c.object_threshold_pa)
        self.planner = planner_for(
            c.planner, None, params, self.contact_detector, rate, self.layout
        )

    def _adjust(self) -> None:
        from softpad.control import inflate_and_adjust

        self._pace_reset()
        adj = inflate_and_adjust(self.box, self.n, on_frame=self._publish_frame)
        self._set_reference(adj.reference_pa)

    def _set_reference(self, reference_pa: NDArray[np.float64]) -> None:
        from softpad.sensing import RunningAverage

        self.reference_pa = np.asarray(reference_pa, dtype=float)
        self.increments = RunningAverage(thesis.FILTER_WINDOW)
        self.contact_ref: NDArray[np.float64] | None = None
        self._filtered = np.zeros(self.n)
        self.groups: list[tuple[int, ...]] = []
        self.changed_at = self.planned_at = -math.inf
        self._publish_plans([])

    def _place_later(self) -> None:
        self.place_at = None
        if self.config.place:
            from softpad.box import SimBox

            if not isinstance(self.box, SimBox):
                raise InputError("place= puts catalogue objects on a sim:// box only")
            self.place_at = self.last_t + self.config.place_after_s

    def _loop(self, max_frames: int | None) -> None:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA, check_frame

        next_diag = 0.0
        while not self.rospy.is_shutdown() and (max_frames is None or self.frames < max_frames):
            frame = self.box.read()
            self._publish_frame(frame)
            # NaN, dropout or over the maximum: HardwareFault (diagnostics ERROR, box made safe)
            self._track(check_frame(frame, self.n, DEFAULT_MAX_PRESSURE_PA))
            if self.place_at is not None and frame.t_s >= self.place_at:
                self._place()
            while not self._requests.empty():
                self._serve(self._requests.get())
            if time.monotonic() >= next_diag:
                self._publish_diagnostics()
                next_diag = time.monotonic() + 1.0

    def _place(self) -> None:
        from softpad.sim import get_object

        for name in self.config.place:
            self.box.world.place_object(get_object(name))  # type: ignore[attr-defined]
        self.place_at = None

    # --- per frame ------------------------------------------------------------------------
    def _pace_reset(self) -> None:
        self._wall0: float | None = None
        self.last_t = 0.0
        self._rate_window: list[float] = []

    def _publish_frame(self, frame: Any) -> None:
        """Publish one frame; a simulated box faster than real time is paced to the wall clock."""
        from softpad.ros import _messages as m

        now = time.monotonic()
        if self._wall0 is None:
            self._wall0, self._box0 = now - 0.0, frame.t_s
        ahead = (frame.t_s - self._box0) - (now - self._wall0)
        if ahead > 0:
            time.sleep(ahead)
        self.frames += 1
        self.last_t = frame.t_s
        self._rate_window = [*self._rate_window[-199:], time.monotonic()]
        stamp = self.rospy.Time.now()
        p = frame.pressures_pa[: self.n]
        for k, pub in enumerate(self.pub_module):
            pub.publish(
                m.fluid_pressure(stamp, k + 1, float(p[k]), self.config.ambient_pressure_pa)
            )
        self.pub_all.publish(m.labelled_array([*p, frame.supply_pa], "module_1..N_then_supply_pa"))
        self._last_pressures = p

    def _track(self, p: NDArray[np.float64]) -> None:
        """Objects from the filtered increments; plan once a changed set has settled; contact."""
        from std_msgs.msg import Bool

        assert self.reference_pa is not None
        d = self.increments.update(np.nan_to_num(p - self.reference_pa))
        self._filtered = d
        groups = self.object_detector.objects(d, self.layout)
        if groups != self.groups:
            self.groups, self.changed_at = groups, self.last_t
        elif (
            self.changed_at > self.planned_at
            and self.last_t - self.changed_at >= self.config.settle_s
        ):
            self._plan(d)
        contact = False
        if self.contact_ref is not None:
            contact = bool(self.contact_detector.update(p))
        self.pub_contact.publish(Bool(contact))

    def _plan(self, increments_pa: NDArray[np.float64]) -> list[Any]:
        objects = self.object_detector.objects(increments_pa, self.layout)
        plans = self.planner.plan(increments_pa, objects, self.layout)
        self.planned_at = self.last_t
        assert self.reference_pa is not None
        self.contact_ref = self.reference_pa + increments_pa  # the pad with the objects on it
        self.contact_detector.reset(self.contact_ref)
        self._publish_plans(plans)
        return plans

    def _publish_plans(self, plans: list[Any]) -> None:
        from softpad.ros import _messages as m

        self.plans = plans
        stamp = self.rospy.Time.now()
        self.pub_objects.publish(m.pose_array(stamp, m.object_poses(plans, self.layout)))
        self.pub_grasps.publish(m.pose_array(stamp, m.grasp_poses(plans, self.layout)))

    # --- services and diagnostics ---------------------------------------------------------
    def _serve(self, r: _Request) -> None:
        try:
            if r.name == "inflate":
                self._adjust()
                assert self.reference_pa is not None
                r.message = "adjusted; reference (Pa): " + _pa(self.reference_pa)
            elif r.name == "capture_reference":
                from softpad.sensing import capture_reference

                reads = []
                for _ in range(thesis.REFERENCE_READS):
                    frame = self.box.read()
                    self._publish_frame(frame)
                    reads.append(frame.pressures_pa[: self.n])
                self._set_reference(capture_reference(reads))
                r.message = "reference (Pa): " + _pa(self.reference_pa)
            else:
                plans = self._plan(self._filtered)
                r.message = json.dumps([p.to_dict(self.layout) for p in plans])
            r.ok = True
        except InputError as exc:
            r.message = str(exc)
        finally:
            r.done.set()

    def _publish_diagnostics(self) -> None:
        from diagnostic_msgs.msg import DiagnosticArray

        from softpad.ros import _messages as m

        rate = 0.0
        w = self._rate_window
        if len(w) > 1 and w[-1] > w[0]:
            rate = (len(w) - 1) / (w[-1] - w[0])
        nominal = float(self.box.sample_rate_hz)
        link = m.diagnostic_status(
            2 if self.fault else 0, "softpad: link", self.fault or "OK", box=self.config.box,
            frames=self.frames,
        )  # fmt: skip
        rate_ok = self.fault is None and rate >= 0.8 * nominal
        rate_st = m.diagnostic_status(
            0 if rate_ok else 1, "softpad: rate", "OK" if rate_ok else "below the box rate",
            rate_hz=f"{rate:.1f}", nominal_hz=f"{nominal:g}",
        )  # fmt: skip
        status = [link, rate_st]
        for k in range(1, self.n + 1):
            status.append(self._channel_status(k))
        msg = DiagnosticArray(status=status)
        msg.header.stamp = self.rospy.Time.now()
        self.pub_diag.publish(msg)

    def _channel_status(self, k: int) -> Any:
        from softpad.control import DEFAULT_MAX_PRESSURE_PA
        from softpad.ros import _messages as m

        p = float(getattr(self, "_last_pressures", np.zeros(self.n))[k - 1])
        bad = not math.isfinite(p) or p > DEFAULT_MAX_PRESSURE_PA
        valve = self.box.valves[k - 1].value if hasattr(self.box, "valves") else "?"
        return m.diagnostic_status(
            2 if bad else 0, f"softpad: channel {k}", "no valid reading or over the maximum"
            if bad else "OK", pressure_pa=f"{p:.1f}", valve=valve,
        )  # fmt: skip


def _pa(values: Any) -> str:
    return " ".join(f"{float(v):.1f}" for v in values)
