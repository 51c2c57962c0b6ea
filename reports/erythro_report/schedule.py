"""ctest's test list, a model of its parallel schedule, and the split into shards.

The list comes from `ctest --show-only=json-v1` in a build folder, with each test's
COST and PROCESSORS properties. COST is seeded by CMake from the committed timings
file (reference_data/timings/full.tsv), so every machine of one commit sees the same
costs, and so the same shards.
"""
import heapq
import json
import re
import statistics
import subprocess
from dataclasses import dataclass

DEFAULT_COST_S = 60.0   # a test with no recorded time, when nothing else is known


@dataclass
class Test:
    name: str
    index: int              # position in ctest's list
    cost: float = 0.0       # COST property (seconds), 0 when unset
    processors: int = 1


class ScheduleError(Exception):
    pass


def ctest_tests(build, label=None):
    """The tests of `build` (optionally of one label), in ctest's order."""
    args = ["ctest", "--test-dir", build, "-N", "--show-only=json-v1"]
    if label:
        args += ["-L", f"^{label}$"]
    try:
        out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
        tests = json.loads(out)["tests"]
    except (OSError, subprocess.CalledProcessError, ValueError, KeyError) as exc:
        raise ScheduleError(f"cannot list the tests of {build} with ctest: {exc}") from exc
    return [_test(t, i) for i, t in enumerate(tests)]


def _test(entry, index):
    props = {p["name"]: p["value"] for p in entry.get("properties", [])}
    return Test(name=entry["name"], index=index, cost=float(props.get("COST", 0.0) or 0.0),
                processors=max(1, int(props.get("PROCESSORS", 1) or 1)))


def ctest_order(tests, cost_data=None):
    """The order in which ctest -j starts tests: highest cost first. ctest takes the COST
    property, or its own CTestCostData.txt average for tests whose COST is 0."""
    cost_data = cost_data or {}
    return sorted(tests, key=lambda t: (-(t.cost or cost_data.get(t.name, 0.0)), t.index))


def simulate(ordered, durations, jobs):
    """Wall time of running `ordered` on `jobs` slots, starting each test as soon as its
    PROCESSORS fit, in the given order. Returns (makespan, {name: start time})."""
    free, now, running, start = jobs, 0.0, [], {}
    waiting = list(ordered)
    while waiting or running:
        for t in list(waiting):
            need = min(t.processors, jobs)
            if need <= free:
                waiting.remove(t)
                free -= need
                start[t.name] = now
                heapq.heappush(running, (now + durations.get(t.name, 0.0), t.index, need))
        if not running:
            break
        now, _, need = heapq.heappop(running)
        free += need
    return now, start


def shard_costs(tests):
    """Each test's cost for the split: its COST, or the median COST when it has none
    (a new case), or DEFAULT_COST_S when no test has one."""
    known = [t.cost for t in tests if t.cost > 0]
    fallback = statistics.median(known) if known else DEFAULT_COST_S
    return {t.name: t.cost if t.cost > 0 else fallback for t in tests}


def shards(tests, count):
    """Splits the tests into `count` shards of about equal cost: longest first, each to
    the shard with the least cost so far (ties: the lower shard). Deterministic."""
    if count < 1:
        raise ScheduleError("the number of shards must be at least 1")
    costs = shard_costs(tests)
    loads = [(0.0, k) for k in range(count)]
    parts = [[] for _ in range(count)]
    for t in sorted(tests, key=lambda t: (-costs[t.name] * t.processors, t.name)):
        load, k = heapq.heappop(loads)
        parts[k].append(t)
        heapq.heappush(loads, (load + costs[t.name] * t.processors, k))
    return [sorted(p, key=lambda t: t.index) for p in parts]


def name_regex(names):
    """A ctest -R regular expression matching exactly these test names."""
    if not names:
        return "^$"   # matches no test name
    return "^(" + "|".join(re.sub(r"([][.^$*+?(){}|\\])", r"\\\1", n) for n in names) + ")$"
