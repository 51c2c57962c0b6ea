"""End-to-end tests of reports/generate.py, run as a subprocess on synthetic records."""
import os
import re
import shutil
import subprocess
import tempfile
import unittest

import h5py

import synthetic

HERE = os.path.dirname(os.path.abspath(__file__))
GENERATE = os.path.join(os.path.dirname(HERE), "generate.py")
PYTHON = "/usr/bin/python3"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


class Workspace:
    """A temporary results folder and report folder, with helpers to fill and run them."""

    def __init__(self):
        self.tmp = tempfile.mkdtemp(prefix="erythro-report-test-")
        self.results = os.path.join(self.tmp, "results")
        self.out = os.path.join(self.tmp, "report")
        os.makedirs(self.results)

    def remove(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def record(self, name):
        return os.path.join(self.results, name)

    def write_expected(self, rows):
        with open(self.record("expected_cases.tsv"), "w", encoding="utf-8") as fh:
            fh.write("# case\tlabels (written by CMake)\n")
            for case, labels in rows:
                fh.write(f"{case}\t{labels}\n")

    def run_generate(self, *extra, out=True):
        args = [PYTHON, GENERATE, *extra]
        if out:
            args += ["--out", self.out]
        return subprocess.run(args, capture_output=True, text=True, timeout=300)

    def read_out(self, name):
        with open(os.path.join(self.out, name), encoding="utf-8") as fh:
            return fh.read()


class GenerateTestCase(unittest.TestCase):
    """Each test gets a fresh workspace `self.ws`."""

    def setUp(self):
        self.ws = Workspace()
        self.addCleanup(self.ws.remove)

    def assert_report_written(self, proc):
        index = os.path.join(self.ws.out, "index.html")
        self.assertEqual(proc.stdout.strip().splitlines()[-1], os.path.abspath(index))
        self.assertTrue(os.path.isfile(index))
        self.assertTrue(os.path.isfile(os.path.join(self.ws.out, "summary.md")))


class SharedReportTestCase(GenerateTestCase):
    """All tests of the class read one report, made once by make_report()."""

    @classmethod
    def setUpClass(cls):
        cls.ws = Workspace()
        cls.proc = cls.make_report(cls.ws)

    @classmethod
    def tearDownClass(cls):
        cls.ws.remove()

    def setUp(self):
        pass


class PassingReport(SharedReportTestCase):
    @staticmethod
    def make_report(ws):
        synthetic.passing_case(ws.record("poiseuille_2d.h5"))
        ws.write_expected([("poiseuille_2d", "verification,full,ci")])
        os.makedirs(ws.record("regression"))
        with open(ws.record("regression/fluid.txt"), "w", encoding="utf-8") as fh:
            fh.write(synthetic.REGRESSION_PASSED)
        return ws.run_generate(ws.results)

    def test_exit_status_0_when_all_pass(self):
        self.assertEqual(self.proc.returncode, 0, self.proc.stderr)
        self.assert_report_written(self.proc)

    def test_images_referenced_by_index_exist(self):
        html = self.ws.read_out("index.html")
        sources = re.findall(r"<img src='([^']+)'", html)
        # convergence, speed-error and series of the case, and the overview figure
        self.assertEqual(len(sources), 4, sources)
        for src in sources:
            self.assertFalse(os.path.isabs(src), src)
            self.assertTrue(src.startswith("img/"), src)
            with open(os.path.join(self.ws.out, src), "rb") as fh:
                self.assertEqual(fh.read(8), PNG_MAGIC, src)

    def test_html_shows_table_sections_and_cheapest_setup(self):
        html = self.ws.read_out("index.html")
        self.assertIn("1 case, 3 metrics, 0 failed cases", html)
        self.assertIn("git revision abc1234", html)
        for text in ("order_bgk_tau0.8", "observed order, BGK", "± 0.1 (absolute)",
                     "chosen for the test", "Local orders, BGK tau=0.8",
                     "Local orders, TRT magic=0.25", "u(y) at x = L/2", "Runs (4)"):
            self.assertIn(text, html)
        self.assertIn("<strong>TRT N=32 (0.096 s, error 0.0005)</strong>", html)
        self.assertIn("<td class=\"pass verdict\">PASS</td>", html)
        self.assertNotIn("class=\"fail", html)

    def test_one_row_per_case_comes_before_the_details(self):
        html = self.ws.read_out("index.html")
        row = ("<td class='num'>3 / 3</td><td class='key'>order_bgk_tau0.8 = 1.98 (2 ± 0.1)</td>"
               "<td class='num'>1.5 s</td>")
        self.assertIn(row, html)
        self.assertLess(html.index(row), html.index("<details class='case' id='case-poiseuille_2d'>"))
        self.assertIn("Slowest tests", html)

    def test_regression_is_summarised_and_its_text_kept(self):
        html = self.ws.read_out("index.html")
        self.assertIn("/fields/velocity", html)
        self.assertIn("within atol", html)
        self.assertIn("large only where the baseline is near 0", html)
        self.assertNotIn("<td>same</td>", html)
        self.assertIn("same  /fields/velocity: max |diff| = 3e-15, max rel = 159", html)   # verbatim

    def test_summary_md_has_one_row_per_case_then_the_metrics(self):
        md = self.ws.read_out("summary.md")
        self.assertIn("**PASS**", md)
        self.assertIn("| verification.fluid | poiseuille_2d | PASS | 3 / 3 | order_bgk_tau0.8 = 1.98 (2 ± 0.1) | 1.5 s |", md)
        self.assertLess(md.index("## Cases"), md.index("## Metrics of each case"))
        self.assertEqual(md.count("poiseuille_2d meets its requirement"), 1)
        self.assertIn("| order_bgk_tau0.8: observed order, BGK | 1.98 | 2 | ± 0.1 (absolute) | PASS |", md)
        self.assertIn("| error_N128: relative L2 error at N=128 | 4e-05 | ≤ 0.0001 |", md)
        self.assertIn("| mass_drift: mass after 1000 steps | 1.001 | 1 | ± 1 % (relative) | PASS | as above |",
                      md)
        self.assertIn("| fluid.txt | PASS | 3 datasets within tolerance (1 identical) |", md)

    def test_regenerating_into_the_same_folder_works(self):
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(len(os.listdir(os.path.join(self.ws.out, "img"))), 4)


class FailingReport(SharedReportTestCase):
    @staticmethod
    def make_report(ws):
        synthetic.passing_case(ws.record("poiseuille_2d.h5"))
        synthetic.failing_case(ws.record("couette_2d.h5"))
        return ws.run_generate(ws.results)

    def test_exit_status_1_and_report_still_written(self):
        self.assertEqual(self.proc.returncode, 1)
        self.assert_report_written(self.proc)
        self.assertIn("couette_2d", self.proc.stderr)
        self.assertIn("order_wall", self.proc.stderr)

    def test_failed_metric_is_red_and_table_sorted_by_family(self):
        html = self.ws.read_out("index.html")
        self.assertIn("<td class=\"fail verdict\">FAIL</td>", html)
        # verification.boundary sorts before verification.fluid
        self.assertLess(html.index("#case-couette_2d"), html.index("#case-poiseuille_2d"))
        self.assertIn("2 cases, 5 metrics, 1 failed case (1 failed metric)", html)
        failed = "<li><a href='#case-couette_2d'><strong>couette_2d</strong></a>: failed metrics order_wall</li>"
        self.assertIn(failed, html)
        self.assertLess(html.index(failed), html.index("<h2 id='cases'>"))

    def test_summary_md_escapes_pipes_and_marks_failure(self):
        md = self.ws.read_out("summary.md")
        self.assertIn("**FAIL**", md)
        self.assertLess(md.index("- **couette_2d**: failed metrics order_wall"), md.index("## Cases"))
        self.assertIn("| order_wall: observed order with bounce-back walls | 1.2 | 2 | "
                      "± 0.1 (absolute) | FAIL | Richardson \\| pipes must survive Markdown |", md)
        self.assertIn("| verification.boundary | couette_2d | FAIL | 1 / 2 | order_wall = 1.2 (2 ± 0.1) |", md)
        self.assertIn("| max_velocity: peak velocity | 0.1 lu/ts | 0.1 lu/ts | "
                      "± 1e-06 lu/ts (absolute) | PASS |", md)


class ExpectedCases(GenerateTestCase):
    def setUp(self):
        super().setUp()
        synthetic.passing_case(self.ws.record("poiseuille_2d.h5"))

    def test_missing_expected_case_exits_1_naming_it(self):
        self.ws.write_expected([("poiseuille_2d", "verification,full,ci"),
                             ("womersley_2d", "verification,full,ci")])
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("womersley_2d", proc.stderr)
        self.assert_report_written(proc)
        self.assertIn("<tr><td>womersley_2d</td><td class=\"invalid verdict\">MISSING</td>",
                      self.ws.read_out("index.html"))
        self.assertIn("|  | womersley_2d | MISSING |  | no result record |  |", self.ws.read_out("summary.md"))

    def test_labels_limit_the_required_cases(self):
        self.ws.write_expected([("poiseuille_2d", "verification,full,ci"),
                             ("long_validation", "validation,full")])
        self.assertEqual(self.ws.run_generate(self.ws.results, "--labels", "ci").returncode, 0)
        self.assertEqual(self.ws.run_generate(self.ws.results, "--labels", "ci,validation").returncode, 1)
        self.assertEqual(self.ws.run_generate(self.ws.results).returncode, 1)

    def test_expect_option_overrides_default_file(self):
        self.ws.write_expected([("absent_case", "full")])
        other = os.path.join(self.ws.tmp, "only_poiseuille.tsv")
        with open(other, "w", encoding="utf-8") as fh:
            fh.write("# comment\npoiseuille_2d\tfull,ci\n")
        self.assertEqual(self.ws.run_generate(self.ws.results, "--expect", other).returncode, 0)


class BadRecords(GenerateTestCase):
    def setUp(self):
        super().setUp()
        synthetic.passing_case(self.ws.record("poiseuille_2d.h5"))

    def test_corrupt_h5_exits_1_naming_the_file(self):
        with open(self.ws.record("broken.h5"), "wb") as fh:
            fh.write(b"\x89HDF\r\n\x1a\n" + b"garbage" * 20)
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("broken.h5", proc.stderr)
        self.assert_report_written(proc)

    def test_h5_without_case_attribute_is_ignored(self):
        with h5py.File(self.ws.record("mesh.h5"), "w") as f:
            f["nodes"] = [1.0, 2.0]
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 0, proc.stderr)

    def test_verdict_other_than_pass_or_fail_is_flagged(self):
        synthetic.write_record(self.ws.record("odd.h5"), "odd_case", verdict="maybe",
                               metrics=[synthetic.metric("m", 1.0, 1.0, 0.1, verdict="skipped")])
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("'maybe'", proc.stderr)
        self.assertIn("'skipped'", proc.stderr)
        self.assertIn("class=\"invalid verdict\"", self.ws.read_out("index.html"))

    def test_root_verdict_contradicting_metrics_is_flagged(self):
        synthetic.write_record(self.ws.record("liar.h5"), "liar", verdict="pass",
                               metrics=[synthetic.metric("m", 2.0, 1.0, 0.1, verdict="fail")])
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("liar", proc.stderr)

    def test_no_records_at_all_exits_1(self):
        os.remove(self.ws.record("poiseuille_2d.h5"))
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("no result records", proc.stderr)

    def test_fixed_length_strings_read_like_variable_length(self):
        synthetic.passing_case(self.ws.record("poiseuille_fixed.h5"), case="poiseuille_fixed",
                               fixed=True)
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        md = self.ws.read_out("summary.md")
        self.assertIn("| verification.fluid | poiseuille_fixed | PASS | 3 / 3 | order_bgk_tau0.8 = 1.98 (2 ± 0.1) |", md)
        self.assertIn("Requirement: poiseuille_fixed meets its requirement", md)
        self.assertNotIn("b'", md)


