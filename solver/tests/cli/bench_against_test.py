#!/usr/bin/env python3
"""The paired run against another build (ci/bench-against.sh), end to end on small boxes.

(a) `erythro bench --coupled-only --aggregation --write-scenes DIR` writes, per box, the scene the
    bench runs, the same cells as [[cells]] entries and the box without cells, and boxes.tsv;
(b) the [[cells]] scene places the same cells as the bench's seeded one (`erythro check`: every
    cell's line, centre and marker spacing, the same text; and every marker at step 0 of a run, bit
    for bit, which the angles decide) with the same aggregation strength,
    the index field every step and no repulsion, so that an older binary can run the same box;
(c) reports/bench_against.py, with this binary on both sides, times every run and writes a record
    holding each run's figures and the scenes; with --grid NX NY, on one box of that grid (the
    grid's two sides not swapped) with each binary's step over its own fluid-only step;
(d) --write-scenes with --scene is refused: a non-zero exit, nothing written.

Usage: bench_against_test.py ERYTHRO SOURCE_DIR WORK_DIR
"""
import math
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy

sys.path.insert(0, os.path.join(sys.argv[2], "reports"))
from bench_against import read_boxes, with_steps  # noqa: E402  (the tool's own reader and step rewrite)

ERYTHRO, SRC, WORK = sys.argv[1:4]
failures = []


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + detail))
    if not condition:
        failures.append(name)


def run(args):
    return subprocess.run(args, capture_output=True, text=True)


