"""The first screen of index.html: verdict, suite time, slowest tests, one row per case."""
import math

from . import formatting as fmt
from .html_common import badge, esc, verdict_cell
from .regression import summary_text
from .timing import duration_text

PROBLEMS_SHOWN = 5   # the rest of a long list is folded, so the verdicts stay on the first screen


def header(report):
    status = "pass" if report.ok else "fail"
    return (f"<header><h1>erythro V&amp;V report {badge(status)}</h1>\n"
            f"<div class='banner {status}'>{esc(fmt.status_text(report))}: "
            f"{esc(fmt.banner_text(report))} <span class='summary'>{esc(fmt.summary_line(report))}"
            f"</span></div>\n<p class='scope'>{esc(fmt.scope_line(report))}</p></header>")


def failures(report, ids):
    """What failed, linked to its section, before anything else."""
    items = []
    for r in report.failed_records:
        names = ", ".join(m.name for m in r.metrics if m.verdict == "fail") or "no failed metric recorded"
        items.append(f"<li><a href='#{ids[r.path]}'><strong>{esc(r.case)}</strong></a>: "
                     f"failed metrics {esc(names)}</li>")
    for c in report.failed_regressions:
        items.append(f"<li><a href='#regression-{esc(c.name)}'><strong>regression {esc(c.name)}"
                     f"</strong></a>: {esc(summary_text(c))}</li>")
    if not items:
        return ""
    shown, folded = items[:PROBLEMS_SHOWN], items[PROBLEMS_SHOWN:]
    more = (f"<details><summary>{len(folded)} more</summary><ul>{''.join(folded)}</ul></details>"
            if folded else "")
    return (f"<h2 id='failed'>Failed ({len(items)})</h2>\n"
            f"<div class='failed'><ul>{''.join(shown)}</ul>{more}</div>")


def problems(report):
    if not report.problems:
        return ""
    items = [f"<li><strong>{esc(p.subject)}</strong>: {esc(p.message)}</li>" for p in report.problems]
    shown, folded = items[:PROBLEMS_SHOWN], items[PROBLEMS_SHOWN:]
    more = (f"<details><summary>{len(folded)} more</summary><ul>{''.join(folded)}</ul></details>"
            if folded else "")
    return (f"<h2 id='problems'>Problems ({len(report.problems)})</h2>\n"
            f"<div class='problems'><ul>{''.join(shown)}</ul>{more}</div>")


def boxes(report, ids):
    """Verdicts by family and the suite's time (left), the slowest tests (right)."""
    return (f"<div class='boxes'><div class='box'>{_suite_time(report)}{_families(report)}</div>"
            f"<div class='box'>{_slowest(report, ids)}</div></div>")


def _families(report):
    rows = []
    for family, records in report.families():
        failed = sum(1 for r in records if r.verdict != "pass")
        cls = "fail" if failed else "pass"
        rows.append(f"<tr><td>{esc(family or '(no family)')}</td><td class='num'>{len(records)}</td>"
                    f"<td class='num {cls}'>{len(records) - failed}</td>"
                    f"<td class='num {'fail' if failed else ''}'>{failed}</td></tr>")
    if report.regression:
        moved = len(report.failed_regressions)
        passed = sum(1 for c in report.regression if c.passed)
        rows.append(f"<tr><td>regression checks</td><td class='num'>{len(report.regression)}</td>"
                    f"<td class='num {'fail' if moved else 'pass'}'>{passed}</td>"
                    f"<td class='num {'fail' if moved else ''}'>{moved}</td></tr>")
    return ("<h2>Verdicts by family</h2><table class='full compact'><tr><th>Family</th>"
            "<th class='num'>cases</th>"
            f"<th class='num'>passed</th><th class='num'>failed</th></tr>{''.join(rows)}</table>")


def _suite_time(report):
    t = report.timing
    lines = []
    if math.isfinite(t.wall_s):
        runs = fmt.plural(t.n_runs, "ctest run")
        shards = f" in {len(t.folders)} folders side by side, the slowest" if len(t.folders) > 1 else ""
        lines.append(f"<span class='big'>{esc(duration_text(t.wall_s))}</span> wall time "
                     f"({esc(runs)}{esc(shards)})")
        if t.measured:
            lines.append(f"sum of test times {esc(duration_text(t.sum_s))} over "
                         f"{esc(fmt.plural(len(t.tests), 'test'))}")
    elif t.measured:
        lines.append(f"<span class='big'>{esc(duration_text(t.sum_s))}</span> sum of the case "
                     "times (no ctest JUnit file, so no wall time)")
    lines.append(f"<span class='desc'>{esc(fmt.time_sources_text(report))}</span>")
    return "<h2>Suite time</h2><p class='tight'>" + "<br>".join(lines) + "</p>"


