#!/usr/bin/env python3
"""Crash-safe output of `erythro run` (issue 17), end to end, with faults injected.

(a) write failures at every point of a run (the test hook ERYTHRO_FAULT_H5_WRITE_AFTER=N,
    docs/cli.md) and real ones (a file-size limit: the kernel refuses the write, EFBIG):
    exit 4 with a message naming run.h5, no partial file, and either no run.h5 or a
    readable one; an earlier run kept by a failed --force rerun is untouched;
(b) SIGTERM and SIGINT: status `interrupted`, exit 143 / 130, a readable run.h5 holding the
    diagnostics so far, run.xdmf beside it;
(c) kill -9: the temporary file holds the diagnostics flushed so far (every 256 samples or
    2 s), an earlier run beside it is untouched, and the next run removes it;
(d) two runs into one folder: the second is refused at once (exit 4, naming the folder and
    the first run's PID), the first completes.

Usage: safe_output_test.py ERYTHRO SOURCE_DIR WORK_DIR
"""
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import h5py

ERYTHRO, SRC, WORK = sys.argv[1:4]
SCENES = os.path.join(SRC, "scenes")
failures = []


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + detail))
    if not condition:
        failures.append(name)


def scene(name):
    return os.path.join(SCENES, name + ".toml")


def run_args(scene_name, out, *settings, force=False):
    args = [ERYTHRO, "run", scene(scene_name), "--out", out, "--quiet"]
    for s in settings:
        args += ["--set", s]
    return args + (["--force"] if force else [])


# A Poiseuille run long enough to be signalled (about 10 s without steady-state stop).
LONG = ("run.steps=1500000", "run.steady_state.check_interval_steps=100000000")


def partials(folder):
    return [f for f in os.listdir(folder) if ".partial-" in f] if os.path.isdir(folder) else []


