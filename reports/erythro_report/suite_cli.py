"""reports/suite.py: the suite's time before it runs, its split into shards, its timings file.

  suite.py expect --build DIR [-j N] [--label full]   expected wall time of `ctest -L full -j N`
  suite.py shard K N --build DIR [--label full]       the ctest -R regex of shard K of N (1-based)
  suite.py times SOURCE... --out FILE [--replace]     writes test times (JUnit or ctest log)

See docs/reports.md, "Time", and docs/reports.md, "Shards".
"""
import argparse
import datetime
import os
import platform
import sys

from .ctest_times import (TimesError, read_ctest_cost_data, read_ctest_log, read_junit,
                          read_times, write_times)
from .schedule import ScheduleError, ctest_order, ctest_tests, name_regex, shards, simulate
from .timing import duration_text

LAST_TIMES = os.path.join("timings", "full.tsv")   # in the build folder, written by ci/vv.sh


def parse_args(argv):
    p = argparse.ArgumentParser(prog="suite.py", description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True)
    e = sub.add_parser("expect", help="print the expected wall time of the suite")
    e.add_argument("--build", default="build")
    e.add_argument("--label", default="full")
    e.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    e.add_argument("--times", action="append", default=[], metavar="FILE",
                   help=f"times to use first (default: BUILD/{LAST_TIMES} if it exists)")
    s = sub.add_parser("shard", help="print the ctest -R regex of shard K of N")
    s.add_argument("index", type=int, metavar="K")
    s.add_argument("count", type=int, metavar="N")
    s.add_argument("--build", default="build")
    s.add_argument("--label", default="full")
    s.add_argument("--list", action="store_true", help="one test name a line instead of a regex")
    s.add_argument("--plan", action="store_true", help="print every shard with its expected time")
    t = sub.add_parser("times", help="write ctest's test times to a timings file")
    t.add_argument("sources", nargs="+", metavar="SOURCE",
                   help="ctest --output-junit files (*.xml) or ctest console logs")
    t.add_argument("--out", required=True, metavar="FILE")
    t.add_argument("--replace", action="store_true",
                   help="drop the tests of FILE that are not in the sources (default: keep them)")
    return p.parse_args(argv)


def expect(args):
    tests = ctest_tests(args.build, args.label)
    cost_data = read_ctest_cost_data(args.build)
    files = args.times or [f for f in [os.path.join(args.build, LAST_TIMES)] if os.path.isfile(f)]
    durations, source = {}, {}
    for t in tests:   # lowest priority first: COST (committed), ctest's average, the files
        for name, value in (("COST", t.cost), ("CTestCostData", cost_data.get(t.name, 0.0))):
            if value > 0:
                durations[t.name], source[t.name] = value, name
    for path in files:
        for name, value in read_times(path).items():
            durations[name], source[name] = value, path
    known = [t for t in tests if t.name in durations]
    wall, _ = simulate(ctest_order(tests, cost_data), durations, args.jobs)
    longest = max(known, key=lambda t: durations[t.name], default=None)
    print(f"Expected wall time of ctest -L {args.label} -j {args.jobs}: about {duration_text(wall)} "
          f"({len(tests)} tests, longest first)")
    if longest:
        print(f"  sum of test times {duration_text(sum(durations[t.name] for t in known))}; longest "
              f"{longest.name} {duration_text(durations[longest.name])}")
    counts = {}
    for t in known:
        counts[source[t.name]] = counts.get(source[t.name], 0) + 1
    parts = [f"{n} from {s}" for s, n in counts.items()]
    if len(known) < len(tests):
        parts.append(f"{len(tests) - len(known)} without a recorded time (counted as 0 s)")
    print(f"  times: {'; '.join(parts) or 'none recorded'}")
    return 0


def shard(args):
    if not 1 <= args.index <= args.count:
        raise ScheduleError(f"shard {args.index} of {args.count}: K must be between 1 and N")
    tests = ctest_tests(args.build, args.label)
    parts = shards(tests, args.count)
    if args.plan:
        for k, part in enumerate(parts, start=1):
            wall, _ = simulate(ctest_order(part), {t.name: t.cost for t in part}, 1)
            print(f"shard {k}/{args.count}: {len(part)} tests, {duration_text(wall)} of recorded "
                  f"time: {' '.join(t.name for t in part)}")
        return 0
    mine = [t.name for t in parts[args.index - 1]]
    print("\n".join(mine) if args.list else name_regex(mine))
    return 0


def times(args):
    measured = {}
    for path in args.sources:
        measured.update(read_junit(path).tests if path.endswith(".xml") else read_ctest_log(path))
    measured = {k: v for k, v in measured.items() if v == v}   # drop NaN
    result = {} if args.replace or not os.path.isfile(args.out) else read_times(args.out)
    result.update(measured)
    today = datetime.date.today().isoformat()
    write_times(args.out, result, [f"{len(measured)} tests measured on {platform.node() or 'this machine'}"
                                   f" ({os.cpu_count()} cores), {today}, from "
                                   + ", ".join(os.path.basename(s) for s in args.sources)])
    print(f"{args.out}: {len(result)} tests ({len(measured)} from this run)")
    return 0


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        return {"expect": expect, "shard": shard, "times": times}[args.command](args)
    except (ScheduleError, TimesError) as exc:
        print(f"suite.py: error: {exc}", file=sys.stderr)
        return 2
