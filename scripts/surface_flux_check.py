#!/usr/bin/env python3
"""The rest-mass flux through a star's surface from a run's data.h5 (exported primitives and metric
only, as an evolution code reads them): no matter crosses the surface of a stationary star in the
frame that rotates with the orbit, (alpha v - B) . n = 0 with B = beta + Omega xi, xi = (-y, x, 0).

At the surface layer (matter points with a 6-neighbour outside the matter) prints the largest
normal velocity |(alpha v - B) . n| (n = grad rho / |grad rho|, differences through matter points only and
the z = 0 mirror; expected to fall at first order: the surface is resolved to a spacing) and the largest
normal mass flux density |rho W gxx^(3/2) (alpha v - B) . n| / rho_max (one order more: rho vanishes at
the surface). Omega is summary's omega (physical).
Usage: scripts/surface_flux_check.py RUN_DIR [RUN_DIR ...]   (needs numpy and h5py)
"""
import os
import sys

import h5py
import numpy as np


def mirrored(a):
    """a [z, y, x] on z >= 0 with its (even) mirror image below z = 0 prepended."""
    return np.concatenate([a[:0:-1], a], axis=0)


def check(run):
    with h5py.File(os.path.join(run, "data.h5"), "r") as f:
        g = f["grid"].attrs
        rho = f["HydroBase/rho"][()]
        w = f["HydroBase/w_lorentz"][()]
        v = [f[f"HydroBase/vel[{c}]"][()] for c in range(3)]
        alpha = f["ADMBase/alp"][()]
        # A run without the shift equation exports no shift: beta = 0.
        beta = [f[f"ADMBase/beta{c}"][()] if f"ADMBase/beta{c}" in f else np.zeros_like(rho) for c in "xyz"]
        gxx = f["ADMBase/gxx"][()]
        omega = float(f["scalars"].attrs["omega"])
        equatorial = str(g["symmetry"]) != "none"
        dx, origin = float(g["dx"]), [float(o) for o in g["origin_xyz"]]
    nz, ny, nx = rho.shape
    y = origin[1] + dx * np.arange(ny)[None, :, None]
    x = origin[0] + dx * np.arange(nx)[None, None, :]
    # grad rho through matter points only (one-sided where a neighbour is outside): a centred
    # difference across the surface reads rho = 0 there and tilts the normal by up to 45 degrees.
    full = mirrored(rho) if equatorial else rho
    inside = full > 0
    grad = []
    for axis in range(3):
        up, down = np.roll(full, -1, axis), np.roll(full, 1, axis)
        up_in, down_in = np.roll(inside, -1, axis), np.roll(inside, 1, axis)
        d = np.where(up_in & down_in, (up - down) / (2 * dx),
                     np.where(up_in, (up - full) / dx, np.where(down_in, (full - down) / dx, 0.0)))
        grad.append(d)
    if equatorial:
        grad = [d[nz - 1:] for d in grad]
    gz, gy, gx = grad
    norm = np.sqrt(gx ** 2 + gy ** 2 + gz ** 2)
    matter = rho > 0
    outside = ~(mirrored(matter) if equatorial else matter)
    pad = np.pad(outside, 1, constant_values=True)
    shift = lambda dz, dy, dxi: pad[1 + dz:pad.shape[0] - 1 + dz, 1 + dy:pad.shape[1] - 1 + dy, 1 + dxi:pad.shape[2] - 1 + dxi]
    touches = shift(1, 0, 0) | shift(-1, 0, 0) | shift(0, 1, 0) | shift(0, -1, 0) | shift(0, 0, 1) | shift(0, 0, -1)
    if equatorial:
        touches = touches[nz - 1:]
    surface = matter & touches & (norm > 0)
    rel = [alpha * v[0] - beta[0] + omega * y, alpha * v[1] - beta[1] - omega * x, alpha * v[2] - beta[2]]
    normal = (rel[0] * gx + rel[1] * gy + rel[2] * gz)[surface] / norm[surface]
    flux = rho[surface] * w[surface] * gxx[surface] ** 1.5 * normal / rho.max()
    print(f"{run}: dx = {dx:.5f}, {surface.sum()} surface points, max |(alpha v - B).n| {np.max(np.abs(normal)):.3e}, "
          f"max |rho W gxx^1.5 (alpha v - B).n|/rho_max {np.max(np.abs(flux)):.3e}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for r in sys.argv[1:]:
        check(r)
