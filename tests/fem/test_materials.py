"""Material models of thesis Table 7.1: analytic stresses, conventions, bad parameters."""

from __future__ import annotations

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.fem import MATERIAL_PRESETS, MODEL_NAMES, MaterialModel, get_material

#: Stretches; the stretch-based models (Ogden, Varga) go through tensortrax eigvalsh, which
#: perturbs repeated eigenvalues slightly, hence rtol 1e-5 in the comparisons below.
STRETCHES = np.array([0.8, 1.0001, 1.3, 1.8, 2.5])

#: Initial shear moduli (Pa) from the Table 7.1 parameters, computed by hand:
#: Mooney-Rivlin 2 (0.4375 + 0.0625) mu; Ogden 1/2 sum mu_i alpha_i; Varga c1 / 2; Yeoh 2 c1.
SHEAR_MODULI = {
    "neo-hookean": 42.0e3,
    "mooney-rivlin": 42.0e3,
    "ogden-1": 0.5 * (22.0 * 1.3 + 0.4 * 5.0 + (-2.0) * (-2.0)) * 1e3,
    "ogden-2": 0.5 * (24.3 * 1.7138 + 0.0667 * 7.0679 + 0.4538 * 3.3659) * 1e3,
    "varga": 42.0e3,
    "yeoh": 34.0e3,
}


def closed_form_uniaxial(name: str, lam: np.ndarray) -> np.ndarray:
    """Textbook incompressible uniaxial Cauchy stresses, written out per model (Pa)."""
    m = MATERIAL_PRESETS[name]
    p = m.parameters
    if name == "neo-hookean":
        return p["mu"] * (lam**2 - 1 / lam)
    if name == "mooney-rivlin":
        return 2 * (lam**2 - 1 / lam) * (p["c1"] + p["c2"] / lam)
    if name == "yeoh":
        e = lam**2 + 2 / lam - 3
        return 2 * (lam**2 - 1 / lam) * (p["c1"] + 2 * p["c2"] * e + 3 * p["c3"] * e**2)
    if name.startswith("ogden"):
        return sum(
            p[f"mu{i}"] * (lam ** p[f"alpha{i}"] - lam ** (-p[f"alpha{i}"] / 2)) for i in (1, 2, 3)
        )
    # varga, c2 = 0: sigma = c1 (lam - lam^-1/2)
    return p["c1"] * (lam - lam**-0.5) + p["c2"] * (lam**0.5 - 1 / lam)


def closed_form_equibiaxial(name: str, lam: np.ndarray) -> np.ndarray:
    """Textbook incompressible equibiaxial Cauchy stresses (Pa)."""
    m = MATERIAL_PRESETS[name]
    p = m.parameters
    if name == "neo-hookean":
        return p["mu"] * (lam**2 - lam**-4)
    if name == "mooney-rivlin":
        return 2 * (lam**2 - lam**-4) * (p["c1"] + p["c2"] * lam**2)
    if name == "yeoh":
        e = 2 * lam**2 + lam**-4 - 3
        return 2 * (lam**2 - lam**-4) * (p["c1"] + 2 * p["c2"] * e + 3 * p["c3"] * e**2)
    if name.startswith("ogden"):
        return sum(
            p[f"mu{i}"] * (lam ** p[f"alpha{i}"] - lam ** (-2 * p[f"alpha{i}"])) for i in (1, 2, 3)
        )
    return p["c1"] * (lam - lam**-2) + p["c2"] * (lam**2 - 1 / lam)


def felupe_cauchy(material: MaterialModel, stretches: tuple[np.ndarray, ...]) -> np.ndarray:
    """Cauchy stress of the FElupe (tensortrax) isochoric energy at diagonal F, (3, 3, n)."""
    n = len(stretches[0])
    F = np.zeros((3, 3, 1, n))
    for i in range(3):
        F[i, i, 0] = stretches[i]
    P = material.felupe_material(automatic_differentiation=True).gradient([F, None])[0]
    J = np.prod(np.stack(stretches), axis=0)
    return np.einsum("iJqc,kJqc->ikqc", P, F)[:, :, 0] / J


@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_shear_modulus_from_table_7_1(name: str) -> None:
    np.testing.assert_allclose(get_material(name).shear_modulus_pa, SHEAR_MODULI[name], rtol=1e-12)
    np.testing.assert_allclose(get_material(name).bulk_modulus_pa, 1e5 * SHEAR_MODULI[name])


@pytest.mark.parametrize("mode", ["uniaxial", "equibiaxial"])
@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_principal_form_matches_closed_form(name: str, mode: str) -> None:
    m = get_material(name)
    closed_form = {"uniaxial": closed_form_uniaxial, "equibiaxial": closed_form_equibiaxial}
    np.testing.assert_allclose(
        getattr(m, f"{mode}_stress_pa")(STRETCHES),
        closed_form[mode](name, STRETCHES),
        rtol=1e-12,
        atol=1e-9,
    )


