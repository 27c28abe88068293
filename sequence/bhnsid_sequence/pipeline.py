"""From the runs to the ISCO: per grid and xhat_A, every quantity splined against M0 at the target
masses; per grid and target, the minima (turning points) of E_b, E_b', E_b with the horizon's mass
and J along xhat_A with every quantity there; the first law dM_ADM = Omega dJ between neighbours;
over the grids, the error model (physics-notes §6.2-6.3)."""
import math
from typing import Dict, List

from .pn import first_law as first_law_pairs
from .reduce import error_model, parabola_minimum, quadratic_at, spline_at
from .runs import Outcome
from .spec import Spec, key

# Tabulated quantities: summary.json's scalar names (physical units; E_b with the bare mass, as
# the paper; E_b' with the puncture mass, physics-notes §6.1).
QUANTITIES = {
    "E_b": "binding_energy",
    "E_b_puncture": "binding_energy_puncture",
    "J_over_M0sq": "j_over_m0sq",
    "Omega_M0": "omega_m0",
    "rho_max": "rho_max",
    "x_a": "x_a",
    "C_B": "bernoulli_constant",
    "sigma": "sigma",
    "P_y_BH": "bh_momentum_y",
}
# Quantities a run may lack (no horizon plugin, or a run of an older build): tabulated at a sequence
# point where every one of its usable runs has them. E_b_irreducible = (M_ADM - M_irr - M_NS)/M0.
OPTIONAL = {
    "M_ADM": "adm_mass",
    "J": "angular_momentum",
    "M_NS": "ns_adm_mass",
    "M_BH_bare": "bh_bare_mass",
    "M_irr": "bh_irreducible_mass",
    "E_b_irreducible": "binding_energy_irreducible",
}
MINIMA = {"E_b": "E_b", "E_b_puncture": "E_b_puncture", "E_b_irreducible": "E_b_irreducible", "J": "J_over_M0sq"}


def _finite(x):
    return x is not None and isinstance(x, (int, float)) and math.isfinite(x)


def at_targets(spec: Spec, outcomes: List[Outcome]) -> Dict:
    """{grid: {x_a: {target: {quantity: value} or {"reason": ...}}}} and M0_max."""
    m0_max = None
    for o in outcomes:
        s = o.scalars or {}
        if (o.status == "converged" and _finite(s.get("rest_mass")) and _finite(s.get("rest_mass_fraction"))
                and s["rest_mass_fraction"] != 0):
            m0_max = s["rest_mass"] / s["rest_mass_fraction"]
            break
    usable = {}  # (grid, x_a) -> its converged runs with every quantity, in one pass over the outcomes
    needed = list(QUANTITIES.values()) + ["rest_mass"]
    for o in outcomes:
        if o.status == "converged" and all(_finite((o.scalars or {}).get(k)) for k in needed):
            usable.setdefault((o.config.grid_index, o.config.x_a), []).append(o)
    out = {}
    for g, grid in enumerate(spec.grids):
        per_grid = out.setdefault(grid.name, {})
        for xa in spec.x_a:
            runs = usable.get((g, xa), [])
            m0 = [o.scalars["rest_mass"] for o in runs]
            cell = per_grid.setdefault(key(xa), {})
            for t in spec.targets:
                if m0_max is None:
                    cell[key(t)] = {"reason": "no converged configuration gives (M0)_max"}
                    continue
                entry = {}
                for name, scalar in QUANTITIES.items():
                    r = spline_at(m0, [o.scalars[scalar] for o in runs], [t * m0_max])[0]
                    if r.value is None:
                        entry = {"reason": r.reason}
                        break
                    entry[name] = r.value
                if "reason" not in entry:
                    for name, scalar in OPTIONAL.items():
                        if all(_finite(o.scalars.get(scalar)) for o in runs):
                            r = spline_at(m0, [o.scalars[scalar] for o in runs], [t * m0_max])[0]
                            if r.value is not None:
                                entry[name] = r.value
                cell[key(t)] = entry
    return {"m0_max": m0_max, "grids": out}


def minima(spec: Spec, table: Dict) -> Dict:
    """{grid: {target: {minimum: {...}}}}: along xhat_A, ordered by Omega M0."""
    out = {}
    for grid in spec.grids:
        for t in spec.targets:
            points = [table["grids"][grid.name][key(xa)][key(t)] for xa in spec.x_a]
            points = [p for p in points if "reason" not in p]
            points.sort(key=lambda p: p["Omega_M0"])
            res = out.setdefault(grid.name, {}).setdefault(key(t), {})
            res["points"] = len(points)
            x = [p["Omega_M0"] for p in points]
            for label, quantity in MINIMA.items():
                if not all(quantity in p for p in points):
                    res[label] = {"reason": f"{quantity} is not in every run (E_b with M_irr needs the horizon plugin)"}
                    continue
                m = parabola_minimum(x, [p[quantity] for p in points])
                if m.x is None:
                    res[label] = {"reason": m.reason}
                    continue
                at = {name: quadratic_at(x, [p[name] for p in points], m.indices, m.x) for name in QUANTITIES}
                at["Omega_M0"] = m.x
                at[quantity] = m.y
                res[label] = at
    return out


