"""Regression comparisons (<results>/regression/NAME.txt, written by `erythro compare`).

Each line of the text is one dataset:

    same  /fields/velocity: max |diff| = 3e-15, max rel = 159 (atol 1e-09, rtol 1e-09)
    MOVED /fields/density: max |diff| = 0.2, max rel = 2e-4 (atol 0, rtol 1e-12); worst at …
    MOVED /series/x: missing or of another shape in the current file

A dataset passes when every element has |current − baseline| ≤ atol + rtol·|baseline|.
"same" therefore does not mean equal, and "max rel" can be large where the baseline is
near zero while the absolute tolerance covers the difference. The report says which
tolerance carried the check instead of repeating "same".
"""
import re
from dataclasses import dataclass, field

_NUM = r"([-+0-9.eEinfaINFA]+)"
_LINE = re.compile(r"^(same|MOVED)\s+(\S.*?): max \|diff\| = " + _NUM + r", max rel = " + _NUM
                   + r" \(atol " + _NUM + r", rtol " + _NUM + r"\)(.*)$")
_MISSING = re.compile(r"^MOVED\s+(\S.*?): (missing or of another shape.*)$")


@dataclass
class DatasetCheck:
    path: str
    passed: bool
    max_abs: float = float("nan")
    max_rel: float = float("nan")
    atol: float = float("nan")
    rtol: float = float("nan")
    detail: str = ""     # e.g. "worst at element 3: baseline 1 -> current 1.2", or why it moved

    @property
    def verdict_text(self):
        """What the check found, in words that cannot contradict the numbers."""
        if not self.passed:
            return "MOVED"
        if self.max_abs == 0:
            return "identical"
        if self.max_abs <= self.atol:
            return "within atol"
        return "within atol + rtol·|baseline|"

    @property
    def rel_note(self):
        """Why a large 'max rel' is not a failure, or ''."""
        if self.passed and self.max_abs <= self.atol and self.max_rel > self.rtol:
            return "large only where the baseline is near 0; |diff| ≤ atol"
        return ""


@dataclass
class RegressionCheck:
    name: str
    text: str
    datasets: list = field(default_factory=list)
    summary: str = ""        # the closing "regression check: …" line
    unparsed: list = field(default_factory=list)

    @property
    def verdict(self):
        """'fail' if a dataset moved or the text says FAILED, 'pass' if every dataset line
        passed, '' when the text has no line this parser knows (shown, not judged)."""
        if "FAILED" in self.summary or any(not d.passed for d in self.datasets):
            return "fail"
        return "pass" if self.datasets else ""

    @property
    def passed(self):
        return self.verdict == "pass"

    @property
    def n_identical(self):
        return sum(1 for d in self.datasets if d.passed and d.max_abs == 0)

    @property
    def n_moved(self):
        return sum(1 for d in self.datasets if not d.passed)


def parse(name, text):
    check = RegressionCheck(name=name, text=text)
    for line in text.splitlines():
        line = line.rstrip()
        if not line:
            continue
        if line.startswith("regression check:"):
            check.summary = line
            continue
        check_line(check, line)
    return check


def check_line(check, line):
    m = _LINE.match(line)
    if m:
        status, path, mabs, mrel, atol, rtol, rest = m.groups()
        check.datasets.append(DatasetCheck(
            path=path, passed=status == "same", max_abs=_float(mabs), max_rel=_float(mrel),
            atol=_float(atol), rtol=_float(rtol), detail=rest.lstrip("; ").strip()))
        return
    m = _MISSING.match(line)
    if m:
        check.datasets.append(DatasetCheck(path=m.group(1), passed=False, detail=m.group(2)))
        return
    check.unparsed.append(line)


def _float(text):
    try:
        return float(text)
    except ValueError:
        return float("nan")


def summary_text(check):
    """'12 datasets within tolerance (9 identical)' or '2 of 12 datasets MOVED'."""
    n = len(check.datasets)
    if not n:
        return "not judged: no comparison line in a known format; see the text"
    if check.n_moved:
        return f"{check.n_moved} of {n} datasets MOVED"
    return f"{n} datasets within tolerance ({check.n_identical} identical)"
