"""Draws every figure of a report into <out>/img/ and names the files.

Paths handed back are relative to the output folder ("img/…png") so that the
folder can be moved as a whole. A figure that fails to draw becomes a Problem
naming the case, and the rest of the report is still written.
"""
import glob
import os
import re
from dataclasses import dataclass, field

from . import plots
from .model import Problem

IMG_DIR = "img"


@dataclass
class CaseFigures:
    convergence: str = ""
    speed_error: str = ""
    series: list = field(default_factory=list)   # one relative path ("" if none) per series
    stability_map: str = ""
    fields: list = field(default_factory=list)   # one relative path ("" if none) per field


@dataclass
class Figures:
    cases: dict = field(default_factory=dict)    # record.path -> CaseFigures
    overview: list = field(default_factory=list)


class _Namer:
    """File names made of a case name, unique within one report."""

    def __init__(self):
        self.used = set()

    def __call__(self, *parts):
        stem = "_".join(re.sub(r"[^A-Za-z0-9.-]+", "-", p).strip("-.") or "x" for p in parts)
        name, n = stem, 2
        while name in self.used:
            name, n = f"{stem}_{n}", n + 1
        self.used.add(name)
        return f"{IMG_DIR}/{name}.png"


def render_all(report, out_dir):
    """Draws all figures; returns Figures and appends drawing failures to report.problems."""
    img_dir = os.path.join(out_dir, IMG_DIR)
    os.makedirs(img_dir, exist_ok=True)
    for stale in glob.glob(os.path.join(img_dir, "*.png")):
        os.remove(stale)
    namer = _Namer()
    figures = Figures()
    for record in report.records:
        figures.cases[record.path] = _render_case(record, out_dir, namer, report.problems)
    try:
        figures.overview = [os.path.relpath(p, out_dir) for p in plots.overview_figures(
            report.records, lambda i: os.path.join(out_dir, namer("speed-against-error", str(i + 1))))]
    except Exception as exc:  # a broken figure must not hide the rest of the report
        report.problems.append(Problem("speed against error", f"figure failed: {exc}"))
    return figures


def _render_case(record, out_dir, namer, problems):
    figs = CaseFigures()
    if record.convergence:
        figs.convergence = _draw(plots.convergence_figure, record, namer(record.case, "convergence"),
                                 out_dir, record, problems)
    if record.speed_error:
        figs.speed_error = _draw(plots.speed_error_figure, record, namer(record.case, "speed-error"),
                                 out_dir, record, problems)
    if plots.has_stability_map(record):
        figs.stability_map = _draw(plots.stability_map_figure, record, namer(record.case, "stability-map"),
                                   out_dir, record, problems)
    for series in record.series:
        figs.series.append(_draw(plots.series_figure, series, namer(record.case, series.name),
                                 out_dir, record, problems))
    for fld in record.fields:
        figs.fields.append(_draw(plots.field_figure, fld, namer(record.case, "field", fld.name),
                                 out_dir, record, problems))
    return figs


def _draw(function, data, rel_path, out_dir, record, problems):
    try:
        return rel_path if function(data, os.path.join(out_dir, rel_path)) else ""
    except Exception as exc:
        problems.append(Problem(record.case, f"{function.__name__} failed: {exc}"))
        return ""
