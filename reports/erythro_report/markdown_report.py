"""summary.md: one row per case first, then the slowest tests, then each case's metrics.

For a CI job summary or a merge-request comment. The requirement is written once per
case, and a tolerance reason once per run of metrics that share it.
"""
from . import formatting as fmt
from .regression import summary_text
from .timing import duration_text


def cell(value):
    """Text safe inside a Markdown table cell."""
    return str(value).replace("\\", "\\\\").replace("|", "\\|").replace("\n", " ").strip()


def _row(cells):
    return "| " + " | ".join(cell(c) for c in cells) + " |"


def _table(headers, rows):
    return [_row(headers), _row(["---"] * len(headers))] + [_row(r) for r in rows] + [""]


CASE_HEADERS = ["Family", "Case", "Verdict", "Metrics passed", "Key figure", "Time"]
METRIC_HEADERS = ["Metric", "Value", "Expected", "Tolerance", "Verdict", "Why this tolerance"]


def render(report):
    lines = ["# erythro V&V report", "",
             f"**{fmt.status_text(report)}**: {fmt.banner_text(report)}", "",
             fmt.summary_line(report), "",
             fmt.scope_line(report), ""]
    lines += _failures(report) + _problems(report)
    missing = [["", case, "MISSING", "", "no result record", ""] for case in report.missing]
    lines += ["## Cases", ""] + _table(CASE_HEADERS, missing + [_case_row(r) for r in report.records])
    lines += _time(report) + _regression(report) + _cheapest(report)
    lines += ["## Metrics of each case", ""]
    for record in report.records:
        lines += _case_metrics(record)
    return "\n".join(lines).rstrip() + "\n"


def _failures(report):
    items = [f"- **{cell(r.case)}**: failed metrics "
             + cell(", ".join(m.name for m in r.metrics if m.verdict == "fail") or "none recorded")
             for r in report.failed_records]
    items += [f"- **regression {cell(c.name)}**: {cell(summary_text(c))}"
              for c in report.failed_regressions]
    return ["## Failed", ""] + items + [""] if items else []


def _problems(report):
    if not report.problems:
        return []
    return ["## Problems", ""] + [f"- **{cell(p.subject)}**: {cell(p.message)}"
                                  for p in report.problems] + [""]


def _time_cell(record):
    text = duration_text(record.time_s)
    return f"{text} (ctest)" if record.time_source == "ctest" else text


def _case_row(r):
    passed = sum(1 for m in r.metrics if m.verdict == "pass")
    return [r.family, r.case, fmt.verdict_text(r.verdict), f"{passed} / {len(r.metrics)}",
            fmt.key_figure_text(fmt.key_metric(r)), _time_cell(r)]


def _time(report):
    t = report.timing
    lines = ["## Time", ""]
    if t.folders:
        lines.append(f"Wall time {duration_text(t.wall_s)} ({fmt.plural(t.n_runs, 'ctest run')}"
                     + (f", {len(t.folders)} folders run side by side" if len(t.folders) > 1 else "")
                     + f"); sum of test times {duration_text(t.sum_s)} over "
                       f"{fmt.plural(len(t.tests), 'test')}.")
    elif t.measured:
        lines.append(f"Sum of case times {duration_text(t.sum_s)} (no ctest JUnit file found).")
    lines += [fmt.time_sources_text(report), ""]
    if t.tests:
        rows = [[x.name, duration_text(x.seconds), x.source] for x in t.slowest()]
        lines += ["Slowest tests:", ""] + _table(["Test", "Time", "Source"], rows)
    return lines


def _regression(report):
    if not report.regression:
        return []
    rows = [[c.name, fmt.verdict_text(c.verdict) if c.verdict else "not judged", summary_text(c)]
            for c in report.regression]
    return ["## Regression checks", ""] + _table(["Check", "Verdict", "Result"], rows)


def _cheapest(report):
    cases = [r for r in report.records if r.speed_error]
    if not cases:
        return []
    return ([f"## Cheapest set-up with error ≤ {fmt.ERROR_TARGET_TEXT}", ""]
            + _table(["Case", "Set-up"], [[r.case, fmt.cheapest_text(r)] for r in cases]))


def _case_metrics(record):
    head = [f"### {record.case}: {fmt.verdict_text(record.verdict)}", ""]
    if record.requirement:
        head += [f"Requirement: {cell(record.requirement)}", ""]
    if not record.metrics:
        return head + ["(no metrics)", ""]
    rows, previous = [], None
    for m in record.metrics:
        reason = m.tolerance_reason
        shown = "as above" if reason and reason == previous else reason
        previous = reason
        rows.append([fmt.metric_title(m), fmt.value_text(m), fmt.expected_text(m),
                     fmt.tolerance_text(m), fmt.verdict_text(m.verdict), shown])
    return head + _table(METRIC_HEADERS, rows)
