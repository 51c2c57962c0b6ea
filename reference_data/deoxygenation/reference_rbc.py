#!/usr/bin/python3
"""Reference solver: O2 release from one still biconcave red blood cell (3D, axisymmetric).

Model (PROVENANCE.md has the sources of every number):
  * cell: Evans–Fung surface of revolution, half-thickness
        z_s(r) = (a/2) sqrt(1 - r²/a²) (c0 + c1 r²/a² + c2 r⁴/a⁴),  r < a,
    a = 3.91 µm, (c0, c1, c2) = (0.207161, 2.002558, -1.122762);
  * domain: the cylinder 0 ≤ r ≤ L, |z| ≤ L (L = 6 µm, a cube-like box of half-width L
    around the cell centre); C = C_b = 20 µM held on r = L and |z| = L; mirror symmetry
    at z = 0 and the axis r = 0 → solved on 0 ≤ r, z ≤ L;
  * free O2, everywhere:   ∂C/∂t = ∇·(D ∇C) + φ C_heme k_off R(C, S)
    bound O2, in the cell: ∂S/∂t = −k_off R(C, S) [+ ∇·(D_Hb ∇S), optional]
    R = S − (1 − S)(P/P50)^n, P = C/α  (LOCAL kinetics, M = 1; O2 released = −C_heme ∂S/∂t)
    D = D_in inside the cell, D_out outside; same solubility α inside and outside; the
    membrane adds no resistance;
  * initial state: cell in equilibrium at P0 = 100 Torr (S0 = Hill(P0), C = α P0),
    medium at C_b; the box is held at C_b, so the final state is S_f = Hill(C_b/α).

Numerics: finite volumes on an (r, z) tensor grid (uniform spacing h around the cell,
geometric cells beyond it), cell mask by VOLUME FRACTION φ of each control volume inside
the surface (exact in z, 32-point midpoint rule in r); control-volume diffusivity
1/D = φ/D_in + (1 − φ)/D_out, face diffusivity by series resistance; fully implicit
variable-step BDF2 in time (first step backward Euler), (modified) Newton on the coupled (C, S)
system with an exact sparse Jacobian (scipy.sparse splu) refreshed every 4th iterate;
Newton stops at |ΔC| < 1e-9 C_b and |ΔS| < 1e-11.

Lumped variant (--lumped M): the cell-mean ("lumped") saturation of the lattice model instead
of the local one. ONE S for the whole cell,
    dS/dt = −(k_off/M) [S − (1 − S)(P̄/P50)^n],   P̄ = Σ_j φ_j V_j C_j / (α Σ_j φ_j V_j)
(heme-volume-weighted mean over the control volumes with φ > 0; P̄ clipped at 0), and the release
C_heme (−dS/dt) spread uniformly over the heme volume: CV j gets φ_j C_heme (k_off/M) R̄ in its C
equation (R̄ the one lumped rate). M > 0 is a rate modifier (M = 1: the plain k_off). Unknowns: C of
all CVs and the one S; same time points, BDF2 and stopping rule; full Newton with the exact
Jacobian, solved as a bordered system (splu of the diffusion block I − γΔt V⁻¹L, factored once per
step since it does not depend on the state, plus the rank-one coupling C_heme φ_j ∂R̄/∂C_k and the S
unknown eliminated exactly by a scalar Schur complement). Bound O2 = C_heme S Σ φV; the output S̄ is S.
--hb-diffusion does not apply (one S has no gradient).

Usage:  reference_rbc.py [--study] [--planar] [--levels 0 1 2] [--t-end T] [--box L]
                         [--hb-diffusion D] [--d-out D] [--lumped M] [--out DIR]
  default: one run at --levels[0], prints the half-time and 90 %/99 % times;
  --study: the given (three) grids/time schedules refined together by 2, observed order
           and Richardson estimate; writes reference_S[_planar].csv and study[_planar].json;
  --planar: the same Evans–Fung section as a PLANAR 2D cell (per unit depth), the exact
           continuum counterpart of the 2D lattice model, with local kinetics;
  --lumped M: lumped (cell-mean) saturation with rate modifier M (above); with --study writes
           reference_S[_planar]_lumped_M<M>.csv and study[_planar]_lumped_M<M>.json (<M> as %g).
Regenerate (PROVENANCE.md):
  reference_rbc.py --study --levels 0 1 2 --t-end 1.8            (3D cell, ~3 min)
  reference_rbc.py --study --levels 0 1 2 --t-end 2.4 --planar   (planar, ~3.5 min)
  reference_rbc.py --study --levels 0 1 2 --t-end 1.8 --lumped 1    (3D, lumped S, M = 1)
  reference_rbc.py --study --levels 0 1 2 --t-end 1.8 --lumped 0.5  (3D, lumped S, M = 0.5)
"""
import argparse
import json
import math
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

