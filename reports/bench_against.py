#!/usr/bin/python3
"""The coupled step of this build against another build's, in one paired run.

Usage: reports/bench_against.py --reference BIN --this BIN [--cells 32 128] [--grid NX NY]
                                [--threads 1 2] [--pairs 3] [--cell-steps 38400] [--node-steps 2e8]
                                [--out FILE.h5] [--scenes DIR]

ci/bench-against.sh builds the other commit and calls this. The boxes are those of
`erythro bench --coupled-only --aggregation` (this binary writes them: --write-scenes), timed by
whole processes (`erythro run`), the binaries in turns, so that both meet the host in the same
state. A step's cost is (T(long) - T(short)) / (long - short): the set-up and the output cancel.
Per box, thread count and pair, in this order:
  reference, same   the box's cells as [[cells]] entries, the index field every step, no
                    repulsion: a scene both binaries read (box<N>_same.toml)
  this, same        the same scene
  this, product     the box as this binary's bench runs it (box<N>_product.toml)
  reference, fluid  the box without cells (box<N>_fluid.toml), for each binary's extra cost
  this, fluid
The figures: ms per step, MLUPS (nodes per step time), the extra cost per cell and step
((coupled - fluid) / cells, each binary its own fluid step), the coupled step over each binary's
own fluid-only step, and the ratios to the reference. With --grid every cell count has one box of
NX x NY nodes (few cells in a large grid: the overhead that scales with the grid, issue 18).
Prints a Markdown table and writes an HDF5 record (docs/performance-coupled-step.md,
"One paired run against an earlier commit"). Exit status 0, or 1 if a run failed.
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

KINDS = [("reference", "same"), ("this", "same"), ("this", "product"), ("reference", "fluid"), ("this", "fluid")]


def with_steps(text, steps):
    """The scene with its run, monitor and diagnostics at `steps` (the bench writes the three equal)."""
    out, n = re.subn(r"^(steps|interval_steps|diagnostics_interval_steps) = \d+$",
                     lambda m: f"{m.group(1)} = {steps}", text, flags=re.M)
    if n != 3:
        raise ValueError(f"expected the three step keys of a bench scene, found {n}")
    return out


def step_counts(cells, nodes, k, cell_steps, node_steps):
    """(short, long): multiples of k (whole index-field intervals), long about cell_steps / cells
    or node_steps / nodes, whichever is fewer (a few cells in a large grid: the grid's budget)."""
    blocks = max(2, math.ceil(min(cell_steps / cells, node_steps / nodes) / k))
    return k * max(1, round(blocks / 6)), k * blocks


def timed_run(binary, scene, threads, workdir):
    """Wall time of `binary run scene` in seconds; raises with the run's message if it fails."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    start = time.perf_counter()
    done = subprocess.run([binary, "run", scene, "--out", os.path.join(workdir, "out"), "--force", "--quiet"],
                          env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{binary} run {scene} exited with {done.returncode}: {done.stderr.strip()[-500:]}")
    return seconds


def version(binary):
    done = subprocess.run([binary, "--version"], capture_output=True, text=True)
    lines = (done.stdout or done.stderr).strip().splitlines()
    return lines[0] if done.returncode == 0 and lines else "unknown"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def load():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def read_boxes(scenes):
    with open(os.path.join(scenes, "boxes.tsv")) as f:
        header = f.readline().rstrip("\n").split("\t")
        return [dict(zip(header, line.rstrip("\n").split("\t"))) for line in f if line.strip()]


def measure_box(box, binaries, threads, pairs, budget, scenes, workdir):
    """Per kind, the ms per step of each pair; budget: (cell_steps, node_steps)."""
    cells, k = int(box["cells"]), int(box["index_update_interval"])
    short, long_ = step_counts(cells, int(box["grid_nx"]) * int(box["grid_ny"]), k, *budget)
    paths = {}
    for kind in ("same", "product", "fluid"):
        with open(os.path.join(scenes, box[kind])) as f:
            text = f.read()
        for steps in (short, long_):
            path = os.path.join(workdir, f"box{cells}_{kind}_{steps}.toml")
            with open(path, "w") as f:
                f.write(with_steps(text, steps))
            paths[kind, steps] = path
    ms = {kind: [] for kind in KINDS}
    for _ in range(pairs):
        for who, kind in KINDS:
            t_short = timed_run(binaries[who], paths[kind, short], threads, workdir)
            t_long = timed_run(binaries[who], paths[kind, long_], threads, workdir)
            ms[who, kind].append((t_long - t_short) / (long_ - short) * 1e3)
    return ms, short, long_


def spread(values, digits):
    return f"{statistics.median(values):.{digits}f} ({min(values):.{digits}f}–{max(values):.{digits}f})"


def mlups(nodes, ms_per_step):
    """Million node updates per second of a grid of `nodes` nodes at the median step time."""
    return nodes / (statistics.median(ms_per_step) * 1e-3) / 1e6


def box_figures(ms, cells):
    """From each pair's ms per step: the extra cost per cell and step (each binary's own fluid
    step subtracted) and the product's ratios to the reference on the same scene, pair by pair."""
    extra = {(who, kind): [(c - f) * 1e3 / cells for c, f in zip(ms[who, kind], ms[who, "fluid"])]
             for who, kind in KINDS if kind != "fluid"}
    step_ratio = [x / y for x, y in zip(ms["this", "product"], ms["reference", "same"])]
    extra_ratio = [x / y for x, y in zip(extra["this", "product"], extra["reference", "same"])]
    over_fluid = {who: [c / f for c, f in zip(ms[who, kind], ms[who, "fluid"])]
                  for who, kind in (("reference", "same"), ("this", "product"))}
    return extra, step_ratio, extra_ratio, over_fluid


