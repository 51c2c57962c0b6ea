"""One collapsible section per case: metrics, figures, then the record's tables."""
from . import formatting as fmt
from .html_common import (badge, collapsible, esc, figure, simple_table, verdict_cell)
from .timing import duration_text

METRIC_HEAD = ("<th>Metric</th><th class='num'>Value</th><th class='num'>Expected</th>"
               "<th>Tolerance</th><th>Verdict</th>")


def case_section(record, figs, anchor):
    """A <details> block, open when the case did not pass."""
    open_ = " open" if record.verdict != "pass" else ""
    src = " (ctest)" if record.time_source == "ctest" else ""
    summary = (f"<summary><h3>{esc(record.case)}</h3> {badge(record.verdict)}"
               f"<span class='muted'>{esc(record.family)} · {esc(duration_text(record.time_s))}{src}"
               f" · {esc(fmt.plural(len(record.metrics), 'metric'))}</span></summary>")
    parts = [
        f"<details class='case' id='{anchor}'{open_}>{summary}",
        f"<p><strong>Requirement:</strong> {esc(record.requirement or '—')}<br>"
        f"<strong>Reference:</strong> {esc(record.reference or '—')}</p>",
        _metrics(record),
        _fields(record, figs),
        _convergence(record, figs),
        _speed_error(record, figs),
        _stability_map(record, figs),
        _series(record, figs),
        _parameters(record),
        _runs(record),
        collapsible("Provenance", _meta(record)),
        "<p class='muted'><a href='#cases'>back to the case table</a></p></details>",
    ]
    return "\n".join(p for p in parts if p)


def metric_cells(m):
    reason = esc(m.tolerance_reason)
    reason_line = f"<div class='reason'>{reason}</div>" if reason else ""
    return (f"<td><code>{esc(m.name)}</code><div class='desc'>{esc(m.description)}</div></td>"
            f"<td class='num'>{esc(fmt.value_text(m))}</td>"
            f"<td class='num'>{esc(fmt.expected_text(m))}</td>"
            f"<td title='{reason}'>{esc(fmt.tolerance_text(m))}{reason_line}</td>"
            f"{verdict_cell(m.verdict)}")


def _metrics(r):
    if not r.metrics:
        return "<h4>Metrics</h4><p class='muted'>No metrics recorded.</p>"
    rows = "".join(f"<tr>{metric_cells(m)}</tr>" for m in r.metrics)
    return f"<h4>Metrics</h4><table class='full'><tr>{METRIC_HEAD}</tr>{rows}</table>"


def _cpu_text(r):
    """The case's CPU time and the cores it kept busy on average (CPU / wall)."""
    if not (r.cpu_time_s > 0):
        return "not recorded"
    cores = f", {r.cpu_time_s / r.wall_time_s:.2f} cores on average" if r.wall_time_s > 0 else ""
    return f"{fmt.number(r.cpu_time_s, 4)} s{cores}"


def _meta(r):
    rows = [("Record", r.path), ("Git revision", r.git_revision), ("Compiler", r.compiler),
            ("Compile flags", r.compile_flags), ("Created (UTC)", r.created_utc),
            ("Wall time (record)", f"{fmt.number(r.wall_time_s, 4)} s"
             if r.wall_time_s > 0 else "not recorded"),
            ("CPU time (record)", _cpu_text(r)),
            ("Time shown", f"{duration_text(r.time_s)} ({r.time_source or 'none'})"),
            ("Schema version", r.schema_version)]
    items = "".join(f"<dt>{esc(k)}</dt><dd>{esc(v) if v else '—'}</dd>" for k, v in rows)
    return f"<dl class='meta'>{items}</dl>"


def _parameters(r):
    if not r.parameters:
        return ""
    rows = [(k, fmt.number(v)) for k, v in r.parameters.items()]
    return collapsible(f"Parameters ({len(rows)})", simple_table(["Parameter", "Value"], rows))


def _runs(r):
    if not r.runs.columns:
        return ""
    rows = [[fmt.number(_cell(r.runs.data[c], i)) for c in r.runs.columns]
            for i in range(r.runs.n_rows)]
    numeric = {j for j, c in enumerate(r.runs.columns) if not isinstance(r.runs.data[c], list)}
    return collapsible(f"Runs ({r.runs.n_rows})", simple_table(r.runs.columns, rows, numeric))


def _cell(column, i):
    if i >= len(column):
        return ""
    value = column[i]
    return value if isinstance(value, str) else float(value)


def _fields(r, figs):
    if not r.fields:
        return ""
    paths = figs.fields if figs else []
    items = [figure(paths[i] if i < len(paths) else "", f.title or f.name)
             for i, f in enumerate(r.fields)]
    return "<h4>Fields</h4><div class='grid'>" + "\n".join(items) + "</div>"


def _convergence(r, figs):
    if not r.convergence:
        return ""
    summary = [(s.name, s.norm, fmt.number(s.formal_order, 4), fmt.number(s.observed_order, 4),
                fmt.number(s.order_tolerance, 3), fmt.asymptotic_text(s), s.asymptotic_rule)
               for s in r.convergence]
    local = "".join(f"<p><strong>Local orders, {esc(s.name)}</strong></p>" + _local_orders(s)
                    for s in r.convergence)
    return "\n".join([
        "<h4>Convergence</h4>",
        figure(figs.convergence if figs else "", f"{r.case}: error against h"),
        simple_table(["Series", "Norm", "Formal order", "Observed order", "Order tolerance",
                      "Asymptotic", "Asymptotic rule"], summary, numeric={2, 3, 4}),
        collapsible("Local orders", local)])


def _local_orders(s):
    rows = []
    for i, h in enumerate(s.h):
        error = s.error[i] if i < len(s.error) else float("nan")
        order = s.local_orders[i - 1] if 0 < i <= len(s.local_orders) else None
        rows.append((fmt.number(float(h)), fmt.number(float(error)),
                     fmt.number(float(order), 4) if order is not None else ""))
    return simple_table(["h", "error", "local order (from the previous h)"], rows, {0, 1, 2})


def _speed_error(r, figs):
    if not r.speed_error:
        return ""
    return ("<h4>Speed against error</h4>"
            + figure(figs.speed_error if figs else "", f"{r.case}: error against wall time, "
                     "one line per parameter set")
            + f"<p>Cheapest set-up with error ≤ {fmt.ERROR_TARGET_TEXT}: "
              f"<strong>{esc(fmt.cheapest_text(r))}</strong></p>")


def _stability_map(r, figs):
    if not figs or not figs.stability_map:
        return ""
    return "<h4>Stability map</h4>" + figure(figs.stability_map, f"{r.case}: stable and diverged runs")


def _series(r, figs):
    if not r.series:
        return ""
    paths = figs.series if figs else []
    items = [figure(paths[i] if i < len(paths) else "", s.title or s.name)
             for i, s in enumerate(r.series)]
    return f"<h4>Series ({len(items)})</h4><div class='grid'>" + "\n".join(items) + "</div>"
