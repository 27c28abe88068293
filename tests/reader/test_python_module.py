"""The Python module (reader/python/bhnsid_reader.py) against the C library, to round-off: every
field, at random points near the puncture, inside the excision cube, in and out of the star and
at z < 0 (the mirror), on a synthetic file written here with h5py and on the real runs given on the
command line; the C side through bhnsid-export (its table is %.17g, so exact doubles). Then the
module's errors for bad input.

    /usr/bin/python3 test_python_module.py BHNSID_EXPORT WORK_DIR DATA.h5 ...
"""

import math
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reader", "python"))
import bhnsid_reader  # noqa: E402

# Both sides sum the same products in the same order; what differs is numpy's pow/sqrt against
# libm's and the held region's conjugate gradients (stopped at 1e-15 relative), so a few ulps.
RTOL, ATOL = 1e-12, 1e-13
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def c_values(export, work, data, x, y, z, fields, order):
    pts = os.path.join(work, "py_points.txt")
    with open(pts, "w") as f:
        for p in zip(x, y, z):
            f.write("%.17g %.17g %.17g\n" % p)
    out = subprocess.run([export, data, "--points", pts, "--fields", ",".join(fields), "--order", str(order)],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("bhnsid-export failed (%d): %s" % (out.returncode, out.stderr))
    lines = out.stdout.splitlines()
    header = lines[0].split("\t")
    table = np.array([[float(w) for w in line.split("\t")] for line in lines[1:]])
    return {name: table[:, header.index(name)] for name in fields}


def write_synthetic(path):
    """An equatorial grid with a puncture, a held cube in beta, a polytropic star with velocity."""
    n, dx = 24, 0.1
    nx, nz = n + 1, n // 2 + 1
    o = -dx * (n // 2)
    k, j, i = np.meshgrid(np.arange(nz), np.arange(nx), np.arange(nx), indexing="ij")
    x, y, z = o + dx * i, o + dx * j, dx * k
    with h5py.File(path, "w") as f:
        f.attrs["format"] = "bhnsid-data"
        f.attrs["format_version"] = np.int64(1)
        f.attrs["status"] = "converged"
        g = f.create_group("grid")
        g.attrs["shape_zyx"] = np.array([nz, nx, nx], dtype=np.float64)
        g.attrs["dx"], g.attrs["sigma"], g.attrs["dx_hat"] = dx, 1.0, dx
        g.attrs["origin_xyz"] = np.array([o, o, 0.0])
        g.attrs["symmetry"] = "equatorial"

        def ds(p, v, parity=1, held=None):
            d = f.create_dataset(p, data=np.asarray(v, dtype=np.float64))
            d.attrs["parity_z"] = np.int64(parity)
            if held:
                d.attrs["held_region_shape"] = "cube"
                d.attrs["held_region_centre"] = np.array(held[0])
                d.attrs["held_region_half_size"] = held[1]
        bh = (-0.43, 0.021, 0.0)
        held = (bh, 0.25)
        inside = np.maximum(np.maximum(abs(x - bh[0]), abs(y - bh[1])), abs(z - bh[2])) <= 0.25 + 1e-9
        ds("/variables/chi", 1 + 0.1 * np.exp(-(x * x + y * y + z * z)))
        ds("/variables/eta", 1 - 0.2 * np.exp(-(x * x + 2 * y * y + z * z)))
        for c, (fn, par) in enumerate(((np.sin(x) * np.cos(y), 1), (0.3 * x * y + 0.1, 1), (z * np.cos(x), -1))):
            ds("/ADMBase/beta" + "xyz"[c], np.where(inside, 0.05 * (c + 1), fn), par, held)
        ds("/ADMBase/kxx", 0.01 * np.cos(x + y) * np.exp(-z * z))
        ds("/ADMBase/kxz", 0.02 * z * np.sin(y), -1)
        rho = 0.1 * np.maximum(0.0, 1 - ((x - 0.4) ** 2 + y * y + z * z) / 0.16)
        ds("/HydroBase/rho", rho)
        ds("/HydroBase/vel[0]", np.where(rho > 0, -0.3 * y, 0.0))
        ds("/HydroBase/vel[1]", np.where(rho > 0, 0.3 * (x - 0.4) + 0.05, 0.0))
        ds("/HydroBase/vel[2]", np.where(rho > 0, 0.1 * z, 0.0), -1)
        s = f.create_group("scalars")
        for name, v in (("bh_bare_mass", 0.2), ("bh_position_x", bh[0]), ("bh_position_y", bh[1]),
                        ("bh_position_z", bh[2])):
            s.attrs[name] = v
        e = f.create_group("eos")
        e.attrs["model"] = "piecewise_polytrope"
        # Two pieces meeting at rho0 = 0.05 with P and eps continuous (K_1 = K_0 rho^(G0 - G1),
        # a_1 = K_0 rho/(G0 - 1) - K_1 rho^(G1 - 1)/(G1 - 1)): both are crossed inside the star.
        k1 = 0.05 ** (2 - 2.5)
        for name, v in (("rho0_lo", [0.0, 0.05]), ("K", [1.0, k1]), ("Gamma", [2.0, 2.5]),
                        ("eps_offset", [0.0, 0.05 - k1 * 0.05 ** 1.5 / 1.5])):
            e.attrs[name] = np.array(v)
    return bh


def points(r, rnd, centres):
    """Random points: in the whole box (z of both signs), and in balls around each centre."""
    lo, hi = np.array(r.lower), np.array(r.upper)
    p = [rnd.uniform(lo, hi, size=(300, 3))]
    for c, radius in centres:
        d = rnd.normal(size=(60, 3))
        d *= (rnd.uniform(0, 1, size=(60, 1)) ** (1 / 3) * radius) / np.linalg.norm(d, axis=1, keepdims=True)
        q = np.clip(np.array(c) + d, lo, hi)
        q[::2, 2] *= -1  # half of them mirrored
        p.append(q)
    p = np.concatenate(p)
    return p[:, 0], p[:, 1], p[:, 2]


def compare(export, work, data, rnd):
    with bhnsid_reader.Reader(data) as r:
        centres = []
        if r.puncture:
            m, pos = r.puncture
            centres += [(pos, 2 * r.dx), (pos, 0.05 * r.dx)]  # near the puncture (never at it)
        if "/ADMBase/betax" in r.datasets and "held_region_centre" in r._file["/ADMBase/betax"].attrs:
            c = r.numeric_attribute("/ADMBase/betax", "held_region_centre")
            centres.append((list(c), r.numeric_attribute("/ADMBase/betax", "held_region_half_size")[0]))
        if "/HydroBase/rho" in r.datasets:
            rho = r._file["/HydroBase/rho"][...]
            kk, jj, ii = np.unravel_index(np.argmax(rho), rho.shape)
            centre = [r.origin[0] + r.dx * ii, r.origin[1] + r.dx * jj, r.origin[2] + r.dx * kk]
            centres.append((centre, 6 * r.dx))  # in, out and across the surface
        x, y, z = points(r, rnd, centres)
        if r.puncture:  # no sample exactly at the pole
            pos = r.puncture[1]
            far = np.sqrt((x - pos[0]) ** 2 + (y - pos[1]) ** 2 + (z - pos[2]) ** 2) > 1e-6 * r.dx
            x, y, z = x[far], y[far], z[far]
        fields = list(r.fields) + ["/variables/chi"] * ("/variables/chi" in r.datasets)
        for order in (4, 6):
            py = r.interpolate(x, y, z, fields, order=order)
            c = c_values(export, work, data, x, y, z, fields, order)
            worst = 0.0
            for name in fields:
                a, b = py[name], c[name]
                check(np.all(np.isfinite(a)), "%s %s order %d: Python gave a non-finite value" % (data, name, order))
                err = np.abs(a - b) / (ATOL + RTOL * np.abs(b))
                worst = max(worst, float(np.max(err)))
                check(np.all(err <= 1), "%s %s order %d: Python and C differ by %.3e (point %d)" % (
                    data, name, order, float(np.max(np.abs(a - b))), int(np.argmax(err))))
            n_mirror = int(np.sum(z < 0))
            print("%s order %d: %d points (%d at z < 0), %d fields, worst |py - c| / (%g + %g |c|) = %.3f" % (
                os.path.basename(os.path.dirname(data)) or data, order, x.size, n_mirror, len(fields), ATOL, RTOL,
                worst))
            check(n_mirror > 20, "too few mirrored points")


def expect_error(code, text, fn, what):
    try:
        fn()
    except bhnsid_reader.ReaderError as e:
        check(e.code == code, "%s: code %d, expected %d (%s)" % (what, e.code, code, e))
        check(text in str(e), "%s: message %r lacks %r" % (what, str(e), text))
        return
    check(False, "%s: no error" % what)


def bad_input(work, synthetic):
    missing = os.path.join(work, "no_such_file.h5")
    expect_error(bhnsid_reader.ERR_IO, "no_such_file.h5", lambda: bhnsid_reader.Reader(missing), "missing file")
    text = os.path.join(work, "py_not_hdf5.h5")
    with open(text, "w") as f:
        f.write("not HDF5\n")
    expect_error(bhnsid_reader.ERR_IO, "not an HDF5 file", lambda: bhnsid_reader.Reader(text), "not HDF5")
    newer = os.path.join(work, "py_version2.h5")
    with h5py.File(newer, "w") as f:
        f.attrs["format"] = "bhnsid-data"
        f.attrs["format_version"] = np.int64(2)
    expect_error(bhnsid_reader.ERR_FORMAT, "format_version 2 is newer", lambda: bhnsid_reader.Reader(newer),
                 "format_version 2")
    other = os.path.join(work, "py_other.h5")
    with h5py.File(other, "w") as f:
        f.attrs["format"] = "something-else"
    expect_error(bhnsid_reader.ERR_FORMAT, "not 'bhnsid-data'", lambda: bhnsid_reader.Reader(other), "other format")
    with bhnsid_reader.Reader(synthetic) as r:
        out = r.upper[0] + 0.5 * r.dx
        expect_error(bhnsid_reader.ERR_OUTSIDE, "outside the grid", lambda: r.interpolate([out], [0], [0], ["alp"]),
                     "point outside")
        # The clamp policy gives the value at the nearest box point instead.
        a = r.interpolate([out], [0.0], [0.0], ["/variables/chi"], outside="clamp")["/variables/chi"]
        b = r.interpolate([r.upper[0]], [0.0], [0.0], ["/variables/chi"])["/variables/chi"]
        check(a[0] == b[0], "clamp: %r != %r" % (a[0], b[0]))
        pos = r.puncture[1]
        expect_error(bhnsid_reader.ERR_PUNCTURE, "puncture", lambda: r.interpolate([pos[0]], [pos[1]], [pos[2]], ["gxx"]),
                     "at the puncture")
        expect_error(bhnsid_reader.ERR_ARGUMENT, "unknown field", lambda: r.interpolate([0], [0], [0], ["gxq"]),
                     "unknown field")
        expect_error(bhnsid_reader.ERR_ARGUMENT, "order 5", lambda: r.interpolate([0], [0], [0], ["alp"], order=5),
                     "odd order")
        expect_error(bhnsid_reader.ERR_ARGUMENT, "not finite",
                     lambda: r.interpolate([math.nan], [0], [0], ["alp"]), "NaN point")


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    export, work = argv[1], argv[2]
    os.makedirs(work, exist_ok=True)
    synthetic = os.path.join(work, "py_synthetic.h5")
    write_synthetic(synthetic)
    rnd = np.random.default_rng(21)
    for data in [synthetic] + argv[3:]:
        compare(export, work, data, rnd)
    bad_input(work, synthetic)
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