HEADER = ("| cells | grid | thr | k | steps | reference, same: ms/step | this, same | this, product "
          "| MLUPS ref / product | extra us/cell: ref | this, same | product | product / ref, step "
          "| product / ref, extra | step / own fluid-only step: ref | product | load start / end |\n|"
          + "---|" * 17)


def table_row(r):
    ms, extra, nodes = r["ms"], r["extra"], r["grid_nx"] * r["grid_ny"]
    return (f"| {r['cells']} | {r['grid_nx']}×{r['grid_ny']} | {r['threads']} | {r['k']} | {r['short']}, {r['long']} "
            f"| {spread(ms['reference', 'same'], 2)} | {spread(ms['this', 'same'], 2)} "
            f"| {spread(ms['this', 'product'], 2)} "
            f"| {mlups(nodes, ms['reference', 'same']):.1f} / {mlups(nodes, ms['this', 'product']):.1f} "
            f"| {spread(extra['reference', 'same'], 1)} | {spread(extra['this', 'same'], 1)} "
            f"| {spread(extra['this', 'product'], 1)} | {spread(r['step_ratio'], 2)} "
            f"| {spread(r['extra_ratio'], 2)} | {spread(r['over_fluid']['reference'], 2)} "
            f"| {spread(r['over_fluid']['this'], 2)} | {r['load_start']} / {r['load_end']} |")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--reference", required=True, help="the other build's erythro")
    p.add_argument("--this", required=True, help="this build's erythro")
    p.add_argument("--cells", type=int, nargs="+", default=[32, 128])
    p.add_argument("--grid", type=int, nargs=2, metavar=("NX", "NY"),
                   help="one box of NX x NY nodes for every cell count (default: each box sized for phi = 0.3)")
    p.add_argument("--threads", type=int, nargs="+", default=[1])
    p.add_argument("--pairs", type=int, default=3, help="rounds of the five runs (default 3)")
    p.add_argument("--cell-steps", type=int, default=38400,
                   help="cells times steps of the long run, about (default 38400: 1 200 steps for 32 cells)")
    p.add_argument("--node-steps", type=float, default=2e8,
                   help="nodes times steps of the long run at most (default 2e8: 766 steps of 480 x 544)")
    p.add_argument("--out", help="the HDF5 record (default: none)")
    p.add_argument("--scenes", help="keep the box scenes here (default: a temporary folder)")
    a = p.parse_args()
    binaries = {"reference": os.path.abspath(a.reference), "this": os.path.abspath(a.this)}
    with tempfile.TemporaryDirectory(prefix="bench_against_") as workdir:
        scenes = a.scenes or os.path.join(workdir, "scenes")
        grid = ["--grid", *map(str, a.grid)] if a.grid else []
        written = subprocess.run([binaries["this"], "bench", "--coupled-only", "--aggregation", "--cells",
                                  *map(str, a.cells), *grid, "--write-scenes", scenes], capture_output=True, text=True)
        if written.returncode != 0:
            print(f"bench_against: {binaries['this']} could not write the scenes: {written.stderr.strip()}",
                  file=sys.stderr)
            return 1
        boxes = read_boxes(scenes)
        print(f"reference: {binaries['reference']} ({version(binaries['reference'])})")
        print(f"this:      {binaries['this']} ({version(binaries['this'])})")
        boxes_are = f"one box of {a.grid[0]} x {a.grid[1]} nodes" if a.grid else "phi = 0.3"
        print(f"processor: {cpu_model()}; {a.pairs} pair(s); aggregation De* = 5, biconcave cells of 184 markers, "
              f"{boxes_are}\n")
        print(HEADER)
        rows = []
        try:
            for box in boxes:
                cells = int(box["cells"])
                for threads in a.threads:
                    load_start = load()
                    budget = (a.cell_steps, a.node_steps)
                    ms, short, long_ = measure_box(box, binaries, threads, a.pairs, budget, scenes, workdir)
                    extra, step_ratio, extra_ratio, over_fluid = box_figures(ms, cells)
                    rows.append(dict(cells=cells, grid_nx=int(box["grid_nx"]), grid_ny=int(box["grid_ny"]),
                                     threads=threads, k=int(box["index_update_interval"]), short=short, long=long_,
                                     ms=ms, extra=extra, step_ratio=step_ratio, extra_ratio=extra_ratio,
                                     over_fluid=over_fluid, load_start=load_start, load_end=load()))
                    print(table_row(rows[-1]), flush=True)
        except RuntimeError as e:
            print(f"bench_against: {e}", file=sys.stderr)
            return 1
        if a.out:
            write_record(a.out, rows, binaries, scenes, boxes, a)
            print(f"\nrecord: {a.out}")
    return 0


