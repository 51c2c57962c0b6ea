#!/usr/bin/python3
"""Model-form floor of a lumped (cell-mean) saturation against the resolved cell.

For each grid level, runs reference_rbc.py's lumped model (--lumped M: one S for the whole cell,
rate k_off/M, driven by the heme-volume-weighted mean P̄) and fits ln M by minimising
    RMS_k [ S_lumped(t_k; M) − S_ref(t_k) ]
over the time points t_k of the reference CSV (column S_fine, the resolved local-kinetics curve;
the model is interpolated linearly in t), with scipy's bounded Brent on M ∈ [0.05, 4]
(tolerance 1e-3 in ln M). Reports per level: the fitted M, RMS and max |misfit| at the fit, and
max |misfit| (and RMS) at M = 1, plus a coarse scan of RMS(M) to show how flat the minimum is.
What remains at the best M is the model-form floor of any lumped-S model of this cell.

Usage:  lumped_floor.py [--levels 0 1] [--planar] [--ref CSV] [--out JSON | --no-write]
  default: 3D cell against reference_S.csv, writes lumped_floor.json;
  --planar: the planar cell against reference_S_planar.csv (writes nothing unless --out is given).
Regenerate (PROVENANCE.md):  lumped_floor.py --levels 0 1
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
from scipy.optimize import minimize_scalar

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reference_rbc as ref  # noqa: E402

M_LO, M_HI = 0.05, 4.0
SCAN = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0)


def read_ref(path):
    with open(path) as fh:
        rows = [ln.strip().split(",") for ln in fh if ln.strip() and not ln.startswith("#")]
    col = {name: j for j, name in enumerate(rows[0])}
    data = np.array(rows[1:], dtype=float)
    return data[:, col["t_s"]], data[:, col["S_fine"]]


def misfit(level, m_rate, t_ref, s_ref):
    t, s, info = ref.run(level, float(t_ref[-1]), lumped=m_rate)
    d = np.interp(t_ref, t, s) - s_ref
    k = int(np.argmax(np.abs(d)))
    return dict(M=m_rate, rms=float(math.sqrt(np.mean(d * d))), max_abs=float(abs(d[k])),
                t_at_max_s=float(t_ref[k]), misfit_at_max=float(d[k]), wall_s=info["wall_s"],
                o2_balance_rel=info["o2_balance_rel"])


def fit_level(level, t_ref, s_ref):
    t0 = time.time()
    evals = []

    def obj(lnm):
        r = misfit(level, math.exp(lnm), t_ref, s_ref)
        evals.append(r)
        return r["rms"]

    opt = minimize_scalar(obj, bounds=(math.log(M_LO), math.log(M_HI)), method="bounded",
                          options=dict(xatol=1e-3))
    best = misfit(level, math.exp(opt.x), t_ref, s_ref)
    at1 = misfit(level, 1.0, t_ref, s_ref)
    scan = [{k: misfit(level, m, t_ref, s_ref)[k] for k in ("M", "rms", "max_abs")} for m in SCAN]
    res = dict(level=level, h_core_um=0.2 / 2 ** level, M_fit=best["M"], ln_M_fit=float(opt.x),
               rms_fit=best["rms"], max_abs_fit=best["max_abs"], t_at_max_fit_s=best["t_at_max_s"],
               misfit_at_max_fit=best["misfit_at_max"],
               rms_M1=at1["rms"], max_abs_M1=at1["max_abs"], t_at_max_M1_s=at1["t_at_max_s"],
               misfit_at_max_M1=at1["misfit_at_max"], brent_evaluations=len(evals),
               scan=scan, wall_s=time.time() - t0)
    print(json.dumps({k: v for k, v in res.items() if k != "scan"}), flush=True)
    for r in scan:
        print(f"   M = {r['M']:<5g} rms = {r['rms']:.5f}  max = {r['max_abs']:.5f}", flush=True)
    return res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1])
    ap.add_argument("--planar", action="store_true")
    ap.add_argument("--ref", default=None, help="reference CSV (default reference_S[_planar].csv)")
    ap.add_argument("--out", default=None, help="output JSON (default lumped_floor.json, 3D only)")
    ap.add_argument("--no-write", action="store_true")
    args = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    ref.PLANAR = args.planar
    ref_path = args.ref or os.path.join(here, "reference_S_planar.csv" if args.planar else "reference_S.csv")
    t_ref, s_ref = read_ref(ref_path)
    t0 = time.time()
    levels = [fit_level(lv, t_ref, s_ref) for lv in args.levels]
    out = dict(description="fit of the rate modifier M of the lumped (cell-mean) saturation model "
                           "(reference_rbc.py --lumped M) to the resolved local-kinetics curve: "
                           "minimise RMS over the reference time points of S_lumped(t; M) - S_ref(t), "
                           "bounded Brent on ln M, M in [0.05, 4], xatol 1e-3",
               command="lumped_floor.py --levels " + " ".join(map(str, args.levels))
                       + (" --planar" if args.planar else ""),
               reference=os.path.basename(ref_path), reference_column="S_fine",
               geometry="planar" if args.planar else "3D axisymmetric", t_end=float(t_ref[-1]),
               n_reference_points=len(t_ref), levels=levels, total_wall_s=time.time() - t0)
    path = args.out or (None if args.planar else os.path.join(here, "lumped_floor.json"))
    if path and not args.no_write:
        with open(path, "w") as fh:
            json.dump(out, fh, indent=1)
        print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