def error_bars(spec: Spec, found: Dict) -> Dict:
    """{target: {minimum: {quantity: {value, error, Q_e, ...} or reason}}} of the finest grid."""
    out = {}
    finest = spec.grids[0].name
    for t in spec.targets:
        for label in MINIMA:
            cells = [found[g.name][key(t)][label] for g in spec.grids]
            res = out.setdefault(key(t), {}).setdefault(label, {})
            if any("reason" in c for c in cells):
                reasons = [f"{g.name}: {c['reason']}" for g, c in zip(spec.grids, cells) if "reason" in c]
                res["reason"] = "; ".join(reasons)
                if "reason" not in found[finest][key(t)][label]:
                    res["values"] = found[finest][key(t)][label]
                continue
            for name in QUANTITIES:
                q = [c[name] for c in cells]
                entry = {"value": q[0], "per_grid": q}
                if len(spec.grids) == 3:
                    e = error_model([g.dx for g in spec.grids], [g.rc for g in spec.grids], q)
                    entry.update(error=e.error_bar, q_exact=e.q_exact, e_truncation=e.e_truncation, e_boundary=e.e_boundary)
                else:
                    entry["error"] = None
                res[name] = entry
    return out


def point_errors(spec: Spec, table: Dict) -> Dict:
    """The error bar of every sequence point (per xhat_A and target) for the figures."""
    out = {}
    if len(spec.grids) != 3:
        return out
    for xa in spec.x_a:
        for t in spec.targets:
            cells = [table["grids"][g.name][key(xa)][key(t)] for g in spec.grids]
            if any("reason" in c for c in cells):
                continue
            errs = {}
            for name in ("E_b", "J_over_M0sq", "Omega_M0"):
                e = error_model([g.dx for g in spec.grids], [g.rc for g in spec.grids], [c[name] for c in cells])
                errs[name] = e.error_bar
            out.setdefault(key(t), {})[key(xa)] = errs
    return out


def first_law(spec: Spec, table: Dict) -> Dict:
    """{grid: {target: [{Omega_M0, residual, x_a}]}}: dM_ADM/(Omega dJ) - 1 between neighbouring
    points of each constant-M0 sequence (ordered by Omega M0; x_a names the pair's two xhat_A), where
    the runs give M_ADM and J. 0 for exact quasi-equilibrium at fixed rest mass, hole mass and
    circulation (Friedman, Uryu & Shibata 2002). With three grids, "error_model" holds per target the
    pairs every grid has, through the paper's error model (the residual is a grid quantity like any
    other): the finest grid's value, its error bar and the extrapolated Q_e."""
    out = {}
    m0_max = table["m0_max"]
    for grid in spec.grids:
        for t in spec.targets:
            points = [table["grids"][grid.name][key(xa)][key(t)] for xa in spec.x_a]
            points = [p for p in points if "reason" not in p and "M_ADM" in p and "J" in p]
            res = out.setdefault(grid.name, {})
            if m0_max is None or len(points) < 2:
                res[key(t)] = {"reason": "fewer than two sequence points with M_ADM and J"}
                continue
            m0 = t * m0_max
            points.sort(key=lambda p: p["Omega_M0"])
            pairs = first_law_pairs([p["Omega_M0"] / m0 for p in points], [p["M_ADM"] for p in points],
                                    [p["J"] for p in points])
            res[key(t)] = [{"Omega_M0": q["omega"] * m0, "residual": q["residual"],
                            "x_a": [key(a["x_a"]), key(b["x_a"])]} for q, a, b in zip(pairs, points, points[1:])]
    if len(spec.grids) == 3:
        out["error_model"] = _first_law_error_model(spec, out)
    return out


def _first_law_error_model(spec: Spec, law: Dict) -> Dict:
    out = {}
    for t in spec.targets:
        cells = [law[g.name].get(key(t)) for g in spec.grids]
        if not all(isinstance(c, list) for c in cells):
            out[key(t)] = []
            continue
        by_pair = [{tuple(p["x_a"]): p for p in c} for c in cells]
        rows = []
        for pair in cells[0]:
            label = tuple(pair["x_a"])
            q = [b.get(label, {}).get("residual") for b in by_pair]
            if not all(_finite(v) for v in q):
                continue
            e = error_model([g.dx for g in spec.grids], [g.rc for g in spec.grids], q)
            rows.append({"x_a": list(label), "Omega_M0": pair["Omega_M0"], "per_grid": q, "value": q[0],
                         "error": e.error_bar, "q_exact": e.q_exact, "e_truncation": e.e_truncation,
                         "e_boundary": e.e_boundary})
        out[key(t)] = rows
    return out
