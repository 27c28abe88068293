#!/usr/bin/python3
"""The first law along a sequence, tested beyond the error model's three grids (docs/lapse.md).

Reads the sequence.json of a three-grid sequence (first_law.error_model: Q = Q_e + e_t dx^2 +
e_b/r_c^2 per pair of neighbours) and of the same sequence on a fourth grid, and prints per pair:
the residual dM_ADM/(Omega dJ) - 1 the three-grid model predicts for the fourth grid against the
one measured there (a test the model can fail), and the least-squares Q_e through all four grids
with its standard error (one degree of freedom). Needs NumPy.
Usage: scripts/first_law_check.py THREE_GRID_DIR FOURTH_GRID_DIR [--target 0.75]
"""
import argparse
import json
import os
import sys

import numpy as np


def load(d, tool="first_law_check"):
    """The sequence.json of sequence directory d; exits with `tool`'s message when it cannot be read."""
    path = os.path.join(d, "sequence.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"{tool}: {path}: {e}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("three_grids")
    p.add_argument("fourth_grid")
    p.add_argument("--target", default="0.75", help="M0/(M0)_max of the sequence, as the tables print it")
    a = p.parse_args()
    three, four = load(a.three_grids), load(a.fourth_grid)
    if len(three["grids"]) != 3 or len(four["grids"]) != 1:
        sys.exit("first_law_check: the first directory needs three grids, the second one")
    grids3 = [(f"n{g['n']}_dx{g['dx']:g}", g["dx"], g["rc"]) for g in three["grids"]]
    g4 = four["grids"][0]
    name4 = f"n{g4['n']}_dx{g4['dx']:g}"
    law3, law4 = three["first_law"], four["first_law"]
    model = {tuple(r["x_a"]): r for r in law3.get("error_model", {}).get(a.target, [])}
    pairs4 = law4.get(name4, {}).get(a.target)
    if not isinstance(pairs4, list):
        sys.exit(f"first_law_check: {a.fourth_grid}: no first-law pairs at target {a.target}")
    print(f"| xhat_A pair | Omega M0 | Q_e (3 grids) | {name4} predicted | {name4} measured | Q_e (4 grids, least squares) |")
    print("|---|---|---|---|---|---|")
    for pair in pairs4:
        label = tuple(pair["x_a"])
        m = model.get(label)
        if m is None or pair["residual"] is None:
            continue
        predicted = m["q_exact"] + m["e_truncation"] * g4["dx"] ** 2 + m["e_boundary"] / g4["rc"] ** 2
        rows = [[1.0, dx * dx, 1.0 / rc ** 2] for _, dx, rc in grids3] + [[1.0, g4["dx"] ** 2, 1.0 / g4["rc"] ** 2]]
        q = np.array(m["per_grid"] + [pair["residual"]])
        A = np.array(rows)
        sol = np.linalg.lstsq(A, q, rcond=None)[0]
        scatter = float(np.sum((q - A @ sol) ** 2))  # four equations, three unknowns
        sigma = float(np.sqrt(np.linalg.inv(A.T @ A)[0, 0] * scatter))
        print(f"| {label[0]}–{label[1]} | {pair['Omega_M0']:.5f} | {m['q_exact']:+.3f} | {predicted:+.3f} | "
              f"{pair['residual']:+.3f} | {sol[0]:+.3f} ± {sigma:.3f} |")


if __name__ == "__main__":
    main()
