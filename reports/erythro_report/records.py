"""Reading one V&V result record (schema: solver/io/result_record.hpp).

A record is an HDF5 file with a root attribute `case`. read_record() returns
None for an HDF5 file without that attribute (not a result record) and raises
RecordError, naming the file, for a file that cannot be read.
"""
import re
from dataclasses import dataclass, field
from typing import Optional

import h5py
import numpy as np

from .fields import FieldError, read_field
from .h5text import (attr_float, attr_text, read_column, read_floats,
                     to_scalar, to_text_list)

SCHEMA_VERSION = 1
VERDICTS = ("pass", "fail")


class RecordError(Exception):
    """A result record that exists but cannot be read."""


@dataclass
class Metric:
    name: str
    description: str
    unit: str
    value: float
    expected: float
    tolerance: float
    comparison: str          # absolute | relative | at_most | at_least
    tolerance_reason: str
    verdict: str             # as written by the C++ test ("" if absent)

    @property
    def verdict_valid(self):
        return self.verdict in VERDICTS


@dataclass
class Convergence:
    name: str
    norm: str
    h: np.ndarray
    error: np.ndarray
    local_orders: np.ndarray
    formal_order: float
    observed_order: float
    order_tolerance: float
    asymptotic: Optional[bool]   # None when the attribute is absent
    asymptotic_rule: str


@dataclass
class SpeedError:
    name: str
    wall_time_s: np.ndarray
    error: np.ndarray
    label: list
    group: list = field(default_factory=list)   # optional: the line each point belongs to


@dataclass
class Series:
    name: str
    title: str
    xlabel: str
    ylabel: str
    x: np.ndarray
    y: np.ndarray
    y_reference: Optional[np.ndarray]
    x_scale: str = "linear"                        # "log" draws x on a logarithmic axis


@dataclass
class Runs:
    columns: list                                  # in the order of attr `columns`
    data: dict = field(default_factory=dict)       # column -> list or float array

    @property
    def n_rows(self):
        return max((len(v) for v in self.data.values()), default=0)


@dataclass
class Record:
    path: str
    case: str
    family: str
    requirement: str
    reference: str
    verdict: str
    git_revision: str
    compiler: str
    compile_flags: str
    created_utc: str
    wall_time_s: float
    schema_version: str
    cpu_time_s: float  # user + system time of the case's process (NaN in older records)
    parameters: dict
    metrics: list
    runs: Runs
    convergence: list
    speed_error: list
    series: list
    fields: list = field(default_factory=list)
    field_errors: list = field(default_factory=list)   # /fields groups that could not be read
    key_metric: str = ""         # root attr `key_metric`: the metric the summary shows
    # Filled in by the model: the time shown and where it came from ("record", "ctest", "").
    time_s: float = float("nan")
    time_source: str = ""

    @property
    def verdict_valid(self):
        return self.verdict in VERDICTS

    @property
    def failed(self):
        return self.verdict == "fail"


def read_record(path):
    """The record in `path`, or None if the file has no root attribute `case`."""
    try:
        with h5py.File(path, "r") as f:
            if "case" not in f.attrs:
                return None
            return _read_root(f, str(path))
    except RecordError:
        raise
    except Exception as exc:  # corrupt file, wrong types, truncated data...
        raise RecordError(f"{path}: cannot read result record: {exc}") from exc


def _attrs(g, texts=(), floats=()):
    """Keyword arguments: each name in `texts` read as text, each in `floats` as float."""
    values = {name: attr_text(g, name) for name in texts}
    values.update({name: attr_float(g, name) for name in floats})
    return values


