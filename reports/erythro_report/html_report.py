"""The HTML report: one self-contained index.html with PNG figures in img/.

Top to bottom: verdict and suite time, the slowest tests, one row per case, the
regression checks, the speed-against-error overview, then one collapsible section
per case and the regression details.
"""
from . import formatting as fmt
from . import html_summary as summary
from .html_case import case_section
from .html_common import CSS, SCRIPT, anchor_ids, badge, esc, figure, verdict_cell


def render(report, figures):
    ids = anchor_ids(report.records)
    parts = [
        _head(),
        summary.header(report),
        summary.failures(report, ids),
        summary.problems(report),
        summary.boxes(report, ids),
        _links(report, figures),
        summary.case_table(report, ids),
        summary.regression_table(report),
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
            f"<title>erythro V&amp;V report</title>\n<style>{CSS}</style>\n"
            f"<script>{SCRIPT}</script>\n</head>\n<body>")


def _links(report, figures):
    links = ["<a href='#cases'>Cases</a>"]
    if report.regression:
        links.append("<a href='#regression-summary'>Regression checks</a>")
    if figures.overview:
        links.append("<a href='#speed'>Speed against error</a>")
    links.append("<a href='#details'>Case details</a>")
    return f"<nav class='links'>{''.join(links)}</nav>"


def _overview(figures):
    if not figures.overview:
        return ""
    body = "\n".join(figure(p, "Error against wall time, one panel per case, one line per "
                               "parameter set") for p in figures.overview)
    return f"<h2 id='speed'>Speed against error</h2>\n{body}"


def _cases(report, figures, ids):
    out = ["<h2 id='details'>Case details</h2><p class='muted'>Click a case to open it; "
           "failed cases are open.</p>"]
    for record in report.records:
        out.append(case_section(record, figures.cases.get(record.path), ids[record.path]))
    return "\n".join(out)


# -- regression ------------------------------------------------------------------------------

def _regression(report):
    if not report.regression:
        return ""
    return ("<h2 id='regression'>Regression details</h2>\n<p class='muted'>A dataset passes when "
            "every element has |current − baseline| ≤ atol + rtol·|baseline|.</p>\n"
            + "\n".join(_regression_check(c) for c in report.regression))


def _regression_check(check):
    verdict = check.verdict or "not judged"
    rows = []
    for d in check.datasets:
        note = d.rel_note or d.detail
        rows.append(f"<tr><td><code>{esc(d.path)}</code></td>{verdict_cell('pass' if d.passed else 'fail')}"
                    f"<td>{esc(d.verdict_text)}</td><td class='num'>{esc(fmt.number(d.max_abs, 3))}</td>"
                    f"<td class='num'>{esc(fmt.number(d.max_rel, 3))}</td>"
                    f"<td class='num'>{esc(fmt.number(d.atol, 3))}</td>"
                    f"<td class='num'>{esc(fmt.number(d.rtol, 3))}</td>"
                    f"<td class='desc'>{esc(note)}</td></tr>")
    table = ("<table class='full'><tr><th>Dataset</th><th>Verdict</th><th>Result</th>"
             "<th class='num'>max |diff|</th><th class='num'>max rel</th><th class='num'>atol</th>"
             f"<th class='num'>rtol</th><th>Note</th></tr>{''.join(rows)}</table>") if rows else ""
    return (f"<details class='case' id='regression-{esc(check.name)}'{'' if check.passed else ' open'}>"
            f"<summary><h3>{esc(check.name)}</h3> {badge(verdict)}</summary>{table}"
            f"<details class='sub'><summary>Text as written by erythro compare</summary>"
            f"<pre>{esc(check.text)}</pre></details></details>")
