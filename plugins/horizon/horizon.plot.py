#!/usr/bin/env python3
"""horizon's picture for `bhnsid plot RUN_DIR` (run as: horizon.plot.py RUN_DIR OUTPUT_DIR).

horizon.png: the apparent horizon from horizon.tsv in the planes z = 0 and y = 0 through the
puncture (physical coordinates), beside the sphere of the same mean radius about the puncture, so
that its shape (pushed against the hole's momentum) shows. Needs Debian's python3-matplotlib and python3-numpy.

Exit 0; 2 when horizon.tsv is missing or malformed, with one line on stderr naming it; 3 on a bug.
The picture is written under a fresh private name in OUTPUT_DIR and renamed into place."""
import os
import signal
import stat
import sys
import tempfile

signal.signal(signal.SIGINT, signal.SIG_DFL)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PROGRAM = "horizon plot"
MAX_BYTES = 1 << 20  # the plugin writes 2 x 361 rows


class BadInput(Exception):
    """An input file that cannot be plotted: one line, exit 2."""


def shown(text):
    return "".join("\\x%02x" % ord(c) if ord(c) < 0x20 or ord(c) == 0x7F else c for c in str(text))


def read_surface(path):
    """horizon.tsv, opened non-blocking and checked to be a regular file of a sane size."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise BadInput(f"{shown(path)}: is missing (add horizon to the run's plugins)") from None
    except OSError as e:
        raise BadInput(f"{shown(path)}: cannot be read: {e.strerror}") from None
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(f.fileno())
        if not stat.S_ISREG(st.st_mode):
            raise BadInput(f"{shown(path)}: is not a regular file")
        if st.st_size > MAX_BYTES:
            raise BadInput(f"{shown(path)}: {st.st_size} bytes, more than a horizon table holds")
        text = f.read().decode("utf-8", errors="replace")
    planes = {"z=0": [], "y=0": []}
    puncture = None
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("#") and "puncture = (" in line:
            try:
                puncture = [float(v) for v in line.split("puncture = (")[1].split(")")[0].split()]
            except ValueError:
                raise BadInput(f"{shown(path)}:{number}: the puncture's position is not three numbers") from None
            if len(puncture) != 3 or not all(np.isfinite(puncture)):
                raise BadInput(f"{shown(path)}:{number}: the puncture's position is not three finite numbers")
        if not line or line.startswith("#"):
            continue
        cells = line.split("\t")
        if len(cells) != 5 or cells[0] not in planes:
            raise BadInput(f"{shown(path)}:{number}: expected 'plane angle x y z'")
        try:
            values = [float(c) for c in cells[2:]]
        except ValueError:
            raise BadInput(f"{shown(path)}:{number}: a coordinate is not a number") from None
        if not all(np.isfinite(values)):
            raise BadInput(f"{shown(path)}:{number}: a coordinate is not finite")
        planes[cells[0]].append(values)
    if not planes["z=0"] or not planes["y=0"]:
        raise BadInput(f"{shown(path)}: no surface in one of the planes z = 0, y = 0")
    if puncture is None:
        raise BadInput(f"{shown(path)}: no 'puncture = (x y z)' in its header")
    return {k: np.array(v) for k, v in planes.items()}, np.array(puncture)


def save(fig, out, name):
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


def picture(run, out):
    planes, puncture = read_surface(os.path.join(run, "horizon.tsv"))
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.5))
    for ax, (plane, (a, b), labels) in zip(axes, [("z=0", (0, 1), ("x", "y")), ("y=0", (0, 2), ("x", "z"))]):
        s = planes[plane]
        centre = puncture[[a, b]]
        radius = np.hypot(s[:, a] - centre[0], s[:, b] - centre[1]).mean()
        t = np.linspace(0, 2 * np.pi, 361)
        ax.plot(centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t), ":", color="grey", label="sphere")
        ax.plot(s[:, a], s[:, b], "-", color="black", label="apparent horizon")
        ax.plot([centre[0]], [centre[1]], "+", color="black", label="puncture")
        ax.set_xlabel(labels[0])
        ax.set_ylabel(labels[1])
        ax.set_title(f"plane {plane.replace('=', ' = ')}")
        ax.set_aspect("equal")
    axes[0].legend(loc="upper right", fontsize="small")
    fig.tight_layout()
    save(fig, out, "horizon.png")


def main():
    if len(sys.argv) != 3:
        print(f"{PROGRAM}: usage: horizon.plot.py RUN_DIR OUTPUT_DIR", file=sys.stderr)
        return 2
    run, out = sys.argv[1:3]
    try:
        picture(run, out)
    except BadInput as e:
        print(f"{PROGRAM}: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"{PROGRAM}: cannot write the picture in {shown(out)}: {e.strerror or shown(e)}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 - a bug: one line, not a traceback
        print(f"{PROGRAM}: internal error: {type(e).__name__}: {shown(e)}", file=sys.stderr)
        return 3
    print(f"{PROGRAM}: horizon.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
