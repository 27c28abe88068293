"""The binding energy of two point masses on circular orbits at third post-Newtonian order, and the
first law of binary quasi-equilibrium between neighbouring sequence points.

E/mu = -(x/2) [1 + e1 x + e2 x^2 + e3 x^3],  x = (M Omega)^(2/3),  nu = m1 m2/M^2, with
  e1 = -3/4 - nu/12,
  e2 = -27/8 + 19 nu/8 - nu^2/24,
  e3 = -675/64 + (34445/576 - 205 pi^2/96) nu - 155 nu^2/96 - 35 nu^3/5184
(Blanchet, Living Rev. Relativity 17, 2 (2014), eq. (233), harmonic/ADM-independent for circular
orbits). Its minimum in x, the point-mass ISCO of this truncation, is at dE/dx = 0. Tidal terms enter
at fifth order, so at wide separation a star and a hole follow it.
"""
import math
from typing import List, Optional, Sequence


def coefficients(nu: float):
    e1 = -0.75 - nu / 12
    e2 = -27 / 8 + 19 * nu / 8 - nu * nu / 24
    e3 = -675 / 64 + (34445 / 576 - 205 * math.pi ** 2 / 96) * nu - 155 * nu * nu / 96 - 35 * nu ** 3 / 5184
    return e1, e2, e3


def energy_per_reduced_mass(m_omega: float, nu: float) -> float:
    """E/mu at M Omega for mass ratio nu (3PN, circular)."""
    x = m_omega ** (2 / 3)
    e1, e2, e3 = coefficients(nu)
    return -0.5 * x * (1 + e1 * x + e2 * x * x + e3 * x ** 3)


def isco_m_omega(nu: float) -> Optional[float]:
    """M Omega at the minimum of the 3PN E(x) (dE/dx = 0 between x = 0.01 and 0.5), or None."""
    e1, e2, e3 = coefficients(nu)

    def slope(x):
        return 1 + 2 * e1 * x + 3 * e2 * x * x + 4 * e3 * x ** 3

    lo, hi = 0.01, 0.5
    if slope(lo) * slope(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if slope(lo) * slope(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return (0.5 * (lo + hi)) ** 1.5


def first_law(omega: Sequence[float], adm_mass: Sequence[float], angular_momentum: Sequence[float]) -> List[dict]:
    """dM_ADM/(Omega dJ) - 1 between neighbours along a sequence ordered by Omega, with Omega at the
    pair's midpoint: 0 for exact quasi-equilibrium (Friedman, Uryu & Shibata 2002)."""
    out = []
    order = sorted(range(len(omega)), key=lambda i: omega[i])
    for a, b in zip(order, order[1:]):
        dj = angular_momentum[b] - angular_momentum[a]
        om = 0.5 * (omega[a] + omega[b])
        if dj == 0 or om == 0:
            out.append({"omega": om, "residual": None, "reason": "dJ = 0 between the pair"})
            continue
        out.append({"omega": om, "residual": (adm_mass[b] - adm_mass[a]) / (om * dj) - 1})
    return out
