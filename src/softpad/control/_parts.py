"""The loop's parts by registered name, made the one way every entry point makes them."""

from __future__ import annotations

from typing import Any

from softpad.control._execution import ExecutionParams
from softpad.layout import GripperSpec, PadLayout


def loop_parts(
    planner: str,
    detector: str,
    sample_rate_hz: float,
    layout: PadLayout,
    gripper: GripperSpec | None,
    params: ExecutionParams,
) -> dict[str, Any]:
    """The planner and contact detector named ``planner`` and ``detector``, made by their
    registries (:data:`softpad.planning.PLANNER_REGISTRY`,
    :data:`softpad.sensing.CONTACT_DETECTOR_REGISTRY`) for the box's rate, the pad, the
    gripper and the loop's thresholds and window: the ``planner`` and ``contact_detector``
    keywords of :class:`~softpad.control.GraspExecution`, as ``softpad run`` and the ROS
    node's ``~grasp`` give them."""
    from softpad.planning import planner_for
    from softpad.sensing import make_contact_detector

    contact = make_contact_detector(
        detector,
        sample_rate_hz,
        layout,
        gripper=gripper,
        contact_threshold_pa=params.contact_threshold_pa,
        object_threshold_pa=params.planner.object_threshold_pa,
        window=params.filter_length,
    )
    plan = planner_for(planner, gripper, params.planner, contact, sample_rate_hz, layout)
    return {"planner": plan, "contact_detector": contact}
