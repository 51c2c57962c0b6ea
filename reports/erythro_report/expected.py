"""The list of expected cases, written by CMake as <results>/expected_cases.tsv.

Format: lines starting with '#' are comments; every other non-blank line is
"case<TAB>label1,label2,...". Labels are compared without regard to case.
"""
from dataclasses import dataclass


@dataclass
class ExpectedCase:
    case: str
    labels: tuple


class ExpectedFileError(Exception):
    """The expected-cases file cannot be read or has a malformed line."""


def parse_labels(text):
    """'ci, Verification' -> ('ci', 'verification')."""
    return tuple(p.strip().lower() for p in text.split(",") if p.strip())


def read_expected(path):
    try:
        with open(path, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise ExpectedFileError(f"{path}: cannot read expected cases: {exc}") from exc
    cases = []
    for number, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        case, _, labels = line.partition("\t") if "\t" in line else _split_spaces(line)
        if not case.strip():
            raise ExpectedFileError(f"{path}:{number}: no case name in {line!r}")
        cases.append(ExpectedCase(case=case.strip(), labels=parse_labels(labels)))
    return cases


def _split_spaces(line):
    parts = line.split(None, 1)
    return parts[0], " ", parts[1] if len(parts) > 1 else ""


def required_cases(expected, labels=None):
    """Names of the expected cases that must have a record.

    With `labels`, only cases carrying at least one of them are required.
    """
    if not labels:
        return [e.case for e in expected]
    wanted = set(labels)
    return [e.case for e in expected if wanted.intersection(e.labels)]