def write_record(path, rows, binaries, scenes, boxes, a):
    """The measurements, both binaries' versions, the host and the scenes, written whole or not at all."""
    partial = f"{path}.partial-{os.getpid()}"
    with h5py.File(partial, "w") as f:
        f.attrs["reference"] = binaries["reference"]
        f.attrs["reference_version"] = version(binaries["reference"])
        f.attrs["this"] = binaries["this"]
        f.attrs["this_version"] = version(binaries["this"])
        f.attrs["processor"] = cpu_model()
        f.attrs["pairs"] = a.pairs
        f.attrs["method"] = "whole processes in turns; ms per step = (T(long) - T(short)) / (long - short)"
        for r in rows:
            g = f.create_group(f"runs/{r['cells']}_t{r['threads']}")
            for key in ("cells", "grid_nx", "grid_ny", "threads", "k", "short", "long"):
                g.attrs[key] = r[key]
            g.attrs["load_start"], g.attrs["load_end"] = r["load_start"], r["load_end"]
            for (who, kind), v in r["ms"].items():
                g[f"ms_per_step/{who}_{kind}"] = np.array(v)
            for (who, kind), v in r["extra"].items():
                g[f"extra_us_per_cell_step/{who}_{kind}"] = np.array(v)
            g["product_over_reference_step"] = np.array(r["step_ratio"])
            g["product_over_reference_extra"] = np.array(r["extra_ratio"])
            g["reference_same_over_fluid"] = np.array(r["over_fluid"]["reference"])
            g["this_product_over_fluid"] = np.array(r["over_fluid"]["this"])
        for box in boxes:
            for kind in ("same", "product", "fluid"):
                with open(os.path.join(scenes, box[kind])) as s:
                    f[f"scenes/{box[kind]}"] = s.read()
    os.replace(partial, path)


if __name__ == "__main__":
    sys.exit(main())
