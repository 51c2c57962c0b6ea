"""ci/vv-shard.sh and ci/vv-merge.sh end to end, on a small CMake project whose tests write
synthetic records (it uses cmake/VVCase.cmake, so COST seeding is exercised too)."""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

from test_merge import normalised

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CASES = ["verification.a", "verification.b", "validation.c", "validation.d", "validation.e"]
TIMES = {"validation.c": 30.0, "verification.a": 20.0, "validation.d": 10.0}   # b, e: unknown

PROJECT = """cmake_minimum_required(VERSION 3.25)
project(fake NONE)
set(ERYTHRO_RESULTS_DIR "${{CMAKE_BINARY_DIR}}/results" CACHE PATH "")
file(MAKE_DIRECTORY "${{ERYTHRO_RESULTS_DIR}}")
set(ERYTHRO_TIMINGS_FILE "${{CMAKE_SOURCE_DIR}}/full.tsv" CACHE FILEPATH "")
enable_testing()
include({root}/cmake/VVCase.cmake)
{cases}
erythro_add_test(NAME unit.fake COMMAND /usr/bin/python3 -c "pass" LABELS unit)
vv_write_manifest()
"""


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=300, **kw)


class ShardScript(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="erythro-shard-test-")
        src, cls.build = os.path.join(cls.tmp, "src"), os.path.join(cls.tmp, "build")
        os.makedirs(src)
        cases = "\n".join(f"vv_add_case(CASE {c} COMMAND /usr/bin/python3 {HERE}/write_case.py {c} "
                          "LABELS verification)" for c in CASES)
        with open(os.path.join(src, "CMakeLists.txt"), "w", encoding="utf-8") as fh:
            fh.write(PROJECT.format(root=ROOT, cases=cases))
        with open(os.path.join(src, "full.tsv"), "w", encoding="utf-8") as fh:
            fh.write("# test\tseconds\n" + "".join(f"{k}\t{v}\n" for k, v in TIMES.items()))
        configure = run(["cmake", "-S", src, "-B", cls.build])
        assert configure.returncode == 0, configure.stderr
        env = dict(os.environ, ERYTHRO_BUILD_DIR=cls.build, ERYTHRO_SKIP_BUILD="1")
        cls.shards = [run(["bash", f"{ROOT}/ci/vv-shard.sh", str(k), "2", os.path.join(cls.tmp, f"s{k}")],
                          env=env) for k in (1, 2)]
        cls.single = run(["bash", f"{ROOT}/ci/vv-shard.sh", "1", "1", os.path.join(cls.tmp, "all")], env=env)
        cls.merge = run(["bash", f"{ROOT}/ci/vv-merge.sh", os.path.join(cls.tmp, "r-merged"),
                         os.path.join(cls.tmp, "s1"), os.path.join(cls.tmp, "s2")])
        cls.one = run(["bash", f"{ROOT}/ci/vv-merge.sh", os.path.join(cls.tmp, "r-one"),
                       os.path.join(cls.tmp, "all")])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def records(self, folder):
        return sorted(n[:-3] for n in os.listdir(os.path.join(self.tmp, folder)) if n.endswith(".h5"))

    def test_cost_is_seeded_from_the_timings_file(self):
        out = run(["ctest", "--test-dir", self.build, "-N", "--show-only=json-v1"]).stdout
        costs = {t["name"]: {p["name"]: p["value"] for p in t["properties"]}.get("COST")
                 for t in json.loads(out)["tests"]}
        self.assertEqual(costs["validation.c"], 30.0)
        self.assertIsNone(costs["verification.b"])

    def test_each_case_runs_in_exactly_one_shard(self):
        for proc in self.shards + [self.single]:
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        s1, s2 = self.records("s1"), self.records("s2")
        self.assertEqual(set(s1) & set(s2), set())
        self.assertEqual(sorted(s1 + s2), sorted(CASES))
        self.assertEqual(self.records("all"), sorted(CASES))
        for k in (1, 2):
            self.assertTrue(os.path.isfile(os.path.join(self.tmp, f"s{k}", "ctest-full.junit.xml")))

    def test_merged_report_passes_and_matches_one_folder(self):
        self.assertEqual(self.merge.returncode, 0, self.merge.stdout + self.merge.stderr)
        folders = [os.path.join(self.tmp, n) for n in ("all", "s1", "s2")]
        one = normalised(os.path.join(self.tmp, "r-one", "summary.md"), folders)
        merged = normalised(os.path.join(self.tmp, "r-merged", "summary.md"), folders)
        cut = lambda text: text[:text.index("## Time")]   # noqa: E731  (times are measured)
        self.assertEqual(cut(one), cut(merged))
        self.assertIn("2 folders run side by side", merged)


if __name__ == "__main__":
    unittest.main()
