"""Analytic reference solutions used to verify the module model."""

from __future__ import annotations

from softpad.errors import InputError, check_finite

#: Coefficient of the clamped square plate under uniform pressure (Timoshenko &
#: Woinowsky-Krieger, Table 35, nu = 0.3; the value depends little on nu).
CLAMPED_SQUARE_COEFFICIENT = 0.00126


def plate_center_deflection_m(
    pressure_pa: float,
    width_m: float,
    thickness_m: float,
    shear_modulus_pa: float,
    poisson_ratio: float = 0.5,
) -> float:
    """Small-deflection centre deflection of a clamped square plate, m.

    ``w_max = 0.00126 p a^4 / D`` with ``D = E t^3 / (12 (1 - nu^2))`` and ``E = 2 mu (1 + nu)``
    (``E = 3 mu`` for the incompressible limit nu -> 0.5). Valid while ``w_max`` is well
    below the thickness (linear Kirchhoff plate theory).

    Parameters
    ----------
    pressure_pa
        Uniform pressure, Pa.
    width_m
        Side ``a`` of the square plate, m.
    thickness_m
        Plate thickness ``t``, m.
    shear_modulus_pa
        Shear modulus ``mu``, Pa.
    poisson_ratio
        Poisson's ratio (0.5 for an incompressible material).
    """
    p = check_finite("pressure_pa", pressure_pa)
    a = check_finite("width_m", width_m)
    t = check_finite("thickness_m", thickness_m)
    mu = check_finite("shear_modulus_pa", shear_modulus_pa)
    nu = check_finite("poisson_ratio", poisson_ratio)
    if a <= 0 or t <= 0 or mu <= 0:
        raise InputError("plate width, thickness and shear modulus must be > 0")
    if not -1.0 < nu <= 0.5:
        raise InputError(f"poisson_ratio must be in (-1, 0.5], got {nu!r}")
    youngs = 2.0 * mu * (1.0 + nu)
    rigidity = youngs * t**3 / (12.0 * (1.0 - nu**2))
    return CLAMPED_SQUARE_COEFFICIENT * p * a**4 / rigidity
