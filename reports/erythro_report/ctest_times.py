"""ctest's own test times: its JUnit output (`ctest --output-junit`) and the timings file.

A JUnit file holds one ctest run: `<testsuite time=… timestamp=…>` with the run's
elapsed wall time, and one `<testcase name=… time=… status=…>` per test.

The timings file (reference_data/timings/full.tsv, build/timings/full.tsv) is text:
lines starting with '#' are comments, every other line is "test<TAB>seconds".
"""
import math
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

JUNIT_SUFFIX = ".junit.xml"


class TimesError(Exception):
    """A JUnit or timings file that cannot be read."""


@dataclass
class CtestRun:
    path: str
    elapsed_s: float                              # the run's wall time (testsuite attr `time`)
    timestamp: str
    tests: dict = field(default_factory=dict)     # test name -> seconds
    status: dict = field(default_factory=dict)    # test name -> "run", "fail", "notrun", …


def read_junit(path):
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise TimesError(f"{path}: cannot read ctest JUnit output: {exc}") from exc
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    if not suites:
        raise TimesError(f"{path}: no <testsuite> element")
    run = CtestRun(path=path, elapsed_s=sum(_seconds(s.get("time")) for s in suites),
                   timestamp=suites[0].get("timestamp", ""))
    for suite in suites:
        for case in suite.iter("testcase"):
            name = case.get("name", "")
            if name:
                run.tests[name] = _seconds(case.get("time"))
                run.status[name] = case.get("status", "")
    return run


def _seconds(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return float("nan")
    return value if math.isfinite(value) and value >= 0 else float("nan")


def junit_files(folder):
    """The ctest JUnit files of a results folder (`*.junit.xml`), sorted."""
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names if n.endswith(JUNIT_SUFFIX)]


def read_times(path):
    """{test: seconds} from a timings file."""
    times = {}
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise TimesError(f"{path}: cannot read timings: {exc}") from exc
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = line.split("\t") if "\t" in line else line.split()
        seconds = _seconds(parts[1]) if len(parts) == 2 else float("nan")
        if math.isnan(seconds):
            raise TimesError(f"{path}:{number}: expected 'test<TAB>seconds', got {line!r}")
        times[parts[0].strip()] = seconds
    return times


def write_times(path, times, comments=()):
    """Writes {test: seconds}, slowest first (ties by name), with '#' comment lines on top."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    rows = sorted(times.items(), key=lambda kv: (-kv[1], kv[0]))
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("# test\tseconds (ctest's own times; read by cmake/VVCase.cmake for COST "
                 "and by reports/suite.py)\n")
        for line in comments:
            fh.write(f"# {line}\n")
        for name, seconds in rows:
            fh.write(f"{name}\t{seconds:.2f}\n")


def read_ctest_cost_data(build):
    """{test: average seconds} from ctest's own BUILD/Testing/Temporary/CTestCostData.txt
    (lines "name runs cost", then "---" and the tests that failed last); {} if absent."""
    path = os.path.join(build, "Testing", "Temporary", "CTestCostData.txt")
    costs = {}
    try:
        with open(path, encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("---"):
                    break
                parts = line.split()
                if len(parts) == 3 and not math.isnan(_seconds(parts[2])):
                    costs[parts[0]] = _seconds(parts[2])
    except OSError:
        return {}
    return costs


_LOG_LINE = re.compile(r"^\s*\d+/\d+ Test\s+#\d+: (\S+) \.+.*?([0-9.]+) sec\s*$")


def read_ctest_log(path):
    """{test: seconds} from ctest's console output ("12/70 Test #13: name .... Passed 17.08 sec")."""
    times = {}
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            for line in fh:
                m = _LOG_LINE.match(line)
                if m:
                    times[m.group(1)] = float(m.group(2))
    except OSError as exc:
        raise TimesError(f"{path}: cannot read ctest output: {exc}") from exc
    return times
