#!/usr/bin/env python3
"""The Kepler limit of both lapses at three separations, for docs/lapse.md.

Runs mu_bn = 1 binaries whose star keeps d/R ~ 6 by its compactness (rho_max = 0.1, 0.05, 0.02 at
d/M_tot ~ 20, 40, 80), on one cube with the faces beyond 2 d and about 10 points per stellar radius,
with lapse_komar (condition virial and static; parfiles/kepler_komar.yaml) and with the paper's lapse
(parfiles/kepler_limit.yaml). Prints, per run, Omega^2 d^3/M_tot against the first post-Newtonian
1 - (3 - nu) M_tot/d, and the fit (1 - Omega^2 d^3/M_tot) d/M_tot = A + B M_tot/d over the three
separations, whose A is 3 - nu at 1PN. M_tot = M_BH + M_NS with M_NS the isolated star's ADM mass at
the same M0 and M_BH the hole's mass column (--hole-mass, default the apparent-horizon mass when the
run has one, else the puncture mass sigma Mhat chi(puncture)); d is the coordinate distance from the
puncture to the star's density maximum. Only the standard library.
Usage: scripts/kepler_limit.py OUTDIR [--n 288 --dx 0.0225] [--only komar_virial,komar_static,paper] [--bhnsid EXE]
A run whose OUTDIR/NAME/summary.json exists is not run again.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_once import run_once  # noqa: E402
EXE = os.path.join(ROOT, "build", "bin", "bhnsid")  # --bhnsid: another build (a copy left alone while runs go on)
# (rho_max, x_A): d/R = 2 (1 + x_A)/(1 - x_A) ~ 5.8, 6.8, 6.0 gives d/M_tot ~ 20, 40, 80 for the TOV
# stars of these central densities (M_NS = 0.1270, 0.0862, 0.0427; R_iso = 0.873, 1.020, 1.146).
CONFIGS = [(0.1, 0.489), (0.05, 0.543), (0.02, 0.497)]
LAPSES = {
    "komar_virial": ("kepler_komar.yaml", ["lapse_komar.condition=virial"]),
    "komar_static": ("kepler_komar.yaml", ["lapse_komar.condition=static"]),
    "paper": ("kepler_limit.yaml", []),
}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("outdir")
    p.add_argument("--n", type=int, default=288)
    p.add_argument("--dx", type=float, default=0.0225)
    p.add_argument("--only", default=",".join(LAPSES))
    p.add_argument("--bhnsid", default=EXE)
    p.add_argument("--hole-mass", default="auto", choices=["auto", "bh_irreducible_mass", "bh_puncture_mass", "bh_bare_mass"])
    a = p.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    print("| lapse | rho_max | d/M_tot | nu | Omega^2 d^3/M_tot | 1 - (3-nu) M_tot/d | deviation | status |")
    print("|---|---|---|---|---|---|---|---|")
    for lapse in a.only.split(","):
        parfile, extra = LAPSES[lapse]
        points = []
        for rho, x_a in CONFIGS:
            out = os.path.join(a.outdir, f"{lapse}_rho{rho}")
            sets = [f"grid.n={a.n}", f"grid.dx={a.dx}", f"star.rho_max={rho}",
                    f"star.x_a={x_a}", "run.max_iterations=120"] + extra
            summary = run_once(a.bhnsid, out, parfile, sets)
            s = summary["scalars"]
            key = a.hole_mass
            if key == "auto":
                key = "bh_irreducible_mass" if "bh_irreducible_mass" in s else "bh_puncture_mass"
            m_bh, m_ns = s[key], s["ns_adm_mass"]
            m_tot, d, omega = m_bh + m_ns, s["separation"], s["omega"]
            nu = m_bh * m_ns / m_tot ** 2
            kepler = omega ** 2 * d ** 3 / m_tot
            pn = 1 - (3 - nu) * m_tot / d
            points.append((m_tot / d, kepler, nu))
            print(f"| {lapse} | {rho} | {d / m_tot:.2f} | {nu:.4f} | {kepler:.5f} | {pn:.5f} | "
                  f"{(kepler - pn) / pn:+.2%} | {summary['status']} ({key}) |")
        # (1 - K) d/M = A + B (M/d): least squares over the separations.
        xs = [x for x, _, _ in points]
        ys = [(1 - k) / x for x, k, _ in points]
        n = len(xs)
        sx, sy, sxx, sxy = sum(xs), sum(ys), sum(x * x for x in xs), sum(x * y for x, y in zip(xs, ys))
        b = (n * sxy - sx * sy) / (n * sxx - sx * sx)
        a_fit = (sy - b * sx) / n
        nu = sum(v for _, _, v in points) / n
        print(f"\n{lapse}: fit (1 - Omega^2 d^3/M_tot) d/M_tot = A + B M_tot/d: A = {a_fit:.3f} "
              f"(1PN: 3 - nu = {3 - nu:.3f}, {(a_fit - (3 - nu)) / (3 - nu):+.1%}), B = {b:.2f}\n", file=sys.stderr)


if __name__ == "__main__":
    main()
