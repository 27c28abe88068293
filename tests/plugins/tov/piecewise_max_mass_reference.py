"""Independent reference for test_tov_presets_maximum_mass.cpp: the maximum ADM mass of the Read,
Lackey, Owen & Friedman (2009) piecewise polytropes SLy, APR4, H4, MS1 (crust: their Table II; core:
Table III), built here from the paper's definitions and integrated in Schwarzschild coordinates with
the pressure as a function of r (not the tov plugin's enthalpy form in isotropic coordinates).
Units G = c = M_sun = 1 with the constants of plugins/eos_piecewise_polytrope/units.hpp.
Run: /usr/bin/python3 piecewise_max_mass_reference.py   (numpy, scipy)
Output: SLy 2.04841127153011, APR4 2.188001070262705, H4 2.0138513946569665, MS1 2.7527768419458503
"""
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

C, G, GM_SUN = 2.99792458e10, 6.67430e-8, 1.3271244e26
M_SUN = GM_SUN / G
LENGTH = GM_SUN / C ** 2
RHO_UNIT = M_SUN / LENGTH ** 3                      # g/cm^3 per code unit
CRUST_K0 = 6.80110e-9                               # P/c^2 = K rho^Gamma, cgs (g/cm^3)
CRUST_GAMMA = [1.58425, 1.28733, 0.62223, 1.35692]
CRUST_RHO = [2.44034e7, 3.78358e11, 2.62780e12]
PRESETS = {'SLy': (34.384, 3.005, 2.988, 2.851), 'APR4': (34.269, 2.830, 3.445, 3.348),
           'H4': (34.669, 2.909, 2.246, 2.144), 'MS1': (34.858, 3.224, 3.033, 1.325)}


def pieces(log_p1, g1, g2, g3):
    """(K, Gamma, rho_lo, a) per piece in code units; P continuous, eps continuous."""
    k, gam, rho = [CRUST_K0], list(CRUST_GAMMA), [0.0] + CRUST_RHO
    for i in range(1, 4):
        k.append(k[i - 1] * CRUST_RHO[i - 1] ** (gam[i - 1] - gam[i]))
    rho1, rho2 = 10 ** 14.7, 10 ** 15.0
    k4 = 10 ** log_p1 / C ** 2 / rho1 ** g1
    junction = (k[3] / k4) ** (1 / (g1 - gam[3]))
    k += [k4, k4 * rho1 ** (g1 - g2), k4 * rho1 ** (g1 - g2) * rho2 ** (g2 - g3)]
    gam += [g1, g2, g3]
    rho += [junction, rho1, rho2]
    kc = [k[i] * RHO_UNIT ** (gam[i] - 1) for i in range(7)]
    rc = [r / RHO_UNIT for r in rho]
    a = [0.0]
    for i in range(1, 7):
        a.append(a[i - 1] + kc[i - 1] * rc[i] ** (gam[i - 1] - 1) / (gam[i - 1] - 1)
                 - kc[i] * rc[i] ** (gam[i] - 1) / (gam[i] - 1))
    return kc, gam, rc, a


def adm_mass(rho_c, par):
    kc, gam, rc, a = par
    p_lo = [kc[i] * rc[i] ** gam[i] for i in range(7)]

    def piece_of(value, bounds):
        i = 0
        while i < 6 and value >= bounds[i + 1]:
            i += 1
        return i

    def energy(rho):
        i = piece_of(rho, rc)
        return rho * (1 + a[i] + kc[i] * rho ** (gam[i] - 1) / (gam[i] - 1))

    def rhs(r, y):
        p, m = y
        if p <= 0:
            return [0.0, 0.0]
        i = piece_of(p, p_lo)
        e = energy((p / kc[i]) ** (1 / gam[i]))
        return [-(e + p) * (m + 4 * np.pi * r ** 3 * p) / (r * (r - 2 * m)), 4 * np.pi * r ** 2 * e]

    i = piece_of(rho_c, rc)
    p_c, e_c, r0 = kc[i] * rho_c ** gam[i], energy(rho_c), 1e-6
    surface = lambda r, y: y[0] - 1e-20 * p_c
    surface.terminal = True
    sol = solve_ivp(rhs, [r0, 100.0], [p_c, 4 / 3 * np.pi * r0 ** 3 * e_c], method='DOP853', rtol=1e-11,
                    atol=[1e-30, 1e-30], events=surface)
    return sol.y[1, -1]


for name, core in PRESETS.items():
    par = pieces(*core)
    best = minimize_scalar(lambda x: -adm_mass(np.exp(x), par), bounds=(np.log(1.2e-3), np.log(5e-3)),
                           method='bounded', options={'xatol': 1e-5})
    print(name, repr(-best.fun), 'at rho_c =', np.exp(best.x) * RHO_UNIT, 'g/cm^3')
