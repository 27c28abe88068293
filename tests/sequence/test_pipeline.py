"""The sequence pipeline on runs whose answer is known: synthetic outcomes where E_b is a parabola
in Omega M0 with a known vertex, shifted on each grid by e_t dx^2 + e_b / rc^2, and every other
quantity linear in the rest mass (so that the splines are exact). The pipeline must find the
vertex on each grid, recover Q_e and the error terms, and skip a failed run."""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence.pipeline import at_targets, error_bars, first_law, minima  # noqa: E402
from bhnsid_sequence.report import first_law_table  # noqa: E402
from bhnsid_sequence.runs import Outcome, configurations  # noqa: E402
from bhnsid_sequence.spec import Grid, Spec  # noqa: E402

M0_MAX = 0.18
OMEGA0, EB0 = 0.0123, -0.004   # the exact minimum
E_T, E_B = 2.0, 0.003          # truncation and boundary error coefficients of E_b


def omega_m0(xa):
    return 0.02 - 0.02 * xa


J_SLOPE = 4.0  # J = 1 + J_SLOPE w along a sequence


def scalars(c, m0_shift=0.0, first_law_factor=1.0):
    grid_error = E_T * c.grid.dx ** 2 + E_B / c.grid.rc ** 2
    rest_mass = 0.8 * c.rho_max + 0.01 * c.x_a + m0_shift
    w = omega_m0(c.x_a)
    return {"rest_mass": rest_mass, "rest_mass_fraction": rest_mass / M0_MAX,
            "binding_energy": 50 * (w - OMEGA0) ** 2 + EB0 + grid_error,
            "binding_energy_puncture": 50 * (w - OMEGA0) ** 2 + EB0 - 0.1,
            "j_over_m0sq": 3.0 - 10 * w, "omega_m0": w, "rho_max": c.rho_max, "x_a": c.x_a,
            "bernoulli_constant": 0.8 + rest_mass, "sigma": 2.0 + c.x_a, "bh_momentum_y": -w,
            # With the horizon's mass: the same parabola, lower; and M_ADM, J with dM_ADM = Omega dJ at
            # fixed M0 (Omega = w/M0): J = 1 + a w, M_ADM = 2 M0 + f a w^2/(2 M0), f = 1 obeying it.
            "binding_energy_irreducible": 50 * (w - OMEGA0) ** 2 + EB0 - 0.05 + grid_error,
            "angular_momentum": 1 + J_SLOPE * w,
            "adm_mass": 2 * rest_mass + first_law_factor * J_SLOPE * w * w / (2 * rest_mass)}