# ---- parameters (PROVENANCE.md, "Parameters") -------------------------------------
A_RBC = 3.91  # µm
EF = (0.207161, 2.002558, -1.122762)
L_BOX = 6.0  # µm, half-width of the box held at C_b (--box)
P50, N_HILL = 26.8, 2.7  # Torr, -
K_OFF = 44.0  # 1/s
C_HEME = 20300.0  # µM
ALPHA = 1.3  # µM/Torr
D_OUT = 2800.0  # µm²/s (--d-out for sensitivity studies)
D_IN = 950.0  # µm²/s
C_B = 20.0  # µM
P0 = 100.0  # Torr
PLANAR = False  # --planar: the same section as a 2D planar (x, z) cell (per unit depth)


def hill(p):
    x = (p / P50) ** N_HILL
    return x / (1.0 + x)


def half_thickness(r):
    r = np.asarray(r, dtype=float)
    x2 = np.clip(r / A_RBC, 0.0, 1.0) ** 2
    z = 0.5 * A_RBC * np.sqrt(np.clip(1.0 - x2, 0.0, None)) * (EF[0] + EF[1] * x2 + EF[2] * x2 * x2)
    return np.where(r < A_RBC, z, 0.0)


def grid_faces(level):
    """Nested faces. Level 0: h = 0.2 µm core; level k: every cell of level k-1 halved."""
    h0 = 0.2
    core_r, core_z = 4.4, 1.6
    def one(core):
        f = list(np.arange(0.0, core + 1e-9, h0))
        dx = h0
        while f[-1] < L_BOX - 1e-9:
            dx = min(dx * 1.15, 1.0)
            f.append(min(f[-1] + dx, L_BOX))
        if L_BOX - f[-2] < 0.5 * dx:  # avoid a sliver cell at the box
            f.pop(-2)
        f = np.array(f)
        for _ in range(level):
            mid = 0.5 * (f[1:] + f[:-1])
            f = np.sort(np.concatenate([f, mid]))
        return f
    return one(core_r), one(core_z)


def volume_fraction(rf, zf, nsub=32):
    """φ[i, j]: fraction of control volume (rf[i]..rf[i+1]) × (zf[j]..zf[j+1]) inside the cell,
    axisymmetric (weight r); exact in z, midpoint rule with nsub points in r."""
    nr, nz = len(rf) - 1, len(zf) - 1
    phi = np.zeros((nr, nz))
    for i in range(nr):
        if rf[i] >= A_RBC:
            break
        s = rf[i] + (np.arange(nsub) + 0.5) / nsub * (rf[i + 1] - rf[i])
        w = (np.ones_like(s) if PLANAR else s)
        w = w / w.sum()
        zs = half_thickness(s)
        lo, hi = zf[:-1][None, :], zf[1:][None, :]
        cover = np.clip(zs[:, None], lo, hi) - lo  # length of [z_j, z_j+1] below z_s
        phi[i, :] = (w[:, None] * cover).sum(axis=0) / (hi - lo)[0]
    return phi


