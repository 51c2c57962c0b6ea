"""Splitting a /speed_error series into the lines drawn: one line per set of parameters.

A series may hold points of several parameter sets, e.g. BGK with labels
"tau=0.6 N=8", "tau=0.6 N=16", "tau=0.8 N=8", …; a line joining them would run from
one τ to another. The points are grouped:

  1. by the series' optional `group` dataset (one string per point), if present;
  2. else by the label without its last `key=value` word ("tau=0.6 N=8" -> "tau=0.6"),
     when that gives more than one group.

Otherwise the series is one line. Within a line the points are joined in the order
of their resolution when every point label ends in `key=<number>` (N=8, N=16, …),
else in the order written; not by wall time, which is noisy for fast runs.
"""
import re
from dataclasses import dataclass

import numpy as np

_LAST_WORD = re.compile(r"^(.*\S)\s+(\w[\w.]*=\S+)$")
_NUMBER_AT_END = re.compile(r"=\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)$")


@dataclass
class SpeedLine:
    name: str
    wall_time_s: np.ndarray
    error: np.ndarray
    labels: list


def lines(series):
    n = min(len(series.wall_time_s), len(series.error))
    labels = [series.label[i] if i < len(series.label) else "" for i in range(n)]
    if len(series.group) == n and len(set(series.group)) > 1:
        groups, point_labels = list(series.group), labels
    else:
        split = [_LAST_WORD.match(label) for label in labels]
        if n and all(split) and len({m.group(1) for m in split}) > 1:
            groups, point_labels = [m.group(1) for m in split], [m.group(2) for m in split]
        else:
            groups, point_labels = [""] * n, labels
    result = []
    for group in dict.fromkeys(groups):
        idx = _in_resolution_order([i for i in range(n) if groups[i] == group], point_labels)
        result.append(SpeedLine(f"{series.name} {group}".strip(), series.wall_time_s[idx],
                                series.error[idx], [point_labels[i] for i in idx]))
    return result


def _in_resolution_order(idx, labels):
    values = [_NUMBER_AT_END.search(labels[i]) for i in idx]
    if not all(values):
        return idx
    try:
        keys = [float(v.group(1)) for v in values]
    except ValueError:
        return idx
    return [i for _, i in sorted(zip(keys, idx))]
