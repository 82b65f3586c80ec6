"""Planners by name (``--planner``): a registry with the entry-point group ``softpad.planners``.

A factory takes a :class:`PlannerContext` (the pad's layout, the box's sample rate, the
gripper, the planner parameters and the loop's contact detector) and returns a
:class:`~softpad.planning.Planner` (docs/architecture.md shows how to add one).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

from softpad.layout import GripperSpec, PadLayout
from softpad.planning._params import PlannerParams
from softpad.planning._plan import Planner, ThesisPlanner
from softpad.registry import Registry
from softpad.sensing import ContactDetector, sensing_ratio


@dataclass(frozen=True)
class PlannerContext:
    """What a planner factory is told about the loop it plans for.

    Parameters
    ----------
    layout
        The pad.
    sample_rate_hz
        Frames per second of the box, hertz.
    gripper
        The gripper's geometry, None when not known (the thesis's 10/4 mounting then).
    params
        Planner parameters (t_o, c_s, default theta); None: the thesis's.
    contact_detector
        The loop's contact detector (a planner may ask how small a rise it senses), None:
        the thesis's.
    catalogue
        Catalogue file of known objects (``softpad learn``) for ``--planner catalogue``; None:
        no object is known.
    """

    layout: PadLayout = field(default_factory=PadLayout)
    sample_rate_hz: float = 100.0
    gripper: GripperSpec | None = None
    params: PlannerParams | None = None
    contact_detector: ContactDetector | None = None
    catalogue: str | None = None

    def sensing_ratio(self) -> float:
        """The contact detector's sensing ratio (:func:`softpad.sensing.sensing_ratio`; 1 for
        the thesis's detector and for one that cannot be probed). Measured on each call: a
        1 kHz detector's probe takes seconds, so only planners that need it ask."""
        if self.contact_detector is None:
            return 1.0
        ratio = sensing_ratio(self.contact_detector, self.sample_rate_hz)
        return 1.0 if ratio is None else ratio


PlannerFactory = Callable[[PlannerContext], Planner]

#: Planners by name; entry-point group ``softpad.planners``.
PLANNER_REGISTRY: Registry[PlannerFactory] = Registry("planner", "softpad.planners")


def register_planner(name: str, factory: PlannerFactory, summary: str | None = None) -> None:
    """Offer ``factory(context) -> Planner`` as ``--planner name`` in every command."""
    PLANNER_REGISTRY.register(name, factory, summary)


def available_planners() -> tuple[str, ...]:
    """Names of the planners (built in, registered, and from entry points)."""
    return PLANNER_REGISTRY.names()


def make_planner(name: str, context: PlannerContext | None = None, **fields: Any) -> Planner:
    """The planner registered as ``name`` for ``context`` (its fields may be given as keywords
    instead: ``make_planner("gripper-aware", gripper=GripperSpec.from_mounting("6/2"))``).
    InputError names an unknown planner and the known ones."""
    return PLANNER_REGISTRY.factory(name)(replace(context or PlannerContext(), **fields))


def planner_for(
    name: str,
    gripper: GripperSpec | None,
    params: PlannerParams | None,
    detector: ContactDetector,
    sample_rate_hz: float,
    layout: PadLayout | None = None,
    catalogue: str | None = None,
) -> Planner:
    """:func:`make_planner` for a loop that detects contact with ``detector`` at
    ``sample_rate_hz`` on ``layout`` (the thesis's 2 x 3 pad when None); ``catalogue``: the
    known objects' file of ``--planner catalogue``."""
    context = PlannerContext(
        layout or PadLayout(), sample_rate_hz, gripper, params, detector, catalogue
    )
    return make_planner(name, context)


def _thesis(context: PlannerContext) -> Planner:
    """the thesis's rules (Section 6.2.1.3), generalised to R x C pads"""
    return ThesisPlanner(context.params)


def _gripper_aware(context: PlannerContext) -> Planner:
    """fingertips on sensed area, opening spanning the object, a retry after a miss"""
    from softpad.planning._gripper_aware import GripperAwarePlanner

    return GripperAwarePlanner(
        context.gripper, context.params, sensing_ratio=context.sensing_ratio()
    )


def _model_based(context: PlannerContext) -> Planner:
    """footprint estimated from the pad model, the grasp most likely to succeed, landings as
    evidence"""
    from softpad.planning._model_based import ModelBasedPlanner

    gripper = context.gripper or GripperSpec()
    return ModelBasedPlanner(gripper, sensing_ratio=context.sensing_ratio())


def _catalogue(context: PlannerContext) -> Planner:
    """known objects (softpad learn) grasped where they were held, unknown ones model-based"""
    from softpad.planning._catalogue import Catalogue, CataloguePlanner, load_catalogue

    n = context.layout.n_modules
    known = load_catalogue(context.catalogue) if context.catalogue else Catalogue(n, 1.0)
    return CataloguePlanner(known, _model_based(context))


register_planner("thesis", _thesis)
register_planner("gripper-aware", _gripper_aware)
register_planner("model-based", _model_based)
register_planner("catalogue", _catalogue)


def plan_by_name(
    planner: str,
    mounting: str,
    delta_pa: Any,
    layout: PadLayout,
    params: PlannerParams,
) -> Any:
    """The plans the registered planner ``planner`` makes of one reading (the thesis's:
    :func:`softpad.planning.plan_grasps`), for the gripper ``mounting``.

    Parameters
    ----------
    planner
        A registered planner's name (:func:`available_planners`).
    mounting
        Gripper mounting ``"10/4"``, ``"6/2"`` or ``"4/0"``.
    delta_pa
        Every module's pressure increment, Pa.
    layout
        The pad.
    params
        The planner's parameters (object threshold t_o, safety shift).

    Returns
    -------
    list of GraspPlan
        One plan per object found.
    """
    from softpad.planning._plan import plan_grasps
    from softpad.sensing import detect_objects

    check_planner_choice(planner, mounting)
    if planner == "thesis":
        return plan_grasps(delta_pa, layout, params)
    gripper = GripperSpec.from_mounting(mounting)
    made = make_planner(planner, layout=layout, gripper=gripper, params=params)
    return made.plan(delta_pa, detect_objects(delta_pa, layout, params.object_threshold_pa), layout)


def check_planner_choice(planner: str, mounting: str) -> None:
    """Refuse an unknown planner or gripper mounting, naming the known ones.

    Parameters
    ----------
    planner
        A planner's name (``--planner``).
    mounting
        A gripper mounting (``--gripper``).
    """
    from softpad import thesis
    from softpad.errors import InputError

    if planner not in (names := available_planners()):
        raise InputError(f"--planner must be one of {', '.join(names)}, got {planner!r}")
    if mounting not in thesis.GRIPPER_MOUNTINGS_M:
        raise InputError(
            f"--gripper must be one of {', '.join(thesis.GRIPPER_MOUNTINGS_M)}, got {mounting!r}"
        )
