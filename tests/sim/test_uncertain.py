"""The simulator's uncertain inputs: one list with ranges and sources, seeded draws that stay in
their ranges and reach the simulated lab (issue 33)."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.sim import (
    OBJECT_UNKNOWNS,
    UNCERTAIN_PARAMETERS,
    LabVariation,
    UncertainParameter,
    draw_uncertain,
    get_object,
    nominal_uncertain,
)

N_SEEDS = 400


def test_every_parameter_has_a_range_and_a_source() -> None:
    names = [p.name for p in UNCERTAIN_PARAMETERS]
    assert len(set(names)) == len(names)
    for p in UNCERTAIN_PARAMETERS:
        assert p.low < p.high, p.name
        assert len(p.source) > 30 and p.sets, p.name
    # the figures the issue names are in the list
    for name in ("pad_tip_stiffness_n_m", "fingertip_friction", "seam_width_m", "sample_rate_hz"):
        assert name in names
    # the pad stiffness range is the project's FEM's (docs/fem.md: 96-187 N/m near 1 kPa)
    k = {p.name: p for p in UNCERTAIN_PARAMETERS}["pad_tip_stiffness_n_m"]
    assert (k.low, k.high) == (96.0, 187.0)


@pytest.mark.parametrize("p", UNCERTAIN_PARAMETERS, ids=lambda p: p.name)
def test_every_nominal_lies_inside_its_sourced_range(p: UncertainParameter) -> None:
    """Issue 45: a nominal outside its own range is a figure the evidence does not support."""
    assert p.low <= p.nominal <= p.high, (p.name, p.nominal, p.low, p.high)
    # the nominal lab passes the same check as a drawn one (no exemption for nominals)
    assert LabVariation.of({p.name: p.nominal}).values[p.name] == p.nominal


def test_the_nominals_are_the_simulators_defaults() -> None:
    """The MuJoCo pad and gripper run at the nominals when nothing is drawn."""
    from softpad.sim import MujocoGripper, PadPhysics

    v = nominal_uncertain()
    assert PadPhysics().local_stiffness_n_m == v["pad_tip_stiffness_n_m"]
    assert PadPhysics().friction == v["pad_friction"]
    assert MujocoGripper().friction == v["fingertip_friction"]
    assert MujocoGripper().grip_force_n == v["grip_force_n"]
    # hard plastic tips (Section 6.3): not the rubber-like 0.8 of before
    assert v["fingertip_friction"] <= 0.7


def test_draws_stay_in_range_are_reproducible_and_spread_uniformly() -> None:
    draws = [draw_uncertain(s) for s in range(N_SEEDS)]
    assert draw_uncertain(7) == draw_uncertain(7)
    for p in UNCERTAIN_PARAMETERS:
        x = np.array([d[p.name] for d in draws])
        assert np.all((p.low <= x) & (x <= p.high)), p.name
        u = (x - p.low) / (p.high - p.low)
        # uniform on [0, 1]: mean 0.5 with standard error 1/sqrt(12 N) = 0.0144; 5 sigma
        assert abs(u.mean() - 0.5) < 5 / np.sqrt(12 * N_SEEDS), p.name
        assert len(set(x.tolist())) == N_SEEDS, p.name  # every seed draws its own value
    # parameters are drawn independently of each other (|r| under 5 / sqrt(N) = 0.25)
    a = np.array([[d[p.name] for p in UNCERTAIN_PARAMETERS] for d in draws])
    r = np.corrcoef(a.T)
    assert np.max(np.abs(r - np.eye(len(r)))) < 5 / np.sqrt(N_SEEDS)


def test_values_are_checked() -> None:
    with pytest.raises(InputError, match="unknown uncertain parameter"):
        LabVariation.of({"nope": 1.0})
    with pytest.raises(InputError, match=r"grip_force_n must be within 10\.\.35"):
        LabVariation.of({"grip_force_n": 90.0})
    with pytest.raises(InputError, match="integer >= 0"):
        draw_uncertain(-1)
    assert LabVariation.of(None).values == nominal_uncertain()


def test_unknown_object_figures_vary_and_keep_the_thesis_mass() -> None:
    lab = LabVariation.of({"charger_brick_scale": 0.9, "cylinder_heavy_x_m": -0.02})
    charger, can = get_object("charger"), get_object("cylinder")
    c2, can2 = lab.object(charger), lab.object(can)
    assert c2.parts[0].size_m[0] == pytest.approx(0.9 * charger.parts[0].size_m[0])
    assert c2.mass_kg == charger.mass_kg  # Table 6.1's mass stays
    heavy = next(p for p in can2.parts if p.name == "heavy part")
    assert heavy.pos_m[0] == pytest.approx(-0.02)
    assert lab.object(get_object("object-1")) == get_object("object-1")


def test_drawn_values_reach_the_simulated_lab() -> None:
    """The drawn stiffness, frictions, grip force and seam appear in the built MuJoCo model;
    rate, sensor noise and tubing in the simulated box."""
    from softpad.sim._mujoco_model import part_geom_xml
    from softpad.trials import TrialConfig
    from softpad.trials._loop import _Trial, varied_lab

    spec = get_object("object-1")
    config = TrialConfig(randomize=True)
    spec2, cfg, lab = varied_lab(spec, 123, config)
    assert lab is not None and lab.values == draw_uncertain(123)
    v = lab.values
    assert cfg.sample_rate_hz == v["sample_rate_hz"]
    assert cfg.position_sigma_m == v["placement_sigma_m"]
    t = _Trial(spec2, (0.1, 0.045, 0.0), 123, cfg, None, None, lab=lab)
    model = t.world.scene.model
    stiff = [float(model.jnt_stiffness[j]) for j in range(model.njnt)]
    assert any(s == pytest.approx(v["pad_tip_stiffness_n_m"], rel=1e-5) for s in stiff)
    frictions = {round(float(f), 5) for f in model.geom_friction[:, 0]}
    assert round(v["fingertip_friction"], 5) in frictions
    # the finger's friction governs its contacts with objects (MuJoCo takes the geom of
    # higher priority; with equal priorities the larger friction, the object's, would win)
    finger = [model.geom(f"finger_{s}").id for s in ("right", "left")]
    assert all(model.geom_priority[f] > 0 for f in finger)
    assert "priority" not in part_geom_xml(spec.parts[0], "o", "1 0 0 1", 0.8)  # objects at 0
    assert round(v["pad_friction"], 5) in frictions
    assert model.actuator_forcerange[:, 1] == pytest.approx(v["grip_force_n"], rel=1e-5)
    assert t.world.response.seam_width_m == pytest.approx(v["seam_width_m"], abs=1e-12)
    assert t.box.sample_rate_hz == pytest.approx(v["sample_rate_hz"])
    assert t.box.pneumatics.tubing_volume_m3 == v["tubing_volume_m3"]
    assert t.box.sensor_params.noise_std_pa == pytest.approx(8.0 * v["sensor_noise_scale"])


def test_a_randomized_trial_reports_its_draws() -> None:
    from softpad.trials import TrialConfig, run_trial, trial_execution_params

    cfg = TrialConfig(trial_execution_params(hold_s=0.2), randomize=True)
    result, _ = run_trial(get_object("object-1"), seed=5, config=cfg)
    assert result.parameters is not None
    assert result.parameters == LabVariation.of(draw_uncertain(5)).to_dict()
    assert result.to_dict()["parameters"] == result.parameters
    plain, _ = run_trial(get_object("object-1"), seed=5, config=TrialConfig(cfg.execution))
    assert plain.parameters is None


@pytest.mark.parametrize("name", sorted(OBJECT_UNKNOWNS))
def test_the_catalogue_objects_are_built_at_the_nominals(name: str) -> None:
    """The nominal lab leaves each catalogue object as it is (the fitted nominals are in
    the catalogue), and a drawn value keeps Table 6.1's mass."""
    spec = get_object(name)
    same = LabVariation.of(None).object(spec)
    for a, b in zip(spec.parts, same.parts, strict=True):
        np.testing.assert_allclose(a.pos_m, b.pos_m, atol=2e-6)
        assert a.mass_kg == pytest.approx(b.mass_kg, rel=1e-5)
        assert a.yaw_rad == pytest.approx(b.yaw_rad, abs=5e-5)  # the JSON's 6 decimals
    p = {q.name: q for q in UNCERTAIN_PARAMETERS}[OBJECT_UNKNOWNS[name]]
    varied = LabVariation.of({p.name: p.low}).object(spec)
    assert sum(q.mass_kg for q in varied.parts) == pytest.approx(spec.mass_kg, rel=1e-9)
    assert varied != spec


