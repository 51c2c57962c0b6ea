"""Gathering result records into one report: reading, sorting and checking.

The C++ tests decide every verdict; nothing here recomputes one. The checks
only flag records that cannot be trusted as written: an unreadable file, a
verdict other than "pass"/"fail", a root verdict that contradicts the metric
verdicts, an unknown schema version, two files for one case, or a required
case without a record.
"""
import datetime
import glob
import os
from dataclasses import dataclass, field

from . import regression
from .timing import SuiteTiming, attach_times, read_runs
from .expected import ExpectedFileError, read_expected, required_cases
from .records import SCHEMA_VERSION, RecordError, read_record


@dataclass
class Problem:
    subject: str   # the file or case concerned
    message: str

    def __str__(self):
        return f"{self.subject}: {self.message}"


@dataclass
class Report:
    results_dirs: list          # one folder, or one per shard
    expect_files: list          # [] when there is no expected list
    labels: tuple
    records: list               # sorted by family, then case
    problems: list
    required: list
    generated_utc: str
    regression: list = field(default_factory=list)   # regression.RegressionCheck, by name
    timing: SuiteTiming = field(default_factory=SuiteTiming)

    @property
    def results_dir(self):
        return ", ".join(self.results_dirs)

    @property
    def expect_file(self):
        return ", ".join(self.expect_files)

    @property
    def missing(self):
        """Required cases without a record, in the order of the expected list."""
        present = {r.case for r in self.records}
        return [case for case in self.required if case not in present]

    @property
    def n_metrics(self):
        return sum(len(r.metrics) for r in self.records)

    @property
    def failed_records(self):
        return [r for r in self.records if r.failed]

    @property
    def n_failed_metrics(self):
        return sum(1 for r in self.records for m in r.metrics if m.verdict == "fail")

    @property
    def revisions(self):
        return sorted({r.git_revision for r in self.records if r.git_revision})

    @property
    def failed_regressions(self):
        return [c for c in self.regression if c.verdict == "fail"]

    @property
    def ok(self):
        return not self.problems and not self.failed_records and not self.failed_regressions

    def families(self):
        """[(family, [records])] in report order."""
        groups = {}
        for r in self.records:
            groups.setdefault(r.family, []).append(r)
        return list(groups.items())


def load_records(results_dirs):
    """All result records in DIR/*.h5 of every folder, and the problems met reading them.

    A case found in two folders (or twice in one) is a problem: check_records names both files.
    """
    records, problems = [], []
    paths = [p for d in results_dirs for p in sorted(glob.glob(os.path.join(d, "*.h5")))]
    for path in paths:
        try:
            record = read_record(path)
        except RecordError as exc:
            problems.append(Problem(path, str(exc).removeprefix(f"{path}: ")))
            continue
        if record is not None:
            records.append(record)
            problems += [Problem(path, f"field picture skipped: {e}") for e in record.field_errors]
    records.sort(key=lambda r: (r.family, r.case))
    return records, problems


def check_records(records):
    problems = []
    seen = {}
    for r in records:
        if r.case in seen:
            problems.append(Problem(r.case, f"two records for one case: {seen[r.case]} and {r.path}"))
        seen.setdefault(r.case, r.path)
        problems.extend(check_record(r))
    return problems


def check_record(r):
    where = f"{r.path} (case {r.case})"
    problems = []
    if _schema_number(r.schema_version) != SCHEMA_VERSION:
        problems.append(Problem(where, f"schema_version is {_shown(r.schema_version)}, "
                                       f"this report reads version {SCHEMA_VERSION}"))
    if not r.verdict_valid:
        problems.append(Problem(where, f"root verdict is {_shown(r.verdict)}, not 'pass' or 'fail'"))
    for m in r.metrics:
        if not m.verdict_valid:
            problems.append(Problem(where, f"metric {m.name}: verdict is {_shown(m.verdict)}, "
                                           "not 'pass' or 'fail'"))
    contradiction = _contradiction(r)
    if contradiction:
        problems.append(Problem(where, contradiction))
    return problems


def _shown(text):
    return repr(text) if text else "missing"


def _schema_number(text):
    try:
        return int(float(text))
    except ValueError:
        return None


def _contradiction(r):
    """A message if the root verdict disagrees with the recorded metric verdicts."""
    failed = [m.name for m in r.metrics if m.verdict == "fail"]
    if r.verdict == "pass" and failed:
        return f"root verdict is 'pass' but metrics failed: {', '.join(failed)}"
    if r.verdict == "pass" and not r.metrics:
        return "root verdict is 'pass' but the record has no metrics"
    all_pass = r.metrics and all(m.verdict == "pass" for m in r.metrics)
    if r.verdict == "fail" and all_pass:
        return "root verdict is 'fail' but every metric passed"
    return ""


def missing_cases(records, required, results_dir):
    present = {r.case for r in records}
    return [Problem(case, f"required case has no result record in {results_dir}")
            for case in required if case not in present]


def read_regression(results_dirs):
    """(checks, problems): a RegressionCheck for each DIR/regression/*.txt, sorted by name.

    The same check in two folders is a problem, as for records.
    """
    checks, problems, seen = [], [], {}
    for folder in results_dirs:
        for path in sorted(glob.glob(os.path.join(folder, "regression", "*.txt"))):
            name = os.path.basename(path)
            if name in seen:
                problems.append(Problem(name, f"two regression texts: {seen[name]} and {path}"))
                continue
            seen[name] = path
            try:
                with open(path, encoding="utf-8", errors="replace") as fh:
                    text = fh.read()
            except OSError as exc:
                text = f"(cannot read {path}: {exc})"
            checks.append(regression.parse(name, text))
    checks.sort(key=lambda c: c.name)
    return checks, problems


def read_required(expect_files, labels):
    """(required cases, problems): the union of the lists; lists that differ are a problem."""
    required, problems, lists = [], [], []
    for path in expect_files:
        try:
            cases = required_cases(read_expected(path), labels)
        except ExpectedFileError as exc:
            problems.append(Problem(path, str(exc).removeprefix(f"{path}: ")))
            continue
        lists.append((path, cases))
        required += [c for c in cases if c not in required]
    for path, cases in lists[1:]:
        if set(cases) != set(lists[0][1]):
            problems.append(Problem(path, f"lists other required cases than {lists[0][0]}: "
                                          "the folders come from different builds"))
    return required, problems


def build_report(results_dirs, expect_files=(), labels=()):
    """Reads everything and returns the Report; every difficulty becomes a Problem.

    results_dirs: one folder, or the folders of the shards of one run, merged here.
    """
    if isinstance(results_dirs, str):
        results_dirs = [results_dirs]
    if isinstance(expect_files, str):
        expect_files = [expect_files] if expect_files else []
    records, problems = load_records(results_dirs)
    required, more = read_required(expect_files, labels)
    problems += more
    problems += check_records(records)
    where = " or ".join(results_dirs)
    problems += missing_cases(records, required, where)
    if not records and not problems:
        problems.append(Problem(where, "no result records (*.h5 with a root attribute 'case')"))
    checks, more = read_regression(results_dirs)
    problems += more
    runs, unreadable = read_runs(results_dirs)
    problems += [Problem(path, message) for path, message in unreadable]
    return Report(results_dirs=list(results_dirs), expect_files=list(expect_files),
                  labels=tuple(labels), records=records, problems=problems, required=required,
                  generated_utc=_now_utc(), regression=checks,
                  timing=attach_times(records, runs))


def _now_utc():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
