"""Numbers, tolerances and per-case findings as plain text (shared by HTML and Markdown)."""
import math

ERROR_TARGET = 1e-3   # the error level for "cheapest set-up"
ERROR_TARGET_TEXT = "1e-3"

COMPARISON_TEXT = {
    "absolute": "absolute",
    "relative": "relative",
    "at_most": "at most",
    "at_least": "at least",
}


def number(x, digits=6):
    """A float with `digits` significant digits; NaN as an em dash."""
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    return f"{x:.{digits}g}"


def with_unit(x, unit, digits=6):
    text = number(x, digits)
    return f"{text} {unit}" if unit and text != "—" else text


def is_flag(metric):
    """A yes/no check written as a number: value 0 or 1 that must be 1, tolerance 0, no unit.

    The C++ cases write these as `absolute` (expected 1, tolerance 0) or `at_least 1`
    (descriptions "1 if …"). A count that must be at least 1 reads the same way ("yes":
    there is one); counts with a unit, and limits of 0 (`at_most 0`: "violations"), keep
    their number.
    """
    if metric.unit or metric.tolerance != 0 or metric.expected != 1 or metric.value not in (0.0, 1.0):
        return False
    return metric.comparison in ("absolute", "at_least")


def is_informative(metric):
    """A measurement without a requirement (a speed on a shared machine): one-sided with an
    infinite limit, so any finite value passes and only NaN fails."""
    e = metric.expected
    return (metric.comparison == "at_least" and e == -math.inf) or (metric.comparison == "at_most" and e == math.inf)


def value_text(metric):
    if is_flag(metric):
        return "yes" if metric.value == 1 else "no"
    return with_unit(metric.value, metric.unit)


def expected_text(metric):
    """Expected value; for one-sided comparisons with its sign (≤ / ≥)."""
    if is_flag(metric):
        return "yes"
    if is_informative(metric):
        return "informative: any finite value"
    text = with_unit(metric.expected, metric.unit)
    if metric.comparison == "at_most":
        return f"≤ {text}"
    if metric.comparison == "at_least":
        return f"≥ {text}"
    return text


def tolerance_text(metric):
    """The tolerance with the kind of comparison, e.g. '± 0.05 (absolute)'."""
    kind = metric.comparison
    tol = metric.tolerance
    if is_flag(metric):
        return "yes/no check"
    if kind == "absolute":
        return f"± {with_unit(tol, metric.unit, 3)} (absolute)"
    if kind == "relative":
        return f"± {number(tol * 100.0, 3)} % (relative)"
    if kind in ("at_most", "at_least"):
        extra = f", tolerance {number(tol, 3)}" if tol and not math.isnan(tol) else ""
        return f"one-sided ({COMPARISON_TEXT[kind]}){extra}"
    return f"{number(tol, 3)} (unknown comparison {kind!r})"


def metric_title(metric):
    return f"{metric.name}: {metric.description}" if metric.description else metric.name


def limit_text(metric):
    """The requirement on the value in one short phrase: '≤ 0.005', '2 ± 0.1', '1 ± 1 %'."""
    if is_flag(metric):
        return "must be yes"
    tol = metric.tolerance
    if metric.comparison == "absolute":
        return f"{number(metric.expected)} ± {with_unit(tol, metric.unit, 3)}"
    if metric.comparison == "relative":
        return f"{with_unit(metric.expected, metric.unit)} ± {number(tol * 100.0, 3)} %"
    return expected_text(metric)


def usage(metric):
    """How much of its allowance a metric uses: 0 at the expected value, 1 at the limit.

    NaN when it cannot be said (a one-sided limit of 0, a zero tolerance, a flag).
    """
    v, e, tol = metric.value, metric.expected, metric.tolerance
    if is_flag(metric) or not all(map(math.isfinite, (v, e))):
        return float("nan")
    if metric.comparison == "absolute":
        return abs(v - e) / tol if tol > 0 else float("nan")
    if metric.comparison == "relative":
        return abs(v - e) / (tol * abs(e)) if tol > 0 and e != 0 else float("nan")
    if metric.comparison == "at_most" and e > 0 and v >= 0:
        return v / e
    if metric.comparison == "at_least" and e > 0 and v > 0:
        return e / v
    return float("nan")


