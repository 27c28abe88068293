#!/usr/bin/env python3
"""Converged values with error bars for the single boosted puncture (physics-notes §9 T2).

For each momentum P: runs parfiles/boosted_puncture.yaml at dx = 0.625, 0.3125, 0.15625 on r_c = 20
(n = 64, 128, 256) and at dx = 0.625 on r_c = 40 (n = 128), then extrapolates M_ADM and chi(puncture)
with the error model of physics-notes §6.2, Q = Q_e + e_t dx^2 + e_b / r_c^2 (e_t from the two finest
runs, e_b from the two boxes), error bar max(|Q_finest - Q_e|, |e_t dx^2|, |e_b / r_c^2|) at the
finest run. Prints a markdown table. Only the standard library.
Usage: scripts/validate_boosted_puncture.py [--momenta 0.1 0.2 0.5 1.0] [--finest 256]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "build", "bin", "bhnsid")
PARFILE = os.path.join(ROOT, "parfiles", "boosted_puncture.yaml")
# physics-notes T2, from an independent axisymmetric solver
REFERENCE = {0.1: (1.006230, 0.0012447), 0.2: (1.024692, 0.0049163)}


def run(out, n, dx, p):
    cmd = [EXE, "run", PARFILE, "--output", out, "--force", "--set", f"grid.n={n}", "--set", f"grid.dx={dx}",
           "--set", f"puncture.momentum=[0,{p},0]"]
    if p >= 1.0:  # the paper's beta_0 = -v/sqrt(1 - v^2), v = P/M, needs P < M: hold -v instead
        cmd += ["--set", "shift.excision_value=plain"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["scalars"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--momenta", type=float, nargs="+", default=[0.1, 0.2, 0.5, 1.0])
    ap.add_argument("--finest", type=int, default=256)
    args = ap.parse_args()
    print("| P/m | M_ADM/m (dx = 0.625, 0.3125, 0.15625; r_c = 40) | extrapolated | chi(punct) - 1 (same runs) | "
          "extrapolated | reference (T2) | P_y, J_z at the faces (n = 256) |")
    print("|---|---|---|---|---|---|---|", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for p in args.momenta:
            runs = {}
            n = 64
            while n <= args.finest:
                print(f"P = {p}: n = {n}", file=sys.stderr)
                runs[n] = run(os.path.join(tmp, f"r{n}"), n, 40.0 / n, p)
                n *= 2
            box = run(os.path.join(tmp, "box"), 128, 0.625, p)
            finest = max(runs)
            coarser = finest // 2
            out = {}
            for key, f in (("adm_mass", lambda s: s["adm_mass"]), ("chi", lambda s: s["chi_puncture"] - 1)):
                # e_b from the dx = 0.625 pair (n = 64 at r_c = 20, n = 128 at r_c = 40), e_t from the finest two
                e_b = (f(box) - f(runs[64])) / (1 / 40.0 ** 2 - 1 / 20.0 ** 2)
                e_t = (f(runs[finest]) - f(runs[coarser])) / ((40.0 / finest) ** 2 - (40.0 / coarser) ** 2)
                value = f(runs[finest]) - e_t * (40.0 / finest) ** 2 - e_b / 400.0
                bar = max(abs(f(runs[finest]) - value), abs(e_t * (40.0 / finest) ** 2), abs(e_b / 400.0))
                out[key] = (value, bar, [f(runs[k]) for k in sorted(runs)], f(box))
            m, c, fin = out["adm_mass"], out["chi"], runs[finest]
            ref = REFERENCE.get(p)
            print(f"| {p} | " + ", ".join(f"{v:.7f}" for v in m[2]) + f"; {m[3]:.7f} | {m[0]:.7f} ± {m[1]:.1e} | "
                  + ", ".join(f"{v:.7f}" for v in c[2]) + f"; {c[3]:.7f} | {c[0]:.7f} ± {c[1]:.1e} | "
                  + (f"{ref[0]:.6f}, {ref[1]:.7f}" if ref else "—")
                  + f" | {fin['momentum_surface_y']:.7f}, {fin['angular_momentum_z']:.7f} |", flush=True)


if __name__ == "__main__":
    main()