def test_object_unknowns_set_what_they_name() -> None:
    """Each setting measured back from the object it builds."""
    lab = LabVariation.of(
        {
            "charger_brick_mass_share": 0.7,
            "toy_right_hand_share": 0.25,
            "limes_pair_gap_m": 0.01,
            "banana_sagitta_m": 0.04,
        }
    )
    charger = lab.object(get_object("charger"))
    assert charger.parts[0].mass_kg == pytest.approx(0.7 * 0.3123)
    toy = {p.name: p.mass_kg for p in lab.object(get_object("toy")).parts}
    assert toy["right hand"] / (toy["right hand"] + toy["left hand"]) == pytest.approx(0.25)
    limes = [np.array(p.pos_m) for p in lab.object(get_object("limes")).parts]
    assert np.linalg.norm(limes[1] - limes[0]) == pytest.approx(0.049 + 0.01)
    for lower in limes[:2]:  # the third rests on both: centres one diameter apart
        assert np.linalg.norm(limes[2] - lower) == pytest.approx(0.049)
    banana = lab.object(get_object("banana")).parts
    a, b = np.array(banana[0].pos_m[:2]), np.array(banana[-1].pos_m[:2])
    u = (b - a) / np.linalg.norm(b - a)
    rel = [np.array(p.pos_m[:2]) - a for p in banana]
    dist = [abs(u[0] * r[1] - u[1] * r[0]) for r in rel]
    assert max(dist) == pytest.approx(0.04)
