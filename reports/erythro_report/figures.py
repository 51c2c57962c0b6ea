"""Draws every figure of a report into <out>/img/ and names the files.

Paths handed back are relative to the output folder ("img/…png") so that the
folder can be moved as a whole. A figure that fails to draw becomes a Problem
naming the case, and the rest of the report is still written.
"""
import glob
import multiprocessing
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

    def resolve(self, drawn):
        """Planned paths -> the drawn ones ("" where nothing was drawn); drawn: a set of paths."""
        def kept(path):
            return path if path in drawn else ""
        self.convergence = kept(self.convergence)
        self.speed_error = kept(self.speed_error)
        self.stability_map = kept(self.stability_map)
        self.series = [kept(p) for p in self.series]
        self.fields = [kept(p) for p in self.fields]


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
    """Draws all figures; returns Figures and appends drawing failures to report.problems.

    The figures are planned first (file names in a fixed order), then drawn by worker
    processes, one per core. Each figure is drawn by itself, so the
    files are the same for any number of workers."""
    img_dir = os.path.join(out_dir, IMG_DIR)
    os.makedirs(img_dir, exist_ok=True)
    for stale in glob.glob(os.path.join(img_dir, "*.png")):
        os.remove(stale)
    namer = _Namer()
    plan = []            # _Job, in drawing order
    figures = Figures()
    for record in report.records:
        figures.cases[record.path] = _plan_case(record, namer, plan)
    overview_pages = plots.overview_pages(report.records)
    overview_paths = [namer("speed-against-error", str(i + 1)) for i in range(len(overview_pages))]
    for page, rel_path in zip(overview_pages, overview_paths):
        plan.append(_Job(plots.overview_page_figure, page, rel_path, "speed against error"))
    outcomes = _draw_all(plan, out_dir)
    drawn = set()  # the paths of the figures that were drawn
    for job, (ok, error) in zip(plan, outcomes):
        if error:
            report.problems.append(Problem(job.owner, error))
        if ok:
            drawn.add(job.rel_path)
    for figs in figures.cases.values():
        figs.resolve(drawn)
    figures.overview = [p for p in overview_paths if p in drawn]
    return figures


@dataclass
class _Job:
    function: object   # plots.*_figure(data, path) -> bool
    data: object
    rel_path: str
    owner: str         # the case (or panel) a failure is reported against


def _plan_case(record, namer, plan):
    """Adds the case's figures to `plan`; returns its CaseFigures holding planned paths."""
    def add(function, data, *name_parts):
        rel_path = namer(record.case, *name_parts)
        plan.append(_Job(function, data, rel_path, record.case))
        return rel_path

    figs = CaseFigures()
    if record.convergence:
        figs.convergence = add(plots.convergence_figure, record, "convergence")
    if record.speed_error:
        figs.speed_error = add(plots.speed_error_figure, record, "speed-error")
    if plots.has_stability_map(record):
        figs.stability_map = add(plots.stability_map_figure, record, "stability-map")
    figs.series = [add(plots.series_figure, series, series.name) for series in record.series]
    figs.fields = [add(plots.field_figure, fld, "field", fld.name) for fld in record.fields]
    return figs


_PLAN = []        # the plan the forked workers read (set just before the pool starts)
_OUT_DIR = ""


def _draw_one(index):
    """(drawn?, error text or "") for _PLAN[index]; never raises (a broken figure must not
    hide the rest of the report)."""
    job = _PLAN[index]
    try:
        return bool(job.function(job.data, os.path.join(_OUT_DIR, job.rel_path))), ""
    except Exception as exc:
        return False, f"{job.function.__name__} failed: {exc}"


def _draw_all(plan, out_dir):
    global _PLAN, _OUT_DIR
    _PLAN, _OUT_DIR = plan, out_dir
    try:
        workers = min(os.cpu_count() or 1, len(plan))
        if workers <= 1 or "fork" not in multiprocessing.get_all_start_methods():
            return [_draw_one(i) for i in range(len(plan))]
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            return pool.map(_draw_one, range(len(plan)), chunksize=4)
    finally:
        _PLAN, _OUT_DIR = [], ""