class Model:
    def __init__(self, level, d_hb=0.0):
        self.rf, self.zf = grid_faces(level)
        rf, zf = self.rf, self.zf
        nr, nz = len(rf) - 1, len(zf) - 1
        self.nr, self.nz = nr, nz
        self.rc = 0.5 * (rf[1:] + rf[:-1])
        self.zc = 0.5 * (zf[1:] + zf[:-1])
        dr, dz = np.diff(rf), np.diff(zf)
        # metric: axisymmetric (per radian) or planar (per unit depth)
        ar = np.ones(len(rf)) if PLANAR else rf.copy()  # area factor of a face at r = rf[i]
        aa = dr.copy() if PLANAR else 0.5 * np.diff(rf ** 2)  # area factor of an axial face
        self.vol = aa[:, None] * dz[None, :]
        self.phi = volume_fraction(rf, zf)
        self.d_hb = d_hb
        idx = np.arange(nr * nz).reshape(nr, nz)
        dcell = 1.0 / (self.phi / D_IN + (1.0 - self.phi) / D_OUT)
        rows, cols, vals = [], [], []
        bcoef = np.zeros((nr, nz))  # Dirichlet conductance (flux = bcoef (C_b - C))
        # radial faces between i and i+1: area rf[i+1] dz, resistance (dr_i/2)/D_i + (dr_i+1/2)/D_i+1
        g = (ar[1:-1][:, None] * dz[None, :]) / (0.5 * dr[:-1, None] / dcell[:-1] + 0.5 * dr[1:, None] / dcell[1:])
        self._pairs(rows, cols, vals, idx[:-1, :], idx[1:, :], g)
        ga = aa[:, None] / (0.5 * dz[None, :-1] / dcell[:, :-1] + 0.5 * dz[None, 1:] / dcell[:, 1:])
        self._pairs(rows, cols, vals, idx[:, :-1], idx[:, 1:], ga)
        bcoef[-1, :] += ar[-1] * dz / (0.5 * dr[-1] / dcell[-1, :])
        bcoef[:, -1] += aa / (0.5 * dz[-1] / dcell[:, -1])
        self.ar, self.aa = ar, aa
        rows += list(idx.ravel()); cols += list(idx.ravel()); vals += list(-bcoef.ravel())
        n = nr * nz
        self.n = n
        self.Lc = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))  # Σ flux, µm³/s per µM
        self.bcoef = bcoef.ravel()
        self.vol_f = self.vol.ravel()
        # S unknowns: control volumes with φ > 0
        self.cell = np.flatnonzero(self.phi.ravel() > 0.0)
        self.m = len(self.cell)
        self.phi_c = self.phi.ravel()[self.cell]
        self.vphi = self.vol_f[self.cell] * self.phi_c  # heme-bearing volume per CV
        self.identity = sp.identity(n + self.m, format="csc")  # of the local model's (C, S) system
        self.Ls = None
        if d_hb > 0.0:
            self.Ls = self._hb_operator(idx, dr, dz)

    @staticmethod
    def _pairs(rows, cols, vals, a, b, g):
        a, b, g = a.ravel(), b.ravel(), g.ravel()
        rows += list(a) + list(b) + list(a) + list(b)
        cols += list(b) + list(a) + list(a) + list(b)
        vals += list(g) + list(g) + list(-g) + list(-g)

    def _hb_operator(self, idx, dr, dz):
        """Hb/HbO2 diffusion of S between heme-bearing CVs: face open fraction min(φ1, φ2)."""
        pos = -np.ones(self.n, dtype=int)
        pos[self.cell] = np.arange(self.m)
        phi = self.phi
        rows, cols, vals = [], [], []
        rf = self.rf
        gr = (self.ar[1:-1][:, None] * dz[None, :]) * self.d_hb / (0.5 * dr[:-1, None] + 0.5 * dr[1:, None])
        gr = gr * np.minimum(phi[:-1], phi[1:])
        ga = self.aa[:, None] * self.d_hb / (0.5 * dz[None, :-1] + 0.5 * dz[None, 1:])
        ga = ga * np.minimum(phi[:, :-1], phi[:, 1:])
        for a, b, g in ((idx[:-1, :], idx[1:, :], gr), (idx[:, :-1], idx[:, 1:], ga)):
            a, b, g = a.ravel(), b.ravel(), g.ravel()
            k = g > 0
            pa, pb, gk = pos[a[k]], pos[b[k]], g[k]
            self._pairs(rows, cols, vals, pa, pb, gk)
        # divide by the heme-bearing volume: d S/dt = (1/(φV)) Σ g ΔS
        L = sp.csr_matrix((vals, (rows, cols)), shape=(self.m, self.m))
        return sp.diags(1.0 / self.vphi) @ L

    def initial(self):
        phi = self.phi.ravel()
        c = phi * ALPHA * P0 + (1.0 - phi) * C_B
        s = np.full(self.m, hill(P0))
        return np.concatenate([c, s])

    def rhs_and_jac(self, x, want_jac=True):
        n, m = self.n, self.m
        c, s = x[:n], x[n:]
        cc = np.maximum(c[self.cell], 0.0)
        q = (cc / (ALPHA * P50)) ** N_HILL
        R = K_OFF * (s - (1.0 - s) * q)  # 1/s
        fc = (self.Lc @ c + self.bcoef * C_B) / self.vol_f
        fc[self.cell] += self.phi_c * C_HEME * R
        fs = -R
        if self.Ls is not None:
            fs = fs + self.Ls @ s
        f = np.concatenate([fc, fs])
        if not want_jac:
            return f, None
        dq = np.where(cc > 0, N_HILL * q / np.maximum(cc, 1e-300), 0.0)
        dR_dc = -K_OFF * (1.0 - s) * dq
        dR_ds = K_OFF * (1.0 + q)
        Jcc = sp.diags(1.0 / self.vol_f) @ self.Lc
        Jcc = Jcc + sp.csr_matrix((self.phi_c * C_HEME * dR_dc, (self.cell, self.cell)), shape=(n, n))
        Jcs = sp.csr_matrix((self.phi_c * C_HEME * dR_ds, (self.cell, np.arange(m))), shape=(n, m))
        Jsc = sp.csr_matrix((-dR_dc, (np.arange(m), self.cell)), shape=(m, n))
        Jss = sp.diags(-dR_ds)
        if self.Ls is not None:
            Jss = Jss + self.Ls
        J = sp.bmat([[Jcc, Jcs], [Jsc, Jss]], format="csc")
        return f, J

    def newton(self, y, base, gdt, t):
        """Modified Newton on y − base − γΔt f(y) = 0, in place: the exact sparse Jacobian,
        refreshed every 4th iterate. Returns the iterations."""
        lu = None
        for it in range(40):
            f, J = self.rhs_and_jac(y, want_jac=(it % 4 == 0))
            F = y - base - gdt * f
            if J is not None:
                lu = spla.splu((self.identity - gdt * J).tocsc())
            dy = lu.solve(-F)
            y += dy
            if newton_converged(self.n, dy):
                return it + 1
        raise RuntimeError(f"Newton did not converge at t = {t}")

    def s_mean(self, x):
        return float((self.vphi * x[self.n:]).sum() / self.vphi.sum())

    def o2_total(self, x):
        """Free + bound O2 in the half domain (µM·µm³ per radian)."""
        c, s = x[:self.n], x[self.n:]
        return float((self.vol_f * c).sum() + (self.vphi * C_HEME * s).sum())

    def outflow(self, x):
        """O2 leaving through the held boundary (µM·µm³/s per radian)."""
        return float((self.bcoef * (x[:self.n] - C_B)).sum())


