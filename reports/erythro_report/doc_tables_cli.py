"""Command line of reports/doc_tables.py: the measured sections of the docs pages.

Every section between `<!-- measured: CASE ... -->` and `<!-- end measured -->` in
docs/verification-*.md and docs/validation-*.md is generated from CASE's result
record (doc_sections.py finds them, doc_markdown.py writes them). --write updates the
pages; --check only compares. A section whose case has no record in the given folders
is left as it is and reported as skipped.

Exit status: 0 every section with a record is up to date (--check) or was written
(--write); 1 a section differs (--check), or a marker, record or page has a problem;
2 usage error.
"""
import argparse
import glob
import os
import sys
from dataclasses import dataclass, field

from .doc_markdown import SectionError, render_section
from .doc_sections import MarkerError, find_sections, replace_bodies
from .records import RecordError, read_record

EXIT_OK, EXIT_FAIL, EXIT_USAGE = 0, 1, 2
PAGE_PATTERNS = ("verification-*.md", "validation-*.md")
DEFAULT_DOCS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))), "docs")


@dataclass
class Outcome:
    """What happened to the sections of all pages."""
    current: list = field(default_factory=list)   # "page:line case" up to date
    changed: list = field(default_factory=list)   # differ from the record (written with --write)
    skipped: list = field(default_factory=list)   # no record in the given folders
    errors: list = field(default_factory=list)    # messages
    shown_cases: set = field(default_factory=set)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="doc_tables.py",
        description="Generate the measured sections of docs/verification-*.md and "
                    "docs/validation-*.md from V&V result records.")
    parser.add_argument("results_dirs", metavar="RESULTS_DIR", nargs="+",
                        help="folder of result records (*.h5); several folders are read as one")
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true", help="rewrite the sections in the pages")
    mode.add_argument("--check", action="store_true",
                      help="change nothing; exit 1 if a section differs from its record")
    parser.add_argument("--docs", metavar="DIR", default=DEFAULT_DOCS,
                        help="folder of the pages (default: the repository's docs/)")
    return parser.parse_args(argv)


def pages_in(docs_dir):
    return sorted(p for pattern in PAGE_PATTERNS
                  for p in glob.glob(os.path.join(docs_dir, pattern)))


def read_records(results_dirs, outcome):
    """The records in DIR/*.h5 of every folder; a file that cannot be read is an error."""
    records = []
    for path in (p for d in results_dirs for p in sorted(glob.glob(os.path.join(d, "*.h5")))):
        try:
            record = read_record(path)
        except RecordError as exc:
            outcome.errors.append(str(exc))
            continue
        if record is not None:
            records.append(record)
    return records


def records_by_case(results_dirs, outcome):
    """{case: record}; unreadable files and cases with two records become errors."""
    by_case, twice = {}, set()
    for r in read_records(results_dirs, outcome):
        if r.case in by_case:
            twice.add(r.case)
            outcome.errors.append(f"{r.case}: two records ({by_case[r.case].path} and {r.path}); "
                                  "its sections are left alone")
        by_case[r.case] = r
    return {case: r for case, r in by_case.items() if case not in twice}


def update_page(path, by_case, outcome, write):
    """Regenerates the sections of one page; writes it when `write` and something changed."""
    name = os.path.relpath(path)
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    try:
        sections = find_sections(text)
    except MarkerError as exc:
        outcome.errors.append(f"{name}: {exc}")
        return
    new_bodies = {}
    for section in sections:
        where = f"{name}:{section.line} {section.case}"
        record = by_case.get(section.case)
        if record is None:
            outcome.skipped.append(where)
            continue
        outcome.shown_cases.add(section.case)
        try:
            body = render_section(record, section)
        except SectionError as exc:
            outcome.errors.append(f"{where}: {exc}")
            continue
        (outcome.current if body == section.body else outcome.changed).append(where)
        new_bodies[section.start] = body
    new_text = replace_bodies(text, new_bodies)
    if write and new_text != text:
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(new_text)


def print_outcome(outcome, by_case, write, stream):
    for where in outcome.changed:
        print(f"doc_tables: {'updated' if write else 'DIFFERS from its record'}: {where}",
              file=stream)
    for where in outcome.skipped:
        print(f"doc_tables: skipped (no record in the given results): {where}", file=stream)
    for message in outcome.errors:
        print(f"doc_tables: error: {message}", file=stream)
    unshown = sorted(set(by_case) - outcome.shown_cases)
    if unshown:
        print(f"doc_tables: records shown in no page: {', '.join(unshown)}", file=stream)
    verb = "updated" if write else "differ"
    print(f"doc_tables: {len(outcome.current)} sections up to date, {len(outcome.changed)} {verb}, "
          f"{len(outcome.skipped)} skipped, {len(outcome.errors)} errors", file=stream)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    for folder in args.results_dirs + [args.docs]:
        if not os.path.isdir(folder):
            print(f"doc_tables.py: error: {folder} is not a folder", file=sys.stderr)
            return EXIT_USAGE
    outcome = Outcome()
    by_case = records_by_case(args.results_dirs, outcome)
    for page in pages_in(args.docs):
        update_page(page, by_case, outcome, write=args.write)
    print_outcome(outcome, by_case, args.write, sys.stderr)
    if outcome.errors or (args.check and outcome.changed):
        return EXIT_FAIL
    return EXIT_OK
