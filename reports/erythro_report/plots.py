"""Figures of the report, drawn with matplotlib's Agg backend and saved as PNG.

Each *_figure function writes one PNG file and returns True, or returns False
(and writes nothing) when there is nothing to plot.
"""
import math

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402

from . import speed  # noqa: E402
from .formatting import ERROR_TARGET, ERROR_TARGET_TEXT, cheapest_setup, number  # noqa: E402

DPI = 110
PANEL_COLUMNS = 3
PANELS_PER_PAGE = 9        # overview figures: up to a 3 × 3 grid each
FORMAL_LINE_SHIFT = 0.5    # formal-order line drawn at half the finest error
MANY_LINES = 8             # more lines than this: a wider figure, the legend on the right


def _new_figure(width=6.4, height=4.6):
    return Figure(figsize=(width, height), dpi=DPI, layout="constrained")


def _save(fig, path):
    fig.savefig(path)
    return True


def _log_points(x, y):
    """x, y truncated to a common length, keeping finite positive pairs only."""
    n = min(len(x), len(y))
    x, y = np.asarray(x[:n], dtype=float), np.asarray(y[:n], dtype=float)
    keep = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    return x[keep], y[keep]


def _fit_line(h, e, slope):
    """Least-squares line log e = slope·log h + c; slope fitted too if not finite."""
    lh, le = np.log(h), np.log(e)
    if not math.isfinite(slope):
        slope = float(np.polyfit(lh, le, 1)[0]) if len(h) >= 2 else float("nan")
    if not math.isfinite(slope):
        return None
    intercept = float(np.mean(le - slope * lh))
    hh = np.array([h.min(), h.max()])
    return hh, np.exp(intercept) * hh ** slope, slope


# -- convergence -----------------------------------------------------------------

def convergence_figure(record, path):
    """All /convergence series of a case: error vs h, fit and formal-order lines.

    One legend entry per series ("name: slope p", marker and fit line) and one for the
    dashed formal-order lines; with many series the legend goes to the right."""
    series = [s for s in record.convergence if len(_log_points(s.h, s.error)[0])]
    if not series:
        return False
    many = len(series) > MANY_LINES
    fig = _new_figure(9.5 if many else 6.4, 5.2 if many else 4.6)
    ax = fig.add_subplot()
    for i, s in enumerate(series):
        _draw_convergence(ax, s, _color(i), _marker(i), s.name if len(series) > 1 else "")
    formal = sorted({s.formal_order for s in series if math.isfinite(s.formal_order)})
    if formal:
        orders = ", ".join(number(p, 3) for p in formal)
        ax.plot([], [], "--", color="0.4", lw=1.0, label=f"formal order {orders} (dashed)")
    norms = sorted({s.norm for s in series if s.norm})
    ax.set_xlabel("h (grid spacing)")
    ax.set_ylabel(f"error ({norms[0]})" if len(norms) == 1 else
                  "error (norms: see the table)" if norms else "error")
    ax.set_title(f"{record.case}: convergence")
    ax.grid(True, which="both", alpha=0.3)
    if many:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                  ncol=1 + len(series) // 26)
    else:
        ax.legend(fontsize=8)
    return _save(fig, path)


def _draw_convergence(ax, series, color, marker, name):
    h, e = _log_points(series.h, series.error)
    fit = _fit_line(h, e, series.observed_order) if len(h) >= 2 else None
    slope = f"slope {number(fit[2], 3)}" if fit else "no fit"
    label = f"{name}: {slope}" if name else f"error, least-squares {slope}"
    ax.loglog(h, e, marker, color=color, ms=5, label=label, ls="none")
    if fit:
        ax.loglog(fit[0], fit[1], "-", color=color, lw=1.2)
    if math.isfinite(series.formal_order) and len(h) >= 2:
        # Through the finest point, shifted down so that it does not hide the fit.
        finest = int(np.argmin(h))
        hh = np.array([h.min(), h.max()])
        anchor = FORMAL_LINE_SHIFT * e[finest]
        ax.loglog(hh, anchor * (hh / h[finest]) ** series.formal_order, "--", color=color,
                  lw=1.0, alpha=0.7)