class LumpedModel(Model):
    """Lumped (cell-mean) saturation, option --lumped M: unknowns x = (C of all n CVs, one S).
    R̄ = (k_off/M)[S − (1 − S) q], q = (P̄/P50)^n, P̄ = Σ w_j C_j / α (w = φV / Σ φV over the cell CVs);
    f_C = V⁻¹(L C + b C_b) + u R̄ with u_j = φ_j C_heme on the cell CVs (0 elsewhere); f_S = −R̄."""

    def __init__(self, level, m_rate):
        super().__init__(level, 0.0)
        if not m_rate > 0.0:
            raise ValueError("--lumped M needs M > 0")
        self.m_rate = m_rate
        self.k_eff = K_OFF / m_rate
        self.w = self.vphi / self.vphi.sum()
        self.u = np.zeros(self.n)
        self.u[self.cell] = self.phi_c * C_HEME
        self.Lv = (sp.diags(1.0 / self.vol_f) @ self.Lc).tocsc()  # ∂f_C/∂C without the kinetics

    def initial(self):
        phi = self.phi.ravel()
        c = phi * ALPHA * P0 + (1.0 - phi) * C_B
        return np.concatenate([c, [hill(P0)]])

    def kinetics(self, x):
        """R̄ (1/s), ∂R̄/∂P̄·(1/α) = ∂R̄/∂C̄ (per µM of the weighted mean C̄) and ∂R̄/∂S."""
        s = x[self.n]
        cbar = float(self.w @ x[:self.n][self.cell])
        cbar = max(cbar, 0.0)
        q = (cbar / (ALPHA * P50)) ** N_HILL
        R = self.k_eff * (s - (1.0 - s) * q)
        dR_dcbar = -self.k_eff * (1.0 - s) * N_HILL * q / cbar if cbar > 0.0 else 0.0
        dR_ds = self.k_eff * (1.0 + q)
        return R, dR_dcbar, dR_ds

    def rhs(self, x):
        c = x[:self.n]
        R = self.kinetics(x)[0]
        fc = (self.Lc @ c + self.bcoef * C_B) / self.vol_f + self.u * R
        return np.concatenate([fc, [-R]])

    def jacobian(self, x):
        """Exact Jacobian as an explicit sparse matrix (dense m×m outer product on the cell
        block): for checks on coarse grids only; run() uses the bordered solve."""
        n = self.n
        _, dRc, dRs = self.kinetics(x)
        v = np.zeros(n)
        v[self.cell] = dRc * self.w
        Jcc = self.Lv + sp.coo_matrix((np.outer(self.u[self.cell], v[self.cell]).ravel(),
                                       (np.repeat(self.cell, self.m), np.tile(self.cell, self.m))), shape=(n, n))
        return sp.bmat([[Jcc, sp.csr_matrix((self.u * dRs)[:, None])],
                        [sp.csr_matrix(-v[None, :]), sp.csr_matrix([[-dRs]])]], format="csc")

    def newton(self, y, base, gdt, t):
        """Full Newton on y − base − γΔt f(y) = 0, in place (exact Jacobian every iterate, bordered
        solve). Returns the iterations."""
        fac = self.factor(gdt)
        for it in range(40):
            F = y - base - gdt * self.rhs(y)
            dy = self.solve(fac, gdt, y, -F)
            y += dy
            if newton_converged(self.n, dy):
                return it + 1
        raise RuntimeError(f"Newton did not converge at t = {t}")

    def factor(self, gdt):
        """splu of B = I − γΔt V⁻¹L (state independent) and y = B⁻¹u."""
        lu = spla.splu((sp.identity(self.n, format="csc") - gdt * self.Lv).tocsc())
        return lu, lu.solve(self.u)

    def solve(self, fac, gdt, x, r):
        """Solve (I − γΔt J(x)) d = r exactly. With v = ∂R̄/∂C (= ∂R̄/∂C̄ · w on the cell CVs):
            B d_C − γΔt u δ = r_C,   d_S + γΔt δ = r_S,   δ = vᵀd_C + ∂R̄/∂S d_S,
        so d_C = B⁻¹r_C + γΔt δ B⁻¹u and δ = (vᵀB⁻¹r_C + ∂R̄/∂S r_S) / (1 + γΔt (∂R̄/∂S − vᵀB⁻¹u))."""
        lu, yu = fac
        n = self.n
        _, dRc, dRs = self.kinetics(x)
        z = lu.solve(r[:n])
        vz = dRc * float(self.w @ z[self.cell])
        vy = dRc * float(self.w @ yu[self.cell])
        delta = (vz + dRs * r[n]) / (1.0 + gdt * (dRs - vy))
        return np.concatenate([z + gdt * delta * yu, [r[n] - gdt * delta]])

    def s_mean(self, x):
        return float(x[self.n])

    def o2_total(self, x):
        """Free + bound O2 in the half domain (µM·µm³ per radian); bound = C_heme S Σ φV."""
        return float((self.vol_f * x[:self.n]).sum() + C_HEME * x[self.n] * self.vphi.sum())


