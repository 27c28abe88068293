"""The physics check of the reader (issue 21): the metric, extrinsic curvature and matter that the
reader returns on a lattice finer than either run's grid satisfy the ADM Hamiltonian and momentum
constraints, evaluated here with this script's own 4th-order finite differences, to the solver's
truncation error: the norms fall by ~4 when the run's dx halves (the solver is second order).

    /usr/bin/python3 check_constraints.py COARSE/data.h5 FINE/data.h5

Both runs must cover one hatted domain (the same parameter file at n, dx and 2n, dx/2). The
lattice is laid in hatted coordinates xhat = x / sigma (each run has its own sigma, so its own
physical box) and the constraints are made hatted (times sigma^2, they have dimension
1/length^2), so that both runs are judged at the same points of the same solution. Excluded: a
ball around the puncture (the 1/r pole's derivatives are not resolved by any lattice), which
covers the shift's excision cube, the outer third of the grid (the outer boundary condition), and
a shell around the star's surface, where rho0 has a kink: the interpolant's error there is O(dx),
not O(dx^2). Judged apart: the vacuum, and the star's interior (few points at n = 32, where the
star's radius is 3 cells, but the only place where the matter terms count). Exit 1 when a ratio
is outside [RATIO_LO, RATIO_HI] (the same run twice gives 1: the check can fail).
"""

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reader", "python"))
import bhnsid_reader  # noqa: E402

# Second order: halving dx divides the norms by 4; accept the pre-asymptotic spread of a coarse
# binary (measured at quickstart n = 32 / 64: H 3.86, M 4.00).
RATIO_LO, RATIO_HI = 2.8, 5.5
# Lagrange points per axis. Order 4 is not enough here: its interpolant's first derivative jumps
# by O(dx^4/dx) = O(dx^3) at every cell face, which the lattice's second differences (spacing h)
# turn into O(dx^3/h); with h fixed at dx_fine/2 that is 4 dx^2 for the coarse run and falls by 8,
# and it dominated (measured: |H| in vacuum 3.9e-2 -> 4.0e-3, ratio 9.6; at order 6 1.55e-2 ->
# 4.0e-3, ratio 3.86: the fine run's norm is the solver's, the coarse one's was the interpolant's).
ORDER = 6
# Excluded, in the coarse run's cells: a ball of HOLE_CELLS dx around the puncture (it covers the
# excision cube, half size 1.5 dx at n = 32), and SURFACE_CELLS dx on either side of the star's
# surface (between 1.5 and 3 the ratios stay within 3.5..3.9 and 3.9..4.0, measured).
HOLE_CELLS, SURFACE_CELLS = 6, 2

FIELDS = ["gxx", "gxy", "gxz", "gyy", "gyz", "gzz", "kxx", "kxy", "kxz", "kyy", "kyz", "kzz",
          "rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz"]


def d1(f, axis, h):
    """4th-order centred first derivative along `axis` ([k][j][i]: axis 2 is x); NaN on the two
    layers at each end, which the region's mask drops."""
    out = np.full_like(f, np.nan)
    n = f.shape[axis]
    s = lambda a, b: tuple(slice(a, b) if ax == axis else slice(None) for ax in range(3))  # noqa: E731
    out[s(2, n - 2)] = (f[s(0, n - 4)] - 8 * f[s(1, n - 3)] + 8 * f[s(3, n - 1)] - f[s(4, n)]) / (12 * h)
    return out


def grad(f, h):
    """[d/dx, d/dy, d/dz] of an array [k][j][i]."""
    return [d1(f, 2, h), d1(f, 1, h), d1(f, 0, h)]


def sym(c):
    """3x3 nested list of the symmetric tensor given as xx xy xz yy yz zz."""
    xx, xy, xz, yy, yz, zz = c
    return [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]


def inverse(g):
    det = (g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[2][1]) - g[0][1] * (g[1][0] * g[2][2] - g[1][2] * g[2][0])
           + g[0][2] * (g[1][0] * g[2][1] - g[1][1] * g[2][0]))
    cof = [[g[(j + 1) % 3][(i + 1) % 3] * g[(j + 2) % 3][(i + 2) % 3]
            - g[(j + 1) % 3][(i + 2) % 3] * g[(j + 2) % 3][(i + 1) % 3] for j in range(3)] for i in range(3)]
    return [[cof[i][j] / det for j in range(3)] for i in range(3)]