def _slowest(report, ids):
    slow = report.timing.slowest()
    if not slow:
        return "<h2>Slowest tests</h2><p class='muted'>No times recorded.</p>"
    top = slow[0].seconds or 1.0
    total = report.timing.sum_s or 1.0
    paths = {r.path: r for r in report.records}
    rows = []
    for t in slow:
        name = esc(t.name)
        if t.record_path in ids:
            name = f"<a href='#{ids[t.record_path]}'>{name}</a>"
        record = paths.get(t.record_path)
        verdict = record.verdict if record else t.ctest_verdict
        verdict = verdict_cell(verdict) if verdict else "<td></td>"
        src = "" if t.source == "record" else " <span class='src'>ctest</span>"
        rows.append(f"<tr><td>{name}</td>{verdict}<td class='num'>{esc(duration_text(t.seconds))}{src}</td>"
                    f"<td class='num'>{100 * t.seconds / total:.0f} %</td><td class='barcell'>"
                    f"<span class='bar' style='width:{100 * t.seconds / top:.1f}%'></span></td></tr>")
    return (f"<h2>Slowest tests</h2><table class='full'><tr><th>Test</th><th>Verdict</th>"
            f"<th class='num'>Time</th><th class='num'>Share</th><th></th></tr>{''.join(rows)}</table>")


def case_table(report, ids):
    """One row per case, grouped by family: case, verdict, metrics passed, key figure, time."""
    rows = []
    if report.missing:
        rows.append(f"<tr class='family'><td colspan='5'>required, but no record "
                    f"({len(report.missing)})</td></tr>")
        rows += [f"<tr><td>{esc(case)}</td>{verdict_cell('')}<td colspan='3' class='desc'>"
                 "no result record: the case did not run, crashed, or ran in no shard</td></tr>"
                 for case in report.missing]
    for family, records in report.families():
        rows.append(f"<tr class='family'><td colspan='5'>{esc(family or '(no family)')} "
                    f"({len(records)})</td></tr>")
        rows += [_case_row(r, ids[r.path]) for r in records]
    head = ("<tr><th>Case</th><th>Verdict</th><th class='num'>Metrics passed</th>"
            "<th>Key figure <span class='desc'>(the failed metric, or the one nearest its limit)"
            "</span></th><th class='num'>Time</th></tr>")
    missing = f", {len(report.missing)} missing" if report.missing else ""
    return (f"<h2 id='cases'>Cases ({len(report.records)}{missing})</h2>\n<table class='full cases'>{head}"
            + "\n".join(rows) + "</table>")


def _case_row(r, anchor):
    passed = sum(1 for m in r.metrics if m.verdict == "pass")
    key = fmt.key_metric(r)
    key_cls = " fail" if key is not None and key.verdict == "fail" else ""
    src = " <span class='src'>ctest</span>" if r.time_source == "ctest" else ""
    return (f"<tr><td><a href='#{anchor}'>{esc(r.case)}</a></td>{verdict_cell(r.verdict)}"
            f"<td class='num'>{passed} / {len(r.metrics)}</td>"
            f"<td class='key{key_cls}'>{esc(fmt.key_figure_text(key))}</td>"
            f"<td class='num'>{esc(duration_text(r.time_s))}{src}</td></tr>")


def regression_table(report):
    if not report.regression:
        return ""
    rows = []
    for check in report.regression:
        verdict = check.verdict or "not judged"
        rows.append(f"<tr><td><a href='#regression-{esc(check.name)}'>{esc(check.name)}</a></td>"
                    f"{verdict_cell(verdict)}<td>{esc(summary_text(check))}</td></tr>")
    return ("<h2 id='regression-summary'>Regression checks</h2><table class='full'><tr><th>Check</th>"
            f"<th>Verdict</th><th>Result</th></tr>{''.join(rows)}</table>")