def schedule(level, t_end):
    """Level-0 time points: dt0 = 2 µs growing by 1.08 per step up to 5 ms; level k halves
    every interval k times (time points nest, as the grids do)."""
    t = [0.0]
    dt = 2e-6
    while t[-1] < t_end - 1e-15:
        t.append(min(t[-1] + dt, t_end))
        dt = min(dt * 1.08, 5e-3)
    t = np.array(t)
    for _ in range(level):
        t = np.sort(np.concatenate([t, 0.5 * (t[1:] + t[:-1])]))
    return t


def bdf2_coefficients(times, k, first):
    """(a0, a1, γ) of step k: backward Euler on the first step, then variable-step BDF2,
    x_k − a0 x_{k−1} + a1 x_{k−2} = γ Δt f(x_k), ω = Δt_k / Δt_{k−1}."""
    if first:
        return 1.0, 0.0, 1.0
    dt = times[k] - times[k - 1]
    w = dt / (times[k - 1] - times[k - 2])
    return (1.0 + w) ** 2 / (1.0 + 2.0 * w), w * w / (1.0 + 2.0 * w), (1.0 + w) / (1.0 + 2.0 * w)


def run_info(mod, level, times, newton_its, t0, tot0, out_int, x, verbose):
    """The run's summary (printed with verbose): grid, steps, Newton iterations, wall time, O2 balance."""
    wall = time.time() - t0
    balance = (tot0 - mod.o2_total(x) - out_int) / (tot0 - mod.o2_total(x))
    info = dict(level=level, nr=mod.nr, nz=mod.nz, h_core=0.2 / 2 ** level, steps=len(times) - 1,
                newton=newton_its, wall_s=wall, cell_cvs=mod.m, o2_balance_rel=balance,
                cell_volume_um3=float((4.0 if PLANAR else 4.0 * math.pi) * mod.vphi.sum()))
    if verbose:
        print(json.dumps(info), flush=True)
    return info


