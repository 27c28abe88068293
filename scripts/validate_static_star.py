#!/usr/bin/env python3
"""Convergence tables of the static star (physics-notes §9 T1) for docs/validation.md.

Runs parfiles/static_star.yaml (or another static-star parfile) at dx = 0.12, 0.06, 0.03, 0.015 on the
cube r_c = 1.92 and at dx = 0.06 on r_c = 3.84 and 7.68, and prints markdown tables of the errors
against the isolated TOV star of the same EOS, computed by the tov plugin (which matches the
independent tov.py reference to 1e-9). Only the standard library: Debian's python3 suffices.
Usage: scripts/validate_static_star.py [--parfile parfiles/static_star.yaml] [--rho-max 0.1]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "bin", "bhnsid")


def run(parfile, out, sets):
    cmd = [EXE, "run", parfile, "--output", out, "--force"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    scalars = summary["scalars"]
    with open(os.path.join(out, "star_axis.tsv")) as f:
        head = f.readline()
        x_c = float(head.split("xhat_C = ")[1].split(";")[0])
        f.readline()
        rows = [list(map(float, line.split())) for line in f]
    centre = min(rows, key=lambda r: abs(r[0] - x_c))
    scalars["chi_centre"], scalars["alpha_centre"] = centre[2], centre[4]
    return scalars


def tov_star(eos_lines, rho_max, out):
    par = os.path.join(out, "tov.yaml")
    with open(par, "w") as f:
        f.write(eos_lines + f"tov: {{central_density: {rho_max}}}\n")
    subprocess.run([EXE, "run", par, "--output", os.path.join(out, "tov"), "--force"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "tov", "summary.json")) as f:
        return json.load(f)["scalars"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parfile", default=os.path.join(ROOT, "parfiles", "static_star.yaml"))
    ap.add_argument("--rho-max", type=float, default=0.1)
    ap.add_argument("--eos", default="plugins: [eos_polytrope, tov]\n",
                    help="YAML lines naming the EOS plugin (and its section) for the TOV reference")
    ap.add_argument("--finest", type=int, default=256, help="largest n at r_c = 1.92")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        t = tov_star(args.eos.replace("\\n", "\n"), args.rho_max, tmp)
        ref = {"sigma": t["radius_isotropic"], "bernoulli_constant": math.sqrt(1 - 2 * t["adm_mass"] / t["radius_areal"]),
               "adm_mass": t["adm_mass"], "adm_mass_falloff": t["adm_mass"], "rest_mass": t["rest_mass"],
               "chi_centre": t["psi_center"], "alpha_centre": t["lapse_center"]}
        runs = {}
        n = 32
        while n <= args.finest:
            dx = 0.12 * 32 / n
            print(f"running n = {n}, dx = {dx:g}", file=sys.stderr)
            runs[(n, dx)] = run(args.parfile, os.path.join(tmp, f"r{n}"),
                                [f"grid.n={n}", f"grid.dx={dx}", f"star.rho_max={args.rho_max}"])
            n *= 2
        for n in (128, 256):
            print(f"running n = {n}, dx = 0.06", file=sys.stderr)
            runs[(n, 0.06)] = run(args.parfile, os.path.join(tmp, f"b{n}"),
                                  [f"grid.n={n}", "grid.dx=0.06", f"star.rho_max={args.rho_max}"])
    names = ["sigma", "bernoulli_constant", "adm_mass", "adm_mass_falloff", "rest_mass", "chi_centre", "alpha_centre"]
    print("| quantity | TOV | " + " | ".join(f"err dx={dx:g}" for (n, dx) in runs if n * dx / 2 == 1.92) + " | ratios |")
    print("|---|---|" + "---|" * (sum(1 for (n, dx) in runs if n * dx / 2 == 1.92) + 1))
    for q in names:
        errs = [runs[k][q] - ref[q] for k in runs if k[0] * k[1] / 2 == 1.92]
        ratios = ", ".join(f"{a / b:.2f}" for a, b in zip(errs, errs[1:]))
        print(f"| {q} | {ref[q]:.9g} | " + " | ".join(f"{e:.3e}" for e in errs) + f" | {ratios} |")
    print()
    print("| quantity | r_c = 1.92 | r_c = 3.84 | r_c = 7.68 | (dx = 0.06) |")
    print("|---|---|---|---|---|")
    for q in names:
        vals = [runs[(64, 0.06)][q], runs[(128, 0.06)][q], runs[(256, 0.06)][q]]
        print(f"| {q} | " + " | ".join(f"{v:.9g}" for v in vals) + " | |")
    iters = ", ".join(f"{int(runs[k]['outer_iterations'])}" for k in runs)
    print(f"\nouter iterations: {iters}")


if __name__ == "__main__":
    main()
