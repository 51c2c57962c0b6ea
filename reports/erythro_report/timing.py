"""How long the suite and each case took.

A case's time is its record's root attribute `wall_time_s` when that is a positive
number; otherwise ctest's own time for the test of the same name, read from the
JUnit files (`*.junit.xml`) in the results folders. Tests without a record (unit,
regression) are timed by ctest alone.

The suite's wall time: the runs in one results folder ran one after the other on
one machine, so their elapsed times add up; shards in separate folders ran side by
side, so the suite took as long as its slowest folder.
"""
import math
from dataclasses import dataclass, field

from .ctest_times import TimesError, junit_files, read_junit

SLOWEST_SHOWN = 10


@dataclass
class TimedTest:
    name: str
    seconds: float
    source: str            # "record" or "ctest"
    record_path: str = ""  # the case's record, "" for a test without one
    ctest_status: str = "" # JUnit status: "run" (passed), "fail", … ("" if not in a JUnit file)

    @property
    def ctest_verdict(self):
        """'pass' / 'fail' from ctest's status, '' when unknown."""
        return {"run": "pass", "fail": "fail"}.get(self.ctest_status, "")


@dataclass
class SuiteTiming:
    folders: list = field(default_factory=list)   # (folder, [CtestRun]) with at least one run
    tests: list = field(default_factory=list)     # TimedTest, slowest first
    untimed_cases: list = field(default_factory=list)

    @property
    def measured(self):
        return bool(self.tests)

    @property
    def wall_s(self):
        """The suite's wall time from ctest's runs, NaN without JUnit files."""
        walls = [sum(run.elapsed_s for run in runs) for _, runs in self.folders]
        return max(walls) if walls else float("nan")

    @property
    def sum_s(self):
        return sum(t.seconds for t in self.tests)

    @property
    def n_runs(self):
        return sum(len(runs) for _, runs in self.folders)

    @property
    def n_ctest_fallback(self):
        return sum(1 for t in self.tests if t.record_path and t.source == "ctest")

    def slowest(self, n=SLOWEST_SHOWN):
        return self.tests[:n]


def read_runs(folders):
    """[(folder, [CtestRun])] and the problems met: (file, message)."""
    result, problems = [], []
    for folder in folders:
        runs = []
        for path in junit_files(folder):
            try:
                runs.append(read_junit(path))
            except TimesError as exc:
                problems.append((path, str(exc).removeprefix(f"{path}: ")))
        if runs:
            result.append((folder, runs))
    return result, problems


def attach_times(records, folders_runs):
    """Sets record.time_s / time_source and returns the SuiteTiming."""
    ctest, status = {}, {}
    for _, runs in folders_runs:
        for run in runs:
            ctest.update({k: v for k, v in run.tests.items() if not math.isnan(v)})
            status.update(run.status)
    timing = SuiteTiming(folders=folders_runs)
    with_record = set()
    for r in records:
        with_record.add(r.case)
        if math.isfinite(r.wall_time_s) and r.wall_time_s > 0:
            r.time_s, r.time_source = r.wall_time_s, "record"
        elif r.case in ctest:
            r.time_s, r.time_source = ctest[r.case], "ctest"
        else:
            r.time_s, r.time_source = float("nan"), ""
            timing.untimed_cases.append(r.case)
            continue
        timing.tests.append(TimedTest(r.case, r.time_s, r.time_source, r.path,
                                      status.get(r.case, "")))
    timing.tests += [TimedTest(name, seconds, "ctest", "", status.get(name, ""))
                     for name, seconds in ctest.items() if name not in with_record]
    timing.tests.sort(key=lambda t: (-t.seconds, t.name))
    return timing


def duration_text(seconds):
    """'42 s', '3 min 05 s', '1 h 02 min'; '—' for NaN."""
    if seconds is None or not math.isfinite(seconds):
        return "—"
    if seconds < 10:
        return f"{seconds:.2g} s" if seconds < 1 else f"{seconds:.1f} s"
    s = int(round(seconds))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {(s % 3600) // 60:02d} min"
