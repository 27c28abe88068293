"""The sequence reduction on known answers: a spline that must be exact, a parabola whose vertex is
known, the error model recovering the coefficients it was built from, and every refusal."""
import sys
import unittest
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "sequence"))
from bhnsid_sequence.paper import PAPER, comparison  # noqa: E402
from bhnsid_sequence.reduce import error_model, parabola_minimum, quadratic_at, spline_at  # noqa: E402


class Spline(unittest.TestCase):
    def test_a_cubic_is_reproduced_to_round_off(self):
        m0 = [0.08, 0.095, 0.11, 0.12, 0.14]
        f = lambda m: 3 - 2 * m + 40 * m ** 2 - 150 * m ** 3  # noqa: E731
        got = spline_at(m0, [f(m) for m in m0], [0.09, 0.13])
        for g, t in zip(got, [0.09, 0.13]):
            self.assertAlmostEqual(g.value, f(t), places=13)

    def test_a_smooth_function_converges_at_fourth_order(self):
        errors = []
        for n in (8, 16):
            m0 = np.linspace(0.1, 0.2, n)
            errors.append(abs(spline_at(m0, np.sin(20 * m0), [0.1537])[0].value - np.sin(20 * 0.1537)))
        self.assertGreater(errors[0] / errors[1], 10)  # 2^4 = 16 asymptotically

    def test_outside_the_range_and_too_few_points_are_reported(self):
        got = spline_at([1, 2, 3, 4], [1, 2, 3, 4], [0.5, 4.5, 2.5])
        self.assertIsNone(got[0].value)
        self.assertIn("outside the computed range [1, 4]", got[0].reason)
        self.assertIsNone(got[1].value)
        self.assertAlmostEqual(got[2].value, 2.5)
        self.assertIn("at least 4", spline_at([1, 2, 3], [1, 2, 3], [2])[0].reason)
        self.assertIn("same M0", spline_at([1, 2, 2, 3], [1, 2, 3, 4], [2])[0].reason)

    def test_unsorted_input_is_sorted(self):
        got = spline_at([3, 1, 4, 2], [9, 1, 16, 4], [2.5])
        self.assertAlmostEqual(got[0].value, 6.25, places=12)


class Minimum(unittest.TestCase):
    def test_vertex_of_a_parabola(self):
        x = np.array([0.008, 0.009, 0.010, 0.011, 0.012])
        m = parabola_minimum(x, (x - 0.0103) ** 2 - 0.0035)
        self.assertAlmostEqual(m.x, 0.0103, places=12)
        self.assertAlmostEqual(m.y, -0.0035, places=14)
        self.assertEqual(m.indices, (1, 2, 3))
        # Another quantity through the same three points, exact for a quadratic.
        self.assertAlmostEqual(quadratic_at(x, 2 + 3 * x - x ** 2, m.indices, m.x), 2 + 3 * 0.0103 - 0.0103 ** 2, places=13)

    def test_minimum_at_an_end_is_no_interior_minimum(self):
        m = parabola_minimum([1, 2, 3, 4], [1, 2, 3, 4])
        self.assertIsNone(m.x)
        self.assertIn("no interior minimum", m.reason)
        self.assertIn("needs 3", parabola_minimum([1, 2], [2, 1]).reason)


