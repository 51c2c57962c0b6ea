"""Tests of reports/doc_tables.py: measured sections of docs pages generated from records."""
import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import synthetic

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from erythro_report.doc_markdown import prose  # noqa: E402
from erythro_report.doc_sections import MarkerError, find_sections, parse_marker  # noqa: E402
from erythro_report.doc_tables_cli import main  # noqa: E402

SCRIPT = os.path.join(os.path.dirname(HERE), "doc_tables.py")
CASE = "validation.capsule_shear"

PAGE = f"""# Validation: capsule

Why the case exists, and how it runs (kept by the tool).

<!-- measured: {CASE} runs: capillary,D where: role=study -->
<!-- end measured -->

Discussion after the table.

<!-- measured: validation.not_run_here -->
Hand-written text of a case without a record.
<!-- end measured -->
"""


def capsule_record(path, d_value=0.355):
    synthetic.write_record(
        path, CASE, family="validation.capsule",
        metrics=[synthetic.metric("D_G=0.10", d_value, 0.342, 0.05, unit="",
                                  description="Taylor deformation at G = 0.1",
                                  reason="Barthes-Biesel *table* | read off a figure"),
                 synthetic.metric("max_area_change", 0.002, 0.005, 0.0, comparison="at_most",
                                  description="max |A/A0 - 1|")],
        runs={"capillary": [0.05, 0.1, 0.1], "D": [0.2, d_value, 0.36],
              "role": ["study", "study", "check"]})


class DocTablesTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="erythro-doc-tables-test-")
        self.addCleanup(shutil.rmtree, self.tmp, True)
        self.results = os.path.join(self.tmp, "results")
        self.docs = os.path.join(self.tmp, "docs")
        os.makedirs(self.results)
        os.makedirs(self.docs)
        self.page = os.path.join(self.docs, "validation-capsule.md")
        self.write_page(PAGE)
        capsule_record(os.path.join(self.results, f"{CASE}.h5"))

    def write_page(self, text):
        with open(self.page, "w", encoding="utf-8") as fh:
            fh.write(text)

    def read_page(self):
        with open(self.page, encoding="utf-8") as fh:
            return fh.read()

    def run_tool(self, mode):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            status = main([self.results, f"--{mode}", "--docs", self.docs])
        return status, err.getvalue()

    def test_write_fills_the_section_then_check_passes(self):
        status, _ = self.run_tool("write")
        self.assertEqual(status, 0)
        text = self.read_page()
        self.assertIn("meets its requirement", text)          # the record's requirement
        self.assertIn("Synthetic et al. (2024)", text)        # its reference
        self.assertIn("git revision abc1234", text)
        self.assertIn(f"`{CASE}.h5`", text)
        self.assertIn("| D_G=0.10 | Taylor deformation at G = 0.1 | 0.355 | 0.342 | ± 0.05 | "
                      "absolute | pass | Barthes-Biesel \\*table\\* \\| read off a figure |", text)
        self.assertIn("| max_area_change | max \\|A/A0 - 1\\| | 0.002 | ≤ 0.005 | — | at most |",
                      text)
        self.assertIn("| capillary | D |\n| --- | --- |\n| 0.05 | 0.2 |\n| 0.1 | 0.355 |\n\n", text)
        self.assertIn("Why the case exists", text)
        self.assertIn("Discussion after the table.", text)
        status, err = self.run_tool("check")
        self.assertEqual(status, 0, err)
        self.assertIn("1 sections up to date, 0 differ, 1 skipped", err)

    def test_changed_number_makes_check_fail_naming_page_and_case(self):
        self.run_tool("write")
        capsule_record(os.path.join(self.results, f"{CASE}.h5"), d_value=0.371)
        before = self.read_page()
        status, err = self.run_tool("check")
        self.assertEqual(status, 1)
        self.assertIn("validation-capsule.md:5 validation.capsule_shear", err)
        self.assertIn("DIFFERS", err)
        self.assertEqual(self.read_page(), before)             # --check writes nothing
        self.assertEqual(self.run_tool("write")[0], 0)
        self.assertIn("| 0.371 |", self.read_page())

    def test_case_without_record_is_skipped_not_emptied(self):
        status, err = self.run_tool("write")
        self.assertEqual(status, 0)
        self.assertIn("Hand-written text of a case without a record.", self.read_page())
        self.assertIn("skipped (no record in the given results): ", err)
        self.assertIn("validation.not_run_here", err)

    def test_unknown_run_column_is_an_error_and_leaves_the_section(self):
        self.write_page(PAGE.replace("runs: capillary,D", "runs: capillary,theta_deg"))
        status, err = self.run_tool("write")
        self.assertEqual(status, 1)
        self.assertIn("no column theta_deg", err)
        self.assertNotIn("Synthetic et al.", self.read_page())

    def test_metric_parameter_and_row_selection(self):
        self.write_page(PAGE.replace("runs: capillary,D where: role=study",
                                     "runs: D where: capillary=0.05|0.1,role=check "
                                     "metrics: max_* params: tau,collision"))
        self.assertEqual(self.run_tool("write")[0], 0)
        text = self.read_page()
        self.assertIn("2 of 2 metrics passed; 1 shown below", text)
        self.assertNotIn("| D_G=0.10 |", text)
        self.assertIn("| tau | 0.8 |\n| collision | BGK |", text)
        self.assertIn("Runs: 1 of 3 rows, selected columns:\n\n| D |\n| --- |\n| 0.36 |", text)

    def test_second_section_of_a_case_shows_only_its_parts(self):
        self.write_page(PAGE + f"\n<!-- measured: {CASE} parts: params params: tau -->\n"
                               "<!-- end measured -->\n")
        self.assertEqual(self.run_tool("write")[0], 0)
        second = self.read_page().split("parts: params")[1]
        self.assertIn("git revision abc1234", second)
        self.assertIn("| tau | 0.8 |", second)
        self.assertNotIn("Requirement", second)
        self.assertNotIn("D_G=0.10", second)

    def test_script_runs_as_a_program(self):
        proc = subprocess.run(["/usr/bin/python3", SCRIPT, self.results, "--check",
                               "--docs", self.docs], capture_output=True, text=True, timeout=60)
        self.assertEqual(proc.returncode, 1, proc.stderr)      # the empty section differs
        proc = subprocess.run(["/usr/bin/python3", SCRIPT, self.results], capture_output=True,
                              text=True, timeout=60)
        self.assertEqual(proc.returncode, 2)                   # --write or --check is required


class MarkersTest(unittest.TestCase):
    def test_settings_of_a_marker(self):
        s = parse_marker("v.case runs: a,b , c metrics: order*,mass params: tau "
                         "where: N=64|128,part=c shear wave", 3)
        self.assertEqual((s.case, s.runs, s.metrics), ("v.case", ["a", "b", "c"], ["order*", "mass"]))
        self.assertEqual(s.params, ["tau"])
        self.assertEqual(s.where, [("N", "64|128"), ("part", "c shear wave")])

    def test_unpaired_markers_are_errors(self):
        with self.assertRaises(MarkerError):
            find_sections("<!-- measured: a -->\ntext\n")
        with self.assertRaises(MarkerError):
            find_sections("<!-- end measured -->\n")
        with self.assertRaises(MarkerError):
            find_sections("<!-- measured: a -->\n<!-- measured: b -->\n<!-- end measured -->\n")

    def test_record_text_is_shown_verbatim(self):
        self.assertEqual(prose("2*3 <= x_1 and <b>, _x_"), "2\\*3 <= x_1 and \\<b>, \\_x\\_")


if __name__ == "__main__":
    unittest.main()
