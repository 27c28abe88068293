"""Read a bhnsid data.h5 (docs/output-format.md, format_version 1) and interpolate its Einstein
Toolkit fields at arbitrary physical points: the Python twin of libbhnsid_reader (h5py and numpy
only). Same rules, same answers (to round-off) as the C library; reader/README.md states them.

    import bhnsid_reader
    with bhnsid_reader.Reader("runs/quickstart/data.h5") as r:
        v = r.interpolate([0.1, 0.2], [0.0, 0.0], [0.05, 0.05], ["alp", "gxx", "rho"])
        print(v["alp"], r.scalars["adm_mass"])
"""

import functools
import math
import operator
import os
import stat
import threading

import h5py
import numpy as np

__all__ = ["Reader", "ReaderError", "ETK_FIELDS", "OK", "ERR_ARGUMENT", "ERR_IO", "ERR_FORMAT",
           "ERR_NOT_FOUND", "ERR_OUTSIDE", "ERR_PUNCTURE", "ERR_EOS", "ERR_VALUE", "ERR_INTERNAL"]

# The C library's status codes (bhnsid_reader.h).
OK, ERR_ARGUMENT, ERR_IO, ERR_FORMAT, ERR_NOT_FOUND, ERR_OUTSIDE, ERR_PUNCTURE, ERR_EOS, ERR_VALUE, \
    ERR_INTERNAL = range(10)

ETK_FIELDS = ["alp", "betax", "betay", "betaz", "gxx", "gxy", "gxz", "gyy", "gyz", "gzz", "kxx", "kxy",
              "kxz", "kyy", "kyz", "kzz", "rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz"]
_SUFFIX = ["xx", "xy", "xz", "yy", "yz", "zz"]
_SYM = [[0, 1, 2], [1, 3, 4], [2, 4, 5]]
_EDGE_TOLERANCE = 1e-9  # in units of dx, as the C library
_OUTSIDE = {"error": 0, "clamp": 1, "extrapolate": 2}


class ReaderError(Exception):
    """An error with the C library's status code in .code."""

    def __init__(self, code, message):
        # One line whatever a path or a field name holds, as the C library and bhnsid-export write it.
        super().__init__("".join("\\x%02x" % ord(c) if ord(c) < 0x20 or ord(c) == 0x7F else c for c in str(message)))
        self.code = code


def _text(v):
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray) and v.shape == () and v.dtype.kind in "SO":
        return _text(v[()])
    if not isinstance(v, str):
        raise ReaderError(ERR_FORMAT, "expected a string attribute, found %r" % (v,))
    return v


def _numbers(v):
    a = np.asarray(v)
    if a.dtype.kind not in "iuf":
        raise ReaderError(ERR_FORMAT, "expected a numeric attribute, found %r" % (v,))
    return a.astype(np.float64).ravel()


def _contract(what, other=ERR_FORMAT):
    """Whatever h5py, numpy or the file throws inside becomes the ReaderError the contract promises
    (reader/README.md): MemoryError is ERR_INTERNAL, an I/O failure of HDF5 ERR_IO, anything else
    `other` (ERR_FORMAT where the file's contents are read), with the file named."""
    def wrap(fn):
        @functools.wraps(fn)
        def guarded(self, *args, **kwargs):
            try:
                return fn(self, *args, **kwargs)
            except ReaderError:
                raise
            except MemoryError:
                raise ReaderError(ERR_INTERNAL, "out of memory while %s %s" % (what, self.path)) from None
            except OSError as e:
                raise ReaderError(ERR_IO, "HDF5 could not read %s (damaged file?): %s" % (self.path, e)) from None
            except Exception as e:  # noqa: BLE001 - the contract: ReaderError and nothing else
                if other == ERR_FORMAT:
                    raise ReaderError(other, "%s: malformed (%s while %s it: %s)" % (
                        self.path, type(e).__name__, what, e)) from None
                raise ReaderError(other, "internal error while %s %s: %s: %s" % (
                    what, self.path, type(e).__name__, e)) from None
        return guarded
    return wrap


