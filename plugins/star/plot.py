#!/usr/bin/env python3
"""star's pictures for `bhnsid plot RUN_DIR` (run as: plot.py RUN_DIR OUTPUT_DIR).

equator.png: the equatorial plane z = 0 of data.h5 (io_hdf5) in physical coordinates: rho0, the
lapse alpha, chi (the regular part of the conformal factor) and |beta|, with the black hole (the
puncture's bare position, when the run has one) and the star's density maximum marked.
outer_iteration.png: the outer iteration from star_history.tsv: sigma, Omegahat, C_B and the
largest relative change per step (log scale), the steps taken at a fraction after a retreat marked.
Needs Debian's python3-matplotlib, python3-h5py and python3-numpy.

Exit 0; 2 when an input file is missing or malformed, with one line on stderr naming it; 3 on a
bug. Each picture is written under a fresh private name in OUTPUT_DIR and renamed into place, so a
name there is never written through (bhnsid plot gives a private folder of its own as OUTPUT_DIR
and moves the pictures on: core/cli/plot.cpp)."""
import math
import os
import signal
import stat
import sys
import tempfile

# Stopped by Ctrl-C or bhnsid plot passing a signal on: end quietly, as the signal says, not with a
# KeyboardInterrupt traceback.
signal.signal(signal.SIGINT, signal.SIG_DFL)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# What a run of bhnsid writes is far below these; a file above them is not one.
MAX_PLANE_POINTS = 1 << 25
MAX_HISTORY_BYTES = 64 << 20
MAX_HISTORY_ROWS = 1000000
HISTORY_COLUMNS = ("iteration", "sigma", "omega_hat", "bernoulli_constant", "change")


PROGRAM = "star plot"


class BadInput(Exception):
    """An input file that cannot be plotted: one line, exit 2."""


def shown(text):
    """Control characters as \\xNN: a message stays one line whatever the folder is called."""
    return "".join("\\x%02x" % ord(c) if ord(c) < 0x20 or ord(c) == 0x7F else c for c in str(text))