def _read_root(f, path):
    return Record(
        path=path,
        **_attrs(f, texts=("case", "family", "requirement", "reference", "verdict", "git_revision",
                           "compiler", "compile_flags", "created_utc", "schema_version",
                           "key_metric"),
                 floats=("wall_time_s", "cpu_time_s")),
        parameters=_read_parameters(f),
        metrics=[_read_metric(n, g) for n, g in _subgroups(f, "metrics")],
        runs=_read_runs(f, path),
        convergence=[_read_convergence(n, g) for n, g in _subgroups(f, "convergence")],
        speed_error=[_read_speed_error(n, g) for n, g in _subgroups(f, "speed_error")],
        series=sorted((_read_series(n, g) for n, g in _subgroups(f, "series")),
                      key=lambda s: natural_key(s.name)),
        **_read_fields(f, path),
    )


def _read_fields(f, path):
    """fields and field_errors: a /fields group that cannot be drawn does not hide the verdict."""
    fields, errors = [], []
    for name, group in _subgroups(f, "fields"):
        try:
            fields.append(read_field(name, group, path))
        except FieldError as exc:
            errors.append(str(exc).removeprefix(f"{path}: "))
    return dict(fields=fields, field_errors=errors)


def natural_key(text):
    """Sort key that puts 'gt=2.0' before 'gt=10.0' (HDF5 lists groups alphabetically)."""
    return [(0, float(part), "") if i % 2 else (1, 0.0, part)
            for i, part in enumerate(re.split(r"(\d+(?:\.\d+)?)", text))]


def _subgroups(f, name):
    """(display name, group) for each group under /name; attr `name` wins if present."""
    if name not in f:
        return []
    parent = f[name]
    items = []
    for key in parent:
        group = parent[key]
        if isinstance(group, h5py.Group):
            items.append((attr_text(group, "name", default=key), group))
    return items


def _read_parameters(f):
    if "parameters" not in f:
        return {}
    return {key: to_scalar(value) for key, value in f["parameters"].attrs.items()}


def _read_metric(name, g):
    return Metric(
        name=name,
        **_attrs(g, texts=("description", "unit", "comparison", "tolerance_reason", "verdict"),
                 floats=("value", "expected", "tolerance")),
    )


def _read_runs(f, path):
    if "runs" not in f:
        return Runs(columns=[])
    group = f["runs"]
    datasets = [k for k in group if isinstance(group[k], h5py.Dataset)]
    if "columns" in group.attrs:
        columns = to_text_list(group.attrs["columns"])
        if len(columns) == 1 and "," in columns[0]:
            # Records written before schema 1 stored the order as one comma-separated string.
            columns = [c for c in columns[0].split(",") if c]
    else:
        columns = sorted(datasets)
    missing = [c for c in columns if c not in datasets]
    if missing:
        raise RecordError(f"{path}: /runs lists columns without a dataset: {', '.join(missing)}")
    return Runs(columns=columns, data={c: read_column(group[c]) for c in columns})


def _read_convergence(name, g):
    asymptotic = None
    if "asymptotic" in g.attrs:
        asymptotic = bool(attr_float(g, "asymptotic", default=0.0))
    return Convergence(
        name=name,
        h=read_floats(g, "h"),
        error=read_floats(g, "error"),
        local_orders=read_floats(g, "local_orders"),
        asymptotic=asymptotic,
        **_attrs(g, texts=("norm", "asymptotic_rule"),
                 floats=("formal_order", "observed_order", "order_tolerance")),
    )


def _read_speed_error(name, g):
    labels = to_text_list(g["label"][()]) if "label" in g else []
    groups = to_text_list(g["group"][()]) if "group" in g else []
    return SpeedError(name=name, wall_time_s=read_floats(g, "wall_time_s"),
                      error=read_floats(g, "error"), label=labels, group=groups)


def _read_series(name, g):
    y_reference = read_floats(g, "y_reference") if "y_reference" in g else None
    if y_reference is not None and y_reference.size == 0:
        y_reference = None
    return Series(name=name, x=read_floats(g, "x"), y=read_floats(g, "y"), y_reference=y_reference,
                  **_attrs(g, texts=("title", "xlabel", "ylabel")), x_scale=attr_text(g, "x_scale", "linear"))
