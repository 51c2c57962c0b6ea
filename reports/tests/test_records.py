"""In-process tests of the reading and formatting modules."""
import os
import shutil
import sys
import tempfile
import unittest
from types import SimpleNamespace

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

import synthetic  # noqa: E402
from erythro_report import formatting as fmt  # noqa: E402
from erythro_report.expected import read_expected, required_cases  # noqa: E402
from erythro_report.model import check_record  # noqa: E402
from erythro_report.records import RecordError, read_record  # noqa: E402


class TempDir(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="erythro-records-test-")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def path(self, name):
        return os.path.join(self.tmp, name)


class ReadRecord(TempDir):
    def read(self, fixed):
        path = self.path(f"rec_{fixed}.h5")
        synthetic.passing_case(path, fixed=fixed)
        return read_record(path)

    def test_fixed_and_variable_length_strings_read_the_same(self):
        fixed, vlen = self.read(True), self.read(False)
        for r in (fixed, vlen):
            self.assertEqual(r.case, "poiseuille_2d")
            self.assertEqual(r.verdict, "pass")
            self.assertEqual(r.parameters, {"N": 64, "collision": "BGK", "tau": 0.8})
            self.assertEqual(r.runs.columns, ["N", "collision", "error"])
            self.assertEqual(r.runs.data["collision"], ["BGK"] * 4)
            self.assertEqual(r.speed_error[0].label, ["N=16", "N=32", "N=64", "N=128"])
            self.assertEqual([m.comparison for m in r.metrics], ["at_most", "relative", "absolute"])
            self.assertEqual(r.convergence[0].norm, "relative L2 velocity")
            self.assertIs(r.convergence[0].asymptotic, True)
            self.assertEqual(r.series[0].xlabel, "y / H")
            self.assertEqual(check_record(r), [])
        self.assertEqual([m.tolerance_reason for m in fixed.metrics],
                         [m.tolerance_reason for m in vlen.metrics])

    def test_series_x_scale_is_read_and_defaults_to_linear(self):
        path = self.path("scales.h5")
        synthetic.write_record(path, "scales", series=[
            dict(name="D_vs_G", x=[0.0025, 0.01, 0.2], y=[0.1, 0.16, 0.42], x_scale="log"),
            dict(name="history", x=[0.1, 0.2], y=[0.3, 0.31])])
        r = read_record(path)
        self.assertEqual([s.x_scale for s in r.series], ["log", "linear"])

    def test_file_without_case_attribute_is_not_a_record(self):
        with h5py.File(self.path("other.h5"), "w") as f:
            f.attrs["kind"] = "mesh"
        self.assertIsNone(read_record(self.path("other.h5")))

    def test_corrupt_file_raises_naming_it(self):
        with open(self.path("bad.h5"), "wb") as fh:
            fh.write(b"not hdf5")
        with self.assertRaisesRegex(RecordError, "bad.h5"):
            read_record(self.path("bad.h5"))

    def test_unknown_schema_version_is_flagged(self):
        synthetic.write_record(self.path("v2.h5"), "v2", schema_version=2,
                               metrics=[synthetic.metric("m", 1.0, 1.0, 0.1)])
        problems = check_record(read_record(self.path("v2.h5")))
        self.assertEqual(len(problems), 1)
        self.assertIn("schema_version", problems[0].message)


class Expected(TempDir):
    def test_comments_labels_and_filter(self):
        with open(self.path("e.tsv"), "w", encoding="utf-8") as fh:
            fh.write("# case\tlabels\n\na\tverification,full,ci\nb\tvalidation,full\nc\tCI\n")
        expected = read_expected(self.path("e.tsv"))
        self.assertEqual([e.case for e in expected], ["a", "b", "c"])
        self.assertEqual(required_cases(expected), ["a", "b", "c"])
        self.assertEqual(required_cases(expected, ("ci",)), ["a", "c"])
        self.assertEqual(required_cases(expected, ("validation", "nothing")), ["b"])


class Formatting(unittest.TestCase):
    def test_cheapest_setup_picks_smallest_wall_time_below_target(self):
        class R:
            speed_error = [
                SimpleNamespace(name="BGK", wall_time_s=np.array([1.0, 2.0, 8.0]),
                                          error=np.array([1e-2, 9e-4, 1e-4]), label=["a", "b", "c"]),
                SimpleNamespace(name="TRT", wall_time_s=np.array([3.0, 0.5]),
                                          error=np.array([5e-4, 2e-3]), label=["d", "e"]),
            ]
        self.assertEqual(fmt.cheapest_setup(R), ("BGK", "b", 2.0, 9e-4))
        self.assertEqual(fmt.cheapest_text(R), "BGK b (2 s, error 0.0009)")
        R.speed_error = R.speed_error[1:2]
        R.speed_error[0].error = np.array([5e-3, 2e-3])
        self.assertEqual(fmt.cheapest_text(R), "none reaches 1e-3")

    def test_number_and_tolerance_text(self):
        self.assertEqual(fmt.number(float("nan")), "—")
        self.assertEqual(fmt.number(0.000123456789), "0.000123457")
        m = SimpleNamespace(comparison="relative", tolerance=0.02, unit="",
                                      expected=1.0, value=1.01)
        self.assertEqual(fmt.tolerance_text(m), "± 2 % (relative)")
        m.comparison = "at_least"
        self.assertEqual(fmt.expected_text(m), "≥ 1")


if __name__ == "__main__":
    unittest.main()


class StabilityMap(TempDir):
    """A record whose runs hold (model, tau, U, stable) gets a stability-map figure."""

    def _record(self, columns):
        from erythro_report.records import Runs
        data = {"model": ["BGK", "BGK", "TRT", "TRT"], "tau": np.array([0.51, 0.6, 0.51, 0.6]),
                "U": np.array([0.1, 0.1, 0.1, 0.1]), "stable": np.array([0.0, 1.0, 1.0, 1.0])}
        data = {k: v for k, v in data.items() if k in columns}
        return SimpleNamespace(case="verification.stability_map", runs=Runs(columns=list(data), data=data))

    def test_map_drawn(self):
        from erythro_report import plots
        record = self._record(plots.STABILITY_COLUMNS)
        path = os.path.join(self.tmp, "map.png")
        self.assertTrue(plots.has_stability_map(record))
        self.assertTrue(plots.stability_map_figure(record, path))
        self.assertGreater(os.path.getsize(path), 1000)

    def test_no_map_without_columns(self):
        from erythro_report import plots
        record = self._record(("model", "tau", "U"))
        self.assertFalse(plots.has_stability_map(record))
        self.assertFalse(plots.stability_map_figure(record, os.path.join(self.tmp, "none.png")))