def regular_file(path, role):
    """Opened non-blocking and checked with fstat: a FIFO or a device is refused, never waited on."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise BadInput(f"{shown(path)}: is missing ({role})") from None
    except OSError as e:
        raise BadInput(f"{shown(path)}: cannot be read: {e.strerror}") from None
    try:
        st = os.fstat(fd)
    finally:
        os.close(fd)
    if not stat.S_ISREG(st.st_mode):
        kind = "a folder" if stat.S_ISDIR(st.st_mode) else "a FIFO" if stat.S_ISFIFO(st.st_mode) else "a device or socket"
        raise BadInput(f"{shown(path)}: is {kind}, not a regular file")
    return st.st_size


def save(fig, out, name):
    """fig as OUTPUT_DIR/name: a fresh private file (O_EXCL), fsynced, then renamed over the name."""
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=out)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format="png", dpi=90)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, os.path.join(out, name))
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    finally:
        plt.close(fig)


def grid_plane(path):
    """data.h5's grid and its z = 0 plane of each panel's dataset, checked: BadInput naming the
    file and what is wrong, for a text file, a truncated one, one without /grid."""
    import h5py

    regular_file(path, "add io_hdf5 to the run's plugins")
    if not h5py.is_hdf5(path):
        raise BadInput(f"{shown(path)}: is not an HDF5 file")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise BadInput(f"{shown(path)}: HDF5 cannot open it (truncated or damaged?): {shown(e)}") from None
    try:
        with f:
            grid = f.get("grid")
            if not isinstance(grid, h5py.Group) or not all(k in grid.attrs for k in ("shape_zyx", "dx", "origin_xyz")):
                raise BadInput(f"{shown(path)}: has no /grid with shape_zyx, dx and origin_xyz: not a bhnsid data.h5")
            shape = np.asarray(grid.attrs["shape_zyx"], dtype=float).ravel()
            dx = float(np.asarray(grid.attrs["dx"], dtype=float).ravel()[0])
            origin = np.asarray(grid.attrs["origin_xyz"], dtype=float).ravel()
            if shape.size != 3 or not all(1 <= s <= 1e6 and s == math.floor(s) for s in shape):
                raise BadInput(f"{shown(path)}: /grid@shape_zyx is not 3 positive integers")
            if not (math.isfinite(dx) and dx > 0) or origin.size != 3 or not np.all(np.isfinite(origin)):
                raise BadInput(f"{shown(path)}: /grid@dx or /grid@origin_xyz is not finite")
            ny, nx = int(shape[1]), int(shape[2])
            if nx * ny > MAX_PLANE_POINTS:
                raise BadInput(f"{shown(path)}: a plane of {nx} x {ny} points, more than a picture can show")
            planes = {}
            for p in ("HydroBase/rho", "ADMBase/alp", "variables/chi", "ADMBase/betax", "ADMBase/betay",
                      "ADMBase/betaz"):
                d = f.get(p)
                if d is None:
                    continue
                if not isinstance(d, h5py.Dataset) or d.shape != tuple(int(s) for s in shape) or d.dtype.kind not in "iuf":
                    raise BadInput(f"{shown(path)}: /{p} is not a dataset of the grid's shape")
                planes[p] = np.asarray(d[0], dtype=float)
            scalars = {}
            if isinstance(f.get("scalars"), h5py.Group):
                for k in ("bh_position_x", "bh_position_y", "star_center_x"):
                    if k in f["scalars"].attrs:
                        v = np.asarray(f["scalars"].attrs[k]).ravel()
                        if v.size == 1 and v.dtype.kind in "iuf" and math.isfinite(float(v[0])):
                            scalars[k] = float(v[0])
            sigma = np.asarray(grid.attrs.get("sigma", np.nan), dtype=float).ravel()
            status = f.attrs.get("status", "unknown")
            status = status.decode("utf-8", "replace") if isinstance(status, bytes) else str(status)
    except BadInput:
        raise
    except (OSError, KeyError, ValueError, TypeError, IndexError, RuntimeError) as e:
        raise BadInput(f"{shown(path)}: cannot be read (truncated or damaged?): {shown(e)}") from None
    x = origin[0] + dx * np.arange(nx)
    y = origin[1] + dx * np.arange(ny)
    return x, y, planes, scalars, float(sigma[0]) if sigma.size else math.nan, shown(status)


def equator(run, out):
    x, y, planes, scalars, sigma, status = grid_plane(os.path.join(run, "data.h5"))
    labels = [("HydroBase/rho", r"$\rho_0$"), ("ADMBase/alp", r"lapse $\alpha$"), ("variables/chi", r"$\chi$")]
    images = [(planes[p], label) for p, label in labels if p in planes]
    if all(f"ADMBase/beta{c}" in planes for c in "xyz"):
        images.append((np.sqrt(sum(planes[f"ADMBase/beta{c}"] ** 2 for c in "xyz")), r"$|\beta|$"))
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
    if images and (scalars.get("bh_position_x") is not None or "star_center_x" in scalars):
        axes.flat[0].legend(loc="upper left", fontsize=8)
    fig.suptitle(f"equatorial plane z = 0, physical coordinates (sigma = {sigma:.6g}); run {status}")
    fig.tight_layout()
    save(fig, out, "equator.png")


def read_history(path):
    """star_history.tsv's columns: a '# name name ...' header, then rows of as many numbers."""
    if regular_file(path, "star writes it") > MAX_HISTORY_BYTES:
        raise BadInput(f"{shown(path)}: larger than {MAX_HISTORY_BYTES >> 20} MiB: not a star history")
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (UnicodeDecodeError, OSError) as e:
        raise BadInput(f"{shown(path)}: cannot be read as text: {shown(e)}") from None
    if not lines or not lines[0].startswith("#"):
        raise BadInput(f"{shown(path)}:1: expected a header '# iteration sigma ...'")
    names = lines[0].lstrip("# ").split()
    missing = [c for c in HISTORY_COLUMNS if c not in names]
    if missing:
        raise BadInput(f"{shown(path)}:1: the header lacks the column(s) {', '.join(missing)}")
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        if not line.strip() or line.startswith("#"):
            continue
        words = line.split()
        try:
            values = [float(w) for w in words]
        except ValueError:
            values = None
        if values is None or len(values) != len(names) or not all(math.isfinite(v) for v in values):
            raise BadInput(f"{shown(path)}:{number}: expected {len(names)} finite numbers, found {shown(line[:80])!r}")
        rows.append(values)
        if len(rows) > MAX_HISTORY_ROWS:
            raise BadInput(f"{shown(path)}: more than {MAX_HISTORY_ROWS} rows: not a star history")
    if not rows:
        raise BadInput(f"{shown(path)}: holds no outer iteration")
    table = np.array(rows)
    return {n: table[:, i] for i, n in enumerate(names)}


def history(run, out):
    col = read_history(os.path.join(run, "star_history.tsv"))
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
    save(fig, out, "outer_iteration.png")


def main():
    if len(sys.argv) != 3:
        print("star plot: usage: plot.py RUN_DIR OUTPUT_DIR", file=sys.stderr)
        return 2
    run, out = sys.argv[1:3]
    try:
        equator(run, out)
        history(run, out)
    except BadInput as e:
        print(f"star plot: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # the output folder: full, read-only, gone
        print(f"{PROGRAM}: cannot write the pictures in {shown(sys.argv[2])}: {e.strerror or shown(e)}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 - a bug: one line, not a traceback
        print(f"star plot: internal error: {type(e).__name__}: {shown(e)}", file=sys.stderr)
        return 3
    print("star plot: equator.png, outer_iteration.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
