#!/usr/bin/python3
"""Generates the measured sections of docs/verification-*.md and docs/validation-*.md
from the V&V result records in RESULTS_DIR.

usage: reports/doc_tables.py RESULTS_DIR [RESULTS_DIR ...] (--write | --check) [--docs DIR]

A section is the text between `<!-- measured: CASE ... -->` and `<!-- end measured -->`.
See docs/reports.md. Run with Debian's /usr/bin/python3 (numpy, h5py).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from erythro_report.doc_tables_cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
