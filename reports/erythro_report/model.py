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
    results_dir: str
    expect_file: str            # "" when there is no expected list
    labels: tuple
    records: list               # sorted by family, then case
    problems: list
    required: list
    generated_utc: str
    regression: list = field(default_factory=list)   # (file name, text)

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
    def ok(self):
        return not self.problems and not self.failed_records

    def families(self):
        """[(family, [records])] in report order."""
        groups = {}
        for r in self.records:
            groups.setdefault(r.family, []).append(r)
        return list(groups.items())


def load_records(results_dir):
    """All result records in results_dir/*.h5 and the problems met reading them."""
    records, problems = [], []
    for path in sorted(glob.glob(os.path.join(results_dir, "*.h5"))):
        try:
            record = read_record(path)
        except RecordError as exc:
            problems.append(Problem(path, str(exc).removeprefix(f"{path}: ")))
            continue
        if record is not None:
            records.append(record)
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


def read_regression(results_dir):
    """(name, text) for each results_dir/regression/*.txt."""
    texts = []
    for path in sorted(glob.glob(os.path.join(results_dir, "regression", "*.txt"))):
        try:
            with open(path, encoding="utf-8", errors="replace") as fh:
                texts.append((os.path.basename(path), fh.read()))
        except OSError as exc:
            texts.append((os.path.basename(path), f"(cannot read {path}: {exc})"))
    return texts


def build_report(results_dir, expect_file="", labels=()):
    """Reads everything and returns the Report; every difficulty becomes a Problem."""
    records, problems = load_records(results_dir)
    required = []
    if expect_file:
        try:
            required = required_cases(read_expected(expect_file), labels)
        except ExpectedFileError as exc:
            problems.append(Problem(expect_file, str(exc).removeprefix(f"{expect_file}: ")))
    problems += check_records(records)
    problems += missing_cases(records, required, results_dir)
    if not records and not problems:
        problems.append(Problem(results_dir, "no result records (*.h5 with a root attribute 'case')"))
    return Report(results_dir=results_dir, expect_file=expect_file, labels=tuple(labels),
                  records=records, problems=problems, required=required,
                  generated_utc=_now_utc(), regression=read_regression(results_dir))


def _now_utc():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