class ErrorModelTest(unittest.TestCase):
    # The paper's Table III grids: (n, dx), rc = n dx / 2.
    configs = {1: [(256, 0.015), (128, 0.03), (160, 0.015)], 10: [(256, 0.01), (128, 0.02), (160, 0.014375)]}

    def test_recovers_the_coefficients(self):
        for mu, cfg in self.configs.items():
            dx = [d for _, d in cfg]
            rc = [n * d / 2 for n, d in cfg]
            q = [-0.01 + 3.0 * d ** 2 + 0.2 / r ** 2 for d, r in zip(dx, rc)]
            e = error_model(dx, rc, q)
            self.assertAlmostEqual(e.q_exact, -0.01, places=12)
            self.assertAlmostEqual(e.e_truncation, 3.0, places=8)
            self.assertAlmostEqual(e.e_boundary, 0.2, places=10)
            self.assertAlmostEqual(e.error_bar, max(abs(q[0] + 0.01), 3.0 * dx[0] ** 2, 0.2 / rc[0] ** 2), places=12)

    def test_configurations_that_cannot_separate_the_errors_are_refused(self):
        with self.assertRaisesRegex(ValueError, "do not separate"):
            error_model([0.03, 0.015, 0.0075], [1.92, 1.92, 1.92], [1, 2, 3])
        with self.assertRaisesRegex(ValueError, "exactly three"):
            error_model([0.03, 0.015], [1.92, 1.2], [1, 2])


class PaperComparison(unittest.TestCase):
    def isco(self, mu, shift=0.0):
        return {f"{t:g}": {"E_b": {q: {"value": v + shift * e, "error": e} for q, (v, e) in row.items()}}
                for t, row in PAPER[mu].items()}

    def test_the_paper_against_itself_is_at_distance_zero_and_one_sigma_is_reported(self):
        text = comparison(1.0, [0.6, 0.75, 0.9], self.isco(1.0), "n256")
        self.assertIn("| E_b | -0.00283 ± 0.00012 | -0.00283 ± 0.00012 | 0.00 |", text)
        # Ours one own error bar off: sqrt(2) combined, distance 1/sqrt(2).
        shifted = comparison(1.0, [0.6], self.isco(1.0, 1.0), "n256")
        self.assertIn("| 0.71 |", shifted)

    def test_mu3_e_b_is_compared_after_the_offset_of_physics_notes_10_2(self):
        isco = self.isco(3.0)
        isco["0.75"]["E_b"]["E_b"]["value"] = -0.94738 + 0.93848  # the stated definition: -0.0089
        text = comparison(3.0, [0.75, 0.85], isco, "n256")
        self.assertIn("physics-notes §10.2) | -0.0089 ± 0.00053 | -0.0089 ± 0.00053 | 0.00 |", text)

    def test_the_halved_reading_maps_the_stated_definition_onto_the_printed_column(self):
        # (M_ADM - 2 M_BH) / (2 M0) = E_b / 2 - (mu - 1)/2 M_NS/M0: twice the printed mu = 1 value, and for
        # mu = 3 twice (printed + (mu - 1)/2 M_NS/M0), land on the printed value at distance zero.
        isco = self.isco(1.0)
        isco["0.75"]["E_b"]["E_b"] = {"value": -0.00706, "error": 0.0005}
        text = comparison(1.0, [0.75], isco, "n256")
        self.assertIn("(validation §14) | -0.00353 ± 0.00025 | -0.00353 ± 0.00025 | 0.00 |", text)
        isco = self.isco(3.0)
        isco["0.75"]["E_b"]["E_b"] = {"value": 2 * (-0.94738 + 0.93848), "error": 0.00106}
        text = comparison(3.0, [0.75], isco, "n256")
        self.assertIn("(validation §14) | -0.94738 ± 0.00053 | -0.94738 ± 0.00053 | 0.00 |", text)
        # Without M_NS/M0 of the row there is no such row, rather than a guess.
        isco = self.isco(3.0)
        isco["0.8"] = isco.pop("0.85")
        self.assertNotIn("validation §14) | -0.93846", comparison(3.0, [0.8], isco, "n256"))

    def test_missing_minima_are_said_not_invented(self):
        text = comparison(1.0, [0.6], {"0.6": {"E_b": {"reason": "no interior minimum"}, "J": {"reason": "x"}}}, "g")
        self.assertIn("no interior minimum", text)
        self.assertIsNone(comparison(2.0, [0.6], {}, "g"))


if __name__ == "__main__":
    unittest.main()
