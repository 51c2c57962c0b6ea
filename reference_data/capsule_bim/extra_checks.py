#!/usr/bin/env python3
"""Extra checks for capsule_bim.py (written to extra_checks.json):
 1. long-time stability of the steady state: continue the N=64 neo-Hookean
    G=0.01 solution from the circle to strain 200 and report D(t) drift;
 2. spectral convergence: N = 16, 32 (from the circle) at G = 0.05."""
import json, os, time
import numpy as np
import capsule_bim as cb

out = {}
# 1. long run
t0 = time.time()
ring = cb.Ring(64, 0.01, "neo_hookean")
dt = 0.75 * 0.01 * 2 * np.pi / 64
X, h = cb.run(ring, cb.circle(64), dt, tmax=200.0, strain_min=1e9, tol=0.0,
              verbose=False, track=False)
ts = np.array(h["t"]); Ds = np.array(h["D"])
out["long_run_G0.01_N64"] = {
    "t": ts[9::10].tolist(), "D": Ds[9::10].tolist(),
    "D_at_60": float(np.interp(60, ts, Ds)), "D_at_200": float(Ds[-1]),
    "area_change": h["area_change"], "wall": time.time() - t0}
print(out["long_run_G0.01_N64"]["D_at_60"], out["long_run_G0.01_N64"]["D_at_200"], flush=True)
# 2. coarse N at G = 0.05
for N in (32, 16):
    ring = cb.Ring(N, 0.05, "neo_hookean")
    dt = 0.75 * 0.05 * 2 * np.pi / N
    X, h = cb.run(ring, cb.circle(N), dt, strain_min=60.0, tol=1e-7,
                  tmax=150.0, verbose=False, track=False)
    A, xc, yc, D, th = cb.shape_measures(ring, X)
    out["G0.05_N%d" % N] = {"D": D, "theta": th,
                            "T": cb.tt_period_snapshot(ring, X), "steady": h["steady"],
                            "strain": h["strain"],
                            "D_range_last_20": float(np.ptp(np.array(h["D"])[-20:]))}
    print(N, D, th, flush=True)
json.dump(out, open(os.path.join(cb.HERE, "extra_checks.json"), "w"), indent=1)
