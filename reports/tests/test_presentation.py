"""In-process tests of what the report says: regression wording, flags, key figures,
speed-against-error lines, series order, field pictures."""
import os
import shutil
import sys
import tempfile
import unittest
from types import SimpleNamespace

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import synthetic  # noqa: E402
from erythro_report import formatting as fmt  # noqa: E402
from erythro_report import regression, speed  # noqa: E402
from erythro_report.plots import field_figure  # noqa: E402
from erythro_report.records import natural_key, read_record  # noqa: E402


class TempDir(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="erythro-presentation-test-")
        self.addCleanup(shutil.rmtree, self.tmp, True)

    def path(self, name):
        return os.path.join(self.tmp, name)


class RegressionWording(unittest.TestCase):
    def test_pass_never_reads_same_next_to_a_large_relative_difference(self):
        check = regression.parse("fluid.txt", synthetic.REGRESSION_PASSED)
        self.assertEqual(check.verdict, "pass")
        step, velocity, density = check.datasets
        self.assertEqual(step.verdict_text, "identical")
        self.assertEqual((velocity.verdict_text, velocity.max_rel), ("within atol", 159.0))
        self.assertIn("baseline is near 0", velocity.rel_note)
        self.assertEqual(density.verdict_text, "within atol + rtol·|baseline|")
        self.assertEqual(regression.summary_text(check), "3 datasets within tolerance (1 identical)")

    def test_moved_and_unknown_text(self):
        moved = regression.parse("fluid.txt", synthetic.REGRESSION_MOVED)
        self.assertEqual(moved.verdict, "fail")
        self.assertIn("worst at element 7", moved.datasets[1].detail)
        self.assertEqual(regression.parse("x.txt", "something else\n").verdict, "")


def metric(value, expected, tolerance, comparison="absolute", description="", unit=""):
    return SimpleNamespace(name="m", value=value, expected=expected, tolerance=tolerance,
                           comparison=comparison, description=description, unit=unit, verdict="pass")


class Flags(unittest.TestCase):
    def test_flags_read_yes_no(self):
        flag = metric(1.0, 1.0, 0.0)
        self.assertTrue(fmt.is_flag(flag))
        self.assertEqual((fmt.value_text(flag), fmt.expected_text(flag), fmt.tolerance_text(flag)),
                         ("yes", "yes", "yes/no check"))
        self.assertEqual(fmt.value_text(metric(0.0, 1.0, 0.0)), "no")
        self.assertTrue(fmt.is_flag(metric(1.0, 1.0, 0.0, "at_least", "1 if the motion is classified")))

    def test_informative_measurements_read_as_such(self):
        speed = metric(-30.7, float("-inf"), 0.0, "at_least", unit="us")
        self.assertTrue(fmt.is_informative(speed))
        self.assertEqual(fmt.limit_text(speed), "informative: any finite value")
        self.assertFalse(fmt.is_informative(metric(2.0, 1.0, 0.0, "at_least")))

    def test_counts_and_zero_limits_keep_their_numbers(self):
        for m in (metric(1.0, 1.0, 0.0, "at_least", "runs that diverged", unit="runs"),
                  metric(2.0, 1.0, 0.0, "at_least"), metric(0.0, 0.0, 0.0, "at_most"),
                  metric(1.0, 1.0, 0.0, unit="cells"), metric(1.0, 1.0, 0.1)):
            self.assertFalse(fmt.is_flag(m), m)

    def test_key_metric_prefers_failed_then_two_sided_nearest_limit(self):
        ms = [metric(0.5, 1.0, 0.0, "at_most"), metric(1.9, 2.0, 0.2), metric(1.0, 1.0, 0.0),
              metric(2.15, 2.0, 0.2)]
        for i, m in enumerate(ms):
            m.name = f"m{i}"
        record = SimpleNamespace(metrics=ms, key_metric="")
        self.assertEqual(fmt.key_metric(record).name, "m3")
        record.key_metric = "m0"
        self.assertEqual(fmt.key_metric(record).name, "m0")
        record.key_metric, ms[1].verdict = "", "fail"
        self.assertEqual(fmt.key_metric(record).name, "m1")


class SpeedLines(unittest.TestCase):
    def series(self, labels, group=()):
        n = len(labels)
        return SimpleNamespace(name="BGK", wall_time_s=np.arange(1.0, n + 1), error=np.ones(n),
                               label=labels, group=list(group))

    def test_different_tau_are_different_lines(self):
        lines = speed.lines(self.series(["tau=0.6 N=8", "tau=0.6 N=16", "tau=0.8 N=8", "tau=0.8 N=16"]))
        self.assertEqual([(ln.name, ln.labels) for ln in lines],
                         [("BGK tau=0.6", ["N=8", "N=16"]), ("BGK tau=0.8", ["N=8", "N=16"])])

    def test_one_parameter_set_stays_one_line(self):
        for labels in (["N=8", "N=16"], ["shear wave N=32", "shear wave N=64"]):
            self.assertEqual([ln.labels for ln in speed.lines(self.series(labels))], [labels])

    def test_points_joined_in_resolution_order(self):
        lines = speed.lines(self.series(["N=32", "N=8", "N=16"]))
        self.assertEqual(lines[0].labels, ["N=8", "N=16", "N=32"])
        self.assertEqual(list(lines[0].wall_time_s), [2.0, 3.0, 1.0])

    def test_group_dataset_wins(self):
        lines = speed.lines(self.series(["a", "b", "c"], group=["x", "y", "x"]))
        self.assertEqual([(ln.name, ln.labels) for ln in lines], [("BGK x", ["a", "c"]), ("BGK y", ["b"])])


class NaturalOrder(unittest.TestCase):
    def test_numbers_sort_by_value(self):
        names = ["shape gt=10.0", "shape gt=2.0", "D", "shape gt=0.0", "h=0.4", "h=0.3125"]
        self.assertEqual(sorted(names, key=natural_key),
                         ["D", "h=0.3125", "h=0.4", "shape gt=0.0", "shape gt=2.0", "shape gt=10.0"])


class Fields(TempDir):
    def test_field_read_and_drawn(self):
        synthetic.write_record(self.path("f.h5"), "f", metrics=[synthetic.metric("m", 1.0, 1.0, 0.1)],
                               fields=[synthetic.velocity_field(),
                                       dict(name="bad", data=np.zeros(4))])
        record = read_record(self.path("f.h5"))
        self.assertEqual([f.name for f in record.fields], ["velocity"])
        self.assertEqual(len(record.field_errors), 1)
        self.assertIn("bad", record.field_errors[0])
        fld = record.fields[0]
        self.assertEqual((fld.data.shape, fld.unit, len(fld.membranes)), ((24, 48), "mm/s", 1))
        self.assertTrue(field_figure(fld, self.path("f.png")))
        self.assertTrue(os.path.getsize(self.path("f.png")) > 1000)


if __name__ == "__main__":
    unittest.main()
