"""The 3PN point-mass binding energy and the first-law residual on known answers: the Newtonian
limit, the test-mass limit's coefficients, the values the reference quotes, a synthetic sequence that
obeys dM = Omega dJ exactly and one that does not."""
import math
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence.pn import coefficients, energy_per_reduced_mass, first_law, isco_m_omega  # noqa: E402


class PostNewtonian(unittest.TestCase):
    def test_newtonian_limit(self):
        # E/mu -> -x/2 = -(M Omega)^(2/3)/2 as M Omega -> 0.
        for nu in (0.0, 0.1875, 0.25):
            self.assertAlmostEqual(energy_per_reduced_mass(1e-9, nu) / (-0.5 * 1e-6), 1, places=5)

    def test_test_mass_limit_is_the_schwarzschild_expansion(self):
        # nu = 0: E/mu = (1 - 2x)/sqrt(1 - 3x) - 1 = -x/2 (1 - 3/4 x - 27/8 x^2 - 675/64 x^3 + ...).
        self.assertEqual(coefficients(0.0), (-0.75, -27 / 8, -675 / 64))

    def test_values_at_the_separations_of_the_comparison(self):
        # Equal masses: E/mu = -0.034 at M Omega = 0.02 and -0.051 at 0.04 (the values the comparison
        # of docs/lapse.md quotes); the 3PN ISCO of the energy function at M Omega = 0.129.
        self.assertAlmostEqual(energy_per_reduced_mass(0.02, 0.25), -0.0342, places=4)
        self.assertAlmostEqual(energy_per_reduced_mass(0.04, 0.25), -0.0509, places=4)
        self.assertAlmostEqual(isco_m_omega(0.25), 0.1287, places=3)


class FirstLaw(unittest.TestCase):
    def test_a_sequence_obeying_it_has_zero_residual(self):
        # M(J) with dM/dJ = Omega(J) = J^-3 (Kepler-like): M = M0 - 1/(2 J^2).
        js = [3.0, 3.1, 3.25, 3.4]
        omegas = [j ** -3 for j in js]
        masses = [1 - 0.5 / j ** 2 for j in js]
        for r in first_law(omegas, masses, js):
            self.assertLess(abs(r["residual"]), 0.01)  # midpoint rule: O(dJ^2)

    def test_a_sequence_violating_it_is_seen(self):
        js = [3.0, 3.1, 3.25, 3.4]
        omegas = [j ** -3 for j in js]
        masses = [1 - 1.5 / j ** 2 for j in js]  # three times the Omega dJ
        for r in first_law(omegas, masses, js):
            self.assertAlmostEqual(r["residual"], 2, delta=0.05)


if __name__ == "__main__":
    unittest.main()