# -- speed against error ------------------------------------------------------------

def speed_error_figure(record, path):
    fig = _new_figure()
    ax = fig.add_subplot()
    if not draw_speed_error(ax, record, title=f"{record.case}: error against wall time"):
        return False
    return _save(fig, path)


def draw_speed_error(ax, record, title, label_points=True):
    """One line per parameter set of each /speed_error series (see speed.py);
    returns the number of lines drawn."""
    drawn = 0
    all_lines = [line for s in record.speed_error for line in speed.lines(s)]
    for i, line in enumerate(all_lines):
        drawn += _draw_speed_line(ax, line, _color(i), _marker(i), label_points)
    if not drawn:
        ax.set_axis_off()
        ax.set_title(title, fontsize=10)
        ax.text(0.5, 0.5, "no positive finite points", ha="center", va="center",
                transform=ax.transAxes, color="0.4")
        return 0
    ax.axhline(ERROR_TARGET, color="0.4", ls=":", lw=1, label=f"error {ERROR_TARGET_TEXT}")
    best = cheapest_setup(record)
    if best:
        ax.loglog([best[2]], [best[3]], "o", ms=13, mfc="none", mec="black",
                  label=f"cheapest ≤ {ERROR_TARGET_TEXT}")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("error")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7 if drawn <= 6 else 6, ncol=1 if drawn <= 6 else 2)
    return drawn


def _color(i):
    return f"C{i % 10}"


