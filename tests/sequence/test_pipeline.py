"""The sequence pipeline on runs whose answer is known: synthetic outcomes where E_b is a parabola
in Omega M0 with a known vertex, shifted on each grid by e_t dx^2 + e_b / rc^2, and every other
quantity linear in the rest mass (so that the splines are exact). The pipeline must find the
vertex on each grid, recover Q_e and the error terms, and skip a failed run."""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence.pipeline import at_targets, error_bars, minima  # noqa: E402
from bhnsid_sequence.runs import Outcome, configurations  # noqa: E402
from bhnsid_sequence.spec import Grid, Spec  # noqa: E402

M0_MAX = 0.18
OMEGA0, EB0 = 0.0123, -0.004   # the exact minimum
E_T, E_B = 2.0, 0.003          # truncation and boundary error coefficients of E_b


def omega_m0(xa):
    return 0.02 - 0.02 * xa


def scalars(c, m0_shift=0.0):
    grid_error = E_T * c.grid.dx ** 2 + E_B / c.grid.rc ** 2
    rest_mass = 0.8 * c.rho_max + 0.01 * c.x_a + m0_shift
    w = omega_m0(c.x_a)
    return {"rest_mass": rest_mass, "rest_mass_fraction": rest_mass / M0_MAX,
            "binding_energy": 50 * (w - OMEGA0) ** 2 + EB0 + grid_error,
            "binding_energy_puncture": 50 * (w - OMEGA0) ** 2 + EB0 - 0.1,
            "j_over_m0sq": 3.0 - 10 * w, "omega_m0": w, "rho_max": c.rho_max, "x_a": c.x_a,
            "bernoulli_constant": 0.8 + rest_mass, "sigma": 2.0 + c.x_a, "bh_momentum_y": -w}


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
