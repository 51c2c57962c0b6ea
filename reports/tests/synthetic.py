"""Small synthetic V&V result records, written with h5py as the C++ writer would.

`fixed=True` stores strings as fixed-length HDF5 strings (bytes when read back),
`fixed=False` as variable-length strings; the reader must handle both.
"""
import h5py
import numpy as np


def _text(value, fixed):
    if not fixed:
        return value
    data = value.encode("utf-8")
    return np.array(data, dtype=f"S{max(1, len(data))}")


def _set_attr(obj, name, value, fixed):
    obj.attrs[name] = _text(value, fixed) if isinstance(value, str) else value


def _string_dataset(group, name, values, fixed):
    if fixed:
        group.create_dataset(name, data=np.array([v.encode() for v in values]))
    else:
        group.create_dataset(name, data=values, dtype=h5py.string_dtype())


def metric(name, value, expected, tolerance, comparison="absolute", verdict="pass",
           description="", unit="", reason="chosen for the test"):
    return dict(name=name, value=value, expected=expected, tolerance=tolerance,
                comparison=comparison, verdict=verdict, description=description or f"the {name}",
                unit=unit, tolerance_reason=reason)


def write_record(path, case, family="verification.fluid", verdict="pass", metrics=(),
                 fixed=False, convergence=(), speed_error=(), series=(), runs=None,
                 parameters=None, git_revision="abc1234", schema_version=1, wall_time_s=1.5,
                 fields=(), key_metric=None):
    with h5py.File(path, "w") as f:
        root = dict(case=case, family=family, requirement=f"{case} meets its requirement",
                    reference="Synthetic et al. (2024)", verdict=verdict,
                    git_revision=git_revision, compiler="GNU 12.2.0", compile_flags="-O3",
                    created_utc="2024-01-01T00:00:00Z")
        for key, value in root.items():
            _set_attr(f, key, value, fixed)
        if wall_time_s is not None:
            f.attrs["wall_time_s"] = wall_time_s
        if key_metric is not None:
            _set_attr(f, "key_metric", key_metric, fixed)
        f.attrs["schema_version"] = np.int32(schema_version)
        params = f.create_group("parameters")
        for key, value in (parameters or {"tau": 0.8, "collision": "BGK", "N": 64}).items():
            _set_attr(params, key, value, fixed)
        group = f.create_group("metrics")
        for m in metrics:
            g = group.create_group(m["name"])
            for key, value in m.items():
                if key != "name":
                    _set_attr(g, key, value, fixed)
        if runs:
            _write_runs(f, runs, fixed)
        for c in convergence:
            _write_convergence(f, c, fixed)
        for s in speed_error:
            g = f.require_group("speed_error").create_group(s["name"])
            g["wall_time_s"] = np.asarray(s["wall_time_s"], dtype=float)
            g["error"] = np.asarray(s["error"], dtype=float)
            _string_dataset(g, "label", s["label"], fixed)
            if "group" in s:
                _string_dataset(g, "group", s["group"], fixed)
        for s in series:
            g = f.require_group("series").create_group(s["name"])
            for key in ("x", "y", "y_reference"):
                if key in s:
                    g[key] = np.asarray(s[key], dtype=float)
            for key in ("title", "xlabel", "ylabel"):
                _set_attr(g, key, s.get(key, ""), fixed)
            if "x_scale" in s:
                _set_attr(g, "x_scale", s["x_scale"], fixed)
        for fld in fields:
            _write_field(f, fld, fixed)


def _write_field(f, fld, fixed):
    g = f.require_group("fields").create_group(fld["name"])
    for key, value in fld.items():
        if key in ("data", "x", "y"):
            g[key] = np.asarray(value, dtype=float)
        elif key == "membranes":
            for i, outline in enumerate(value):
                g.require_group("membranes")[str(i)] = np.asarray(outline, dtype=float)
        elif key != "name":
            _set_attr(g, key, value, fixed)


def velocity_field(name="velocity", nx=48, ny=24):
    """|u| of a channel flow around a circular cell, with the cell's outline."""
    x = (np.arange(nx) + 0.5) / nx * 2.0
    y = (np.arange(ny) + 0.5) / ny
    xx, yy = np.meshgrid(x, y)
    speed = 4 * yy * (1 - yy) * (1 - np.exp(-((xx - 1) ** 2 + (yy - 0.5) ** 2) / 0.02))
    angle = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    outline = np.column_stack([1 + 0.15 * np.cos(angle), 0.5 + 0.15 * np.sin(angle)])
    return dict(name=name, data=speed, x=x, y=y, membranes=[outline], title="|u| at t = T",
                quantity="|u|", unit="mm/s", xlabel="x (mm)", ylabel="y (mm)")


