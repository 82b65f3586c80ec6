"""Simulated grasp trials of an object set on one pad design.

Each trial is the whole closed loop of Section 6.2 (``softpad.control.GraspExecution``: adjust
to p0, save the reference, wait for the object, plan, approach, descend until contact at t_g,
close, lift, hold) on the simulated box (chamber gas, valves, sensor noise) over the *analytic*
world (:class:`softpad.sim.AnalyticWorld`): it takes any R x C grid and pitch and runs a trial in
about 0.1 s, where the MuJoCo world of ``softpad trials`` is set up for the thesis's 2 x 3 pad
and 45 mm domes (``softpad.trials`` builds it with the default layout and pad physics) and
takes about a second per trial. The box's module characteristic is the design's finite-element
response (:meth:`FemResponse.characteristic`).

Trial ``k`` of an object uses :func:`softpad.trials.trial_seed` (experiment seed, object name,
k) for its placement noise and sensor noise, the same on every design: the designs are compared
on common random numbers.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from softpad import thesis
from softpad.errors import MM_AS_M, MS_AS_S, InputError, check_range

#: The box's valves of a design's trials (:attr:`TrialOptions.valves`).
VALVE_CHOICES = ("thesis", "sized")


def channel_capacity_m3_pa(characteristic: Any, pressure_pa: float) -> float:
    """Volume of atmospheric air a module's channel takes per pascal at ``pressure_pa``
    (isothermal, unloaded): ``dV/dp + (V + V_tubing) / (p_atm + p)``, m^3/Pa."""
    from softpad.sim import PneumaticParams

    pn = PneumaticParams()
    v = float(characteristic.volume_m3(pressure_pa, 0.0))
    c = float(characteristic.volume_slope_m3_pa(pressure_pa, 0.0))
    return c + (v + pn.tubing_volume_m3) / (pn.atmosphere_pa + pressure_pa)


def valve_scale(characteristic: Any, p0_pa: float) -> float:
    """Orifice scale of ``"sized"`` valves: the channel capacity of ``characteristic`` at p0
    over that of the thesis's module (:class:`softpad.sim.AnalyticCharacteristic`'s defaults,
    the project's FEM of the 45 mm module) at the thesis's p0."""
    from softpad.sim import AnalyticCharacteristic

    reference = channel_capacity_m3_pa(AnalyticCharacteristic(), thesis.P0_PA)
    return channel_capacity_m3_pa(characteristic, p0_pa) / reference


@dataclass(frozen=True)
class TrialOptions:
    """How the trials of a sweep are run."""

    #: Trials per object and seed.
    trials: int = 1
    #: Planner name (:func:`softpad.planning.available_planners`).
    planner: str = "thesis"
    #: Contact detector name (:func:`softpad.sensing.available_contact_detectors`).
    detector: str = "thesis"
    #: Hold time after the lift, seconds (thesis: 15 s).
    hold_s: float = thesis.HOLD_S
    #: Placement noise (normal), metres and radians (as ``softpad trials``: 3 mm, 3 degrees).
    position_sigma_m: float = 3e-3
    #: Placement noise (normal), metres and radians (as ``softpad trials``: 3 mm, 3 degrees).
    yaw_sigma_rad: float = math.radians(3.0)
    #: Box sample rate, hertz.
    sample_rate_hz: float = 100.0
    #: Sensor noise on.
    noise: bool = True
    #: Draw the uncertain inputs per trial (:data:`softpad.sim.UNCERTAIN_PARAMETERS`, seeded
    #: by the trial seed): tip stiffness, fingertip friction and grip force of the analytic
    #: world's gripper, sample rate, sensor noise, placement noise, the charger's and the
    #: can's unknowns; the design's own FEM pad keeps its seam and tubing.
    randomize: bool = False
    #: The gripper's mounting: None, each object's (the set's); ``"auto"``, chosen from the
    #: pad's reading of the placed object (:func:`softpad.planning.choose_mounting`); or one
    #: of ``"10/4"``, ``"6/2"``, ``"4/0"`` for every object.
    mounting: str | None = None
    #: The box's valves: ``"thesis"``, the thesis's orifices on every module; ``"sized"``,
    #: orifices scaled by the module's channel capacity over the thesis pad's
    #: (:func:`valve_scale`), so that a valve opening moves the pressure as much as on the
    #: thesis's pad (small modules need it: with the thesis's valves a 22.5 mm module cannot
    #: be adjusted to p0 within the tolerance, docs/design.md).
    valves: str = "thesis"

    def __post_init__(self) -> None:
        from softpad.planning import PLANNER_REGISTRY
        from softpad.sensing import CONTACT_DETECTOR_REGISTRY

        if (
            isinstance(self.trials, bool)
            or not isinstance(self.trials, int)
            or not 1 <= self.trials <= 100
        ):
            raise InputError(
                f"trials per object must be an integer from 1 to 100, got {self.trials!r}"
            )
        PLANNER_REGISTRY.factory(self.planner)  # InputError naming the known ones
        CONTACT_DETECTOR_REGISTRY.factory(self.detector)
        check_range("trial options hold_s", self.hold_s, 0.0, 60.0, "s", MS_AS_S)
        # a placement spread beyond a module pitch is a unit mix-up (as TrialConfig says)
        check_range(
            "trial options position_sigma_m", self.position_sigma_m, 0.0, 0.05, "m", MM_AS_M
        )
        check_range("trial options yaw_sigma_rad", self.yaw_sigma_rad, 0.0, math.pi, "rad")
        check_range("trial options sample_rate_hz", self.sample_rate_hz, 1.0, 100_000.0, "Hz")
        from softpad.trials import check_mounting_choice

        check_mounting_choice(self.mounting, "trial options mounting")
        if self.valves not in VALVE_CHOICES:
            raise InputError(
                f"trial options valves must be one of {', '.join(VALVE_CHOICES)}, got "
                f"{self.valves!r}"
            )

    def to_dict(self) -> dict[str, Any]:
        """The options (SI), part of every cache key."""
        return asdict(self)


def run_design_trials(
    design: Any, response: Any, object_set: Any, seed: int, options: TrialOptions
) -> list[dict[str, Any]]:
    """Every trial of ``object_set`` on ``design`` for one experiment seed.

    Parameters
    ----------
    design
        A :class:`~softpad.design.PadDesign`.
    response
        Its :class:`~softpad.design.FemResponse` (or the response's dict).
    object_set
        An :class:`~softpad.design.ObjectSet`.
    seed
        Experiment seed.
    options
        How to run the trials.

    Returns
    -------
    One dict per trial: ``object``, ``trial``, ``seed``, ``success``, ``outcome``,
    ``contact_delay_s`` (None when no contact was detected), ``sim_time_s``.
    """
    from softpad.design._response import FemResponse

    if isinstance(response, dict):
        response = FemResponse.from_dict(response)
    characteristic = response.characteristic()
    out = []
    for obj in object_set.objects:
        for k in range(options.trials):
            out.append(_one_trial(design, characteristic, object_set, obj, seed, k, options))
    return out


def _one_trial(
    design: Any,
    characteristic: Any,
    object_set: Any,
    obj: Any,
    seed: int,
    k: int,
    options: TrialOptions,
) -> dict[str, Any]:
    """One trial of one object (see :func:`run_design_trials`)."""
    from softpad.control import ExecutionError
    from softpad.errors import HardwareFault
    from softpad.harness import SimulatedRobot
    from softpad.sim import AnalyticWorld, Placement, SimGripper
    from softpad.trials import TrialConfig, perturbed_placement, trial_seed

    s = trial_seed(seed, obj.name, k)
    options, lab, physics = _varied(options, s)
    spec = obj.placed_on((design.cols * design.pitch_m, design.rows * design.pitch_m))
    spec = spec if lab is None else lab.object(spec)
    noise = TrialConfig(
        position_sigma_m=options.position_sigma_m, yaw_sigma_rad=options.yaw_sigma_rad
    )
    placement = Placement(*perturbed_placement(spec, s, noise))
    mounting = _mounting(
        design, characteristic, object_set.mounting(obj), spec, placement, s, options, lab
    )
    world = AnalyticWorld(design.layout, SimGripper.mounting(mounting, **physics))
    box = _trial_box(design, world, characteristic, s, options, lab)
    robot = SimulatedRobot(world)
    loop = _trial_loop(
        design, world, box, robot, options, lambda: world.place_object(spec, placement)
    )
    record: dict[str, Any] = {"object": obj.name, "trial": k, "seed": seed, "mounting": mounting}
    if lab is not None:
        record["parameters"] = lab.to_dict()
    with box:
        try:
            result = loop.run()
        except (ExecutionError, HardwareFault) as exc:
            outcome = "box_fault" if isinstance(exc, HardwareFault) else "object_not_detected"
            return {**record, "success": False, "outcome": outcome, "contact_delay_s": None,
                    "sim_time_s": box.time_s}  # fmt: skip
    return {
        **record,
        "success": result.outcome == "held",
        "outcome": result.outcome,
        "contact_delay_s": _contact_delay_s(result, robot),
        "sim_time_s": box.time_s,
    }


def _mounting(
    design: Any,
    characteristic: Any,
    own: str,
    spec: Any,
    placement: Any,
    seed: int,
    options: TrialOptions,
    lab: Any,
) -> str:
    """The trial's mounting: the object's own (``options.mounting`` None), the one named, or
    (``"auto"``) the one chosen from the design pad's reading of the placed object
    (:func:`softpad.planning.choose_mounting`), read on a separate world and box at p0."""
    if options.mounting is None:
        return own
    if options.mounting != "auto":
        return str(options.mounting)
    from softpad.box import SimBox
    from softpad.planning import choose_mounting
    from softpad.sim import AnalyticWorld, SensorParams
    from softpad.trials import read_increments

    world = AnalyticWorld(design.layout)
    box = SimBox(
        world,
        channels=max(8, design.layout.n_modules),
        sample_rate_hz=options.sample_rate_hz,
        seed=seed % (2**31),
        characteristic=characteristic,
        sensor=(SensorParams() if lab is None else lab.sensor())
        if options.noise
        else SensorParams.ideal(),
        initial_pressure_pa=design.p0_pa,
    )
    p = (placement.x_m, placement.y_m, placement.yaw_rad)
    return choose_mounting(read_increments(world, box, spec, p), design.layout)


def _trial_box(
    design: Any, world: Any, characteristic: Any, seed: int, options: TrialOptions, lab: Any
) -> Any:
    """The simulated box of one trial: the design's module characteristic, its valves
    (``options.valves``), the trial's sensor noise (drawn by ``lab`` when randomized), started
    at 0.9 p0 with the sweep's safety limits."""
    from softpad.box import SafetyLimits, SimBox
    from softpad.sim import PneumaticParams, SensorParams

    pneumatics = PneumaticParams()
    if options.valves == "sized":
        k = valve_scale(characteristic, design.p0_pa)
        pneumatics = PneumaticParams(
            inflate_orifice_m2=pneumatics.inflate_orifice_m2 * k,
            deflate_orifice_m2=pneumatics.deflate_orifice_m2 * k,
        )
    box = SimBox(
        world,
        channels=max(8, design.layout.n_modules),
        sample_rate_hz=options.sample_rate_hz,
        seed=seed % (2**31),
        characteristic=characteristic,
        pneumatics=pneumatics,
        sensor=(SensorParams() if lab is None else lab.sensor())
        if options.noise
        else SensorParams.ideal(),
        initial_pressure_pa=0.9 * design.p0_pa,
    )
    box.safety_limits = SafetyLimits(max_pressure_pa=9.5e3, release_pa=2.5e3)
    return box


def _trial_loop(
    design: Any, world: Any, box: Any, robot: Any, options: TrialOptions, place_objects: Any
) -> Any:
    """The closed loop of one trial: inflation to the design's p0, the named planner and
    contact detector on the design's layout and the analytic world's gripper."""
    from softpad.control import InflationParams
    from softpad.harness import build_loop
    from softpad.planning import planner_for
    from softpad.sensing import make_contact_detector
    from softpad.trials import trial_execution_params

    layout = design.layout
    params = trial_execution_params(
        inflation=InflationParams(target_pa=design.p0_pa, max_pressure_pa=9.5e3),
        hold_s=options.hold_s,
    )
    detector = make_contact_detector(options.detector, box.sample_rate_hz, layout)
    geometry = world.gripper.geometry
    planner = planner_for(
        options.planner, geometry, params.planner, detector, box.sample_rate_hz, layout
    )
    return build_loop(
        box,
        robot,
        params=params,
        layout=layout,
        planner=planner,
        contact_detector=detector,
        place_objects=place_objects,
    ).execution


def _contact_delay_s(result: Any, robot: Any) -> float | None:
    """Seconds from the first touch to the first grasp's detected contact, or None."""
    if result.grasps and robot.touches:
        g, t = result.grasps[0], robot.touches[0]
        if g.detected_at_s is not None and t.first_touch_s is not None:
            return float(g.detected_at_s - t.first_touch_s)
    return None


def _varied(options: TrialOptions, seed: int) -> tuple[TrialOptions, Any, dict[str, float]]:
    """With ``options.randomize``: the options with the drawn placement noise and sample rate,
    the :class:`softpad.sim.LabVariation` of ``seed`` and the analytic gripper's drawn fields;
    else the options, None and no fields."""
    if not options.randomize:
        return options, None, {}
    from softpad.trials import drawn_placement

    options, lab = drawn_placement(options, seed)
    v = lab.values
    physics = {
        "tip_stiffness_n_m": v["pad_tip_stiffness_n_m"],
        "friction": v["fingertip_friction"],
        "grip_force_n": v["grip_force_n"],
    }
    return options, lab, physics
