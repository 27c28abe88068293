"""The reduction of a sequence (physics-notes §6.2-6.3; the paper's Sequences section):
splines of every quantity against the rest mass M0 at fixed xhat_A, the minimum of E_b along a
constant-M0 sequence, and the error model over the grid configurations.

Pure numpy/scipy: no run is read here (see runs.py), so every rule is tested on known answers
(tests/sequence/test_reduce.py).
"""
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from scipy.interpolate import CubicSpline


@dataclass
class AtTarget:
    """A quantity at a target M0, or why it is not there."""
    value: Optional[float]
    reason: str = ""


def spline_at(m0: Sequence[float], values: Sequence[float], targets: Sequence[float]) -> list:
    """Each quantity against M0 through a cubic spline (not-a-knot: exact for a cubic), evaluated
    at each target M0. A target outside the computed range is reported, never extrapolated."""
    m0 = np.asarray(m0, float)
    values = np.asarray(values, float)
    if m0.size < 4:
        return [AtTarget(None, f"{m0.size} converged rho_max values, a cubic spline needs at least 4") for _ in targets]
    order = np.argsort(m0)
    m0, values = m0[order], values[order]
    if np.any(np.diff(m0) <= 0):
        return [AtTarget(None, "two configurations have the same M0") for _ in targets]
    spline = CubicSpline(m0, values)
    out = []
    for t in targets:
        if t < m0[0] or t > m0[-1]:
            out.append(AtTarget(None, f"M0 = {t:.6g} lies outside the computed range [{m0[0]:.6g}, {m0[-1]:.6g}]"))
        else:
            out.append(AtTarget(float(spline(t))))
    return out


@dataclass
class Minimum:
    """The minimum of y(x) along a sequence: the vertex of the parabola through the discrete minimum
    and its two neighbours, and those three points' indices; `reason` says why there is none."""
    x: Optional[float]
    y: Optional[float]
    indices: tuple = ()
    reason: str = ""


def parabola_minimum(x: Sequence[float], y: Sequence[float]) -> Minimum:
    """The paper's rule for the ISCO: the discrete minimum must be interior; a minimum at an end
    of the sequence is "no interior minimum" (the paper's mu = 10, 0.45 row)."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    if x.size < 3:
        return Minimum(None, None, (), f"{x.size} point{'' if x.size == 1 else 's'}, a parabola needs 3")
    i = int(np.argmin(y))
    if i == 0 or i == x.size - 1:
        return Minimum(None, None, (), "no interior minimum (the smallest value is at an end of the sequence)")
    idx = (i - 1, i, i + 1)
    c2, c1, c0 = np.polyfit(x[list(idx)], y[list(idx)], 2)
    if not c2 > 0:
        return Minimum(None, None, idx, "the parabola through the minimum and its neighbours opens downwards")
    xv = -c1 / (2 * c2)
    return Minimum(float(xv), float(np.polyval([c2, c1, c0], xv)), idx)


def quadratic_at(x: Sequence[float], q: Sequence[float], indices: tuple, at: float) -> float:
    """Another tabulated quantity at the minimum: the parabola through the same three points
    (physics-notes §6.3, an interpretation)."""
    x = np.asarray(x, float)
    q = np.asarray(q, float)
    return float(np.polyval(np.polyfit(x[list(indices)], q[list(indices)], 2), at))


@dataclass
class ErrorModel:
    q_exact: float      # Q_e
    e_truncation: float  # e_t
    e_boundary: float    # e_b
    error_bar: float     # of the first (finest) configuration


def error_model(dx: Sequence[float], rc: Sequence[float], q: Sequence[float]) -> ErrorModel:
    """Q_n = Q_e + e_t dx_n^2 + e_b / rc_n^2 through three configurations (paper eq. errorbar);
    the error bar of the first is max(|Q_1 - Q_e|, |e_t dx_1^2|, |e_b / rc_1^2|)."""
    if not (len(dx) == len(rc) == len(q) == 3):
        raise ValueError(f"the error model needs exactly three grid configurations, got {len(q)}")
    a = np.array([[1.0, d * d, 1.0 / (r * r)] for d, r in zip(dx, rc)])
    if abs(np.linalg.det(a)) < 1e-12 * np.abs(a).max() ** 3:
        raise ValueError("the three grid configurations do not separate dx from rc (two share both, or all one rc)")
    qe, et, eb = np.linalg.solve(a, np.asarray(q, float))
    err = max(abs(q[0] - qe), abs(et * dx[0] ** 2), abs(eb / rc[0] ** 2))
    return ErrorModel(float(qe), float(et), float(eb), float(err))
