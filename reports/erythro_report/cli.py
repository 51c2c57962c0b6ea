"""Command line of the report generator (see docs/reports.md).

Exit status: 0 every case passed; 1 a case failed or a record is missing,
unreadable or inconsistent; 2 usage error.
"""
import argparse
import os
import sys

from . import html_report, markdown_report
from .expected import parse_labels
from .model import build_report
from .regression import summary_text

EXIT_OK, EXIT_FAIL, EXIT_USAGE = 0, 1, 2
EXPECTED_NAME = "expected_cases.tsv"


class UsageError(Exception):
    pass


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="generate.py",
        description="Write an HTML and Markdown report from erythro V&V result records.")
    parser.add_argument("results_dirs", metavar="RESULTS_DIR", nargs="+",
                        help="folder of result records (*.h5); several folders (one per shard) "
                             "are merged into one report")
    parser.add_argument("--out", required=True, metavar="DIR",
                        help="output folder (index.html, summary.md, img/)")
    parser.add_argument("--expect", metavar="FILE",
                        help=f"expected cases (default: every RESULTS_DIR/{EXPECTED_NAME} that exists)")
    parser.add_argument("--labels", metavar="L1,L2",
                        help="require only expected cases carrying one of these labels")
    return parser.parse_args(argv)   # exits with status 2 on a malformed command line


def check_usage(args):
    """(expect_files, labels) after checking the arguments; raises UsageError."""
    for folder in args.results_dirs:
        if not os.path.isdir(folder):
            raise UsageError(f"RESULTS_DIR {folder} is not a folder")
    if len(set(map(os.path.realpath, args.results_dirs))) != len(args.results_dirs):
        raise UsageError("a RESULTS_DIR is given twice")
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        raise UsageError(f"--out {args.out} exists and is not a folder")
    if args.expect is None:
        expect = [p for p in (os.path.join(d, EXPECTED_NAME) for d in args.results_dirs)
                  if os.path.isfile(p)]
    elif not os.path.isfile(args.expect):
        raise UsageError(f"--expect {args.expect}: no such file")
    else:
        expect = [args.expect]
    labels = parse_labels(args.labels) if args.labels is not None else ()
    if args.labels is not None and not labels:
        raise UsageError("--labels needs at least one label")
    if labels and not expect:
        raise UsageError(f"--labels needs an expected-cases list (--expect or RESULTS_DIR/{EXPECTED_NAME})")
    return expect, labels


def write_outputs(report, out_dir):
    """Draws the figures and writes index.html and summary.md; returns index.html's path."""
    from .figures import render_all  # matplotlib is loaded only when a report is drawn
    os.makedirs(out_dir, exist_ok=True)
    figures = render_all(report, out_dir)
    index = os.path.join(out_dir, "index.html")
    with open(index, "w", encoding="utf-8") as fh:
        fh.write(html_report.render(report, figures))
    with open(os.path.join(out_dir, "summary.md"), "w", encoding="utf-8") as fh:
        fh.write(markdown_report.render(report))
    return index


def print_findings(report, stream=sys.stderr):
    for problem in report.problems:
        print(f"report: {problem}", file=stream)
    for record in report.failed_records:
        failed = [m.name for m in record.metrics if m.verdict == "fail"]
        detail = f"failed metrics: {', '.join(failed)}" if failed else "no failed metric recorded"
        print(f"report: case {record.case} FAILED ({record.path}); {detail}", file=stream)
    for check in report.failed_regressions:
        print(f"report: regression {check.name} FAILED: {summary_text(check)}", file=stream)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        expect, labels = check_usage(args)
    except UsageError as exc:
        print(f"generate.py: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    report = build_report(args.results_dirs, expect, labels)
    try:
        index = write_outputs(report, args.out)
    except OSError as exc:
        print_findings(report)
        print(f"generate.py: error: cannot write the report to {args.out}: {exc}", file=sys.stderr)
        return EXIT_FAIL
    print_findings(report)
    print(os.path.abspath(index))
    return EXIT_OK if report.ok else EXIT_FAIL
