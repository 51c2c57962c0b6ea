"""In-process tests of ctest times, the suite time, the schedule model and the shards."""
import os
import re
import shutil
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import synthetic  # noqa: E402
from erythro_report import schedule  # noqa: E402
from erythro_report.ctest_times import read_junit, read_times, write_times  # noqa: E402
from erythro_report.records import read_record  # noqa: E402
from erythro_report.timing import attach_times, duration_text, read_runs  # noqa: E402


def write_junit(path, elapsed, tests):
    """A file as `ctest --output-junit` writes it; tests: {name: (seconds, status)}."""
    cases = "".join(f'\t<testcase name="{n}" classname="{n}" time="{t}" status="{s}">\n'
                    f'\t\t<system-out>…</system-out>\n\t</testcase>\n' for n, (t, s) in tests.items())
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(f'<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="x" tests="{len(tests)}" '
                 f'failures="0" disabled="0" skipped="0" hostname="" time="{elapsed}" '
                 f'timestamp="2026-01-01T00:00:00" >\n{cases}</testsuite>\n')


class TempDir(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="erythro-timing-test-")
        self.addCleanup(shutil.rmtree, self.tmp, True)

    def path(self, *parts):
        path = os.path.join(self.tmp, *parts)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        return path


class Times(TempDir):
    def test_record_time_first_then_ctest(self):
        synthetic.passing_case(self.path("a", "p.h5"), case="p")
        synthetic.write_record(self.path("b", "q.h5"), "q", wall_time_s=None,
                               metrics=[synthetic.metric("m", 1.0, 1.0, 0.1)])
        write_junit(self.path("a", "ctest-full.junit.xml"), 100, {"p": (2.0, "run"), "unit.x": (7.0, "run")})
        write_junit(self.path("b", "ctest-full.junit.xml"), 300, {"q": (30.0, "fail")})
        write_junit(self.path("b", "ctest-benchmark.junit.xml"), 50, {"benchmark.fluid": (50.0, "run")})
        records = [read_record(self.path("a", "p.h5")), read_record(self.path("b", "q.h5"))]
        runs, problems = read_runs([self.path("a"), self.path("b")])
        timing = attach_times(records, runs)
        self.assertEqual(problems, [])
        self.assertEqual([(r.time_s, r.time_source) for r in records], [(1.5, "record"), (30.0, "ctest")])
        self.assertEqual([t.name for t in timing.tests], ["benchmark.fluid", "q", "unit.x", "p"])
        self.assertEqual(timing.tests[1].ctest_verdict, "fail")
        self.assertEqual(timing.wall_s, 350)       # folders side by side; runs in a folder add up
        self.assertEqual(timing.n_ctest_fallback, 1)

    def test_timings_file_round_trip_and_junit(self):
        write_times(self.path("t.tsv"), {"a": 1.0, "b": 20.5}, ["measured here"])
        self.assertEqual(read_times(self.path("t.tsv")), {"a": 1.0, "b": 20.5})
        with open(self.path("t.tsv"), encoding="utf-8") as fh:
            self.assertEqual(fh.read().splitlines()[2], "b\t20.50")   # slowest first
        write_junit(self.path("j.junit.xml"), 12, {"a": (1.25, "run")})
        self.assertEqual(read_junit(self.path("j.junit.xml")).tests, {"a": 1.25})

    def test_duration_text(self):
        self.assertEqual([duration_text(s) for s in (0.5, 42, 185, 3720, float("nan"))],
                         ["0.5 s", "42 s", "3 min 05 s", "1 h 02 min", "—"])


class Schedule(unittest.TestCase):
    tests = [schedule.Test(n, i, c) for i, (n, c) in enumerate(
        [("u1", 1), ("v.long", 100), ("v.mid", 40), ("v.new", 0), ("r.x", 30), ("u2", 2)])]

    def test_longest_first_on_two_slots(self):
        order = schedule.ctest_order(self.tests)
        self.assertEqual(order[0].name, "v.long")
        durations = {t.name: t.cost for t in self.tests}
        wall, start = schedule.simulate(order, durations, 2)
        self.assertEqual(wall, 100)          # the longest runs alone while the rest share a slot
        self.assertEqual(start["v.long"], 0)
        self.assertEqual(schedule.simulate(order, durations, 1)[0], 173)

    def test_processors_wait_for_free_slots(self):
        tests = [schedule.Test("a", 0, 10, 2), schedule.Test("b", 1, 10, 1), schedule.Test("c", 2, 10, 1)]
        wall, start = schedule.simulate(tests, {"a": 10, "b": 10, "c": 10}, 2)
        self.assertEqual((wall, start["b"]), (20, 10))

    def test_shards_cover_every_test_once_and_balance(self):
        for count in (1, 2, 3, 7):
            parts = schedule.shards(self.tests, count)
            names = sorted(t.name for p in parts for t in p)
            self.assertEqual(names, sorted(t.name for t in self.tests))
            self.assertEqual(parts, schedule.shards(list(reversed(self.tests)), count))  # deterministic
        loads = [sum(schedule.shard_costs(self.tests)[t.name] for t in p)
                 for p in schedule.shards(self.tests, 2)]
        self.assertEqual(sorted(loads), [101, 102])   # v.new counts as the median cost, 30

    def test_regex_matches_exactly_the_names(self):
        regex = re.compile(schedule.name_regex(["v.long", "r.x"]))
        self.assertTrue(regex.match("v.long") and regex.match("r.x"))
        self.assertFalse(regex.match("vXlong") or regex.match("v.long_ci") or regex.match("r.x2"))


if __name__ == "__main__":
    unittest.main()