def key_metric(record):
    """The metric the one-row summary shows: the record's `key_metric` if it names one,
    else the first failed metric, else the one nearest its limit: among the metrics
    compared with an expected value (absolute, relative) if there are any, since these
    carry the case's claim, else among the one-sided ones; else the first."""
    by_name = {m.name: m for m in record.metrics}
    if record.key_metric in by_name:
        return by_name[record.key_metric]
    failed = [m for m in record.metrics if m.verdict != "pass"]
    if failed:
        return failed[0]
    rated = [(m.comparison in ("absolute", "relative"), usage(m), -i)
             for i, m in enumerate(record.metrics) if not math.isnan(usage(m))]
    if rated:
        return record.metrics[-max(rated)[2]]
    return record.metrics[0] if record.metrics else None


def key_figure_text(metric):
    """'order BGK = 1.915 (≥ 1.8)' for the one-row summary."""
    if metric is None:
        return "no metrics"
    return f"{metric.name} = {value_text(metric)} ({limit_text(metric)})"


def verdict_text(verdict):
    if verdict in ("pass", "fail", "not judged"):
        return verdict.upper()
    return f"INVALID ({verdict!r})" if verdict else "MISSING"


def cheapest_setup(record, target=ERROR_TARGET):
    """(series, label, wall_time_s, error) of the fastest point with error ≤ target, or None."""
    best = None
    for s in record.speed_error:
        for i, (t, e) in enumerate(zip(s.wall_time_s, s.error)):
            if not (math.isfinite(t) and math.isfinite(e)) or e > target:
                continue
            if best is None or t < best[2]:
                label = s.label[i] if i < len(s.label) else f"point {i + 1}"
                best = (s.name, label, float(t), float(e))
    return best


def cheapest_text(record):
    best = cheapest_setup(record)
    if best is None:
        return f"none reaches {ERROR_TARGET_TEXT}"
    name, label, wall, error = best
    return f"{name} {label} ({number(wall, 3)} s, error {number(error, 3)})"


def asymptotic_text(series):
    if series.asymptotic is None:
        return "not recorded"
    return "yes" if series.asymptotic else "no"


def plural(n, word, words=None):
    return f"{n} {word if n == 1 else (words or word + 's')}"


def status_text(report):
    """'PASS' or 'FAIL' for the whole report."""
    return "PASS" if report.ok else "FAIL"


def summary_line(report):
    """'3 cases, 9 metrics, 1 failed case (2 failed metrics), 0 problems; git revision …; …'."""
    failed = len(report.failed_records)
    revisions = ", ".join(report.revisions) or "not recorded"
    revision_word = "git revision" if len(report.revisions) <= 1 else "git revisions"
    return (f"{plural(len(report.records), 'case')}, {plural(report.n_metrics, 'metric')}, "
            f"{plural(failed, 'failed case')} ({plural(report.n_failed_metrics, 'failed metric')}), "
            f"{plural(len(report.problems), 'problem')}; "
            f"{revision_word} {revisions}; generated {report.generated_utc}")


def scope_line(report):
    """Where the records came from and which cases were required."""
    folders = report.results_dirs
    if len(folders) == 1:
        text = f"Records read from {folders[0]}"
    else:
        text = f"Records merged from {len(folders)} folders ({', '.join(folders)})"
    if report.expect_files:
        text += f"; expected cases from {', '.join(report.expect_files)}"
        if report.labels:
            text += f" (labels {', '.join(report.labels)})"
        text += f": {plural(len(report.required), 'required case')}"
    else:
        text += "; no expected-cases list, so no case is required"
    return text + "."


def banner_text(report):
    """'All 54 cases passed.' or '1 case failed, 2 problems.' (and the regression checks)."""
    checks = report.regression
    if report.ok:
        text = f"All {plural(len(report.records), 'case')} passed"
        if checks:
            text += f"; all {plural(len(checks), 'regression check')} within tolerance"
        return text + "."
    parts = []
    if report.failed_records:
        parts.append(f"{plural(len(report.failed_records), 'case')} of {len(report.records)} failed")
    if report.failed_regressions:
        parts.append(plural(len(report.failed_regressions), "regression check") + " moved")
    if report.problems:
        parts.append(plural(len(report.problems), "problem"))
    return ", ".join(parts) + "."


def time_sources_text(report):
    """Where the case times come from, e.g. 'Case times: 50 from the records, 4 from ctest'."""
    by_source = {"record": 0, "ctest": 0, "": 0}
    for r in report.records:
        by_source[r.time_source] = by_source.get(r.time_source, 0) + 1
    parts = [f"{by_source['record']} from the records (wall_time_s)"]
    if by_source["ctest"]:
        parts.append(f"{by_source['ctest']} from ctest (the record has no wall_time_s)")
    if by_source[""]:
        parts.append(f"{by_source['']} without a time")
    return "Case times: " + ", ".join(parts) + "."