@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_felupe_energy_gives_analytic_uniaxial_stress(name: str) -> None:
    """sigma_11 - sigma_22 of the automatic-differentiation energy at F = diag(l, l^-1/2, l^-1/2)."""
    m = get_material(name)
    lam = STRETCHES
    sigma = felupe_cauchy(m, (lam, lam**-0.5, lam**-0.5))
    np.testing.assert_allclose(
        sigma[0, 0] - sigma[1, 1], closed_form_uniaxial(name, lam), rtol=1e-5, atol=1e-3
    )


@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_felupe_energy_gives_analytic_equibiaxial_stress(name: str) -> None:
    m = get_material(name)
    lam = STRETCHES
    sigma = felupe_cauchy(m, (lam, lam, lam**-2))
    np.testing.assert_allclose(
        sigma[0, 0] - sigma[2, 2], closed_form_equibiaxial(name, lam), rtol=1e-5, atol=1e-3
    )


@pytest.mark.parametrize("name", MODEL_NAMES, ids=MODEL_NAMES)
def test_isochoric_energy_is_blind_to_volume_change(name: str) -> None:
    """W_iso(C_bar): a pure dilatation leaves the stress deviator and the energy at rest."""
    m = get_material(name)
    j = np.array([0.9, 1.0, 1.1])
    s = j ** (1 / 3)
    sigma = felupe_cauchy(m, (s, s, s))
    deviator = sigma - np.trace(sigma)[None, None] / 3 * np.eye(3)[:, :, None]
    np.testing.assert_allclose(deviator, 0.0, atol=1e-6 * m.shear_modulus_pa)


def test_thesis_ogden_equals_felupe_ogden_with_converted_moduli() -> None:
    """Thesis mu_i/alpha_i (...) is FElupe's 2 mu_i'/alpha_i^2 (...) with mu_i' = mu_i alpha_i / 2."""
    import felupe.constitution.tensortrax as mat

    m = get_material("ogden-1")
    alphas = [m.parameters[f"alpha{i}"] for i in (1, 2, 3)]
    mus = [m.parameters[f"mu{i}"] * a / 2 for i, a in zip((1, 2, 3), alphas, strict=True)]
    builtin = mat.Hyperelastic(mat.models.hyperelastic.ogden, mu=mus, alpha=alphas)
    rng = np.random.default_rng(7)
    F = np.eye(3)[:, :, None, None] + 0.2 * rng.standard_normal((3, 3, 1, 5))
    ours = m.felupe_material(automatic_differentiation=True).gradient([F, None])[0]
    theirs = builtin.gradient([F, None])[0]
    np.testing.assert_allclose(ours, theirs, rtol=1e-8, atol=1e-8)


def test_tensortrax_neo_hookean_matches_felupe_hand_coded() -> None:
    import felupe as fem

    m = get_material("neo-hookean")
    rng = np.random.default_rng(3)
    F = np.eye(3)[:, :, None, None] + 0.3 * rng.standard_normal((3, 3, 2, 4))
    ours = m.felupe_material(automatic_differentiation=True).gradient([F, None])[0]
    theirs = m.felupe_material().gradient([F, None])[0]
    assert isinstance(m.felupe_material(), fem.NeoHooke)
    np.testing.assert_allclose(ours, theirs, rtol=1e-8, atol=1e-6)


@pytest.mark.parametrize(
    ("kind", "params", "fragment"),
    [
        ("neo-hookean", {"mu": -1.0}, "-1 Pa"),
        ("neo-hookean", {"mu": 0.0}, "0 Pa"),
        ("yeoh", {"c1": -5.0, "c2": 10.0, "c3": 1.0}, "-10 Pa"),
        ("mooney-rivlin", {"c1": 1e3, "c2": -2e3}, "-2000"),
        (
            "ogden",
            {"mu1": -1e3, "mu2": 0.0, "mu3": 0.0, "alpha1": 2.0, "alpha2": 1.0, "alpha3": 1.0},
            "-1000",
        ),
    ],
    ids=["nh-negative", "nh-zero", "yeoh-negative-c1", "mr-negative-sum", "ogden-negative"],
)
def test_non_convex_parameters_are_rejected_naming_the_value(
    kind: str, params: dict[str, float], fragment: str
) -> None:
    with pytest.raises(InputError, match="not convex") as info:
        MaterialModel("bad", kind, params)
    assert fragment in str(info.value)


def test_unknown_model_and_bad_parameters_are_input_errors() -> None:
    with pytest.raises(InputError, match="'rubber'"):
        get_material("rubber")
    with pytest.raises(InputError, match="needs parameters"):
        MaterialModel("x", "yeoh", {"c1": 1.0})
    with pytest.raises(InputError, match="finite"):
        MaterialModel("x", "neo-hookean", {"mu": float("nan")})
    with pytest.raises(InputError, match="no parameter"):
        get_material("yeoh").with_parameters(mu=1.0)
