"""Hyperelastic material models of EcoFlex 00-30 (thesis Section 7.1.1, Table 7.1).

Every model is nearly incompressible, ``W = W_iso(C_bar) + kappa/2 (J - 1)^2`` with
``kappa = 1e5 mu`` (thesis Section 7.1.1); the isochoric part is written here with the
thesis's own forms (not FElupe's conventions) and differentiated automatically by
tensortrax. The volumetric part is added by the finite-element formulation
(:class:`softpad.fem.ModuleModel`), which keeps the pressure and volume ratio as separate
fields.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from softpad.errors import InputError, check_finite

#: Ratio of the initial bulk modulus to the initial shear modulus (thesis: kappa = 1e5 mu).
BULK_TO_SHEAR = 1.0e5

#: Model kinds and the parameter names each one takes (all in Pa, exponents dimensionless).
_KIND_PARAMETERS: dict[str, tuple[str, ...]] = {
    "neo-hookean": ("mu",),
    "mooney-rivlin": ("c1", "c2"),
    "ogden": ("mu1", "mu2", "mu3", "alpha1", "alpha2", "alpha3"),
    "varga": ("c1", "c2"),
    "yeoh": ("c1", "c2", "c3"),
}


@dataclass(frozen=True)
class MaterialModel:
    """A nearly incompressible hyperelastic model with its parameters.

    Parameters
    ----------
    name
        Preset name (``neo-hookean``, ``mooney-rivlin``, ``ogden-1``, ``ogden-2``, ``varga``,
        ``yeoh``) or a user label.
    kind
        Strain-energy form: ``neo-hookean``, ``mooney-rivlin``, ``ogden``, ``varga``, ``yeoh``.
    parameters
        Parameter values: moduli in Pa, Ogden exponents ``alpha_i`` dimensionless.
        Forms (thesis Section 7.1.1, bars for isochoric quantities):

        - neo-Hookean: ``W = mu/2 (I1 - 3)``
        - Mooney-Rivlin: ``W = c1 (I1 - 3) + c2 (I2 - 3)``
        - Ogden: ``W = sum_i mu_i/alpha_i (l1^a_i + l2^a_i + l3^a_i - 3)``
        - Varga: ``W = c1 (l1 + l2 + l3 - 3) + c2 (l1 l2 + l2 l3 + l1 l3 - 3)``
        - Yeoh: ``W = c1 (I1 - 3) + c2 (I1 - 3)^2 + c3 (I1 - 3)^3``
    bulk_to_shear
        ``kappa / mu`` (dimensionless); the thesis uses 1e5.

    Raises
    ------
    InputError
        When a parameter is missing, not finite, or the energy is not convex at rest
        (initial shear modulus <= 0, or Yeoh ``c1 <= 0``).
    """

    name: str
    kind: str
    parameters: Mapping[str, float] = field(default_factory=dict)
    bulk_to_shear: float = BULK_TO_SHEAR

    def __post_init__(self) -> None:
        if self.kind not in _KIND_PARAMETERS:
            raise InputError(
                f"unknown material kind {self.kind!r}; expected one of {sorted(_KIND_PARAMETERS)}"
            )
        names = _KIND_PARAMETERS[self.kind]
        missing = [n for n in names if n not in self.parameters]
        extra = [n for n in self.parameters if n not in names]
        if missing or extra:
            raise InputError(
                f"material {self.name!r} ({self.kind}) needs parameters {list(names)}, "
                f"got {sorted(self.parameters)}"
            )
        params = {n: check_finite(f"{self.name}.{n}", self.parameters[n]) for n in names}
        object.__setattr__(self, "parameters", params)
        check_finite("bulk_to_shear", self.bulk_to_shear)
        if self.bulk_to_shear <= 0:
            raise InputError(f"bulk_to_shear must be > 0, got {self.bulk_to_shear}")
        if self.kind == "ogden":
            for i in (1, 2, 3):
                if params[f"alpha{i}"] == 0.0:
                    raise InputError(f"material {self.name!r}: alpha{i} must be non-zero")
        mu0 = self.shear_modulus_pa
        if not mu0 > 0:
            raise InputError(
                f"material {self.name!r}: initial shear modulus {mu0:.4g} Pa <= 0, "
                "the strain energy is not convex at rest"
            )
        if self.kind == "yeoh" and params["c1"] <= 0:
            raise InputError(
                f"material {self.name!r}: Yeoh c1 = {params['c1']:.4g} Pa must be > 0 "
                "(energy not convex at rest)"
            )

    # ------------------------------------------------------------------ derived values
    @property
    def shear_modulus_pa(self) -> float:
        """Initial (small-strain) shear modulus mu in Pa.

        neo-Hookean ``mu``; Mooney-Rivlin ``2 (c1 + c2)``; Ogden ``1/2 sum mu_i alpha_i``;
        Varga ``(c1 + c2) / 2``; Yeoh ``2 c1``.
        """
        p = self.parameters
        if self.kind == "neo-hookean":
            return p["mu"]
        if self.kind == "mooney-rivlin":
            return 2.0 * (p["c1"] + p["c2"])
        if self.kind == "ogden":
            return 0.5 * sum(p[f"mu{i}"] * p[f"alpha{i}"] for i in (1, 2, 3))
        if self.kind == "varga":
            return 0.5 * (p["c1"] + p["c2"])
        return 2.0 * p["c1"]  # yeoh

    @property
    def bulk_modulus_pa(self) -> float:
        """Initial bulk modulus kappa = bulk_to_shear * mu, Pa (thesis: kappa = 1e5 mu)."""
        return self.bulk_to_shear * self.shear_modulus_pa

    @property
    def youngs_modulus_pa(self) -> float:
        """Small-strain Young's modulus ``E = 9 kappa mu / (3 kappa + mu)``, Pa (about 3 mu)."""
        k, m = self.bulk_modulus_pa, self.shear_modulus_pa
        return 9.0 * k * m / (3.0 * k + m)

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Names of the parameters of this kind, in canonical order."""
        return _KIND_PARAMETERS[self.kind]

    def with_parameters(self, **values: float) -> MaterialModel:
        """Return a copy with some parameters replaced (Pa / dimensionless)."""
        unknown = [k for k in values if k not in self.parameters]
        if unknown:
            raise InputError(
                f"material {self.name!r} has no parameter(s) {unknown}; "
                f"it has {list(self.parameter_names)}"
            )
        return replace(self, parameters={**self.parameters, **values})

    def to_dict(self) -> dict[str, Any]:
        """Plain-data description (name, kind, parameters, bulk_to_shear, shear modulus)."""
        return {
            "name": self.name,
            "kind": self.kind,
            "parameters": dict(self.parameters),
            "bulk_to_shear": self.bulk_to_shear,
            "shear_modulus_pa": self.shear_modulus_pa,
        }

    # ------------------------------------------------------------------ energies
    def isochoric_energy(self) -> Callable[..., Any]:
        """Return ``W_iso(C)`` written with :mod:`tensortrax.math` (thesis forms, J^-1/3 scaled).

        The function takes the right Cauchy-Green tensor ``C`` and returns the isochoric
        strain energy density in Pa; FElupe differentiates it automatically.
        """
        return _isochoric_energy(self.kind, dict(self.parameters))

    def felupe_material(self, automatic_differentiation: bool = False) -> Any:
        """The isochoric part as a FElupe material.

        Every model is written with tensortrax (automatic differentiation) in the thesis's
        form. The neo-Hookean model, whose FElupe hand-coded ``NeoHooke(mu)`` without bulk
        modulus is exactly ``mu/2 (I1_bar - 3)``, uses that faster implementation unless
        ``automatic_differentiation`` is set (the tests check both agree).
        """
        if self.kind == "neo-hookean" and not automatic_differentiation:
            import felupe as fem

            return fem.NeoHooke(mu=self.parameters["mu"])
        import felupe.constitution.tensortrax as mat

        return mat.Hyperelastic(self.isochoric_energy())

    # ------------------------------------------------------------------ analytic stresses
    def principal_stress_derivatives(self, stretches: np.ndarray) -> np.ndarray:
        """``lambda_i dW/dlambda_i`` of the incompressible model, Pa.

        Parameters
        ----------
        stretches
            Principal stretches, shape ``(..., 3)``, with ``l1 l2 l3 = 1``.

        Returns
        -------
        numpy.ndarray
            ``lambda_i dW/dlambda_i``, shape ``(..., 3)``; the Cauchy stress of the
            incompressible material is ``sigma_i = lambda_i dW/dlambda_i - p``.
        """
        lam = np.asarray(stretches, dtype=float)
        p = self.parameters
        if self.kind in ("neo-hookean", "mooney-rivlin", "yeoh"):
            sq = lam**2
            i1 = sq.sum(axis=-1, keepdims=True)
            if self.kind == "neo-hookean":
                w1, w2 = 0.5 * p["mu"] + 0 * i1, 0 * i1
            elif self.kind == "mooney-rivlin":
                w1, w2 = p["c1"] + 0 * i1, p["c2"] + 0 * i1
            else:
                e = i1 - 3.0
                w1 = p["c1"] + 2.0 * p["c2"] * e + 3.0 * p["c3"] * e**2
                w2 = 0 * i1
            # dI1/dl_i = 2 l_i, dI2/dl_i = 2 l_i (I1 - l_i^2)
            return 2.0 * sq * w1 + 2.0 * sq * (i1 - sq) * w2
        if self.kind == "ogden":
            out = np.zeros_like(lam)
            for i in (1, 2, 3):
                out += p[f"mu{i}"] * lam ** p[f"alpha{i}"]
            return out
        # varga: l_i dW/dl_i = c1 l_i + c2 l_i (l_j + l_k)
        total = lam.sum(axis=-1, keepdims=True)
        return p["c1"] * lam + p["c2"] * lam * (total - lam)

    def uniaxial_stress_pa(self, stretch: np.ndarray) -> np.ndarray:
        """Cauchy stress of incompressible uniaxial tension, Pa.

        Stretches ``(l, l^-1/2, l^-1/2)``, lateral stress zero: ``sigma = s_1 - s_2`` with
        ``s_i = lambda_i dW/dlambda_i``. The nominal stress is ``sigma / l``.
        """
        s = np.asarray(stretch, dtype=float)
        lam = np.stack([s, s**-0.5, s**-0.5], axis=-1)
        d = self.principal_stress_derivatives(lam)
        return d[..., 0] - d[..., 1]

    def equibiaxial_stress_pa(self, stretch: np.ndarray) -> np.ndarray:
        """Cauchy stress of incompressible equibiaxial tension, Pa.

        Stretches ``(l, l, l^-2)``, out-of-plane stress zero: ``sigma = s_1 - s_3``.
        """
        s = np.asarray(stretch, dtype=float)
        lam = np.stack([s, s, s**-2.0], axis=-1)
        d = self.principal_stress_derivatives(lam)
        return d[..., 0] - d[..., 2]


def _isochoric_energy(kind: str, p: dict[str, float]) -> Callable[..., Any]:
    """Build the tensortrax strain-energy function of one model kind (isochoric invariants)."""
    from tensortrax.math import sum as tsum
    from tensortrax.math import trace
    from tensortrax.math.linalg import det, eigvalsh

    if kind == "neo-hookean":
        mu = p["mu"]

        def energy(C: Any) -> Any:
            i1 = det(C) ** (-1.0 / 3.0) * trace(C)
            return mu / 2.0 * (i1 - 3.0)

    elif kind == "mooney-rivlin":
        c1, c2 = p["c1"], p["c2"]

        def energy(C: Any) -> Any:
            j23 = det(C) ** (-1.0 / 3.0)
            i1 = j23 * trace(C)
            i2 = (i1**2 - j23**2 * trace(C @ C)) / 2.0
            return c1 * (i1 - 3.0) + c2 * (i2 - 3.0)

    elif kind == "yeoh":
        c1, c2, c3 = p["c1"], p["c2"], p["c3"]

        def energy(C: Any) -> Any:
            e = det(C) ** (-1.0 / 3.0) * trace(C) - 3.0
            return c1 * e + c2 * e**2 + c3 * e**3

    elif kind == "ogden":
        terms = [(p[f"mu{i}"], p[f"alpha{i}"]) for i in (1, 2, 3)]

        def energy(C: Any) -> Any:
            # squared isochoric principal stretches
            wc = det(C) ** (-1.0 / 3.0) * eigvalsh(C)
            return tsum([m / a * (tsum(wc ** (a / 2.0)) - 3.0) for m, a in terms])

    elif kind == "varga":
        c1, c2 = p["c1"], p["c2"]

        def energy(C: Any) -> Any:
            lam = (det(C) ** (-1.0 / 3.0) * eigvalsh(C)) ** 0.5
            i1 = tsum(lam)
            # l1 l2 + l2 l3 + l1 l3 = (sum^2 - sum of squares) / 2
            i2 = (i1**2 - tsum(lam**2)) / 2.0
            return c1 * (i1 - 3.0) + c2 * (i2 - 3.0)

    else:  # pragma: no cover - guarded by MaterialModel
        raise InputError(f"unknown material kind {kind!r}")
    return energy


def _presets() -> dict[str, MaterialModel]:
    mu = 42.0e3
    return {
        "neo-hookean": MaterialModel("neo-hookean", "neo-hookean", {"mu": mu}),
        "mooney-rivlin": MaterialModel(
            "mooney-rivlin", "mooney-rivlin", {"c1": 0.4375 * mu, "c2": 0.0625 * mu}
        ),
        "ogden-1": MaterialModel(
            "ogden-1",
            "ogden",
            {
                "mu1": 22.0e3,
                "mu2": 0.4e3,
                "mu3": -2.0e3,
                "alpha1": 1.3,
                "alpha2": 5.0,
                "alpha3": -2.0,
            },
        ),
        "ogden-2": MaterialModel(
            "ogden-2",
            "ogden",
            {
                "mu1": 24.3e3,
                "mu2": 0.0667e3,
                "mu3": 0.4538e3,
                "alpha1": 1.7138,
                "alpha2": 7.0679,
                "alpha3": 3.3659,
            },
        ),
        "varga": MaterialModel("varga", "varga", {"c1": 2.0 * mu, "c2": 0.0}),
        "yeoh": MaterialModel("yeoh", "yeoh", {"c1": 17.0e3, "c2": -0.2e3, "c3": 0.023e3}),
    }


#: Presets of thesis Table 7.1 (EcoFlex 00-30), keyed by CLI name.
MATERIAL_PRESETS: dict[str, MaterialModel] = _presets()

#: Preset names in the order of Table 7.1.
MODEL_NAMES: tuple[str, ...] = tuple(MATERIAL_PRESETS)


def get_material(name: str | MaterialModel) -> MaterialModel:
    """Return the preset called ``name`` (a :class:`MaterialModel` passes through).

    Raises
    ------
    InputError
        For an unknown name; the message lists the known ones.
    """
    if isinstance(name, MaterialModel):
        return name
    key = str(name).strip().lower().replace("_", "-")
    aliases = {
        "neohookean": "neo-hookean",
        "neo-hooke": "neo-hookean",
        "mooneyrivlin": "mooney-rivlin",
    }
    key = aliases.get(key, key)
    if key not in MATERIAL_PRESETS:
        raise InputError(f"unknown model {name!r}; expected one of {', '.join(MODEL_NAMES)}")
    return MATERIAL_PRESETS[key]
