"""Merging shard folders: the report of two shards equals the report of one folder."""
import filecmp
import os
import re
import shutil
import subprocess
import tempfile
import unittest

import synthetic
from test_generate import GENERATE, PYTHON

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MERGE = os.path.join(ROOT, "ci", "vv-merge.sh")

CASES = {   # case -> shard that runs it
    "verification.poiseuille": 1, "verification.couette": 2, "validation.capsule": 2,
    "verification.womersley": 1,
}
EXPECTED = "".join(f"{case}\tverification,full\n" for case in CASES)


def write_case(folder, case):
    if case == "verification.couette":
        synthetic.failing_case(os.path.join(folder, f"{case}.h5"), case=case)
    else:
        synthetic.passing_case(os.path.join(folder, f"{case}.h5"), case=case)


def fill(folder, cases, regression=True):
    os.makedirs(os.path.join(folder, "regression"), exist_ok=True)
    for case in cases:
        write_case(folder, case)
    with open(os.path.join(folder, "expected_cases.tsv"), "w", encoding="utf-8") as fh:
        fh.write("# case\tlabels\n" + EXPECTED)
    if regression:
        with open(os.path.join(folder, "regression", "fluid.txt"), "w", encoding="utf-8") as fh:
            fh.write(synthetic.REGRESSION_PASSED)


def normalised(path, folders):
    """A report file without what differs by construction: folder names and the time."""
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    for folder in folders:
        text = text.replace(folder, "RESULTS")
    text = re.sub(r"generated \d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", "generated …", text)
    return "\n".join(line for line in text.splitlines() if "Records read from" not in line
                     and "Records merged from" not in line)


class MergeShards(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="erythro-merge-test-")
        cls.single, cls.shard1, cls.shard2 = (os.path.join(cls.tmp, n) for n in ("all", "s1", "s2"))
        fill(cls.single, CASES)
        fill(cls.shard1, [c for c, k in CASES.items() if k == 1])
        fill(cls.shard2, [c for c, k in CASES.items() if k == 2], regression=False)
        cls.one = cls.run_report(os.path.join(cls.tmp, "r-one"), cls.single)
        cls.merged = subprocess.run(["bash", MERGE, os.path.join(cls.tmp, "r-merged"), cls.shard1,
                                     cls.shard2], capture_output=True, text=True, timeout=300)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def run_report(cls, out, *folders):
        return subprocess.run([PYTHON, GENERATE, *folders, "--out", out], capture_output=True,
                              text=True, timeout=300)

    def test_same_verdict_and_exit_status(self):
        self.assertEqual(self.one.returncode, 1)   # couette fails, in both
        self.assertEqual(self.merged.returncode, 1, self.merged.stderr)
        self.assertIn("case verification.couette FAILED", self.merged.stderr)
        self.assertNotIn("no result record", self.merged.stderr)

    def test_merged_report_equals_the_single_folder_report(self):
        folders = [self.single, self.shard1, self.shard2]
        for name in ("summary.md", "index.html"):
            one = normalised(os.path.join(self.tmp, "r-one", name), folders)
            merged = normalised(os.path.join(self.tmp, "r-merged", name), folders)
            self.assertEqual(one, merged, name)
        images = sorted(os.listdir(os.path.join(self.tmp, "r-one", "img")))
        self.assertEqual(images, sorted(os.listdir(os.path.join(self.tmp, "r-merged", "img"))))
        match, mismatch, errors = filecmp.cmpfiles(os.path.join(self.tmp, "r-one", "img"),
                                                   os.path.join(self.tmp, "r-merged", "img"),
                                                   images, shallow=False)
        self.assertEqual((mismatch, errors), ([], []))

    def test_a_case_in_two_shards_is_an_error(self):
        folder = os.path.join(self.tmp, "s3")
        fill(folder, ["verification.poiseuille"], regression=False)
        proc = self.run_report(os.path.join(self.tmp, "r-twice"), self.shard1, self.shard2, folder)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("two records for one case", proc.stderr)
        self.assertIn(os.path.join(folder, "verification.poiseuille.h5"), proc.stderr)

    def test_a_case_in_no_shard_is_an_error(self):
        proc = self.run_report(os.path.join(self.tmp, "r-missing"), self.shard1)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("verification.couette: required case has no result record", proc.stderr)


if __name__ == "__main__":
    unittest.main()
