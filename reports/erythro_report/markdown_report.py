"""summary.md: the pass/fail table (and problems) in Markdown, e.g. for a CI summary."""
from . import formatting as fmt


def cell(value):
    """Text safe inside a Markdown table cell."""
    return str(value).replace("\\", "\\\\").replace("|", "\\|").replace("\n", " ").strip()


def _row(cells):
    return "| " + " | ".join(cell(c) for c in cells) + " |"


HEADERS = ["Case", "Requirement", "Metric", "Value", "Expected", "Tolerance", "Verdict",
           "Why this tolerance"]


def render(report):
    lines = ["# erythro V&V report", "",
             f"**{fmt.status_text(report)}**: {fmt.summary_line(report)}", "",
             fmt.scope_line(report), ""]
    lines += _problems(report)
    lines += ["## Pass/fail table", "", _row(HEADERS), _row(["---"] * len(HEADERS))]
    for record in report.records:
        lines += _case_rows(record)
    lines += [""] + _cheapest(report) + _regression(report)
    return "\n".join(lines).rstrip() + "\n"


def _problems(report):
    if not report.problems:
        return []
    return ["## Problems", ""] + [f"- **{cell(p.subject)}**: {cell(p.message)}"
                                  for p in report.problems] + [""]


def _case_rows(record):
    if not record.metrics:
        return [_row([record.case, record.requirement, "(no metrics)", "", "", "",
                      fmt.verdict_text(record.verdict), ""])]
    return [_row([record.case, record.requirement, fmt.metric_title(m), fmt.value_text(m),
                  fmt.expected_text(m), fmt.tolerance_text(m), fmt.verdict_text(m.verdict),
                  m.tolerance_reason])
            for m in record.metrics]


def _cheapest(report):
    cases = [r for r in report.records if r.speed_error]
    if not cases:
        return []
    return ([f"## Cheapest set-up with error ≤ {fmt.ERROR_TARGET_TEXT}", "", _row(["Case", "Set-up"]),
             _row(["---", "---"])]
            + [_row([r.case, fmt.cheapest_text(r)]) for r in cases] + [""])


def _regression(report):
    if not report.regression:
        return []
    return (["## Regression", "", "Comparisons (shown in full in index.html):", ""]
            + [f"- `{name}`" for name, _ in report.regression] + [""])
