# Run by ParaView's pvbatch (Debian package paraview + python3-paraview): opens a run's
# run.xdmf with ParaView's XDMF reader, as a user does, and checks that every field of
# every time step arrives with the names, shapes and values of run.h5 (read with h5py):
# the fluid grid in the x-y plane, velocity as a 3-component vector, concentrations as
# scalars, membranes as closed polylines (one edge per marker). Exit status 1 on a mismatch.
#   pvbatch check_xdmf.py OUT_DIR
import os
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import XDMFReader

out = sys.argv[1]
problems = []


def expect(ok, what):
    if not ok:
        problems.append(what)


h5 = h5py.File(os.path.join(out, "run.h5"), "r")
nx, ny = int(h5["grid"].attrs["nx"]), int(h5["grid"].attrs["ny"])
h = float(h5["grid"].attrs["spacing_um"])
frames = sorted(h5["fields"].keys())
reader = XDMFReader(FileNames=[os.path.join(out, "run.xdmf")])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
expect(len(times) == len(frames), f"{len(times)} time steps in the XDMF, {len(frames)} field frames in run.h5")

for t, name in zip(times, frames):
    group = h5["fields"][name]
    expect(abs(group.attrs["time_s"] - t) <= 1e-12 * max(1.0, abs(t)), f"frame {name}: time {t} != {group.attrs['time_s']}")
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    blocks = {}
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        # ParaView names the blocks of later time steps "fluid[1]", "fluid[2]", ...
        blocks[it.GetCurrentMetaData().Get(data.NAME()).split("[")[0]] = it.GetCurrentDataObject()
        it.GoToNextItem()
    fluid = blocks.get("fluid")
    expect(fluid is not None, f"frame {name}: no fluid block (blocks: {sorted(blocks)})")
    if fluid is None:
        continue
    expect(fluid.GetDimensions() == (nx, ny, 1), f"frame {name}: grid {fluid.GetDimensions()} != ({nx}, {ny}, 1)")
    b = fluid.GetBounds()
    expect(abs(b[0] - 0.5 * h) < 1e-9 and abs(b[1] - (nx - 0.5) * h) < 1e-9 and abs(b[2] - 0.5 * h) < 1e-9
           and abs(b[3] - (ny - 0.5) * h) < 1e-9 and b[4] == 0.0 and b[5] == 0.0,
           f"frame {name}: bounds {b} not the x-y plane of nodes at (i + 1/2) h")
    pd = fluid.GetPointData()
    for field in group.keys():
        ref = np.asarray(group[field])
        array = pd.GetArray(field)
        expect(array is not None, f"frame {name}: field {field} missing in ParaView")
        if array is None:
            continue
        got = np.array([array.GetTuple(i) for i in range(array.GetNumberOfTuples())])
        want = ref.reshape(nx * ny, -1)
        expect(got.shape == want.shape, f"frame {name}: {field} shape {got.shape} != {want.shape}")
        if got.shape == want.shape:
            expect(np.array_equal(got, want), f"frame {name}: {field} values differ (max {np.max(np.abs(got - want))})")
        expect("units" in group[field].attrs, f"frame {name}: {field} has no units attribute")
    if "cells" in h5 and name in h5["cells"]:
        cells = h5["cells"][name]
        membranes = blocks.get("membranes")
        expect(membranes is not None, f"frame {name}: no membranes block")
        if membranes is not None:
            xy = np.asarray(cells["positions"])
            pts = np.array([membranes.GetPoint(i) for i in range(membranes.GetNumberOfPoints())])
            expect(pts.shape == (xy.shape[0], 3), f"frame {name}: {pts.shape[0]} membrane points, {xy.shape[0]} markers")
            if pts.shape == (xy.shape[0], 3):
                expect(np.array_equal(pts[:, :2], xy) and not np.any(pts[:, 2]), f"frame {name}: marker positions differ")
            expect(membranes.GetNumberOfCells() == xy.shape[0], f"frame {name}: {membranes.GetNumberOfCells()} edges")
            expect(cells["offsets"].dtype.kind == "i" and cells["edges"].dtype.kind == "i",
                   f"frame {name}: marker counts stored as {cells['offsets'].dtype}, not integers")

if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"{out}: {len(frames)} frames open in ParaView's XDMF reader with the values of run.h5")