def constraints(v, h):
    """Hamiltonian H = R + K^2 - K_ij K^ij - 16 pi rho_E and momentum M^i = D_j(K^ij - gamma^ij K)
    - 8 pi S^i of the fields v (name -> lattice array) with spacing h, for a general 3-metric."""
    g = sym([v["g" + s] for s in ("xx", "xy", "xz", "yy", "yz", "zz")])
    K = sym([v["k" + s] for s in ("xx", "xy", "xz", "yy", "yz", "zz")])
    gi = inverse(g)
    R3 = range(3)
    dg = [[grad(g[i][j], h) for j in R3] for i in R3]  # dg[i][j][k] = d_k g_ij
    # Gamma^k_ij = 1/2 g^kl (d_i g_lj + d_j g_li - d_l g_ij)
    low = [[[0.5 * (dg[l][j][i] + dg[l][i][j] - dg[i][j][l]) for j in R3] for i in R3] for l in R3]
    gam = [[[sum(gi[k][l] * low[l][i][j] for l in R3) for j in R3] for i in R3] for k in R3]
    dgam = [[[grad(gam[k][i][j], h) for j in R3] for i in R3] for k in R3]  # dgam[k][i][j][m]
    # R_ij = d_k G^k_ij - d_j G^k_ik + G^k_kl G^l_ij - G^k_jl G^l_ik
    ricci = [[sum(dgam[k][i][j][k] - dgam[k][i][k][j] for k in R3)
              + sum(gam[k][k][l] * gam[l][i][j] - gam[k][j][l] * gam[l][i][k] for k in R3 for l in R3)
              for j in R3] for i in R3]
    R = sum(gi[i][j] * ricci[i][j] for i in R3 for j in R3)
    Ku = [[sum(gi[i][a] * gi[j][b] * K[a][b] for a in R3 for b in R3) for j in R3] for i in R3]
    trK = sum(gi[i][j] * K[i][j] for i in R3 for j in R3)
    KK = sum(K[i][j] * Ku[i][j] for i in R3 for j in R3)
    rho, press, eps, W = v["rho"], v["press"], v["eps"], v["w_lorentz"]
    vel = [v["vel[%d]" % c] for c in R3]
    with np.errstate(divide="ignore", invalid="ignore"):
        h_enth = np.where(rho > 0, 1 + eps + press / np.where(rho > 0, rho, 1), 1.0)
    rho_e = rho * h_enth * W * W - press
    H = R + trK * trK - KK - 16 * math.pi * rho_e
    T = [[Ku[i][j] - gi[i][j] * trK for j in R3] for i in R3]
    dT = [[grad(T[i][j], h) for j in R3] for i in R3]
    M = []
    for i in R3:
        div = sum(dT[i][j][j] for j in R3)
        div = div + sum(gam[i][j][k] * T[k][j] + gam[j][j][k] * T[i][k] for j in R3 for k in R3)
        S_up = rho * h_enth * W * W * vel[i]  # S^i = rho h W^2 v^i (Valencia v^i)
        M.append(div - 8 * math.pi * S_up)
    return H, M


def lattice(reader, h_hat, box_hat):
    """The lattice points (physical) of the hatted box [-bx, bx] x [-by, by] x [-bz, bz] (z < 0:
    the mirror), spacing h_hat, and its shape."""
    sigma = reader.numeric_attribute("/grid", "sigma")[0]
    axes = [np.arange(-round(b / h_hat), round(b / h_hat) + 1) * h_hat for b in box_hat]
    zh, yh, xh = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")
    return sigma, (xh, yh, zh)