def wait_for_partial(folder, process, timeout=10.0):
    """Waits until the run has created its temporary run.h5 (it holds the folder's lock by then)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and process.poll() is None:
        if partials(folder):
            return True
        time.sleep(0.02)
    return False


def status_of(path):
    with h5py.File(path, "r") as f:
        return f["metadata"].attrs["status"], len(f["diagnostics/step"])


def xdmf_resolves(folder):
    """Every HDF5 path that run.xdmf names exists in the run.h5 beside it."""
    root = ET.parse(os.path.join(folder, "run.xdmf")).getroot()
    items = [d.text.strip() for d in root.iter("DataItem") if d.get("Format") == "HDF"]
    for item in items:
        name, path = item.split(":", 1)
        with h5py.File(os.path.join(folder, name), "r") as f:
            if path not in f:
                return False
    return True


def readable_or_absent(folder):
    path = os.path.join(folder, "run.h5")
    if not os.path.exists(path):
        return True
    try:
        status_of(path)
        return xdmf_resolves(folder)
    except Exception:
        return False


def fault_injection():
    """(a) The N-th HDF5 write and every later one fail, for N = 1 … until the run succeeds."""
    def short(steps, fields, samples):
        return (f"run.steps={steps}", f"output.fields_interval_steps={fields}",
                f"output.diagnostics_interval_steps={samples}")
    cases = [  # scene, settings, stride of N: fluid only (every write), cells, transport
        ("poiseuille", short(400, 200, 50), 1),
        ("capsule_shear", short(20, 10, 5), 7),
        ("rbc_deoxygenation", short(20, 10, 5), 7),
    ]
    for name, settings, stride in cases:
        out = os.path.join(WORK, "fault", name)
        tried, bad = 0, []
        n = 1
        while n < 1000:
            shutil.rmtree(out, ignore_errors=True)
            env = dict(os.environ, ERYTHRO_FAULT_H5_WRITE_AFTER=str(n))
            r = subprocess.run(run_args(name, out, *settings), env=env, capture_output=True, text=True, timeout=60)
            if r.returncode == 0:
                break
            tried += 1
            message_ok = re.search(r"erythro: error: cannot write '.*run\.h5'.*No space left on device", r.stderr)
            if r.returncode != 4 or not message_ok or partials(out) or not readable_or_absent(out):
                bad.append(f"N={n}: exit {r.returncode}, partials {partials(out)}, stderr {r.stderr.strip()!r}")
            n += stride
        check(f"fault_injection_{name}", tried > 10 and not bad and n < 1000,
              f"{tried} faults, run never succeeded" if n >= 1000 else "; ".join(bad[:3]))
        print(f"     {name}: {tried} runs, first failing write N = 1 to {n - stride} in steps of {stride}; "
              f"N = {n} lets the run complete")


def file_size_limit():
    """(a) Real write failures: the kernel refuses writes past a file-size limit (EFBIG)."""
    out = os.path.join(WORK, "limit")
    settings = ("run.steps=4000", "output.fields_interval_steps=1000", "output.diagnostics_interval_steps=10")
    outcomes = []
    for kib in range(0, 520, 40):  # the complete run.h5 has about 480 KiB (300 of them /profiles)
        def limit(kib=kib):
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a failed write, not a killed process
            resource.setrlimit(resource.RLIMIT_FSIZE, (kib * 1024, resource.RLIM_INFINITY))
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        r = subprocess.run(run_args("poiseuille", out, *settings), preexec_fn=limit, capture_output=True, text=True,
                           timeout=60)
        ok = (r.returncode == 0 and readable_or_absent(out)) or (
            r.returncode == 4 and "run.h5" in r.stderr and not os.path.exists(os.path.join(out, "run.h5")))
        outcomes.append((kib, r.returncode))
        if not ok or partials(out):
            detail = f"exit {r.returncode}, partials {partials(out)}, {r.stderr.strip()!r}"
            check(f"file_size_limit_{kib}k", False, detail)
            return
    codes = {code for _, code in outcomes}
    check("file_size_limit", codes == {0, 4}, f"expected failed and complete runs: {outcomes}")
    print("     limits (KiB, exit):", outcomes)


def failed_force_rerun_keeps_earlier_run():
    """(a) A --force rerun that cannot write leaves the earlier run.h5 and run.xdmf as they were."""
    out = os.path.join(WORK, "keep")
    shutil.rmtree(out, ignore_errors=True)
    settings = ("run.steps=400", "output.fields_interval_steps=200")
    subprocess.run(run_args("poiseuille", out, *settings), capture_output=True, check=True)
    before = {n: open(os.path.join(out, n), "rb").read() for n in ("run.h5", "run.xdmf")}
    env = dict(os.environ, ERYTHRO_FAULT_H5_WRITE_AFTER="40")
    r = subprocess.run(run_args("poiseuille", out, *settings, force=True), env=env, capture_output=True, text=True)
    after = {n: open(os.path.join(out, n), "rb").read() for n in ("run.h5", "run.xdmf")}
    check("failed_force_rerun_keeps_earlier_run", r.returncode == 4 and before == after and not partials(out),
          f"exit {r.returncode}, files changed: {before != after}, partials {partials(out)}")


def interrupted(sig, code):
    """(b) A signal ends the run after the step in progress, with its output in place."""
    name = signal.Signals(sig).name
    out = os.path.join(WORK, "signal_" + name)
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.Popen(run_args("poiseuille", out, *LONG, "output.diagnostics_interval_steps=10"),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    started = wait_for_partial(out, p)
    time.sleep(0.3)
    p.send_signal(sig)
    _, err = p.communicate(timeout=30)
    try:
        status, samples = status_of(os.path.join(out, "run.h5"))
        index_ok = xdmf_resolves(out)
    except Exception as e:  # no file, or not readable
        status, samples, index_ok = repr(e), 0, False
    check(f"interrupted_by_{name}",
          started and p.returncode == code and status == "interrupted" and samples > 0 and index_ok
          and f"interrupted by {name} after step" in err and not partials(out),
          f"exit {p.returncode}, status {status}, {samples} samples, index {index_ok}, partials {partials(out)}, "
          f"stderr {err.strip()!r}")


def killed(out, *settings, seconds, force=False):
    """Runs into `out`, kills it with SIGKILL after `seconds`; returns its PID."""
    p = subprocess.Popen(run_args("poiseuille", out, *LONG, *settings, force=force),
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_partial(out, p)
    time.sleep(seconds)
    p.kill()
    p.wait()
    return p.pid


def kill_9_and_rerun():
    """(c) What a killed run leaves, and the next run's clean-up."""
    # Samples every 20 000 steps (a few per second): only the 2 s flush puts them on disk.
    out = os.path.join(WORK, "kill_slow")
    shutil.rmtree(out, ignore_errors=True)
    pid = killed(out, "output.diagnostics_interval_steps=20000", seconds=2.6)
    left = partials(out)
    samples = -1
    if left:
        with h5py.File(os.path.join(out, left[0]), "r") as f:
            samples = len(f["diagnostics/step"])
    check("kill_9_flushed_by_time", left == [f"run.h5.partial-{pid}"] and samples > 0,
          f"partials {left}, {samples} samples")

    r = subprocess.run(run_args("poiseuille", out, "run.steps=400"), capture_output=True, text=True)
    note = f"removed '{out}/run.h5.partial-{pid}' left by process {pid}, which is no longer running"
    check("rerun_removes_stale_partial",
          r.returncode == 0 and note in r.stderr and not partials(out) and readable_or_absent(out),
          f"exit {r.returncode}, partials {partials(out)}, stderr {r.stderr.strip()!r}")

    # A --force rerun killed: the earlier pair stays whole; samples every step: the flush
    # every 256 samples has put some on disk within the first second.
    before = {n: open(os.path.join(out, n), "rb").read() for n in ("run.h5", "run.xdmf")}
    pid = killed(out, "output.diagnostics_interval_steps=1", seconds=0.5, force=True)
    after = {n: open(os.path.join(out, n), "rb").read() for n in ("run.h5", "run.xdmf")}
    left = partials(out)
    samples = -1
    if left:
        with h5py.File(os.path.join(out, left[0]), "r") as f:
            samples = len(f["diagnostics/step"])
    check("killed_force_rerun_keeps_earlier_pair", before == after and xdmf_resolves(out), "run.h5 or run.xdmf changed")
    check("kill_9_flushed_by_count", samples >= 256, f"partials {left}, {samples} samples")
    r = subprocess.run(run_args("poiseuille", out, "run.steps=400", force=True), capture_output=True, text=True)
    check("force_rerun_after_kill", r.returncode == 0 and f"partial-{pid}" in r.stderr and not partials(out)
          and xdmf_resolves(out), f"exit {r.returncode}, partials {partials(out)}, stderr {r.stderr.strip()!r}")


