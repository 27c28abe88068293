#!/usr/bin/env python3
"""The fluid's vorticity from a run's data.h5, built from the exported primitives only (as an evolution
code would read them), not from the velocity potential's own stencil.

h u_i = h W gamma_ij v^j with gamma_ij = gxx delta_ij (conformally flat), h = 1 + eps + P/rho from the
exported rho, press, eps; the z component of the curl, omega_xy = d_x(h u_y) - d_y(h u_x), by centred
differences over two spacings at the matter points three points or more inside the star in x and y. Prints the rms and max of
omega_xy there and, for scale, 2 Omega <h u^t gxx> (the corotating flow's vorticity, Omega the physical
angular velocity from summary.json: omega, or omega_hat/sigma). An irrotational star's vorticity is
truncation error and falls with resolution; a corotating star's is about that scale.
Usage: scripts/vorticity_check.py [--band N] RUN_DIR [RUN_DIR ...]   (needs numpy and h5py; N = 3 points:
double it with the resolution to keep the band's width)
"""
import json
import os
import sys

import h5py
import numpy as np


BAND = 3


def check(run):
    with h5py.File(os.path.join(run, "data.h5"), "r") as f:
        rho = f["HydroBase/rho"][()]
        press = f["HydroBase/press"][()]
        eps = f["HydroBase/eps"][()]
        w = f["HydroBase/w_lorentz"][()]
        vx = f["HydroBase/vel[0]"][()]
        vy = f["HydroBase/vel[1]"][()]
        gxx = f["ADMBase/gxx"][()]
    summary = json.load(open(os.path.join(run, "summary.json")))["scalars"]
    sigma = summary["sigma"]
    n = rho.shape[2] - 1
    params = open(os.path.join(run, "params.yaml")).read()
    dx_hat = float([line.split(":")[1].split("#")[0] for line in params.splitlines() if line.strip().startswith("dx:")][0])
    dx = sigma * dx_hat
    matter = rho > 0
    h = np.where(matter, 1 + eps + np.divide(press, rho, out=np.zeros_like(rho), where=matter), 1.0)
    hux, huy = h * w * gxx * vx, h * w * gxx * vy
    # Arrays are [z, y, x]; omega_xy = d_x(h u_y) - d_y(h u_x).
    # The curl with differences over two spacings, (f(i+2) - f(i-2))/(4 dx): the exported velocity is
    # the potential's centred difference, and a curl by the same stencil would vanish identically
    # (D_x D_y = D_y D_x); this one does not, and measures the truncation error. At points whose x-y
    # neighbours within `band` points are matter (next to the surface the velocities are one-sided).
    band = BAND
    inner = np.ones_like(matter[:, band:-band, band:-band])
    for d in range(-band, band + 1):
        inner &= matter[:, band:-band, band + d:matter.shape[2] - band + d] & matter[:, band + d:matter.shape[1] - band + d, band:-band]
    curl = ((huy[:, band:-band, band + 2:matter.shape[2] - band + 2] - huy[:, band:-band, band - 2:matter.shape[2] - band - 2])
            - (hux[:, band + 2:matter.shape[1] - band + 2, band:-band] - hux[:, band - 2:matter.shape[1] - band - 2, band:-band])) / (4 * dx)
    values = curl[inner]
    omega = summary.get("omega", summary["omega_hat"] / sigma)
    scale = 2 * omega * np.mean((h * w * gxx)[matter])
    print(f"{run}: n = {n}, {values.size} points, vorticity rms {np.sqrt(np.mean(values ** 2)):.3e}, "
          f"max {np.max(np.abs(values)):.3e}; 2 Omega <h u^t gxx> = {scale:.3e}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) >= 2 and args[0] == "--band":
        BAND = int(args[1])
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    for r in args:
        check(r)