class SpeedErrorTarget(GenerateTestCase):
    def test_none_reaches_the_error_target(self):
        synthetic.write_record(self.ws.record("coarse.h5"), "coarse",
                               metrics=[synthetic.metric("m", 1.0, 1.0, 0.1)],
                               speed_error=[synthetic.speed_series("BGK", 0.01, 0.5)])
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("none reaches 1e-3", self.ws.read_out("index.html"))
        self.assertIn("| coarse | none reaches 1e-3 |", self.ws.read_out("summary.md"))


class RegressionMoved(GenerateTestCase):
    def test_a_moved_dataset_fails_the_report(self):
        synthetic.passing_case(self.ws.record("poiseuille_2d.h5"))
        os.makedirs(self.ws.record("regression"))
        with open(self.ws.record("regression/fluid.txt"), "w", encoding="utf-8") as fh:
            fh.write(synthetic.REGRESSION_MOVED)
        proc = self.ws.run_generate(self.ws.results)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("regression fluid.txt FAILED: 1 of 2 datasets MOVED", proc.stderr)
        self.assertIn("| fluid.txt | FAIL | 1 of 2 datasets MOVED |", self.ws.read_out("summary.md"))


class UsageErrors(GenerateTestCase):
    def test_usage_errors_exit_2(self):
        synthetic.passing_case(self.ws.record("poiseuille_2d.h5"))
        cases = {
            "no arguments": ([], False),
            "no --out": ([self.ws.results], False),
            "unknown option": ([self.ws.results, "--colour"], True),
            "results folder missing": ([os.path.join(self.ws.tmp, "nowhere")], True),
            "--expect file missing": ([self.ws.results, "--expect", os.path.join(self.ws.tmp, "x.tsv")], True),
            "--labels without expected list": ([self.ws.results, "--labels", "ci"], True),
        }
        for name, (args, out) in cases.items():
            with self.subTest(name):
                proc = self.ws.run_generate(*args, out=out)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertTrue(proc.stderr.strip())


if __name__ == "__main__":
    unittest.main()
