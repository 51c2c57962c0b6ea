#!/usr/bin/python3
"""Independent reference for the coupled steady NO/O2 state across the layers of an arteriole
(erythro case verification.transport_arteriole_no_o2; PROVENANCE.md beside this file).

    /usr/bin/python3 reference_data/arteriole_no_o2/reference_arteriole.py            # write the CSV
    /usr/bin/python3 reference_data/arteriole_no_o2/reference_arteriole.py --check    # compare with it

A 1D cell-centred finite-volume discretisation (faces on every layer interface) of

    D_NO L C_NO - k_NO(r) C_NO + R1(P) [EC]                                   = 0
    D_O2 L C_O2 - R1(P) [EC] - R5(P, C_NO) [SM, tissue] - k_ex (C_O2 - a P_core) [core] = 0

with L = d2/dr2 (planar) or (1/r) d/dr(r d/dr) (cylindrical), P = C_O2/a, zero flux at the centre
and at the tissue edge, R1 = R_max P/(P + Km_eNOS), R5 = Q_max P/(P + Km (1 + C_NO/C_ref)),
solved by Newton's method on the full nonlinear system (scipy sparse LU), on four grids
h = 0.5, 0.25, 0.125, 0.0625 um; the values at the sample points (linear interpolation between
cell centres) are Richardson-extrapolated from the two finest grids (second order), and the
difference between that and the finest grid is reported as the error estimate. It shares no
code with erythro (no lattice Boltzmann, no time stepping).
"""
import csv
import pathlib
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

# docs/parameters.md section 4 (Kim-laboratory set)
LUMEN = 25.0          # um
EC, SM, TISSUE = 2.5, 10.0, 100.0
D_NO, D_O2 = 3300.0, 2800.0
ALPHA = 1.3           # uM/Torr
LAMBDA_B = 382.5      # 1/s, whole blood at Hct 40 %
R_MAX = 50.0          # uM/s at wall shear stress 2.4 Pa
KM_ENOS = 4.7         # Torr
K_NO_WALL = 1.0       # 1/s, SM and tissue
Q_SM, Q_TISSUE = 5.0, 50.0   # uM/s
KM_O2 = 1.0           # Torr
C_REF = 27e-3         # uM
P_CORE = 70.0         # Torr
K_EX = 1.0e4          # 1/s, core O2 exchange towards a P_CORE
WIDTHS = (2.0, 3.0, 5.0)
SAMPLES = {"EC": LUMEN + EC / 2, "SM": LUMEN + EC + SM / 2, "tissue": LUMEN + EC + SM + 10.0}


def core_rate(delta):
    r = LUMEN / (LUMEN - delta)
    return 0.5 * LAMBDA_B * (1.0 + r * r)  # R4


def layers(delta):
    """(thickness, compartment) from the centre out."""
    return [(LUMEN - delta, "core"), (delta, "plasma"), (EC, "endothelium"), (SM, "smooth_muscle"),
            (TISSUE, "tissue")]


def grid(delta, h):
    comp, edges = [], [0.0]
    for t, c in layers(delta):
        n = int(round(t / h))
        assert abs(n * h - t) < 1e-9, (t, h)
        comp += [c] * n
        edges.append(edges[-1] + t)
    n = len(comp)
    xc = (np.arange(n) + 0.5) * h
    return xc, np.array(comp)


def residual_and_jacobian(u, xc, comp, h, cyl, delta):
    n = len(xc)
    C_no, C_o2 = u[:n], u[n:]
    P = C_o2 / ALPHA
    faces = np.arange(1, n) * h                     # interior faces
    w_face = faces if cyl else np.ones(n - 1)
    w_cell = xc if cyl else np.ones(n)
    rows, cols, vals = [], [], []
    F = np.zeros(2 * n)

    def add(i, j, v):
        rows.append(i); cols.append(j); vals.append(v)

    for off, D, C in ((0, D_NO, C_no), (n, D_O2, C_o2)):
        flux = D * w_face * (C[1:] - C[:-1]) / h    # into cell i from i+1
        F[off:off + n - 1] += flux / h
        F[off + 1:off + n] -= flux / h
        for i in range(n - 1):
            c = D * w_face[i] / h / h
            add(off + i, off + i + 1, c); add(off + i, off + i, -c)
            add(off + i + 1, off + i, c); add(off + i + 1, off + i + 1, -c)
    # reactions, times the cell weight
    k_no = np.where(comp == "core", core_rate(delta), np.where(np.isin(comp, ["smooth_muscle", "tissue"]), K_NO_WALL, 0.0))
    ec = comp == "endothelium"
    Pp = np.maximum(P, 0.0)
    R1 = np.where(ec, R_MAX * Pp / (Pp + KM_ENOS), 0.0)
    dR1_dC = np.where(ec & (P > 0), R_MAX * KM_ENOS / (Pp + KM_ENOS) ** 2 / ALPHA, 0.0)
    Q = np.where(comp == "smooth_muscle", Q_SM, np.where(comp == "tissue", Q_TISSUE, 0.0))
    Kn = KM_O2 * (1.0 + np.maximum(C_no, 0.0) / C_REF)
    R5 = Q * Pp / (Pp + Kn)
    dR5_dC = np.where(P > 0, Q * Kn / (Pp + Kn) ** 2 / ALPHA, 0.0)
    dR5_dno = np.where(C_no > 0, -Q * Pp / (Pp + Kn) ** 2 * KM_O2 / C_REF, 0.0)
    core = comp == "core"
    ex = np.where(core, K_EX * (C_o2 - ALPHA * P_CORE), 0.0)
    F[:n] += w_cell * (-k_no * C_no + R1)
    F[n:] += w_cell * (-R1 - R5 - ex)
    for i in range(n):
        add(i, i, -w_cell[i] * k_no[i])
        add(i, n + i, w_cell[i] * dR1_dC[i])
        add(n + i, n + i, -w_cell[i] * (dR1_dC[i] + dR5_dC[i] + (K_EX if core[i] else 0.0)))
        add(n + i, i, -w_cell[i] * dR5_dno[i])
    J = sp.csr_matrix((vals, (rows, cols)), shape=(2 * n, 2 * n))
    return F, J


