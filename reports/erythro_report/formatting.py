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


def value_text(metric):
    return with_unit(metric.value, metric.unit)


def expected_text(metric):
    """Expected value; for one-sided comparisons with its sign (≤ / ≥)."""
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


def verdict_text(verdict):
    if verdict in ("pass", "fail"):
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
    text = f"Records read from {report.results_dir}"
    if report.expect_file:
        text += f"; expected cases from {report.expect_file}"
        if report.labels:
            text += f" (labels {', '.join(report.labels)})"
        text += f": {plural(len(report.required), 'required case')}"
    else:
        text += "; no expected-cases list, so no case is required"
    return text + "."