def evaluate(path, h_hat, box_hat, order):
    with bhnsid_reader.Reader(path) as r:
        sigma, (xh, yh, zh) = lattice(r, h_hat, box_hat)
        vals = r.interpolate((sigma * xh).ravel(), (sigma * yh).ravel(), (sigma * zh).ravel(), FIELDS, order=order)
        v = {k: a.reshape(xh.shape) for k, a in vals.items()}
        H, M = constraints(v, sigma * h_hat)
        # The star's extent from trilinear rho0, which does not ring beyond the surface as the
        # higher orders do (the mask must not depend on the order judged).
        star = r.interpolate((sigma * xh).ravel(), (sigma * yh).ravel(), (sigma * zh).ravel(), ["rho"],
                             order=2)["rho"].reshape(xh.shape) > 0
        mass, pos = r.puncture
        bh_hat = [p / sigma for p in pos]
        dx_hat = r.dx / sigma
        cube = r.numeric_attribute("/ADMBase/betax", "held_region_half_size")[0] / sigma
    # Hatted: the constraints have dimension 1/length^2 (x sigma^2 to the hatted ones).
    return dict(H=H * sigma**2, M=[m * sigma**2 for m in M], star=star, x=(xh, yh, zh), bh=bh_hat,
                dx=dx_hat, cube=cube, mass_hat=mass / sigma)


def dilate(mask, cells):
    out = mask.copy()
    for _ in range(cells):
        grown = out.copy()
        for axis in range(3):
            grown[tuple(slice(1, None) if a == axis else slice(None) for a in range(3))] |= \
                out[tuple(slice(None, -1) if a == axis else slice(None) for a in range(3))]
            grown[tuple(slice(None, -1) if a == axis else slice(None) for a in range(3))] |= \
                out[tuple(slice(1, None) if a == axis else slice(None) for a in range(3))]
        out = grown
    return out


def l2(a, mask, h_hat):
    return math.sqrt(float(np.sum(a[mask] ** 2)) * h_hat**3)


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    coarse_path, fine_path = argv[1], argv[2]
    with bhnsid_reader.Reader(fine_path) as r:
        sigma = r.numeric_attribute("/grid", "sigma")[0]
        dx_fine_hat = r.dx / sigma
        half_hat = (r.upper[0] - r.lower[0]) / 2 / sigma
    h_hat = dx_fine_hat / 2
    b = 0.6 * half_hat  # 8 coarse cells from the outer boundary at n = 32
    box = (b, b, b / 2)
    runs = [evaluate(p, h_hat, box, ORDER) for p in (coarse_path, fine_path)]
    xh, yh, zh = runs[0]["x"]
    dx_c = runs[0]["dx"]
    # One region for both runs: the union of what either run excludes.
    finite = np.ones(xh.shape, dtype=bool)
    near_hole = np.zeros(xh.shape, dtype=bool)
    star = np.zeros(xh.shape, dtype=bool)
    for run in runs:
        finite &= np.isfinite(run["H"]) & np.all([np.isfinite(m) for m in run["M"]], axis=0)
        bx, by, bz = run["bh"]
        near_hole |= np.sqrt((xh - bx) ** 2 + (yh - by) ** 2 + (zh - bz) ** 2) < HOLE_CELLS * dx_c
        star |= run["star"]
    cells = int(round(SURFACE_CELLS * dx_c / h_hat))
    vacuum = finite & ~near_hole & ~dilate(star, cells)
    interior = finite & ~near_hole & ~dilate(~star, cells)
    print("lattice %s points, h_hat = %.4g (the runs' dx_hat %.4g and %.4g), box_hat +-%s, order %d" % (
        "x".join(map(str, xh.shape[::-1])), h_hat, dx_c, runs[1]["dx"], box, ORDER))
    failed = False
    for name, mask, least in (("vacuum", vacuum, 10000), ("star interior", interior, 200)):
        hn = [l2(run["H"], mask, h_hat) for run in runs]
        mn = [math.sqrt(sum(l2(m, mask, h_hat) ** 2 for m in run["M"])) for run in runs]
        print("%-28s %7d points: L2 |H| %.4e -> %.4e ratio %.3f;  L2 |M| %.4e -> %.4e ratio %.3f" % (
            name, int(mask.sum()), hn[0], hn[1], hn[0] / hn[1], mn[0], mn[1], mn[0] / mn[1]))
        if mask.sum() < least:
            print("FAIL: only %d points in the judged region" % mask.sum())
            failed = True
        for what, n in (("Hamiltonian", hn), ("momentum", mn)):
            ratio = n[0] / n[1]
            if not RATIO_LO <= ratio <= RATIO_HI:
                print("FAIL: the %s constraint's norm fell by %.3f, outside [%g, %g]" % (what, ratio, RATIO_LO, RATIO_HI))
                failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
