"""The HTML report: one self-contained index.html with PNG figures in img/."""
import html
import re

from . import formatting as fmt

CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; margin: 0 auto;
       max-width: 1200px; padding: 1rem 2rem 3rem; color: #1d1d1f; line-height: 1.45; }
h1 { margin-bottom: .2rem; }
h2 { border-bottom: 2px solid #d0d7de; padding-bottom: .2rem; margin-top: 2.5rem; }
h3 { margin-top: 2rem; }
h4 { margin: 1.4rem 0 .4rem; color: #444; }
.summary { font-size: 1.05rem; }
.scope, .muted { color: #666; font-size: .9rem; }
.banner { padding: .6rem 1rem; border-radius: 6px; font-weight: 600; margin: .8rem 0; }
.banner.pass { background: #dcf5dc; color: #145214; border: 1px solid #9ad29a; }
.banner.fail { background: #fbdcdb; color: #8a1c1c; border: 1px solid #e59a97; }
.problems { background: #fff4e5; border: 1px solid #f0b45a; border-radius: 6px; padding: .5rem 1.5rem; }
nav.toc { background: #f6f8fa; border: 1px solid #d0d7de; border-radius: 6px; padding: .4rem 1.2rem; }
nav.toc ul, nav.toc ol { margin: .2rem 0; }
table { border-collapse: collapse; margin: .5rem 0 1rem; font-size: .9rem; }
th, td { border: 1px solid #d0d7de; padding: .25rem .5rem; text-align: left; vertical-align: top; }
th { background: #f0f3f6; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.pass, .badge.pass { background: #dcf5dc; color: #145214; font-weight: 600; }
td.fail, .badge.fail { background: #fbdcdb; color: #8a1c1c; font-weight: 600; }
td.invalid, .badge.invalid { background: #ffe9b3; color: #7a4b00; font-weight: 600; }
.badge { border-radius: 4px; padding: 0 .4rem; font-size: .8rem; }
.desc, .reason { color: #555; font-size: .8rem; }
.reason { font-style: italic; }
td.req { max-width: 22rem; font-size: .85rem; }
dl.meta { display: grid; grid-template-columns: max-content auto; gap: .15rem 1rem; font-size: .9rem; }
dl.meta dt { font-weight: 600; color: #444; }
dl.meta dd { margin: 0; }
figure { margin: .5rem 0 1rem; }
figure img { max-width: 100%; border: 1px solid #e1e4e8; }
figcaption { font-size: .85rem; color: #555; }
pre { background: #f6f8fa; border: 1px solid #d0d7de; padding: .6rem; overflow-x: auto; font-size: .85rem; }
code { font-size: .9em; }
.wide { overflow-x: auto; }
"""


def esc(value):
    return html.escape(str(value), quote=True)


def _verdict_class(verdict):
    return verdict if verdict in ("pass", "fail") else "invalid"


def _verdict_cell(verdict):
    return f'<td class="{_verdict_class(verdict)}">{esc(fmt.verdict_text(verdict))}</td>'


def _badge(verdict):
    return f'<span class="badge {_verdict_class(verdict)}">{esc(fmt.verdict_text(verdict))}</span>'


def anchor_ids(records):
    """record.path -> unique HTML id for its section."""
    ids, used = {}, set()
    for r in records:
        base = "case-" + (re.sub(r"[^A-Za-z0-9_.-]+", "-", r.case).strip("-") or "x")
        anchor, n = base, 2
        while anchor in used:
            anchor, n = f"{base}-{n}", n + 1
        used.add(anchor)
        ids[r.path] = anchor
    return ids


# -- page ---------------------------------------------------------------------------

def render(report, figures):
    ids = anchor_ids(report.records)
    parts = [
        _head(),
        _header(report),
        _toc(report, figures, ids),
        _problems(report),
        _results_table(report, ids),
        _overview(figures),
        _cases(report, figures, ids),
        _regression(report),
        "<footer class='muted'><p>Written by reports/generate.py. The C++ V&amp;V tests decide "
        "every verdict; this report only shows them.</p></footer>",
        "</body>\n</html>\n",
    ]
    return "\n".join(p for p in parts if p)


def _head():
    return ("<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
            f"<title>erythro V&amp;V report</title>\n<style>{CSS}</style>\n</head>\n<body>")


def _header(report):
    status = "pass" if report.ok else "fail"
    if report.ok:
        banner = f"All {fmt.plural(len(report.records), 'case')} passed."
    else:
        banner = (f"FAIL: {fmt.plural(len(report.failed_records), 'case')} failed, "
                  f"{fmt.plural(len(report.problems), 'problem')}.")
    return (f"<header><h1>erythro V&amp;V report</h1>\n"
            f"<p class='summary'>{esc(fmt.summary_line(report))}</p>\n"
            f"<div class='banner {status}'>{esc(banner)}</div>\n"
            f"<p class='scope'>{esc(fmt.scope_line(report))}</p></header>")


def _toc(report, figures, ids):
    items = []
    if report.problems:
        items.append(f"<li><a href='#problems'>Problems ({len(report.problems)})</a></li>")
    items.append("<li><a href='#results'>Pass/fail table</a></li>")
    if figures.overview:
        items.append("<li><a href='#speed'>Speed against error</a></li>")
    families = []
    for family, records in report.families():
        cases = "".join(f"<li><a href='#{ids[r.path]}'>{esc(r.case)}</a> {_badge(r.verdict)}</li>"
                        for r in records)
        families.append(f"<li>{esc(family or '(no family)')}<ul>{cases}</ul></li>")
    items.append(f"<li><a href='#cases'>Cases</a><ul>{''.join(families)}</ul></li>")
    if report.regression:
        items.append("<li><a href='#regression'>Regression</a></li>")
    return f"<nav class='toc'><h2>Contents</h2><ol>{''.join(items)}</ol></nav>"


def _problems(report):
    if not report.problems:
        return ""
    items = "".join(f"<li><strong>{esc(p.subject)}</strong>: {esc(p.message)}</li>"
                    for p in report.problems)
    return f"<h2 id='problems'>Problems</h2>\n<div class='problems'><ul>{items}</ul></div>"


# -- pass/fail table ------------------------------------------------------------------

METRIC_HEAD = "<th>Metric</th><th>Value</th><th>Expected</th><th>Tolerance</th><th>Verdict</th>"


def _results_table(report, ids):
    rows = [row for r in report.records for row in _case_rows(r, ids[r.path])]
    head = f"<tr><th>Case</th><th>Requirement</th>{METRIC_HEAD}</tr>"
    return (f"<h2 id='results'>Pass/fail table</h2>\n<table class='results'>\n{head}\n"
            + "\n".join(rows) + "\n</table>")


def _case_rows(record, anchor):
    """Table rows of one case; the case and requirement cells span its metrics."""
    span = max(1, len(record.metrics))
    lead = (f"<td rowspan='{span}'><a href='#{anchor}'>{esc(record.case)}</a>"
            f"<div class='desc'>{esc(record.family)}</div></td>"
            f"<td rowspan='{span}' class='req'>{esc(record.requirement)}</td>")
    if not record.metrics:
        return [f"<tr>{lead}<td colspan='4'><em>(no metrics)</em></td>"
                f"{_verdict_cell(record.verdict)}</tr>"]
    cells = [metric_cells(m) for m in record.metrics]
    return [f"<tr>{lead if i == 0 else ''}{c}</tr>" for i, c in enumerate(cells)]


def metric_cells(m):
    reason = esc(m.tolerance_reason)
    reason_line = f"<div class='reason'>{reason}</div>" if reason else ""
    return (f"<td><code>{esc(m.name)}</code><div class='desc'>{esc(m.description)}</div></td>"
            f"<td class='num'>{esc(fmt.value_text(m))}</td>"
            f"<td class='num'>{esc(fmt.expected_text(m))}</td>"
            f"<td title='{reason}'>{esc(fmt.tolerance_text(m))}{reason_line}</td>"
            f"{_verdict_cell(m.verdict)}")


# -- figures ------------------------------------------------------------------------------

def _figure(path, caption):
    if not path:
        return f"<p class='muted'>{esc(caption)}: nothing to plot.</p>"
    return (f"<figure><img src='{esc(path)}' alt='{esc(caption)}' loading='lazy'>"
            f"<figcaption>{esc(caption)}</figcaption></figure>")


def _overview(figures):
    if not figures.overview:
        return ""
    body = "\n".join(_figure(p, "Error against wall time, one panel per case") for p in figures.overview)
    return f"<h2 id='speed'>Speed against error</h2>\n{body}"


# -- per case -------------------------------------------------------------------------------

def _cases(report, figures, ids):
    out = ["<h2 id='cases'>Cases</h2>"]
    for record in report.records:
        out.append(case_section(record, figures.cases.get(record.path), ids[record.path]))
    return "\n".join(out)


def case_section(record, figs, anchor):
    parts = [
        f"<section class='case' id='{anchor}'>",
        f"<h3>{esc(record.case)} {_badge(record.verdict)}</h3>",
        _meta(record),
        _case_metrics(record),
        _parameters(record),
        _runs(record),
        _convergence(record, figs),
        _speed_error(record, figs),
        _stability_map(record, figs),
        _series(record, figs),
        "<p class='muted'><a href='#results'>back to the table</a></p></section>",
    ]
    return "\n".join(p for p in parts if p)


def _meta(r):
    rows = [("Family", r.family), ("Requirement", r.requirement), ("Reference", r.reference),
            ("Verdict", fmt.verdict_text(r.verdict)), ("Record", r.path),
            ("Git revision", r.git_revision), ("Compiler", r.compiler),
            ("Compile flags", r.compile_flags), ("Created (UTC)", r.created_utc),
            ("Wall time", f"{fmt.number(r.wall_time_s, 4)} s"),
            ("Schema version", r.schema_version)]
    items = "".join(f"<dt>{esc(k)}</dt><dd>{esc(v) if v else '—'}</dd>" for k, v in rows)
    return f"<dl class='meta'>{items}</dl>"


def _case_metrics(r):
    if not r.metrics:
        return "<h4>Metrics</h4><p class='muted'>No metrics recorded.</p>"
    rows = "".join(f"<tr>{metric_cells(m)}</tr>" for m in r.metrics)
    return f"<h4>Metrics</h4><table><tr>{METRIC_HEAD}</tr>{rows}</table>"


def _simple_table(headers, rows, numeric=()):
    head = "".join(f"<th>{esc(h)}</th>" for h in headers)
    body = []
    for row in rows:
        cells = "".join(f"<td class='num'>{esc(v)}</td>" if i in numeric else f"<td>{esc(v)}</td>"
                        for i, v in enumerate(row))
        body.append(f"<tr>{cells}</tr>")
    return f"<div class='wide'><table><tr>{head}</tr>{''.join(body)}</table></div>"


def _parameters(r):
    if not r.parameters:
        return ""
    rows = [(k, fmt.number(v)) for k, v in r.parameters.items()]
    return "<h4>Parameters</h4>" + _simple_table(["Parameter", "Value"], rows)


def _runs(r):
    if not r.runs.columns:
        return ""
    rows = []
    for i in range(r.runs.n_rows):
        rows.append([fmt.number(_cell(r.runs.data[c], i)) for c in r.runs.columns])
    numeric = {j for j, c in enumerate(r.runs.columns) if not isinstance(r.runs.data[c], list)}
    return (f"<h4>Runs ({r.runs.n_rows})</h4>"
            + _simple_table(r.runs.columns, rows, numeric))


def _cell(column, i):
    if i >= len(column):
        return ""
    value = column[i]
    return value if isinstance(value, str) else float(value)


def _convergence(r, figs):
    if not r.convergence:
        return ""
    summary = [(s.name, s.norm, fmt.number(s.formal_order, 4), fmt.number(s.observed_order, 4),
                fmt.number(s.order_tolerance, 3), fmt.asymptotic_text(s), s.asymptotic_rule)
               for s in r.convergence]
    parts = ["<h4>Convergence</h4>",
             _figure(figs.convergence if figs else "", f"{r.case}: error against h"),
             _simple_table(["Series", "Norm", "Formal order", "Observed order", "Order tolerance",
                            "Asymptotic", "Asymptotic rule"], summary, numeric={2, 3, 4})]
    for s in r.convergence:
        parts.append(f"<p><strong>Local orders, {esc(s.name)}</strong></p>" + _local_orders(s))
    return "\n".join(parts)


def _local_orders(s):
    rows = []
    for i, h in enumerate(s.h):
        error = s.error[i] if i < len(s.error) else float("nan")
        order = s.local_orders[i - 1] if 0 < i <= len(s.local_orders) else None
        rows.append((fmt.number(float(h)), fmt.number(float(error)),
                     fmt.number(float(order), 4) if order is not None else ""))
    return _simple_table(["h", "error", "local order (from the previous h)"], rows, {0, 1, 2})


def _speed_error(r, figs):
    if not r.speed_error:
        return ""
    return ("<h4>Speed against error</h4>"
            + _figure(figs.speed_error if figs else "", f"{r.case}: error against wall time")
            + f"<p>Cheapest set-up with error ≤ {fmt.ERROR_TARGET_TEXT}: "
              f"<strong>{esc(fmt.cheapest_text(r))}</strong></p>")


def _stability_map(r, figs):
    if not figs or not figs.stability_map:
        return ""
    return "<h4>Stability map</h4>" + _figure(figs.stability_map, f"{r.case}: stable and diverged runs")


def _series(r, figs):
    if not r.series:
        return ""
    paths = figs.series if figs else []
    items = [_figure(paths[i] if i < len(paths) else "", s.title or s.name)
             for i, s in enumerate(r.series)]
    return "<h4>Series</h4>" + "\n".join(items)


# -- regression ------------------------------------------------------------------------------

def _regression(report):
    if not report.regression:
        return ""
    blocks = [f"<details open><summary><code>{esc(name)}</code></summary><pre>{esc(text)}</pre></details>"
              for name, text in report.regression]
    return "<h2 id='regression'>Regression</h2>\n" + "\n".join(blocks)
