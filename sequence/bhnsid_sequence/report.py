"""sequence.json, the tables in the layout of the paper's Tables I and II (Markdown and CSV), the
first law between neighbours, and the figures E_b(Omega M0) and J/M0^2(Omega M0) per target mass,
minima marked, and E_b with the horizon's mass beside the 3PN point-mass curve. Every file is
written under a fresh private name, fsynced and renamed (safe_io.write_atomic)."""
import csv
import io
import json
from pathlib import Path

from .paper import comparison
from .pn import energy_per_reduced_mass
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


def first_law_table(spec, law):
    """Markdown: per target, dM_ADM/(Omega dJ) - 1 between neighbours on each grid (finest first),
    pairs matched by their two xhat_A; with three grids the error model's Q_e and the finest grid's
    error bar."""
    names = [g.name for g in spec.grids]
    model = law.get("error_model")
    extra = ["finest ± error bar", "Q_e (error model)"] if model is not None else []
    md = ["| M0/(M0)_max | xhat_A pair | Omega M0 (pair) | " + " | ".join(names + extra) + " |",
          "|" + "---|" * (len(names) + len(extra) + 3)]
    for t in spec.targets:
        cells = [law[n].get(key(t)) for n in names]
        if not isinstance(cells[0], list):
            md.append(f"| {key(t)} | — | — | " + " | ".join("—" for _ in names + extra) + f" |  ({cells[0]['reason']})")
            continue
        fits = {tuple(r["x_a"]): r for r in (model or {}).get(key(t), [])}
        for pair in cells[0]:
            label = tuple(pair["x_a"])
            row = []
            for c in cells:
                match = [p for p in c if tuple(p["x_a"]) == label] if isinstance(c, list) else []
                r = match[0]["residual"] if match else None
                row.append("—" if r is None else f"{r:+.3f}")
            if model is not None:
                f = fits.get(label)
                row += ["—", "—"] if f is None else [f"{f['value']:+.3f} ± {f['error']:.3f}", f"{f['q_exact']:+.3f}"]
            md.append(f"| {key(t)} | {label[0]}–{label[1]} | {pair['Omega_M0']:.5f} | " + " | ".join(row) + " |")
    return "\n".join(md) + "\n"


def post_newtonian_figure(spec, table, out_dir: Path):
    """eb_irreducible.png: E_b = (M_ADM - M_irr - M_NS)/M0 of the finest grid against Omega M0, with
    the 3PN point-mass E at the same M_tot Omega (M_tot = M_irr + M_NS), scaled to M0; [] when the
    runs have no horizon mass."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    finest = spec.grids[0].name
    fig, ax = plt.subplots(figsize=(6, 4.5))
    drawn = False
    for t in spec.targets:
        pts = [table["grids"][finest][key(xa)][key(t)] for xa in spec.x_a]
        pts = sorted((p for p in pts if "E_b_irreducible" in p and "M_irr" in p and "M_NS" in p),
                     key=lambda p: p["Omega_M0"])
        if not pts:
            continue
        m0 = t * table["m0_max"]
        line = ax.plot([p["Omega_M0"] for p in pts], [p["E_b_irreducible"] for p in pts], "o-", ms=3,
                       label=f"$M_0 = {key(t)}\\,(M_0)_{{max}}$")
        m_bh, m_ns = pts[0]["M_irr"], pts[0]["M_NS"]
        m_tot = m_bh + m_ns
        nu, mu_red = m_bh * m_ns / m_tot ** 2, m_bh * m_ns / m_tot
        lo, hi = pts[0]["Omega_M0"], pts[-1]["Omega_M0"]
        xs = [lo + (hi - lo) * i / 50 for i in range(51)]
        ys = [energy_per_reduced_mass(x * m_tot / m0, nu) * mu_red / m0 for x in xs]
        ax.plot(xs, ys, "--", color=line[0].get_color(), lw=1)
        drawn = True
    if not drawn:
        plt.close(fig)
        return []
    ax.plot([], [], "--", color="grey", label="3PN point masses")
    ax.set_xlabel(r"$\Omega M_0$")
    ax.set_ylabel(r"$(M_{ADM} - M_{irr} - M_{NS})/M_0$")
    ax.set_title(f"$\\mu_{{bn}} = {spec.mass_ratio:g}$, {finest}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    try:
        write_with(out_dir / "eb_irreducible.png", lambda f: fig.savefig(f, format="png", dpi=120))
    finally:
        plt.close(fig)
    return ["eb_irreducible.png"]


def write_all(spec, outcomes, table, found, errors, errors_at_points, out_dir: Path, law=None):
    runs = [{"dir": str(o.config.relative_dir), "grid": o.config.grid.name, "x_a": o.config.x_a,
             "rho_max": o.config.rho_max, "status": o.status, "message": o.message, "seconds": o.seconds}
            for o in outcomes]
    doc = {"format": "bhnsid-sequence", "format_version": 1, "file": str(spec.file), "base": str(spec.base),
           "mass_ratio": spec.mass_ratio, "targets": spec.targets,
           "grids": [{"n": g.n, "dx": g.dx, "rc": g.rc} for g in spec.grids],
           "m0_max": table["m0_max"], "runs": runs, "at_targets": table["grids"], "minima": found,
           "isco": errors, "point_errors": errors_at_points, "first_law": law or {}}
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
    if law:
        write_atomic(out_dir / "first_law.md", first_law_table(spec, law))
    return figures(spec, table, found, errors_at_points, out_dir) + post_newtonian_figure(spec, table, out_dir)