def first_markers(scene_path, name):
    """The markers at step 0 of a one-step run of the scene: every cell's positions, in cell order."""
    with open(scene_path) as f:
        text = with_steps(f.read(), 1)
    path = os.path.join(WORK, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(WORK, name)
    if run([ERYTHRO, "run", path, "--out", out, "--force", "--quiet"]).returncode != 0:
        return None
    with h5py.File(os.path.join(out, "run.h5"), "r") as f:
        return f["cells/0000000000/positions"][()]


def check_lines(scene):
    """`erythro check` of a scene: its lines, without the first (the scene's own name and path)."""
    done = run([ERYTHRO, "check", scene])
    return done.returncode, done.stdout.splitlines()[1:]


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
scenes = os.path.join(WORK, "scenes")

# (a)
done = run([ERYTHRO, "bench", "--coupled-only", "--aggregation", "--cells", "2", "3", "--write-scenes", scenes])
check("write-scenes exits 0", done.returncode == 0, done.stderr)
boxes = read_boxes(scenes) if os.path.exists(os.path.join(scenes, "boxes.tsv")) else []
check("boxes.tsv lists the two boxes", [b.get("cells") for b in boxes] == ["2", "3"], str(boxes))
for box in boxes:
    for kind in ("product", "same", "fluid"):
        check(f"box {box['cells']}: {kind} scene written", os.path.isfile(os.path.join(scenes, box[kind])))

# (b)
for box in boxes:
    cells = int(box["cells"])
    rc_product, product = check_lines(os.path.join(scenes, box["product"]))
    rc_same, same = check_lines(os.path.join(scenes, box["same"]))
    check(f"box {cells}: both scenes pass erythro check", rc_product == 0 and rc_same == 0)
    cells_product = [line for line in product if re.match(r"\s*cell \d+ \(", line)]
    cells_same = [line for line in same if re.match(r"\s*cell \d+ \(", line)]
    check(f"box {cells}: the same {cells} cells", len(cells_product) == cells and cells_same == cells_product,
          "\n".join(cells_product + ["--"] + cells_same))
    # The lines above give centres and spacings, not the angles: the markers themselves, bit for bit.
    markers_product = first_markers(os.path.join(scenes, box["product"]), f"markers{cells}_product")
    markers_same = first_markers(os.path.join(scenes, box["same"]), f"markers{cells}_same")
    check(f"box {cells}: the same markers at step 0", markers_product is not None and markers_same is not None
          and numpy.array_equal(markers_product, markers_same))
    agg_product = [line for line in product if "aggregation" in line or "De*" in line]
    agg_same = [line for line in same if "aggregation" in line or "De*" in line]
    check(f"box {cells}: the same aggregation", agg_product != [] and agg_same == agg_product,
          "\n".join(agg_product + ["--"] + agg_same))
    check(f"box {cells}: the same scene rebuilds the index field every step",
          any("every 1 step" in line for line in same), "\n".join(same))
    check(f"box {cells}: the same scene has no repulsion",
          not any(line.lstrip().startswith("repulsion") for line in same)
          and any(line.lstrip().startswith("repulsion") for line in product))

# (c), on a box of --grid whose two sides differ
record = os.path.join(WORK, "against.h5")
grid_scenes = os.path.join(WORK, "grid_scenes")
done = run([sys.executable, os.path.join(SRC, "reports", "bench_against.py"), "--reference", ERYTHRO, "--this",
            ERYTHRO, "--cells", "2", "--grid", "96", "80", "--pairs", "1", "--cell-steps", "20", "--out", record,
            "--scenes", grid_scenes])
check("bench_against.py exits 0", done.returncode == 0, done.stderr + done.stdout)
check("bench_against.py prints a row for the box",
      any(line.startswith("| 2 | 96×80 |") for line in done.stdout.splitlines()), done.stdout)
grid_boxes = read_boxes(grid_scenes) if os.path.exists(os.path.join(grid_scenes, "boxes.tsv")) else []
check("--grid: boxes.tsv gives the grid", [(b["grid_nx"], b["grid_ny"]) for b in grid_boxes] == [("96", "80")],
      str(grid_boxes))
if grid_boxes:
    rc, lines = check_lines(os.path.join(grid_scenes, grid_boxes[0]["product"]))
    check("--grid: the product scene has 96 x 80 nodes", rc == 0 and any(
        re.match(r"\s*nodes\s+96 × 80\s", line) for line in lines), "\n".join(lines[:6]))
if os.path.exists(record):
    with h5py.File(record, "r") as f:
        g = f.get("runs/2_t1")
        check("the record holds the box", g is not None, str(list(f.keys())))
        if g is not None:
            for who, kind in [("reference", "same"), ("this", "same"), ("this", "product"), ("reference", "fluid"),
                              ("this", "fluid")]:
                v = g.get(f"ms_per_step/{who}_{kind}")
                # finite, not positive: runs this short differ by less than the host's noise
                check(f"record: {who}, {kind} timed", v is not None and len(v) == 1 and math.isfinite(v[0]))
            coupled, fluid = g.get("ms_per_step/this_product"), g.get("ms_per_step/this_fluid")
            extra = g.get("extra_us_per_cell_step/this_product")
            over_fluid = g.get("this_product_over_fluid")
            check("record: the extra cost is (coupled - fluid) / cells",
                  all(x is not None for x in (coupled, fluid, extra)) and extra[0] == (coupled[0] - fluid[0]) * 1e3 / 2)
            check("record: the step over its own fluid-only step is coupled / fluid",
                  all(x is not None for x in (coupled, fluid, over_fluid)) and over_fluid[0] == coupled[0] / fluid[0])
            check("record: the grid", (g.attrs.get("grid_nx"), g.attrs.get("grid_ny")) == (96, 80), str(dict(g.attrs)))
        check("record: the scenes kept", "scenes" in f and len(f["scenes"]) == 3)
        check("record: both versions", "this_version" in f.attrs and "reference_version" in f.attrs)
else:
    check("the record written", False, record)
check("no partial record left", not any(".partial-" in name for name in os.listdir(WORK)), str(os.listdir(WORK)))

# (d)
done = run([ERYTHRO, "bench", "--coupled-only", "--scene", os.path.join(SRC, "scenes", "rbc_channel.toml"),
            "--write-scenes", os.path.join(WORK, "refused")])
check("--write-scenes with --scene refused", done.returncode != 0 and not os.path.exists(os.path.join(WORK, "refused")),
      f"exit {done.returncode}")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