def concurrent_runs():
    """(d) Two runs into one folder: the second is refused, the first completes."""
    out = os.path.join(WORK, "concurrent")
    shutil.rmtree(out, ignore_errors=True)
    about_2_s = ("run.steps=200000", "run.steady_state.check_interval_steps=100000000",
                 "output.diagnostics_interval_steps=10")
    first = subprocess.Popen(run_args("poiseuille", out, *about_2_s),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    started = wait_for_partial(out, first)
    refusals = []
    for force in (False, True):
        t0 = time.monotonic()
        r = subprocess.run(run_args("poiseuille", out, "run.steps=400", force=force), capture_output=True, text=True)
        refusals.append((r.returncode, time.monotonic() - t0, r.stderr.strip()))
    still_running = first.poll() is None
    _, err = first.communicate(timeout=60)
    status = status_of(os.path.join(out, "run.h5"))[0] if os.path.exists(os.path.join(out, "run.h5")) else None
    expected = f"output folder '{out}' is in use by another erythro run (PID {first.pid})"
    refused_at_once = all(code == 4 and seconds < 5 and expected in e for code, seconds, e in refusals)
    check("second_run_refused", started and still_running and refused_at_once,
          f"started {started}, first still running {still_running}, refusals {refusals}")
    check("first_run_completes", first.returncode == 0 and status == "completed" and not partials(out),
          f"exit {first.returncode}, status {status}, stderr {err.strip()!r}")


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
t0 = time.monotonic()
fault_injection()
file_size_limit()
failed_force_rerun_keeps_earlier_run()
interrupted(signal.SIGTERM, 143)
interrupted(signal.SIGINT, 130)
kill_9_and_rerun()
concurrent_runs()
print(f"{len(failures)} failed, {time.monotonic() - t0:.1f} s")
sys.exit(1 if failures else 0)