def _marker(i):
    return "osD^v<>"[(i // 10) % 7]


def _draw_speed_line(ax, line, color, marker, label_points):
    t, e = _log_points(line.wall_time_s, line.error)
    if len(t) == 0:
        return 0
    ax.loglog(t, e, "-", marker=marker, color=color, ms=4, label=line.name)
    if label_points:
        for ti, ei, text in zip(line.wall_time_s, line.error, line.labels):
            if ti > 0 and ei > 0 and math.isfinite(ti) and math.isfinite(ei):
                ax.annotate(text, (ti, ei), textcoords="offset points", xytext=(4, 4),
                            fontsize=7, color=color)
    return 1


def overview_pages(records):
    """The cases with /speed_error, grouped into pages of up to 3 × 3 panels."""
    cases = [r for r in records if r.speed_error]
    return [cases[i:i + PANELS_PER_PAGE] for i in range(0, len(cases), PANELS_PER_PAGE)]


def overview_page_figure(records, path):
    """'Speed against error', one panel per case of `records` (one page)."""
    cols = min(PANEL_COLUMNS, len(records))
    rows = math.ceil(len(records) / cols)
    fig = _new_figure(4.3 * cols, 3.5 * rows)
    fig.suptitle("Speed against error")
    for i, record in enumerate(records):
        draw_speed_error(fig.add_subplot(rows, cols, i + 1), record, record.case,
                         label_points=False)
    return _save(fig, path)


# -- plain series --------------------------------------------------------------------

def series_figure(series, path):
    """y against x, with y_reference dashed when recorded; a short series (a study's
    points rather than a history) is drawn with markers, x on a log axis when asked."""
    n = min(len(series.x), len(series.y))
    if n == 0:
        return False
    fig = _new_figure(6.0, 4.0)
    ax = fig.add_subplot()
    ax.plot(series.x[:n], series.y[:n], "o-" if n <= 20 else "-", color="C0", lw=2,
            label=series.ylabel or "y")
    ref = series.y_reference
    if ref is not None:
        m = min(len(series.x), len(ref))
        ax.plot(series.x[:m], ref[:m], "--", color="black", lw=1, label="reference")
    if series.x_scale == "log" and np.all(series.x[:n] > 0):
        ax.set_xscale("log")
    ax.set_xlabel(series.xlabel or "x")
    ax.set_ylabel(series.ylabel or "y")
    ax.set_title(series.title or series.name)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


# -- stability map -----------------------------------------------------------------

STABILITY_COLUMNS = ("model", "tau", "U", "stable")


def has_stability_map(record):
    """A record whose /runs table holds (model, tau, U, stable) rows: a stability scan."""
    return all(c in record.runs.data for c in STABILITY_COLUMNS)


def stability_map_figure(record, path):
    """One panel per collision model: stable (o) and diverged (x) runs over
    τ − ½ (log axis, so the region near ½ is visible) and the velocity amplitude U."""
    if not has_stability_map(record):
        return False
    data = record.runs.data
    models = [str(m) for m in data["model"]]
    tau = np.asarray(data["tau"], dtype=float)
    amp = np.asarray(data["U"], dtype=float)
    stable = np.asarray(data["stable"], dtype=float) > 0.5
    names = list(dict.fromkeys(models))
    cols = min(len(names), 2)
    rows = math.ceil(len(names) / cols)
    fig = _new_figure(5.0 * cols, 3.6 * rows)
    axes = np.atleast_1d(fig.subplots(rows, cols, sharex=True, sharey=True)).ravel()
    for ax, name in zip(axes, names):
        mine = np.array([m == name for m in models])
        ok, bad = mine & stable, mine & ~stable
        ax.semilogx(tau[ok] - 0.5, amp[ok], "o", color="C2", ms=5, label="stable")
        ax.semilogx(tau[bad] - 0.5, amp[bad], "x", color="C3", ms=6, label="diverged")
        ax.set_title(name)
        ax.set_xlabel("τ − ½")
        ax.set_ylabel("velocity amplitude U (lattice)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize="small", loc="lower right")
    for ax in axes[len(names):]:
        ax.set_visible(False)
    fig.suptitle(f"{record.case}: stability map")
    return _save(fig, path)


# -- field pictures ------------------------------------------------------------------

def field_figure(fld, path):
    """A /fields picture: the 2-D data as colours, with its colour bar and the membranes
    drawn as closed outlines on top."""
    data = np.ma.masked_invalid(fld.data)
    if data.count() == 0:
        return False
    ny, nx = fld.data.shape
    x = fld.x if fld.x is not None else np.arange(nx, dtype=float)
    y = fld.y if fld.y is not None else np.arange(ny, dtype=float)
    aspect = (np.ptp(y) + 1e-300) / (np.ptp(x) + 1e-300) if nx > 1 and ny > 1 else 1.0
    # About 4.4 in of the 6.4 in width is the picture (the rest: labels, colour bar), so this
    # height keeps the colour bar as tall as the picture.
    fig = _new_figure(6.4, min(max(4.4 * aspect + 1.0, 2.4), 7.5))
    ax = fig.add_subplot()
    mesh = ax.pcolormesh(_edges(x), _edges(y), data, shading="flat", cmap="viridis")
    for outline in fld.membranes:
        closed = np.vstack([outline, outline[:1]])
        ax.plot(closed[:, 0], closed[:, 1], "-", color="white", lw=1.6)
        ax.plot(closed[:, 0], closed[:, 1], "-", color="#d62728", lw=0.9)
    ax.set_aspect("equal")
    label = fld.quantity or fld.name
    fig.colorbar(mesh, ax=ax, label=f"{label} ({fld.unit})" if fld.unit else label, shrink=0.9)
    ax.set_xlabel(fld.xlabel or ("x" if fld.x is not None else "x (node)"))
    ax.set_ylabel(fld.ylabel or ("y" if fld.y is not None else "y (node)"))
    ax.set_title(fld.title or fld.name, fontsize=10)
    return _save(fig, path)


def _edges(centres):
    """Cell edges around cell centres (uniform or not)."""
    c = np.asarray(centres, dtype=float)
    if len(c) == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])
