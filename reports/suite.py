#!/usr/bin/python3
"""The suite's expected time, its split into shards and its timings file.

Usage: reports/suite.py {expect,shard,times} ...
(see docs/reports.md, "Time", and docs/reports.md, "Shards").
Needs only the Python standard library and ctest.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from erythro_report.suite_cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