def _regular_file(path):
    """ERR_IO unless path is a regular file: opened non-blocking and checked with fstat before h5py
    sees it, so that a FIFO is refused at once instead of waited on."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise ReaderError(ERR_IO, "no such file: " + path) from None
    except OSError as e:
        raise ReaderError(ERR_IO, "cannot read %s: %s" % (path, e.strerror)) from None
    try:
        mode = os.fstat(fd).st_mode
    finally:
        os.close(fd)
    if stat.S_ISDIR(mode):
        raise ReaderError(ERR_IO, path + " is a directory, not a data.h5")
    if not stat.S_ISREG(mode):
        kind = "a FIFO" if stat.S_ISFIFO(mode) else "a socket" if stat.S_ISSOCK(mode) else "a device"
        raise ReaderError(ERR_IO, "%s is %s, not a regular file" % (path, kind))


def _memory_bytes():
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return 0


def _in_region(held, tol, dx, dy, dz):
    cube, _, h = held
    if cube:
        return np.maximum(np.maximum(np.abs(dx), np.abs(dy)), np.abs(dz)) <= h + tol
    return np.sqrt(dx * dx + dy * dy + dz * dz) <= h + tol


def _harmonic_fill(r, held, parity, values, path):
    """The held region's points (with their mirror under equatorial symmetry) get the discrete
    harmonic function whose Dirichlet data are the first points outside: the C library's fill,
    the same conjugate-gradient iteration."""
    _, c, h = held
    tol = 1e-9 * r.dx
    # Clamped while still floats, as the C library: a half-size of 1e300 means the whole grid.
    bound = 1.0 + max(r.nx, r.ny, r.nz)
    clamp = lambda t: min(max(t, -bound), bound)  # noqa: E731
    lo = lambda cc, o: int(clamp(math.floor(clamp((cc - h - o) / r.dx)) - 1))  # noqa: E731
    hi = lambda cc, o: int(clamp(math.ceil(clamp((cc + h - o) / r.dx)) + 1))  # noqa: E731
    i0, i1 = max(0, lo(c[0], r.origin[0])), min(r.nx - 1, hi(c[0], r.origin[0]))
    j0, j1 = max(0, lo(c[1], r.origin[1])), min(r.ny - 1, hi(c[1], r.origin[1]))
    czl, czh = (min(c[2], -c[2]), max(c[2], -c[2])) if r.equatorial else (c[2], c[2])
    k0, k1 = max(r.kmin, lo(czl, r.origin[2])), min(r.nz - 1, hi(czh, r.origin[2]))
    if i0 > i1 or j0 > j1 or k0 > k1:
        return 0
    k, j, i = np.meshgrid(np.arange(k0, k1 + 1), np.arange(j0, j1 + 1), np.arange(i0, i1 + 1), indexing="ij")
    x, y, z = r.origin[0] + r.dx * i, r.origin[1] + r.dx * j, r.origin[2] + r.dx * k
    inside = _in_region(held, tol, x - c[0], y - c[1], z - c[2])
    if r.equatorial:
        inside |= _in_region(held, tol, x - c[0], y - c[1], -z - c[2])
    ids = -np.ones(inside.shape, dtype=np.int64)
    ids[inside] = np.arange(np.count_nonzero(inside))
    pi, pj, pk = i[inside], j[inside], k[inside]  # C order: k slowest, as the C library
    n = pi.size
    if n == 0:
        return 0
    nbr = -np.ones((n, 6), dtype=np.int64)
    diag, b = np.zeros(n), np.zeros(n)
    known = 0
    for d, (oi, oj, ok) in enumerate(((-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1))):
        qi, qj, qk = pi + oi, pj + oj, pk + ok
        ingrid = (qi >= 0) & (qi < r.nx) & (qj >= 0) & (qj < r.ny) & (qk >= r.kmin) & (qk < r.nz)
        diag += ingrid
        inbox = ingrid & (qi >= i0) & (qi <= i1) & (qj >= j0) & (qj <= j1) & (qk >= k0) & (qk <= k1)
        v = np.full(n, -1, dtype=np.int64)
        v[inbox] = ids[qk[inbox] - k0, qj[inbox] - j0, qi[inbox] - i0]
        nbr[:, d] = v
        data = ingrid & (v < 0)
        known += int(np.count_nonzero(data))
        sign = np.where(qk[data] < 0, float(parity), 1.0)
        b[data] += sign * values[np.abs(qk[data]), qj[data], qi[data]]
    if known == 0:
        raise ReaderError(ERR_FORMAT, "%s: the held region (a %s of half-size %.17g about (%.17g, %.17g, %.17g)) "
                          "covers the whole grid; nothing to fill it from" % (
                              path, "cube" if held[0] else "sphere", h, c[0], c[1], c[2]))
    xs, res, p = np.zeros(n), b.copy(), b.copy()
    bnorm = math.sqrt(float(np.dot(b, b)))
    rr = float(np.dot(res, res))
    has = nbr >= 0
    idx = np.where(has, nbr, 0)
    for _ in range(4 * n + 100 if bnorm > 0 else 0):
        ap = diag * p - np.sum(np.where(has, p[idx], 0.0), axis=1)
        alpha = rr / float(np.dot(p, ap))
        xs += alpha * p
        res -= alpha * ap
        rr_new = float(np.dot(res, res))
        if math.sqrt(rr_new) <= 1e-15 * bnorm:
            break
        beta = rr_new / rr
        rr = rr_new
        p = res + beta * p
    keep = pk >= 0
    filled = xs[keep]
    if r.equatorial and parity < 0:
        filled = np.where(pk[keep] == 0, 0.0, filled)
    values[pk[keep], pj[keep], pi[keep]] = filled
    return int(np.count_nonzero(keep))


class _Field:
    def __init__(self, values, parity, held):
        self.values, self.parity, self.held = values, parity, held


class Reader:
    """One open data.h5. Datasets are read on first use and kept; interpolate() may be called from
    several threads."""

    def __init__(self, path):
        self._file = None
        try:
            self.path = os.fsdecode(path)
        except TypeError:
            raise ReaderError(ERR_ARGUMENT, "the path %r is not a file name" % (path,)) from None
        if not self.path or "\0" in self.path:
            raise ReaderError(ERR_ARGUMENT, "the path %r is not a file name" % (self.path,))
        _regular_file(self.path)
        try:
            is_hdf5 = h5py.is_hdf5(self.path)
        except (OSError, ValueError):
            is_hdf5 = False
        if not is_hdf5:
            raise ReaderError(ERR_IO, self.path + " is not an HDF5 file")
        try:
            self._file = h5py.File(self.path, "r")
        except Exception as e:  # noqa: BLE001 - h5py raises OSError, and others on odd files
            raise ReaderError(ERR_IO, "HDF5 could not open %s (damaged or locked?): %s" % (self.path, e)) from None
        self._lock = threading.Lock()
        self._fields = {}
        try:
            self._open()
        except BaseException:
            self._file.close()
            raise

    # -- opening -------------------------------------------------------------------------------

    def _fail(self, what):
        return ReaderError(ERR_FORMAT, self.path + ": " + what)

    @_contract("opening")
    def _open(self):
        f = self._file
        if "format" not in f.attrs:
            raise self._fail("not a bhnsid data.h5 (no root attribute 'format')")
        fmt = _text(f.attrs["format"])
        if fmt != "bhnsid-data":
            raise self._fail("format is '%s', not 'bhnsid-data': not a bhnsid data file" % fmt)
        if "format_version" not in f.attrs:
            raise self._fail("no root attribute 'format_version'")
        version = _numbers(f.attrs["format_version"])
        if version.size != 1:
            raise self._fail("format_version is not a single number")
        if version[0] > 1:
            raise self._fail("format_version %.17g is newer than this reader understands (1): use a newer "
                             "bhnsid reader" % version[0])
        if version[0] != 1:
            raise self._fail("format_version %.17g is not supported (this reader reads 1)" % version[0])
        self._read_grid()
        self.datasets = sorted("/%s/%s" % (g, n) for g in ("ADMBase", "HydroBase", "variables")
                               if isinstance(f.get(g), h5py.Group)
                               for n in f[g] if isinstance(f[g].get(n), h5py.Dataset))
        self._dataset_set = set(self.datasets)
        self.scalars = {}
        if isinstance(f.get("scalars"), h5py.Group):
            for name in sorted(f["scalars"].attrs):
                try:
                    a = np.asarray(f["scalars"].attrs[name])
                except (OSError, TypeError, ValueError):
                    continue  # a type h5py cannot read is not a number: skipped, as the C library does
                if a.dtype.kind in "iuf" and a.size == 1:
                    self.scalars[name] = float(a.ravel()[0])
        self._read_eos()
        self.fields = [n for n in ETK_FIELDS if self._answerable(n)]

    def _read_grid(self):
        f = self._file
        if not isinstance(f.get("grid"), h5py.Group):
            raise self._fail("no group /grid")
        a = f["grid"].attrs
        for key in ("shape_zyx", "dx", "origin_xyz", "symmetry"):
            if key not in a:
                raise ReaderError(ERR_NOT_FOUND, "no attribute /grid@%s in the file" % key)
        shape = _numbers(a["shape_zyx"])
        if shape.size != 3:
            raise self._fail("/grid@shape_zyx does not hold 3 numbers")
        for s in shape:
            if not (1 <= s <= 1e6 and s == math.floor(s)):
                raise self._fail("/grid@shape_zyx holds %.17g, not a positive integer" % s)
        self.nz, self.ny, self.nx = (int(s) for s in shape)
        dx = _numbers(a["dx"])
        if dx.size != 1 or not (dx[0] > 0) or not math.isfinite(dx[0]):
            raise self._fail("/grid@dx is not one positive number")
        self.dx = float(dx[0])
        origin = _numbers(a["origin_xyz"])
        if origin.size != 3 or not np.all(np.isfinite(origin)):
            raise self._fail("/grid@origin_xyz does not hold 3 finite numbers")
        self.origin = [float(o) for o in origin]
        symmetry = _text(a["symmetry"])
        if symmetry not in ("equatorial", "none"):
            raise self._fail("/grid@symmetry is '%s' (this reader knows 'equatorial' and 'none')" % symmetry)
        self.equatorial = symmetry == "equatorial"
        if self.equatorial and abs(self.origin[2]) > 1e-12 * self.dx:
            raise self._fail("equatorial symmetry with origin z = %.17g (must be 0)" % self.origin[2])
        self.kmin = -(self.nz - 1) if self.equatorial else 0
        first, last = [0, 0, self.kmin], [self.nx - 1, self.ny - 1, self.nz - 1]
        self.lower = [self.origin[a] + self.dx * first[a] for a in range(3)]
        self.upper = [self.origin[a] + self.dx * last[a] for a in range(3)]

    def _read_eos(self):
        self.eos, self.eos_problem = None, ""
        e = self._file.get("eos")
        if not isinstance(e, h5py.Group) or "model" not in e.attrs:
            self.eos_problem = "the file's /eos has no 'model' attribute (written before the EOS formulas were stored)"
            return
        model = _text(e.attrs["model"])
        if model != "piecewise_polytrope":
            self.eos_problem = "the file's EOS is of model '%s', which this reader cannot evaluate" % model
            return
        try:
            lo, k, gamma, a = (_numbers(e.attrs[n]) for n in ("rho0_lo", "K", "Gamma", "eps_offset"))
        except KeyError as missing:
            raise ReaderError(ERR_NOT_FOUND, "no attribute /eos@%s in the file" % missing.args[0])
        n = lo.size
        if n == 0 or k.size != n or gamma.size != n or a.size != n:
            raise self._fail("/eos: rho0_lo, K, Gamma and eps_offset must be non-empty and of one length")
        if lo[0] != 0:
            raise self._fail("/eos@rho0_lo must start at 0")
        for i in range(n):
            if i > 0 and not lo[i] > lo[i - 1]:
                raise self._fail("/eos@rho0_lo must increase")
            if not (k[i] > 0 and gamma[i] > 1 and all(math.isfinite(v) for v in (k[i], gamma[i], a[i]))):
                raise self._fail("/eos: piece %d needs K > 0, Gamma > 1 and a finite offset" % i)
        self.eos = (lo, k, gamma, a)

    def close(self):
        if self._file is not None:
            self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- metadata ------------------------------------------------------------------------------

    @_contract("reading an attribute of")
    def string_attribute(self, obj, name):
        """A string attribute, e.g. ("/", "status"), ("/eos", "description")."""
        with self._lock:
            if not isinstance(obj, str) or not isinstance(name, str):
                raise ReaderError(ERR_ARGUMENT, "the object and attribute names must be strings")
            node = self._file.get(obj)
            if node is None or name not in node.attrs:
                raise ReaderError(ERR_NOT_FOUND, "no attribute %s@%s in the file" % (obj, name))
            return _text(node.attrs[name])

    @_contract("reading an attribute of")
    def numeric_attribute(self, obj, name):
        """A numeric attribute as a 1-D float64 array."""
        with self._lock:
            if not isinstance(obj, str) or not isinstance(name, str):
                raise ReaderError(ERR_ARGUMENT, "the object and attribute names must be strings")
            node = self._file.get(obj)
            if node is None or name not in node.attrs:
                raise ReaderError(ERR_NOT_FOUND, "no attribute %s@%s in the file" % (obj, name))
            return _numbers(node.attrs[name])

    @property
    def puncture(self):
        """(bare mass, (x, y, z)) when /scalars@bh_bare_mass > 0, else None."""
        m = self.scalars.get("bh_bare_mass")
        if m is None or not m > 0:
            return None
        pos = []
        for key in ("bh_position_x", "bh_position_y", "bh_position_z"):
            if key not in self.scalars:
                raise ReaderError(ERR_FORMAT, "%s has bh_bare_mass but no /scalars@%s" % (self.path, key))
            pos.append(self.scalars[key])
        return m, pos

    # -- datasets ------------------------------------------------------------------------------

    def field(self, path):
        """The dataset at path in memory ([k][j][i], filled in its held region), loaded once."""
        if not isinstance(path, str):
            raise ReaderError(ERR_ARGUMENT, "a dataset path must be a string, not %r" % (path,))
        with self._lock:
            if path not in self._fields:
                self._fields[path] = self._load(path)
            return self._fields[path]

    @_contract("loading a dataset of")
    def _load(self, path):
        if path not in self._dataset_set:
            raise ReaderError(ERR_NOT_FOUND, "no dataset %s in %s" % (path, self.path))
        d = self._file[path]
        if d.ndim != 3:
            raise self._fail(path + " is not a 3-D dataset")
        if d.shape != (self.nz, self.ny, self.nx):
            raise self._fail("%s has shape %d x %d x %d, not /grid@shape_zyx" % ((path,) + d.shape))
        if d.dtype.kind not in "iuf":
            raise self._fail(path + " does not hold numbers")
        # The shape comes from the file: a damaged or hostile one may claim more than any memory.
        size = 8.0 * self.nz * self.ny * self.nx
        memory = _memory_bytes()
        if memory and size > memory:
            raise ReaderError(ERR_INTERNAL, "out of memory: %s holds %d x %d x %d doubles (%.3g GiB), more than this "
                              "machine can hold" % (path, self.nz, self.ny, self.nx, size / 2 ** 30))
        values = np.ascontiguousarray(d[...], dtype=np.float64)
        parity = 1
        if "parity_z" in d.attrs:
            p = _numbers(d.attrs["parity_z"])
            if p.size != 1 or p[0] not in (1, -1):
                raise self._fail(path + "@parity_z is not 1 or -1")
            parity = int(p[0])
        elif self.equatorial:
            raise self._fail(path + " has no parity_z, which equatorial symmetry needs")
        held = None
        if "held_region_shape" in d.attrs:
            shape = _text(d.attrs["held_region_shape"])
            if shape not in ("cube", "sphere"):
                raise self._fail("%s@held_region_shape is '%s', not 'cube' or 'sphere'" % (path, shape))
            try:
                c = _numbers(d.attrs["held_region_centre"])
                h = _numbers(d.attrs["held_region_half_size"])
            except KeyError:
                c, h = np.zeros(0), np.zeros(0)
            if c.size != 3 or h.size != 1 or not h[0] >= 0 or not np.all(np.isfinite(np.r_[c, h])):
                raise self._fail(path + ": held_region_centre (3 numbers) or held_region_half_size (>= 0) is "
                                 "malformed")
            held = (shape == "cube", [float(v) for v in c], float(h[0]))
        bad = np.flatnonzero(~np.isfinite(values.ravel()))
        if bad.size:
            raise self._fail("%s holds a non-finite value at flat index %d" % (path, bad[0]))
        if held is not None:
            _harmonic_fill(self, held, parity, values, path)
        return _Field(values, parity, held)

    def _answerable(self, name):
        try:
            self._plan([name], check_only=True)
            return True
        except ReaderError:
            return False

    # -- interpolation -------------------------------------------------------------------------

    def _stencils(self, x, y, z, order, outside):
        """Per axis: start indices (npts,), weights (npts, order); the effective points; and which
        points are extrapolated to."""
        first, last = [0, 0, self.kmin], [self.nx - 1, self.ny - 1, self.nz - 1]
        coords, starts, weights, points = (x, y, z), [], [], []
        extrapolated = np.zeros(x.shape, dtype=bool)
        for a in range(3):
            c = coords[a]
            bad = np.flatnonzero(~np.isfinite(c))
            if bad.size:
                p = bad[0]
                raise ReaderError(ERR_ARGUMENT, "%s is not finite" % self._point(p, x, y, z))
            t = (c - self.origin[a]) / self.dx
            out = (t < first[a] - _EDGE_TOLERANCE) | (t > last[a] + _EDGE_TOLERANCE)
            if outside == 0 and np.any(out):
                p = int(np.flatnonzero(out)[0])
                raise ReaderError(ERR_OUTSIDE, "%s is outside the grid: %s must lie in [%.17g, %.17g]" % (
                    self._point(p, x, y, z), "xyz"[a], self.lower[a], self.upper[a]))
            point = c.copy()
            if outside == 2:
                extrapolated |= out
            move = ~out if outside != 1 else np.ones_like(out)
            clamped = np.where(move, np.clip(t, first[a], last[a]), t)
            changed = clamped != t
            point[changed] = self.origin[a] + self.dx * clamped[changed]
            t = clamped
            # Clamped as floats first: an extrapolated t of 1e300 must not overflow the conversion.
            start = np.clip(np.floor(t), first[a] - order, last[a] + order).astype(np.int64) - (order // 2 - 1)
            start = np.clip(start, first[a], last[a] - order + 1)
            u = t - start
            w = np.empty((t.size, order))
            for j in range(order):
                num, den = np.ones_like(u), 1.0
                for m in range(order):
                    if m != j:
                        num = num * (u - m)
                        den *= j - m
                w[:, j] = num / den
            starts.append(start)
            weights.append(w)
            points.append(point)
        return starts, weights, points, extrapolated

    @staticmethod
    def _point(p, x, y, z):
        return "point %d (%.17g, %.17g, %.17g)" % (p, x[p], y[p], z[p])

    def _interp(self, fld, starts, weights):
        """sum_c wz sum_b wy sum_a wx f, in the C library's order."""
        wx, wy, wz = weights
        p = wx.shape[1]
        total = np.zeros(wx.shape[0])
        for c in range(p):
            k = starts[2] + c
            sign = np.where(k < 0, float(fld.parity), 1.0)
            kk = np.abs(k)
            sy = np.zeros_like(total)
            for b in range(p):
                j = starts[1] + b
                sx = np.zeros_like(total)
                for a in range(p):
                    sx = sx + wx[:, a] * fld.values[kk, j, starts[0] + a]
                sy = sy + wy[:, b] * sx
            total = total + wz[:, c] * (sign * sy)
        return total

    def _plan(self, names, check_only=False):
        has = self._dataset_set.__contains__
        puncture = self.scalars.get("bh_bare_mass", 0) > 0
        plan, needs = [], set()

        def need(path, why):
            if not has(path):
                raise ReaderError(ERR_NOT_FOUND, "%s has no %s, which %s needs" % (self.path, path, why))
            needs.add(path)
            return path

        metric = fluid = False
        for name in names:
            if name.startswith("/"):
                plan.append(("raw", need(name, "the request '%s'" % name)))
            elif name == "alp":
                if puncture:
                    metric = True
                    # alp phi = eta - c M/(2r): the paper's regular eta (c = 0) or lapse_komar's eta~ and c.
                    if has("/variables/eta") or not has("/variables/eta_regular"):
                        plan.append(("lapse", (need("/variables/eta", "alp = eta/phi at a puncture (or "
                                                    "/variables/eta_regular with /scalars@lapse_komar_c)"), 0.0)))
                    else:
                        if "lapse_komar_c" not in self.scalars:
                            raise ReaderError(ERR_FORMAT, "%s has /variables/eta_regular but no /scalars@lapse_komar_c"
                                              % self.path)
                        plan.append(("lapse", (need("/variables/eta_regular", "alp = (eta~ - c M/(2r))/phi at a "
                                                    "puncture"), self.scalars["lapse_komar_c"])))
                else:
                    plan.append(("raw", need("/ADMBase/alp", "alp")))
            elif name in ("betax", "betay", "betaz") or (name[:1] == "k" and name[1:] in _SUFFIX):
                path = "/ADMBase/" + name
                plan.append(("raw", path) if has(path) else ("zero", None))
            elif name[:1] == "g" and name[1:] in _SUFFIX:
                metric = True
                plan.append(("metric", _SUFFIX.index(name[1:])))
            elif name in ("rho", "press", "eps"):
                fluid = True
                if name != "rho" and has("/HydroBase/rho") and self.eos is None:
                    raise ReaderError(ERR_EOS, "cannot compute %s: %s (rho is available)" % (name, self.eos_problem))
                plan.append((name, None))
            elif name in ("vel[0]", "vel[1]", "vel[2]"):
                fluid = True
                plan.append(("vel", int(name[4])))
            elif name == "w_lorentz":
                fluid = metric = True
                plan.append(("w_lorentz", None))
            else:
                raise ReaderError(ERR_ARGUMENT, "unknown field '%s' (known: %s, or a dataset path such as "
                                  "/variables/chi)" % (name, " ".join(ETK_FIELDS)))
        hydro = fluid and has("/HydroBase/rho")
        if hydro:
            needs.add("/HydroBase/rho")
            for c in range(3):
                need("/HydroBase/vel[%d]" % c, "the fluid (HydroBase/rho is present)")
        if metric:
            if puncture:
                need("/variables/chi", "the metric at a puncture (phi = M/2r + chi)")
                self.puncture  # raises if the position is missing
            else:
                for s in _SUFFIX:
                    need("/ADMBase/g" + s, "the metric")
        if not check_only:
            for path in sorted(needs):
                self.field(path)
        return plan, puncture, hydro

    @_contract("interpolating", ERR_INTERNAL)
    def interpolate(self, x, y, z, fields=None, order=4, outside="error"):
        """The fields (default: self.fields) at the physical points (x, y, z): a dict name -> array.
        order: Lagrange points per axis (2, 4, 6, 8); outside: "error", "clamp" or "extrapolate"."""
        if fields is None:
            fields = self.fields
        if isinstance(fields, str):
            fields = [fields]
        try:
            fields = list(fields)
        except TypeError:
            raise ReaderError(ERR_ARGUMENT, "fields must be a list of names, not %r" % (fields,)) from None
        for name in fields:
            if not isinstance(name, str):
                raise ReaderError(ERR_ARGUMENT, "a field name must be a string, not %r" % (name,))
        try:
            order = operator.index(order)
        except TypeError:
            order = repr(order)
        if order not in (2, 4, 6, 8):
            raise ReaderError(ERR_ARGUMENT, "interpolation order %r is not supported (2, 4, 6 or 8 points per "
                              "axis)" % (order,))
        if not isinstance(outside, str) or outside not in _OUTSIDE:
            raise ReaderError(ERR_ARGUMENT, "unknown out-of-grid policy %r" % (outside,))
        for axis, count in zip("xyz", (self.nx, self.ny, self.nz - self.kmin)):
            if count < order:
                raise ReaderError(ERR_ARGUMENT, "the grid has %d points along %s, fewer than interpolation order "
                                  "%d needs" % (count, axis, order))
        try:
            x, y, z = (np.atleast_1d(np.asarray(v, dtype=np.float64)).ravel() for v in (x, y, z))
        except (TypeError, ValueError) as e:
            raise ReaderError(ERR_ARGUMENT, "x, y and z must be numbers: %s" % e) from None
        if not x.size == y.size == z.size:
            raise ReaderError(ERR_ARGUMENT, "x, y and z differ in length")
        plan, puncture, hydro = self._plan(fields)
        # Far extrapolation overflows on purpose, and is reported below: numpy must not print.
        with np.errstate(all="ignore"):
            return self._evaluate(x, y, z, fields, plan, puncture, hydro, order, outside)

    def _evaluate(self, x, y, z, fields, plan, puncture, hydro, order, outside):
        starts, weights, points, extrapolated = self._stencils(x, y, z, order, _OUTSIDE[outside])
        ip = lambda path: self._interp(self.field(path), starts, weights)  # noqa: E731
        cache = {}

        def phi_and_metric():
            if "g" not in cache:
                if puncture:
                    m, pos = self.puncture
                    d = [points[a] - pos[a] for a in range(3)]
                    r = np.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
                    cache["pole"] = m / (2 * r)
                    phi = cache["pole"] + ip("/variables/chi")
                    g = phi ** 4
                    at = (r == 0) | ((phi > 0) & ~np.isfinite(g) & ~extrapolated)
                    bad = np.flatnonzero(at | ~np.isfinite(g) | ~(phi > 0))
                    if bad.size:
                        p = bad[0]
                        where = "point %d (%.17g, %.17g, %.17g)" % (p, points[0][p], points[1][p], points[2][p])
                        if at[p]:
                            raise ReaderError(ERR_PUNCTURE, where + " is at the puncture, where the metric is infinite")
                        # Far outside the box the edge polynomial of chi runs away: the point is too
                        # far to extrapolate to, which is not the puncture's doing.
                        what = "%s: the conformal factor phi = M/(2r) + chi = %.17g is not a positive number" % (
                            where, phi[p])
                        if extrapolated[p]:
                            raise ReaderError(ERR_OUTSIDE, what + " there: the point lies too far outside the grid for "
                                              "chi to be extrapolated (clamp it, or keep it near the grid)")
                        raise ReaderError(ERR_VALUE, what + " (/variables/chi is too negative there)")
                    zero = np.zeros_like(g)
                    cache["phi"], cache["g"] = phi, [g, zero, zero, g, zero, g]
                else:
                    cache["g"] = [ip("/ADMBase/g" + s) for s in _SUFFIX]
            return cache["g"]

        def rho():
            if "rho" not in cache:
                # Interpolation overshoots below zero just outside the surface: vacuum there.
                cache["rho"] = np.maximum(0.0, ip("/HydroBase/rho")) if hydro else np.zeros_like(x)
            return cache["rho"]

        out = {}
        for name, (kind, arg) in zip(fields, plan):
            if kind == "raw":
                v = ip(arg)
            elif kind == "zero":
                v = np.zeros_like(x)
            elif kind == "lapse":
                phi_and_metric()
                path, strength = arg
                v = (ip(path) - strength * cache["pole"]) / cache["phi"]
            elif kind == "metric":
                v = phi_and_metric()[arg].copy()
            elif kind == "rho":
                v = rho().copy()
            elif kind in ("press", "eps"):
                v = self._eos(rho(), kind)
            elif kind == "vel":
                v = np.where(rho() > 0, ip("/HydroBase/vel[%d]" % arg), 0.0) if hydro else np.zeros_like(x)
            else:  # w_lorentz
                v = np.ones_like(x)
                inside = rho() > 0
                if np.any(inside):
                    g = phi_and_metric()
                    vv = [ip("/HydroBase/vel[%d]" % c) for c in range(3)]
                    v2 = np.zeros_like(x)
                    for a in range(3):
                        for b in range(3):
                            v2 = v2 + g[_SYM[a][b]] * vv[a] * vv[b]
                    bad = np.flatnonzero(inside & ~(v2 < 1))
                    if bad.size:
                        p = bad[0]
                        raise ReaderError(ERR_VALUE, "point %d (%.17g, %.17g, %.17g): the interpolated velocity has "
                                          "gamma_ij v^i v^j = %g >= 1, no Lorentz factor" % (
                                              p, points[0][p], points[1][p], points[2][p], v2[p]))
                    v = np.where(inside, 1 / np.sqrt(1 - v2), 1.0)
            bad = np.flatnonzero(extrapolated & ~np.isfinite(v))
            if bad.size:
                p = bad[0]
                raise ReaderError(ERR_OUTSIDE, "point %d (%.17g, %.17g, %.17g): %s is not finite there: the point lies "
                                  "too far outside the grid to extrapolate to (clamp it, or keep it near the grid)" % (
                                      p, points[0][p], points[1][p], points[2][p], name))
            out[name] = v
        return out

    def _eos(self, rho, kind):
        out = np.zeros_like(rho)
        if self.eos is None:
            return out  # vacuum file: no HydroBase, nothing to compute
        lo, k, gamma, a = self.eos
        piece = np.zeros(rho.shape, dtype=np.int64)
        for i in range(1, lo.size):
            piece[rho >= lo[i]] = i
        pos = rho > 0
        for i in range(lo.size):
            sel = pos & (piece == i)
            r = rho[sel]
            if kind == "press":
                out[sel] = k[i] * np.power(r, gamma[i])
            else:
                out[sel] = a[i] + k[i] * np.power(r, gamma[i] - 1) / (gamma[i] - 1)
        return out