def newton_converged(n, dy):
    """The stopping rule of both models: |ΔC| < 1e-9 C_b and |ΔS| < 1e-11."""
    return np.max(np.abs(dy[:n])) < 1e-9 * C_B and np.max(np.abs(dy[n:])) < 1e-11


def integrate(mod, level, t_end, verbose=False):
    """The time loop of both models: BDF2 steps on the level's schedule, each solved in place by
    mod.newton(y, base, γΔt, t) (which returns its iterations); S̄ and the O2 outflow recorded."""
    times = schedule(level, t_end)
    x = mod.initial()
    x_old = None
    S = [mod.s_mean(x)]
    tot0 = mod.o2_total(x)
    out_int, out_prev = 0.0, mod.outflow(x)
    newton_its, t0 = 0, time.time()
    for k in range(1, len(times)):
        dt = times[k] - times[k - 1]
        a0, a1, gam = bdf2_coefficients(times, k, x_old is None)
        base = a0 * x - (a1 * x_old if x_old is not None else 0.0)
        y = x.copy()
        newton_its += mod.newton(y, base, gam * dt, times[k])
        x_old, x = x, y
        S.append(mod.s_mean(x))
        o = mod.outflow(x)
        out_int += 0.5 * (o + out_prev) * dt
        out_prev = o
    return times, np.array(S), run_info(mod, level, times, newton_its, t0, tot0, out_int, x, verbose)