class Pipeline(unittest.TestCase):
    def setUp(self):
        self.spec = Spec(file=Path("synthetic.yaml"), base=Path("base.yaml"), mass_ratio=1.0,
                         x_a=[0.2, 0.3, 0.35, 0.4, 0.5], rho_max=[0.12, 0.13, 0.14, 0.15, 0.16],
                         targets=[0.6], grids=[Grid(256, 0.015), Grid(128, 0.03), Grid(160, 0.015)])
        self.outcomes = [Outcome(c, "converged", "", scalars(c)) for c in configurations(self.spec)]

    def test_vertex_error_model_and_every_quantity(self):
        table = at_targets(self.spec, self.outcomes)
        self.assertAlmostEqual(table["m0_max"], M0_MAX, places=14)
        found = minima(self.spec, table)
        for g in self.spec.grids:
            m = found[g.name]["0.6"]["E_b"]
            self.assertAlmostEqual(m["Omega_M0"], OMEGA0, places=12)
            self.assertAlmostEqual(m["E_b"], EB0 + E_T * g.dx ** 2 + E_B / g.rc ** 2, places=12)
            # Linear in Omega M0 through the same three points: exact.
            self.assertAlmostEqual(m["J_over_M0sq"], 3.0 - 10 * OMEGA0, places=11)
            self.assertAlmostEqual(m["P_y_BH"], -OMEGA0, places=12)
        isco = error_bars(self.spec, found)["0.6"]["E_b"]
        e = isco["E_b"]
        self.assertAlmostEqual(e["q_exact"], EB0, places=11)
        self.assertAlmostEqual(e["e_truncation"], E_T, places=6)
        self.assertAlmostEqual(e["e_boundary"], E_B, places=9)
        fine = self.spec.grids[0]
        self.assertAlmostEqual(e["error"], max(E_T * fine.dx ** 2 + E_B / fine.rc ** 2, E_T * fine.dx ** 2,
                                               E_B / fine.rc ** 2), places=12)
        # Omega M0 does not depend on the grid: no error at all.
        self.assertLess(isco["Omega_M0"]["error"], 1e-12)

    def test_turning_point_with_the_horizon_mass_and_the_first_law(self):
        # E_b with M_irr has its minimum at the same Omega M0; the first law holds between every pair
        # of neighbours (to the splines' accuracy in 1/M0), and a sequence with three times the
        # Omega dJ shows a residual of 2.
        found = minima(self.spec, at_targets(self.spec, self.outcomes))
        for g in self.spec.grids:
            self.assertAlmostEqual(found[g.name]["0.6"]["E_b_irreducible"]["Omega_M0"], OMEGA0, places=12)
        law = first_law(self.spec, at_targets(self.spec, self.outcomes))
        for g in self.spec.grids:
            pairs = law[g.name]["0.6"]
            self.assertEqual(len(pairs), 4)
            for p in pairs:
                self.assertLess(abs(p["residual"]), 1e-4)
        broken = [Outcome(c, "converged", "", scalars(c, first_law_factor=3.0)) for c in configurations(self.spec)]
        for p in first_law(self.spec, at_targets(self.spec, broken))["n256_dx0.015"]["0.6"]:
            self.assertAlmostEqual(p["residual"], 2.0, delta=1e-3)

    def test_the_first_law_residual_through_the_error_model(self):
        # A residual carrying e_t dx^2 + e_b / rc^2 on each grid (M_ADM's Omega dJ part scaled by
        # 1 + that) must extrapolate back to 0, pair by pair, matched by their xhat_A.
        def law_error(g):
            return 30.0 * g.dx ** 2 + 0.4 / g.rc ** 2
        outcomes = [Outcome(c, "converged", "", scalars(c, first_law_factor=1.0 + law_error(c.grid)))
                    for c in configurations(self.spec)]
        law = first_law(self.spec, at_targets(self.spec, outcomes))
        rows = law["error_model"]["0.6"]
        self.assertEqual([r["x_a"] for r in rows], [p["x_a"] for p in law["n256_dx0.015"]["0.6"]])
        self.assertEqual(len(rows), 4)
        fine = self.spec.grids[0]
        for r in rows:
            self.assertAlmostEqual(r["value"], law_error(fine), delta=1e-4)
            self.assertLess(abs(r["q_exact"]), 1e-4)
            self.assertAlmostEqual(r["e_truncation"], 30.0, delta=0.5)
            self.assertAlmostEqual(r["e_boundary"], 0.4, delta=1e-3)
        md = first_law_table(self.spec, law)
        self.assertIn("Q_e (error model)", md)
        self.assertIn("| 0.3–0.2 |", md)

    def test_without_the_horizon_mass_its_minimum_has_a_reason(self):
        for o in self.outcomes:
            del o.scalars["binding_energy_irreducible"]
        found = minima(self.spec, at_targets(self.spec, self.outcomes))
        self.assertIn("horizon plugin", found["n256_dx0.015"]["0.6"]["E_b_irreducible"]["reason"])
        self.assertAlmostEqual(found["n256_dx0.015"]["0.6"]["E_b"]["Omega_M0"], OMEGA0, places=12)

    def test_a_failed_run_is_left_out_and_too_few_is_a_reason(self):
        for o in self.outcomes:
            if o.config.grid_index == 0 and o.config.x_a == 0.35 and o.config.rho_max in (0.13, 0.14):
                o.status, o.message, o.scalars = "failed", "Roche limit", None
        found = minima(self.spec, at_targets(self.spec, self.outcomes))
        # Three rho_max left at xhat_A = 0.35: no spline there, so four points remain on grid 0,
        # still with an interior minimum (the vertex stays exact: E_b is a parabola).
        self.assertEqual(found["n256_dx0.015"]["0.6"]["points"], 4)
        self.assertAlmostEqual(found["n256_dx0.015"]["0.6"]["E_b"]["Omega_M0"], OMEGA0, places=12)
        table = at_targets(self.spec, self.outcomes)
        self.assertIn("at least 4", table["grids"]["n256_dx0.015"]["0.35"]["0.6"]["reason"])


if __name__ == "__main__":
    unittest.main()
