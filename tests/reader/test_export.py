"""bhnsid-export, run as a user would: a points file in, a TSV table out whose values are the
stored datasets at grid points (h5py reads them independently), and for bad input a non-zero
exit with a message naming the file at fault; --output is atomic and never replaces a file
unless --force.

    /usr/bin/python3 test_export.py BHNSID_EXPORT WORK_DIR DATA.h5
"""

import os
import subprocess
import sys

import h5py
import numpy as np

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(exe, *args):
    return subprocess.run([exe] + list(args), capture_output=True, text=True)


def main(argv):
    exe, work, data = argv[1], argv[2], argv[3]
    os.makedirs(work, exist_ok=True)
    with h5py.File(data, "r") as f:
        g = f["grid"].attrs
        o, dx = g["origin_xyz"], float(g["dx"])
        rho = f["HydroBase/rho"][...]
        alp = f["ADMBase/alp"][...]
        kxz = f["ADMBase/kxz"][...]
        parity_kxz = int(f["ADMBase/kxz"].attrs["parity_z"])
    # Grid points: the star's centre, an off-centre point, and the mirror of one (z < 0).
    kk, jj, ii = np.unravel_index(np.argmax(rho), rho.shape)
    idx = [(ii, jj, kk), (ii - 3, jj + 2, 1), (ii - 2, jj + 1, 2)]
    pts = [(o[0] + dx * i, o[1] + dx * j, o[2] + dx * k) for i, j, k in idx]
    pts[2] = (pts[2][0], pts[2][1], -pts[2][2])
    points = os.path.join(work, "export_points.txt")
    with open(points, "w") as f:
        f.write("# x y z (physical)\n")
        for p in pts:
            f.write("%.17g %.17g %.17g\n\n" % p)
    table = os.path.join(work, "export_table.tsv")
    if os.path.exists(table):
        os.remove(table)
    r = run(exe, data, "--points", points, "--output", table, "--fields", "rho,kxz,/ADMBase/alp")
    check(r.returncode == 0, "export failed: %s" % r.stderr)
    lines = open(table).read().splitlines()
    check(lines[0].split("\t") == ["x", "y", "z", "rho", "kxz", "/ADMBase/alp"], "header %r" % lines[0])
    check(len(lines) == 4, "%d lines, expected 4" % len(lines))
    for n, (i, j, k) in enumerate(idx):
        v = [float(w) for w in lines[n + 1].split("\t")]
        sign = -1 if n == 2 else 1
        want = [rho[k, j, i], kxz[k, j, i] * (parity_kxz if sign < 0 else 1), alp[k, j, i]]
        # At a grid point the Lagrange weights are 1 and 0: the stored double exactly, up to the
        # last bit of the coordinate's round trip.
        for got, exp, name in zip(v[3:], want, ("rho", "kxz", "alp")):
            check(abs(got - exp) <= 1e-14 * max(1.0, abs(exp)), "point %d %s: %r != stored %r" % (n, name, got, exp))
    check(not os.path.exists(table + ".partial"), "the .partial file was left behind")

    # Never replaces a file it was not asked to replace; --force does, atomically.
    before = open(table).read()
    r = run(exe, data, "--points", points, "--output", table, "--fields", "alp")
    check(r.returncode == 2 and "exists" in r.stderr and table in r.stderr, "existing output: %d %s" % (
        r.returncode, r.stderr))
    check(open(table).read() == before, "the existing output was changed")
    r = run(exe, data, "--points", points, "--output", table, "--fields", "alp", "--force")
    check(r.returncode == 0 and open(table).read().splitlines()[0] == "x\ty\tz\talp", "--force: %s" % r.stderr)
    # A failing run (a point outside) leaves the old table in place and no .partial.
    outside = os.path.join(work, "export_outside.txt")
    with open(outside, "w") as f:
        f.write("0 0 0\n%.17g 0 0\n" % (o[0] - 2 * dx))
    before = open(table).read()
    r = run(exe, data, "--points", outside, "--output", table, "--force")
    check(r.returncode == 2 and "outside the grid" in r.stderr and outside in r.stderr and "point 1" in r.stderr,
          "point outside: %d %s" % (r.returncode, r.stderr))
    check(open(table).read() == before and not os.path.exists(table + ".partial"), "a failed run touched the output")

    # Bad input: exit code and a message naming the file.
    missing = os.path.join(work, "export_missing.h5")
    r = run(exe, missing, "--points", points)
    check(r.returncode == 1 and missing in r.stderr, "missing data file: %d %s" % (r.returncode, r.stderr))
    r = run(exe, data, "--points", os.path.join(work, "no_points.txt"))
    check(r.returncode == 2 and "no_points.txt" in r.stderr, "missing points file: %d %s" % (r.returncode, r.stderr))
    bad = os.path.join(work, "export_bad.txt")
    for content, text in (("0 0 0\n1 2\n", ":2: expected three numbers"), ("0 0 zero\n", ":1: 'zero' is not a number")):
        with open(bad, "w") as f:
            f.write(content)
        r = run(exe, data, "--points", bad)
        check(r.returncode == 2 and bad + text in r.stderr, "malformed points %r: %d %s" % (content, r.returncode, r.stderr))
    r = run(exe, data, "--points", points, "--fields", "alp,nonsense")
    check(r.returncode == 2 and "unknown field 'nonsense'" in r.stderr, "unknown field: %s" % r.stderr)
    r = run(exe, data, "--points", points, "--order", "5")
    check(r.returncode == 2 and "order 5" in r.stderr, "odd order: %s" % r.stderr)
    r = run(exe, data)
    check(r.returncode == 2 and "--points" in r.stderr, "no --points: %s" % r.stderr)
    # A file-size limit (ulimit -f) killed export by SIGXFSZ, silently, its temporary left behind.
    many = os.path.join(work, "many_points.txt")
    with open(many, "w") as f:
        f.write("0 0 0\n" * 20000)
    limited = os.path.join(work, "limited")
    os.makedirs(limited, exist_ok=True)
    r = subprocess.run([exe, data, "--points", many, "--output", os.path.join(limited, "t.tsv")], capture_output=True,
                       text=True, preexec_fn=lambda: __import__("resource").setrlimit(
                           __import__("resource").RLIMIT_FSIZE, (65536, 65536)))
    check(r.returncode in (1, 2) and r.stderr.count("\n") == 1 and os.listdir(limited) == [],
          "a file-size limit: exit %d, %r, left %s" % (r.returncode, r.stderr, os.listdir(limited)))
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
