#!/usr/bin/env python3
"""PNG plots of a `bhnsid validate` directory, like the IRE figures of the paper: each equation's
residual along the x axis at dx, dx/2, dx/4, multiplied by 1, 4, 16, so that second-order
convergence shows as curves lying on top of each other.
Usage: scripts/plot_validate.py DIR/validate.json DIR   (called by bhnsid validate)
Exit 0; 2 when validate.json is missing or malformed, with one line on stderr naming it; 3 on a bug.
Each PNG is written under a fresh private name in DIR (O_EXCL) and renamed into place: a name in
DIR is never written through.
"""
import json
import math
import os
import signal
import stat
import sys
import tempfile

# Stopped by a signal passed on by validate: end quietly, not with a KeyboardInterrupt traceback.
signal.signal(signal.SIGINT, signal.SIG_DFL)

import matplotlib  # noqa: E402

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


MAX_REPORT_BYTES = 256 << 20


PROGRAM = "plot_validate"


class BadInput(Exception):
    """validate.json cannot be plotted: one line, exit 2."""


def shown(text):
    return "".join("\\x%02x" % ord(c) if ord(c) < 0x20 or ord(c) == 0x7F else c for c in str(text))


def load_report(path):
    """validate.json, read only when it is a regular file (a FIFO is refused, never waited on)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as e:
        raise BadInput(f"{shown(path)}: cannot be read: {e.strerror}") from None
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(f.fileno())
        if not stat.S_ISREG(st.st_mode):
            raise BadInput(f"{shown(path)}: is not a regular file")
        if st.st_size > MAX_REPORT_BYTES:
            raise BadInput(f"{shown(path)}: larger than {MAX_REPORT_BYTES >> 20} MiB: not a validate report")
        text = f.read()
    try:
        report = json.loads(text.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as e:
        raise BadInput(f"{shown(path)}: is not JSON: {shown(e)}") from None
    if not isinstance(report, dict) or not isinstance(report.get("axis_rescaled"), dict) or \
            not isinstance(report["axis_rescaled"].get("x"), list) or not isinstance(report.get("levels"), list):
        raise BadInput(f"{shown(path)}: lacks axis_rescaled.x or levels: not a report of bhnsid validate")
    return report


def save(fig, out_dir, name):
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=out_dir)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format="png", dpi=110)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, os.path.join(out_dir, name))  # atomic: a crash never leaves a half-written plot
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    finally:
        plt.close(fig)


def plot(report, out_dir):
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
        save(fig, out_dir, f"residual_{eq}.png")


def main():
    if len(sys.argv) != 3:
        print("plot_validate: usage: plot_validate.py DIR/validate.json DIR", file=sys.stderr)
        return 2
    try:
        report = load_report(sys.argv[1])
        try:
            plot(report, sys.argv[2])
        except (KeyError, IndexError, TypeError, ValueError, AttributeError) as e:
            raise BadInput(f"{shown(sys.argv[1])}: malformed ({type(e).__name__}: {shown(e)})") from None
    except BadInput as e:
        print(f"plot_validate: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # the output folder: full, read-only, gone
        print(f"{PROGRAM}: cannot write the pictures in {shown(sys.argv[2])}: {e.strerror or shown(e)}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 - a bug: one line, not a traceback
        print(f"plot_validate: internal error: {type(e).__name__}: {shown(e)}", file=sys.stderr)
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