def solve(delta, h, cyl):
    xc, comp = grid(delta, h)
    n = len(xc)
    u = np.concatenate([np.full(n, 0.1), np.full(n, ALPHA * P_CORE)])
    F, J = residual_and_jacobian(u, xc, comp, h, cyl, delta)
    for it in range(200):
        du = spl.spsolve(J.tocsc(), -F)
        # Converged when the full Newton correction is below 1e-11 of each species' largest value
        # (the residual then sits at its round-off floor, where no step can lower it).
        if np.max(np.abs(du[:n])) < 1e-11 * np.max(np.abs(u[:n])) and \
           np.max(np.abs(du[n:])) < 1e-11 * np.max(np.abs(u[n:])):
            break
        # Damped Newton: keep both concentrations positive (the rate laws have a kink at 0), then
        # halve the step until the residual falls.
        shrinking = du < 0
        lam = min(1.0, 0.9 * np.min(u[shrinking] / -du[shrinking])) if shrinking.any() else 1.0
        norm = np.linalg.norm(F)
        while True:
            trial = u + lam * du
            F_trial, J_trial = residual_and_jacobian(trial, xc, comp, h, cyl, delta)
            if np.linalg.norm(F_trial) <= (1.0 - 1e-4 * lam) * norm or lam < 1e-6:
                break
            lam *= 0.5
        u, F, J = trial, F_trial, J_trial
    else:
        raise RuntimeError("Newton did not converge")
    return xc, u[:n], u[n:] / ALPHA


def sample(xc, f, x):
    return float(np.interp(x, xc, f))


def reference_rows():
    out = []
    for geometry, cyl in (("planar", False), ("axisymmetric", True)):
        for delta in WIDTHS:
            levels = [solve(delta, h, cyl) for h in (0.5, 0.25, 0.125, 0.0625)]
            for point, x in SAMPLES.items():
                for name, idx in (("NO_uM", 1), ("PO2_torr", 2)):
                    v = [sample(lv[0], lv[idx], x) for lv in levels]
                    extrapolated = v[3] + (v[3] - v[2]) / 3.0           # Richardson, second order
                    order = np.log2(abs(v[1] - v[2]) / abs(v[2] - v[3])) if v[2] != v[3] else float("nan")
                    out.append({"geometry": geometry, "cfl_um": delta, "point": point, "position_um": x,
                                "quantity": name, "value": extrapolated,
                                "error_estimate": abs(extrapolated - v[3]), "observed_order": order})
    return out


def main():
    target = pathlib.Path(__file__).with_name("reference_arteriole.csv")
    rows = reference_rows()
    fields = ["geometry", "cfl_um", "point", "position_um", "quantity", "value", "error_estimate", "observed_order"]
    if "--check" in sys.argv:
        with open(target) as f:
            stored = list(csv.DictReader(f))
        worst = max(abs(float(s["value"]) - r["value"]) / abs(r["value"]) for s, r in zip(stored, rows))
        print(f"largest relative difference from {target.name}: {worst:.2e}")
        return 0 if worst < 1e-9 and len(stored) == len(rows) else 1
    with open(target, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{r[k]:.12g}" if isinstance(r[k], float) else r[k]) for k in fields})
    for r in rows:
        print(f"{r['geometry']:13s} {r['cfl_um']:3g} {r['point']:7s} {r['quantity']:9s} {r['value']:.8g} "
              f"(error {r['error_estimate']:.1e}, order {r['observed_order']:.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