def run(level, t_end, d_hb=0.0, verbose=False, lumped=None):
    """lumped: None for the local model, else the rate modifier M of the lumped model."""
    mod = Model(level, d_hb) if lumped is None else LumpedModel(level, lumped)
    return integrate(mod, level, t_end, verbose)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--study", action="store_true")
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--hb-diffusion", type=float, default=0.0, help="D_Hb in µm²/s (0: off)")
    ap.add_argument("--out", default=".")
    ap.add_argument("--d-out", type=float, default=2800.0, help="D_O2 in the medium, µm²/s")
    ap.add_argument("--planar", action="store_true", help="planar 2D section instead of the 3D cell")
    ap.add_argument("--box", type=float, default=6.0, help="half-width L of the held box, µm")
    ap.add_argument("--lumped", type=float, default=None, metavar="M",
                    help="lumped (cell-mean) saturation with rate modifier M > 0 (absent: local kinetics)")
    args = ap.parse_args()
    if args.lumped is not None and not args.lumped > 0.0:
        ap.error("--lumped M needs M > 0")
    if args.lumped is not None and args.hb_diffusion != 0.0:
        ap.error("--hb-diffusion does not apply to --lumped (one S for the cell)")
    global L_BOX, PLANAR, D_OUT
    L_BOX = args.box
    D_OUT = args.d_out
    PLANAR = args.planar
    s0, sf = hill(P0), hill(C_B / ALPHA)
    t_end = args.t_end if args.t_end else 2.5
    if not args.study:
        t, S, info = run(args.levels[0], t_end, args.hb_diffusion, verbose=True, lumped=args.lumped)
        frac = (S - sf) / (s0 - sf)
        for q in (0.5, 0.1, 0.01):
            k = np.argmax(frac <= q)
            print(f"(S - Sf)/(S0 - Sf) = {q}: t = {t[k]:.4g} s" if frac[k] <= q else f"not reached {q}")
        return
    t0 = time.time()
    res = [run(lv, t_end, args.hb_diffusion, verbose=True, lumped=args.lumped) for lv in args.levels]
    tc = res[0][0]
    curves = []
    for t, S, _ in res:  # restrict every level to the coarse time points (they nest)
        pos = np.searchsorted(t, tc)
        assert np.allclose(t[pos], tc, rtol=0, atol=1e-12)
        curves.append(S[pos])
    S1, S2, S3 = curves[-3], curves[-2], curves[-1]
    d12, d23 = np.max(np.abs(S1 - S2)), np.max(np.abs(S2 - S3))
    p = math.log(d12 / d23) / math.log(2.0)
    rich = d23 / (2 ** p - 1.0)  # remaining max error of the finest curve
    p_fix = 1.0  # conservative: first order (staircase/volume-fraction interface)
    rich_conservative = d23 / (2 ** p_fix - 1.0)
    S_rich = S3 + (S3 - S2) / (2 ** p - 1.0)
    frac = (S3 - sf) / (s0 - sf)
    def tq(q):
        k = int(np.argmax(frac <= q))
        # linear interpolation between k-1 and k
        f0, f1 = frac[k - 1], frac[k]
        return float(tc[k - 1] + (q - f0) / (f1 - f0) * (tc[k] - tc[k - 1]))
    study = dict(S0=s0, S_final=sf, t_end=t_end, d_hb=args.hb_diffusion,
                 levels=[r[2] for r in res], max_diff_coarse_mid=float(d12), max_diff_mid_fine=float(d23),
                 observed_order=p, richardson_max_error_fine=float(rich),
                 first_order_error_bound_fine=float(rich_conservative),
                 t_half_s=tq(0.5), t_90_s=tq(0.1), t_99_s=tq(0.01), total_wall_s=time.time() - t0)
    print(json.dumps(study, indent=1))
    tag = ("_planar" if PLANAR else "") + ("" if args.hb_diffusion == 0 else f"_dhb{args.hb_diffusion:g}")
    if args.lumped is not None:
        tag += f"_lumped_M{args.lumped:g}"
    with open(f"{args.out}/reference_S{tag}.csv", "w") as fh:
        if args.lumped is None:
            fh.write("# single RBC deoxygenation, cell-averaged saturation (volume-weighted); "
                     "reference_rbc.py --study; PROVENANCE.md\n")
        else:
            cmd = " ".join(["reference_rbc.py --study --levels"] + [str(lv) for lv in args.levels]
                           + [f"--t-end {t_end:g}"] + (["--planar"] if PLANAR else [])
                           + ([f"--box {L_BOX:g}"] if L_BOX != 6.0 else [])
                           + ([f"--d-out {D_OUT:g}"] if D_OUT != 2800.0 else [])
                           + [f"--lumped {args.lumped:g}"])
            fh.write(f"# single RBC deoxygenation, LUMPED cell-mean saturation S (one S per cell, "
                     f"rate modifier M = {args.lumped:g}); {cmd}; PROVENANCE.md\n")
        fh.write("t_s,S_fine,S_richardson,S_mid,S_coarse\n")
        for k in range(len(tc)):
            fh.write(f"{tc[k]:.9g},{S3[k]:.9f},{S_rich[k]:.9f},{S2[k]:.9f},{S1[k]:.9f}\n")
    with open(f"{args.out}/study{tag}.json", "w") as fh:
        json.dump(study, fh, indent=1)


if __name__ == "__main__":
    sys.exit(main())
