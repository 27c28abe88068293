#!/usr/bin/python3
"""A corotating and an irrotational sequence of the same rest mass side by side (docs/irrotational.md).

Reads the sequence.json of two runs of `bhnsid sequence` with the same points and grids that differ
in the flow plugin. Per grid, and through the error model Q = Q_e + e_t dx^2 + e_b/r_c^2 where the
sequences have its three grids, prints at each xhat_A: Omega M0 and J of both flows, and the
difference of J at equal Omega and rest mass (the irrotational J interpolated linearly in Omega to the
corotating point), J_co - J_irr, against I Omega: the spin of the corotating star if it rotated
rigidly at Omega as an isolated star (I from Hartle's slow-rotation equations for the TOV star of
the same rest mass, scripts/hartle_inertia.py). The binding energy E_b (with M_irr) of both is
printed beside them. Needs NumPy and SciPy.
Usage: scripts/flow_comparison.py COROTATING_DIR IRROTATIONAL_DIR [--target 0.75]
"""
import argparse
import os
import sys

import numpy as np
from scipy.optimize import brentq

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hartle_inertia  # noqa: E402
from first_law_check import load  # noqa: E402


def grid_name(g):
    return f"n{g['n']}_dx{g['dx']:g}"


def columns(seq, target, keys):
    """{x_a: {key: [value per grid]}} for the points converged on every grid."""
    out = {}
    names = [grid_name(g) for g in seq["grids"]]
    for name in names:
        for x_a, targets in seq["at_targets"].get(name, {}).items():
            point = targets.get(target)
            if point is None or any(point.get(k) is None for k in keys):
                continue
            row = out.setdefault(float(x_a), {k: {} for k in keys})
            for k in keys:
                row[k][name] = point[k]
    return {x: {k: [v[k][n] for n in names] for k in keys} for x, v in out.items()
            if all(len(v[k]) == len(names) for k in keys)}


def extrapolate(seq, values):
    """Q_e of the error model through the three grids (the values themselves on one grid)."""
    if len(seq["grids"]) != 3:
        return values[0]
    a = np.array([[1.0, g["dx"] ** 2, 1.0 / g["rc"] ** 2] for g in seq["grids"]])
    return float(np.linalg.solve(a, np.array(values))[0])


def inertia_of_rest_mass(m0):
    """I of the isolated slowly rotating star with rest mass m0 (on the stable branch)."""
    rho_c = brentq(lambda r: hartle_inertia.star(r)[5] - m0, 0.01, 0.3, xtol=1e-10)
    return hartle_inertia.star(rho_c)[2], rho_c


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("corotating")
    p.add_argument("irrotational")
    p.add_argument("--target", default="0.75", help="M0/(M0)_max of the sequences, as the tables print it")
    p.add_argument("--grid", help="one grid's values (as n128_dx0.03) instead of the error model's Q_e")
    a = p.parse_args()
    co, irr = load(a.corotating, "flow_comparison"), load(a.irrotational, "flow_comparison")
    if [grid_name(g) for g in co["grids"]] != [grid_name(g) for g in irr["grids"]]:
        sys.exit("flow_comparison: the two sequences are not on the same grids")
    m0 = float(a.target) * co["m0_max"]
    inertia, rho_c = inertia_of_rest_mass(m0)
    keys = ("Omega_M0", "J", "E_b_irreducible")
    cols = {"co": columns(co, a.target, keys), "irr": columns(irr, a.target, keys)}
    names = [grid_name(g) for g in co["grids"]]
    if a.grid is not None and a.grid not in names:
        sys.exit(f"flow_comparison: no grid {a.grid} in the sequences ({', '.join(names)})")
    label = a.grid or ("Q_e (three grids)" if len(names) == 3 else names[0])
    pick = (lambda seq, v: v[names.index(a.grid)]) if a.grid else extrapolate
    print(f"M0 = {m0:.6f}: isolated star rho_c = {rho_c:.6f}, I = {inertia:.6f} (Hartle); values: {label}")
    best = {f: {x: {k: pick(co, v[k]) for k in keys} for x, v in c.items()} for f, c in cols.items()}
    irr_points = sorted((v["Omega_M0"], v["J"], v["E_b_irreducible"]) for v in best["irr"].values())
    if len(irr_points) < 2:
        sys.exit("flow_comparison: fewer than two irrotational points converged on every grid")
    w_irr = np.array([q[0] for q in irr_points])
    print("| xhat_A | Omega M0 (co) | Omega M0 (irr) | J co | J irr | E_b/M_irr co | E_b/M_irr irr | "
          "J_co - J_irr at equal Omega | I Omega | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for x in sorted(best["co"]):
        c = best["co"][x]
        i = best["irr"].get(x)
        w = c["Omega_M0"]
        if i is None:
            continue
        inside = w_irr[0] <= w <= w_irr[-1]
        j_irr = float(np.interp(w, w_irr, [q[1] for q in irr_points])) if inside else float("nan")
        spin = inertia * w / m0
        dj = c["J"] - j_irr
        print(f"| {x:g} | {w:.5f} | {i['Omega_M0']:.5f} | {c['J']:.6f} | {i['J']:.6f} | {c['E_b_irreducible']:+.6f} | "
              f"{i['E_b_irreducible']:+.6f} | {dj:.6f} | {spin:.6f} | {dj / spin:.3f} |")


if __name__ == "__main__":
    main()