def _write_runs(f, runs, fixed):
    g = f.create_group("runs")
    columns = list(runs)
    if fixed:
        g.attrs["columns"] = np.array([c.encode() for c in columns])
    else:
        g.attrs["columns"] = np.array(columns, dtype=h5py.string_dtype())
    for column, values in runs.items():
        if isinstance(values[0], str):
            _string_dataset(g, column, values, fixed)
        else:
            g[column] = np.asarray(values, dtype=float)


def _write_convergence(f, c, fixed):
    g = f.require_group("convergence").create_group(c["name"])
    h = np.asarray(c["h"], dtype=float)
    error = np.asarray(c["error"], dtype=float)
    g["h"], g["error"] = h, error
    g["local_orders"] = np.diff(np.log(error)) / np.diff(np.log(h))
    slope = float(np.polyfit(np.log(h), np.log(error), 1)[0])
    _set_attr(g, "norm", "relative L2 velocity", fixed)
    g.attrs["formal_order"] = c.get("formal_order", 2.0)
    g.attrs["observed_order"] = slope
    g.attrs["order_tolerance"] = 0.1
    g.attrs["asymptotic"] = np.int32(1)
    _set_attr(g, "asymptotic_rule", "local orders within 0.1 of each other", fixed)


def convergence_series(name, order, c=0.5, n=(16, 32, 64, 128)):
    h = 1.0 / np.asarray(n, dtype=float)
    wiggle = 1.0 + 0.03 * np.cos(np.arange(len(h)))
    return dict(name=name, h=h, error=c * h ** order * wiggle)


def speed_series(name, base_time, base_error, order=2.0, n=(16, 32, 64, 128)):
    n = np.asarray(n, dtype=float)
    return dict(name=name, wall_time_s=base_time * (n / n[0]) ** 3,
                error=base_error * (n[0] / n) ** order, label=[f"N={int(k)}" for k in n])


def passing_case(path, case="poiseuille_2d", fixed=False):
    """A passing case with convergence, speed-error, series and runs."""
    x = np.linspace(0.0, 1.0, 41)
    write_record(
        path, case, fixed=fixed,
        metrics=[metric("order_bgk_tau0.8", 1.98, 2.0, 0.1, description="observed order, BGK"),
                 metric("error_N128", 4e-5, 1e-4, 0.0, comparison="at_most", unit="",
                        description="relative L2 error at N=128"),
                 metric("mass_drift", 1.001, 1.0, 0.01, comparison="relative",
                        description="mass after 1000 steps")],
        runs={"N": [16, 32, 64, 128], "collision": ["BGK"] * 4,
              "error": [3.1e-3, 7.9e-4, 2.0e-4, 5.0e-5]},
        convergence=[convergence_series("BGK tau=0.8", 2.0),
                     convergence_series("TRT magic=0.25", 2.0, c=0.2)],
        speed_error=[speed_series("BGK", 0.01, 5e-3), speed_series("TRT", 0.012, 2e-3)],
        series=[dict(name="velocity profile", x=x, y=4 * x * (1 - x) * 1.002,
                     y_reference=4 * x * (1 - x), title="u(y) at x = L/2", xlabel="y / H",
                     ylabel="u / u_max")])


def failing_case(path, case="couette_2d", fixed=True):
    write_record(
        path, case, family="verification.boundary", verdict="fail", fixed=fixed,
        metrics=[metric("order_wall", 1.2, 2.0, 0.1, verdict="fail",
                        description="observed order with bounce-back walls",
                        reason="Richardson | pipes must survive Markdown"),
                 metric("max_velocity", 0.1, 0.1, 1e-6, verdict="pass",
                        description="peak velocity", unit="lu/ts")],
        convergence=[convergence_series("bounce-back", 1.2)],
        speed_error=[speed_series("BGK", 0.02, 8e-3, order=1.2)])


# Regression texts as `erythro compare` writes them (solver/io/baseline_compare.cpp).
REGRESSION_PASSED = """same  /diagnostics/step: max |diff| = 0, max rel = 0 (atol 0, rtol 0)
same  /fields/velocity: max |diff| = 3e-15, max rel = 159 (atol 1e-09, rtol 1e-09)
same  /fields/density: max |diff| = 2e-13, max rel = 2e-16 (atol 0, rtol 1e-12)
regression check: all quantities within tolerance
"""
REGRESSION_MOVED = """same  /diagnostics/step: max |diff| = 0, max rel = 0 (atol 0, rtol 0)
MOVED /fields/density: max |diff| = 0.2, max rel = 0.0002 (atol 0, rtol 1e-12); worst at element 7: baseline 1000 -> current 1000.2
regression check: FAILED
"""
