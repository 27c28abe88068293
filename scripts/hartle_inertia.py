#!/usr/bin/env python3
"""The moment of inertia of a slowly rotating Gamma = 2, K = 1 polytrope (Hartle 1967), independent of
bhnsid: the TOV equations in areal coordinates with the frame-dragging equation
    (1/r^4) d/dr (r^4 j d(omega_bar)/dr) + (4/r) (dj/dr) omega_bar = 0,   j = exp(-(nu + lambda)/2),
integrated from the centre with omega_bar(0) = 1 to the surface R; outside, omega = 2J/r^3, so
J = R^4 omega_bar'(R)/6 and Omega = omega_bar(R) + 2J/R^3, I = J/Omega. Also prints the integral
without frame dragging, I_0 = (8 pi/3) Int r^4 (rho + P) e^{(lambda - nu)/2} dr, and omega_bar/Omega at the
centre, and the rest mass M0 = 4 pi Int r^2 rho0 e^{lambda/2} dr. The reference of the star plugin's spin test (tests/plugins/star/test_spin.cpp).
Usage: scripts/hartle_inertia.py [RHO_C ...]   (default 0.01 0.05 0.1); needs numpy and scipy.
"""
import sys

import numpy as np
from scipy.integrate import solve_ivp


def energy_density(pressure):
    """rho = rho0 (1 + eps) with P = rho0^2, eps = rho0 (Gamma = 2, K = 1)."""
    rho0 = np.sqrt(max(pressure, 0.0))
    return rho0 + rho0 * rho0


def star(rho_c):
    def rhs(r, y):
        m, p, nu, w, dw = y
        rho = energy_density(p) if p > 0 else 0.0
        e_lambda = 1.0 / (1.0 - 2.0 * m / r)
        dm = 4.0 * np.pi * r * r * rho
        dnu = 2.0 * (m + 4.0 * np.pi * r ** 3 * p) * e_lambda / (r * r)
        dp = -(rho + p) * dnu / 2.0
        dlambda = (2.0 * dm / r - 2.0 * m / (r * r)) * e_lambda
        j = np.exp(-nu / 2.0) * np.sqrt(1.0 - 2.0 * m / r)
        dj = -0.5 * j * (dnu + dlambda)
        ddw = (-(4.0 / r) * j * dw - dj * dw - 4.0 * dj / r * w) / j
        return [dm, dp, dnu, dw, ddw]

    def surface(r, y):
        return y[1]
    surface.terminal = True
    r0 = 1e-6
    y0 = [4.0 / 3.0 * np.pi * r0 ** 3 * energy_density(rho_c ** 2), rho_c ** 2, 0.0, 1.0, 0.0]
    sol = solve_ivp(rhs, [r0, 20.0], y0, events=surface, rtol=1e-11, atol=1e-14, max_step=1e-3)
    radius = sol.t[-1]
    m, _, nu, w, dw = sol.y[:, -1]
    j_spin = radius ** 4 * dw / 6.0
    omega = w + 2.0 * j_spin / radius ** 3
    # nu normalised to the exterior Schwarzschild value at the surface.
    nu_all = sol.y[2] + np.log(1.0 - 2.0 * m / radius) - nu
    rho = np.array([energy_density(p) if p > 0 else 0.0 for p in sol.y[1]])
    integrand = sol.t ** 4 * (rho + sol.y[1]) * np.exp(-nu_all / 2.0) / np.sqrt(1.0 - 2.0 * sol.y[0] / sol.t)
    no_drag = 8.0 * np.pi / 3.0 * np.trapz(integrand, sol.t)
    rho0 = np.sqrt(np.clip(sol.y[1], 0.0, None))
    rest_mass = 4.0 * np.pi * np.trapz(sol.t ** 2 * rho0 / np.sqrt(1.0 - 2.0 * sol.y[0] / sol.t), sol.t)
    return m, radius, j_spin / omega, no_drag, 1.0 / omega, rest_mass


def main():
    densities = [float(a) for a in sys.argv[1:]] or [0.01, 0.05, 0.1]
    print("rho_c\tM\tM0\tR_areal\tI\tI_no_drag\tomega_bar_c/Omega\tI/(M R^2)")
    for rho_c in densities:
        m, radius, inertia, no_drag, centre, rest_mass = star(rho_c)
        print(f"{rho_c}\t{m:.7f}\t{rest_mass:.7f}\t{radius:.7f}\t{inertia:.7f}\t{no_drag:.7f}\t{centre:.5f}\t"
              f"{inertia / (m * radius ** 2):.5f}")


if __name__ == "__main__":
    main()
