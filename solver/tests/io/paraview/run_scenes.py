#!/usr/bin/python3
"""Runs every scene of scenes/ for a few steps and checks its output in ParaView's XDMF
reader (check_xdmf.py under pvbatch). Usage: run_scenes.py ERYTHRO SCENES_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys
import tomllib

erythro, scenes, work = sys.argv[1:4]
here = os.path.dirname(os.path.abspath(__file__))
pvbatch = shutil.which("pvbatch")
if not pvbatch:
    sys.exit("pvbatch not found: install Debian's paraview and python3-paraview (ci/install-deps.sh)")
failed = []
for name in sorted(f for f in os.listdir(scenes) if f.endswith(".toml")):
    path = os.path.join(scenes, name)
    with open(path, "rb") as f:
        run = tomllib.load(f).get("run", {})
    # A short run with a field output at the start, the middle and the end. A scene that
    # gives run.duration_s is copied without it (steps and duration_s exclude each other).
    out = os.path.join(work, name[:-5])
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(work, exist_ok=True)
    if "duration_s" in run:
        copy = os.path.join(work, name)
        with open(copy, "w") as f:
            f.write("\n".join(l for l in open(path).read().splitlines() if not l.strip().startswith("duration_s")) + "\n")
        path = copy
    cmd = [erythro, "run", path, "--out", out, "--quiet", "--force",
           "--set", "run.steps=40", "--set", "output.fields_interval_steps=20"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        failed.append(f"{name}: erythro run failed ({r.returncode}): {r.stderr.strip()}")
        continue
    c = subprocess.run([pvbatch, os.path.join(here, "check_xdmf.py"), out], capture_output=True, text=True)
    print(c.stdout.strip())
    if c.returncode != 0:
        failed.append(f"{name}: {c.stdout.strip()} {c.stderr.strip()[-2000:]}")
if failed:
    print("\n".join(failed))
    sys.exit(1)
