#!/usr/bin/env python3
"""hydro_corotating's pictures for `bhnsid plot RUN_DIR` (run as: plot.py RUN_DIR OUTPUT_DIR).

equator.png: the equatorial plane z = 0 of data.h5 (io_hdf5) in physical coordinates: rho0, the
lapse alpha, chi (the regular part of the conformal factor) and |beta|, with the black hole (the
puncture's bare position, when the run has one) and the star's density maximum marked.
outer_iteration.png: the outer iteration from star_history.tsv: sigma, Omegahat, C_B and the
largest relative change per step (log scale), the steps taken at a fraction after a retreat marked.
Needs Debian's python3-matplotlib, python3-h5py and python3-numpy."""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def fail(message):
    sys.exit(f"hydro_corotating plot: {message}")


def equator(run, out):
    import h5py

    path = os.path.join(run, "data.h5")
    if not os.path.exists(path):
        fail(f"{path} is missing: add io_hdf5 to the run's plugins")
    f = h5py.File(path, "r")
    origin, dx = f["grid"].attrs["origin_xyz"], f["grid"].attrs["dx"]
    ny, nx = f["grid"].attrs["shape_zyx"][1:].astype(int)
    x = origin[0] + dx * np.arange(nx)
    y = origin[1] + dx * np.arange(ny)
    panels = [("HydroBase/rho", r"$\rho_0$"), ("ADMBase/alp", r"lapse $\alpha$"), ("variables/chi", r"$\chi$")]
    images = [(f[p][0], label) for p, label in panels if p in f]
    if all(f"ADMBase/beta{c}" in f for c in "xyz"):
        beta = np.sqrt(sum(f[f"ADMBase/beta{c}"][0] ** 2 for c in "xyz"))
        images.append((beta, r"$|\beta|$"))
    scalars = f["scalars"].attrs
    fig, axes = plt.subplots(2, 2, figsize=(11, 10), squeeze=False)
    for ax, (values, label) in zip(axes.flat, images):
        mesh = ax.pcolormesh(x, y, values, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, shrink=0.85)
        if "bh_position_x" in scalars:
            ax.plot(scalars["bh_position_x"], scalars.get("bh_position_y", 0.0), "x", color="red", ms=10, mew=2,
                    label="black hole")
        if "star_center_x" in scalars:
            ax.plot(scalars["star_center_x"], 0.0, "+", color="white", ms=12, mew=2, label="star (density max)")
        ax.set_title(label)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_aspect("equal")
    for ax in list(axes.flat)[len(images):]:
        ax.axis("off")
    axes.flat[0].legend(loc="upper left", fontsize=8)
    fig.suptitle(f"equatorial plane z = 0, physical coordinates (sigma = {f['grid'].attrs['sigma']:.6g}); "
                 f"run {f.attrs['status']}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "equator.png"), dpi=90)
    plt.close(fig)


def history(run, out):
    path = os.path.join(run, "star_history.tsv")
    if not os.path.exists(path):
        fail(f"{path} is missing")
    names = open(path).readline().lstrip("# ").split()
    rows = np.atleast_2d(np.loadtxt(path))
    col = {n: rows[:, i] for i, n in enumerate(names)}
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for ax, (name, label) in zip(axes.flat[:3], [("sigma", r"$\sigma$"), ("omega_hat", r"$\hat\Omega$"),
                                               ("bernoulli_constant", r"$C_B$")]):
        ax.plot(col["iteration"], col[name], "o-", ms=3)
        ax.set_title(label)
        ax.set_xlabel("outer step")
    ax = axes.flat[3]
    ax.semilogy(col["iteration"], np.maximum(col["change"], 1e-16), "o-", ms=3, label="largest relative change")
    if "step_fraction" in col:
        short = col["step_fraction"] < 1
        ax.semilogy(col["iteration"][short], np.maximum(col["change"][short], 1e-16), "s", color="red",
                    label="after a retreat (shorter step)")
    ax.set_title("change per outer step")
    ax.set_xlabel("outer step")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "outer_iteration.png"), dpi=90)
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        fail("usage: plot.py RUN_DIR OUTPUT_DIR")
    run, out = sys.argv[1:3]
    equator(run, out)
    history(run, out)
    print(f"hydro_corotating plot: equator.png, outer_iteration.png in {out}")


if __name__ == "__main__":
    main()
