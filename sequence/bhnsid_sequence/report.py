"""sequence.json, the tables in the layout of the paper's Tables I and II (Markdown and CSV), and
the figures E_b(Omega M0) and J/M0^2(Omega M0) per target mass, minima marked. Every file is
written under a fresh private name, fsynced and renamed (safe_io.write_atomic)."""
import csv
import io
import json
from pathlib import Path

from .paper import comparison
from .pipeline import MINIMA
from .safe_io import write_atomic, write_with
from .spec import key

TABLE_I = ["E_b", "J_over_M0sq", "Omega_M0", "rho_max"]
TABLE_II = ["x_a", "C_B", "sigma", "P_y_BH"]


def _cell(entry, name):
    if "reason" in entry and name not in entry:
        return "—"
    v = entry.get(name)
    if v is None:
        return "—"
    if entry[name].get("error") is None:
        return f"{v['value']:.6g}"
    return f"{v['value']:.6g} ± {v['error']:.2g}"


def tables(spec, errors, minimum="E_b"):
    """Markdown and CSV rows: mu, M0/M0max, then Table I's and Table II's quantities."""
    header = ["mu_bn", "M0/(M0)_max"] + TABLE_I + TABLE_II
    md = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(header + [h + "_error" for h in TABLE_I + TABLE_II] + ["note"])
    for t in spec.targets:
        e = errors[key(t)][minimum]
        note = e.get("reason", "")
        if note and "values" not in e:
            md.append(f"| {spec.mass_ratio:g} | {key(t)} | " + " | ".join(["—"] * (len(header) - 2)) + f" |  ({note})")
            w.writerow([spec.mass_ratio, t] + [""] * 2 * len(TABLE_I + TABLE_II) + [note])
            continue
        if "values" in e:  # the finest grid has a minimum, another has none: no error bar
            md.append(f"| {spec.mass_ratio:g} | {key(t)} | " + " | ".join(f"{e['values'][q]:.6g}" for q in TABLE_I + TABLE_II)
                      + f" |  (no error bar: {note})")
            w.writerow([spec.mass_ratio, t] + [e["values"][q] for q in TABLE_I + TABLE_II] + [""] * len(TABLE_I + TABLE_II)
                       + [note])
            continue
        md.append(f"| {spec.mass_ratio:g} | {key(t)} | " + " | ".join(_cell(e, q) for q in TABLE_I + TABLE_II) + " |")
        w.writerow([spec.mass_ratio, t] + [e[q]["value"] for q in TABLE_I + TABLE_II]
                   + [e[q]["error"] if e[q]["error"] is not None else "" for q in TABLE_I + TABLE_II] + [""])
    return "\n".join(md) + "\n", buf.getvalue()


def figures(spec, table, found, errors_at_points, out_dir: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    finest = spec.grids[0].name
    written = []
    for quantity, label, minimum, fname in (("E_b", "$E_b$", "E_b", "eb.png"),
                                            ("J_over_M0sq", "$J/M_0^2$", "J", "j.png")):
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for t in spec.targets:
            pts = []
            for xa in spec.x_a:
                p = table["grids"][finest][key(xa)][key(t)]
                if "reason" in p:
                    continue
                err = errors_at_points.get(key(t), {}).get(key(xa), {})
                pts.append((p["Omega_M0"], p[quantity], err.get(quantity, 0.0), err.get("Omega_M0", 0.0)))
            pts.sort()
            if not pts:
                continue
            xs, ys, dy, dxs = zip(*pts)
            line = ax.errorbar(xs, ys, yerr=dy, xerr=dxs, marker="o", ms=3, capsize=2,
                               label=f"$M_0 = {key(t)}\\,(M_0)_{{max}}$")
            m = found[finest][key(t)][minimum]
            if "reason" not in m:
                ax.plot([m["Omega_M0"]], [m["E_b" if quantity == "E_b" else "J_over_M0sq"]], "*", ms=12,
                        color=line[0].get_color())
        ax.set_xlabel(r"$\Omega M_0$")
        ax.set_ylabel(label)
        ax.set_title(f"$\\mu_{{bn}} = {spec.mass_ratio:g}$, {finest} (minima: stars)")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
        fig.tight_layout()
        try:
            write_with(out_dir / fname, lambda f: fig.savefig(f, format="png", dpi=120))
        finally:
            plt.close(fig)
        written.append(fname)
    return written


def write_all(spec, outcomes, table, found, errors, errors_at_points, out_dir: Path):
    runs = [{"dir": str(o.config.relative_dir), "grid": o.config.grid.name, "x_a": o.config.x_a,
             "rho_max": o.config.rho_max, "status": o.status, "message": o.message, "seconds": o.seconds}
            for o in outcomes]
    doc = {"format": "bhnsid-sequence", "format_version": 1, "file": str(spec.file), "base": str(spec.base),
           "mass_ratio": spec.mass_ratio, "targets": spec.targets,
           "grids": [{"n": g.n, "dx": g.dx, "rc": g.rc} for g in spec.grids],
           "m0_max": table["m0_max"], "runs": runs, "at_targets": table["grids"], "minima": found,
           "isco": errors, "point_errors": errors_at_points}
    write_atomic(out_dir / "sequence.json", json.dumps(doc, indent=1) + "\n")
    for minimum in MINIMA:
        md, text = tables(spec, errors, minimum)
        write_atomic(out_dir / f"table_min_{minimum}.md", md)
        write_atomic(out_dir / f"table_min_{minimum}.csv", text)
    paper = comparison(spec.mass_ratio, spec.targets, errors, spec.grids[0].name)
    if paper:
        write_atomic(out_dir / "paper_comparison.md", paper)
    failed = [r for r in runs if r["status"] != "converged"]
    lines = [f"| {r['dir']} | {r['status']} | {r['message'][:200]} |" for r in failed]
    write_atomic(out_dir / "failures.md", "| configuration | status | cause |\n|---|---|---|\n" + "\n".join(lines) + "\n")
    return figures(spec, table, found, errors_at_points, out_dir)
