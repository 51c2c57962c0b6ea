#!/usr/bin/python3
"""Writes the erythro V&V report from the result records in RESULTS_DIR.

usage: reports/generate.py RESULTS_DIR [RESULTS_DIR ...] --out DIR [--expect FILE] [--labels ci,...]

Several RESULTS_DIRs (one per shard of a run) are merged into one report.

See docs/reports.md. Run with Debian's /usr/bin/python3 (numpy, matplotlib, h5py).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from erythro_report.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
