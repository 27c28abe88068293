#!/usr/bin/env python3
"""PNG plots of a `bhnsid validate` directory, like the IRE figures of the paper: each equation's
residual along the x axis at dx, dx/2, dx/4, multiplied by 1, 4, 16, so that second-order
convergence shows as curves lying on top of each other.
Usage: scripts/plot_validate.py DIR/validate.json DIR   (called by bhnsid validate)
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

GROUPS = {
    "hamiltonian": ["hamiltonian"],
    "momentum": ["momentum_x", "momentum_y", "momentum_z"],
    "lapse": ["lapse"],
    "shift": ["shift_x", "shift_y", "shift_z"],
    "bernoulli": ["bernoulli"],
}
TITLES = {
    "hamiltonian": "Hamiltonian constraint",
    "momentum": "momentum constraint",
    "lapse": "maximal slicing (d_t K)",
    "shift": "minimal distortion (D^j Sigma_ij)",
    "bernoulli": "Bernoulli (h alpha / lorentz - C_B)",
}


def main():
    report = json.load(open(sys.argv[1]))
    out_dir = sys.argv[2]
    axis = report["axis_rescaled"]
    x = axis["x"]
    region = report.get("axis_region", ["away"] * len(x))
    levels = report["levels"]
    for eq, columns in GROUPS.items():
        if eq not in report.get("equations", {}) or report["equations"][eq]["verdict"].startswith("exact"):
            continue
        present = [c for c in columns if c in axis]
        if not present:
            continue
        fig, panels = plt.subplots(len(present), 1, figsize=(7, 2.6 * len(present)), sharex=True, squeeze=False)
        for panel, column in zip(panels[:, 0], present):
            away = []
            for q, series in enumerate(axis[column]):
                pts = [(xi, v, r) for xi, v, r in zip(x, series, region) if v is not None and not (isinstance(v, float) and math.isnan(v))]
                if not pts:
                    continue
                label = ", ".join(f"{k} = {v}" for k, v in levels[q]["parameters"].items() if k.endswith(".n")) + f", x {4 ** q}"
                panel.plot([p[0] for p in pts], [p[1] for p in pts], marker=".", lw=1, ms=3, label=label)
                away += [p[1] for p in pts if p[2] == "away"]
            # The excluded regions (puncture, star surface) shaded; the scale set by the points away from them.
            for xi, r in zip(x, region):
                if r in ("puncture", "surface"):
                    h = 0.5 * (x[1] - x[0])
                    panel.axvspan(xi - h, xi + h, color="0.85" if r == "puncture" else "#f5deb3", lw=0)
            if away:
                lo, hi = min(away), max(away)
                pad = 0.15 * (hi - lo) if hi > lo else 1e-30 + abs(hi)
                panel.set_ylim(lo - pad, hi + pad)
            panel.set_ylabel(column)
            panel.axhline(0, color="0.6", lw=0.5)
        verdict = report["equations"][eq]["verdict"]
        orders = report["equations"][eq]["order_l2"]
        shown = ", ".join("-" if o is None else f"{o:.2f}" for o in orders)
        panels[0, 0].set_title(f"{TITLES[eq]}: L2 orders {shown}; {verdict}", fontsize=9)
        panels[0, 0].legend(fontsize=8)
        panels[-1, 0].set_xlabel("x (hatted); shaded: left out of the norms (grey: puncture, tan: star surface)")
        fig.tight_layout()
        path = os.path.join(out_dir, f"residual_{eq}.png")
        fig.savefig(path + ".tmp.png", dpi=110)
        os.replace(path + ".tmp.png", path)  # atomic: a crash never leaves a half-written plot
        plt.close(fig)


if __name__ == "__main__":
    main()
