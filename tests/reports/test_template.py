"""Templates: placeholders, literal constants, and the lint that keeps numbers out of prose."""

import unittest

from reports.core import template


class Render(unittest.TestCase):
    def test_placeholders_and_literals(self):
        text = "TPD {{tpd}} at p_d = {{=0.75}}."
        self.assertEqual(template.render(text, {"tpd": "0.84"}, "t.md"), "TPD 0.84 at p_d = 0.75.")

    def test_unknown_placeholder_names_the_line(self):
        with self.assertRaisesRegex(template.TemplateError, r"t\.md:2: no check produced '\{\{missing\}\}'"):
            template.render("line one\n{{missing}}", {}, "t.md")


class Lint(unittest.TestCase):
    def test_numbers_in_prose_are_flagged(self):
        text = ("JDT-VB's TPD is 0.84 here.\n"
                "It is 12 % higher.\n"
                "Within ± a bit.\n"
                "Lower at 47 of 50 steps.\n")
        problems = template.lint(text, "t.md")
        self.assertEqual(len(problems), 4)
        self.assertTrue(problems[0].startswith("t.md:1: a decimal"))
        self.assertIn("'47 of 50'", problems[3])

    def test_counts_words_and_one_digit_decimals_are_flagged(self):
        """The gaps issue 50 found: "9.9", "87 iterations", "45 out of 50", "twelve percent",
        "a factor of ten", "10 000 trials", "3×"."""
        lines = ["GOSPA rises to about 9.9 in one run.", "It ran 87 iterations.", "At 45 out of 50 steps.",
                 "It is twelve percent lower.", "Faster by a factor of ten.", "We ran 10 000 trials.",
                 "It is 3× slower.", "At least 95 % of resamples."]
        problems = template.lint("\n".join(lines), "t.md")
        self.assertEqual([p.split(":")[1] for p in problems], [str(i) for i in range(1, len(lines) + 1)])
        self.assertIn("'9.9'", problems[0])
        self.assertIn("'10 000 trials'", problems[5])
        self.assertIn("'95 %'", problems[7])

    def test_references_and_grid_sizes_are_not_counts(self):
        text = ("See Sec. 1.3, §4.1, eqs 138–141 and eqs (145)–(147), Table IV, issue 31.\n"
                "A 2×3 grid and n×3 grids; {{=0.4}} and {{=200}} trials are constants.\n")
        self.assertEqual(template.lint(text, "t.md"), [])

    def test_placeholders_code_links_and_constants_are_not(self):
        text = ("TPD {{tpd}} at p_d = {{=0.75}}, N_c = 125, Fig. 3, eq (32).\n"
                "`--threads 2 --trials 0.25` and [the run](results/x/0.75.csv)\n"
                "```sh\ndabench run --tol 0.001\n```\n"
                "<!-- 0.12 in a comment -->\n")
        self.assertEqual(template.lint(text, "t.md"), [])


if __name__ == "__main__":
    unittest.main()
