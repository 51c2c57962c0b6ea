#pragma once
// Collision of the nine populations of one node, with Guo forcing.
// Internal to the fluid layer; inlined into the stream–collide kernel.
#include "fluid/collision.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::fluid::detail {

// Relaxation rates of one node: ω+ = 1/τ (viscous), ω− (TRT only; = ω+ for BGK), and the
// times τ± − ½ that carry Guo's source into the equilibrium (eq 1.5b).
struct Rates {
  double omega_plus, omega_minus;
  double lag_plus = 0.5, lag_minus = 0.5;  // τ+ − ½, τ− − ½
};

inline Rates rates_for(CollisionModel model, double tau, double magic) {
  if (model == CollisionModel::trt) {
    const double lag_minus = magic / (tau - 0.5);  // τ− − ½ (eq 1.7)
    return {1.0 / tau, 1.0 / (0.5 + lag_minus), tau - 0.5, lag_minus};
  }
  return {1.0 / tau, 1.0 / tau, tau - 0.5, tau - 0.5};  // BGK, regularized: one rate
}

// f: the nine streamed populations of the node, stored as deviations from the rest
// weights, f̃_i = f_i − w_i (see fluid_lattice.hpp), overwritten with post-collision ones.
// Moments (docs/model.md eq 1.3): ρ = 1 + Σf̃, ρu = Σ f̃ c + F/2.
//  BGK (eq 14, 17): f' = f − ω(f − f^eq) + (1 − ω/2) S = (1 − ω) f + ω f^eq + (1 − ω/2) S,
//  TRT: f' = f − ω+(f⁺ − f^eq⁺) − ω−(f⁻ − f^eq⁻) + (1 − ω+/2) S⁺ + (1 − ω−/2) S⁻,
//  S_i = w_i [ (c_i − u)·F/c_s² + (c_i·u)(c_i·F)/c_s⁴ ]  (Guo et al. 2002),
//  split S⁺_i = w_i[(c_i·u)(c_i·F)/c_s⁴ − u·F/c_s²], S⁻_i = w_i (c_i·F)/c_s².
//  BGK and TRT add the source inside the relaxation (eq 1.5b): with b± = (τ± − ½) F/ρ,
//  f^eq⁺ + (τ+ − ½) S⁺ = w_i [(ρ − 1) + ρ (4.5 (c·u)(c·u + 2 c·b⁺) − 1.5 u·(u + 2 b⁺))] and
//  f^eq⁻ + (τ− − ½) S⁻ = 3 w_i ρ c·(u + b⁻), and ω± (τ± − ½) = 1 − ω±/2: the same values
//  as the two terms written apart, at about a third of the source's operations.
//  Regularized (Latt & Chopard 2006, Math Comput Simul 72:165), with
//  Q_i = c_i c_i − c_s² I and Guo forcing:
//    Π^neq = Σ c_i c_i (f_i − f^eq_i) + ½(uF + Fu)   (non-equilibrium stress with the
//            force correction, the part ∝ the strain rate: Guo et al. 2002, PRE 65:046308)
//    f^neq,R_i = w_i Q_i : Π^neq / (2 c_s⁴)           (projection on the 2nd Hermite order)
//    f'_i = f^eq_i + (1 − ω) f^neq,R_i + ½ S_i.
//  This is BGK-plus-Guo, f' = f^R − ω(f^R − f^eq) + (1 − ω/2) S, applied to the
//  regularised populations f^R = f^eq + f^neq,R − ½ S, i.e. to the projection of f
//  on the Hermite orders 0–2 (it keeps ρ, Σ c f = ρu − F/2 and Σ c c f; S holds
//  only orders 1 and 2). Hence Σ f' = Σ f and Σ c f' = Σ c f + F exactly, and the
//  2nd moment after collision equals BGK's: the model differs from BGK only in the
//  discarded 3rd/4th-order (ghost) moments, which it resets to equilibrium.
// The velocity the collision relaxes towards, u = (Σ c f̃ + F/2)/ρ of the streamed populations
// (eq 1.3): returned for a caller that needs it (the kernel's velocity output, eq 1.3b).
struct CollisionVelocity {
  double ux, uy;
};

template <CollisionModel Model, bool HasForce>
inline CollisionVelocity collide_node(double* f, Rates r, double Fx, double Fy) {
  using namespace d2q9;
  const double drho = f[0] + f[1] + f[2] + f[3] + f[4] + f[5] + f[6] + f[7] + f[8];
  const double rho = 1.0 + drho;
  double jx = f[1] - f[3] + f[5] - f[6] - f[7] + f[8];
  double jy = f[2] - f[4] + f[5] + f[6] - f[7] - f[8];
  if constexpr (HasForce) {
    jx += 0.5 * Fx;
    jy += 0.5 * Fy;
  }
  const double inv_rho = 1.0 / rho;
  const double ux = jx * inv_rho, uy = jy * inv_rho;
  const double uu_term = -1.5 * (ux * ux + uy * uy);
  // f^eq_i − w_i = w_i [ (ρ − 1) + ρ (3 c·u + 4.5 (c·u)² − 1.5 u·u) ]  (eq 16, shifted)

  if constexpr (Model == CollisionModel::bgk) {
    // Written per pair (i, ī) of opposite directions, like TRT below: f^eq_i = E⁺ ± E⁻
    // with E⁺ = w_i [ (ρ − 1) + ρ (4.5 (c·u)² − 1.5 u·u) ] and E⁻ = 3 w_i ρ (c·u), and
    // f' = (1 − ω) f + ω f^eq (eq 14) — a third fewer operations than direction by
    // direction. With a force, E± take Guo's source as in eq 1.5b (b = b⁺ = b⁻).
    const double om = r.omega_plus;
    const double keep = 1.0 - om;
    double bx = 0.0, by = 0.0, uu = uu_term;
    if constexpr (HasForce) {
      const double lag = r.lag_plus * inv_rho;
      bx = lag * Fx;
      by = lag * Fy;
      uu = -1.5 * (ux * (ux + 2.0 * bx) + uy * (uy + 2.0 * by));
    }
    f[0] = keep * f[0] + om * (w[0] * (drho + rho * uu));
    constexpr int pos[4] = {1, 2, 5, 6};
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int i = pos[k], j = opposite[i];
      const double cu = dot_c(i, ux, uy);
      double cq = cu * cu, cv = cu;  // (c·u)(c·u + 2 c·b) and c·(u + b)
      if constexpr (HasForce) {
        const double cb = dot_c(i, bx, by);
        cq = cu * (cu + 2.0 * cb);
        cv = cu + cb;
      }
      const double e_plus = om * (w[i] * (drho + rho * (uu + 4.5 * cq)));
      const double e_minus = om * (w[i] * rho * 3.0 * cv);
      f[i] = keep * f[i] + (e_plus + e_minus);
      f[j] = keep * f[j] + (e_plus - e_minus);
    }
  } else if constexpr (Model == CollisionModel::regularized) {
    const double om = r.omega_plus;
    const double uF = HasForce ? ux * Fx + uy * Fy : 0.0;
    // Raw second moments of the stored deviations: Σ c c f = Σ c c f̃ + c_s² I.
    const double sxx = f[1] + f[3] + f[5] + f[6] + f[7] + f[8];
    const double syy = f[2] + f[4] + f[5] + f[6] + f[7] + f[8];
    const double sxy = f[5] - f[6] + f[7] - f[8];
    // Π^neq = Σ c c f − (ρ c_s² I + ρ u u) + ½(uF + Fu)   (D2Q9 equilibrium moments exact).
    double pxx = sxx - drho / 3.0 - rho * ux * ux;
    double pyy = syy - drho / 3.0 - rho * uy * uy;
    double pxy = sxy - rho * ux * uy;
    if constexpr (HasForce) {
      pxx += ux * Fx;
      pyy += uy * Fy;
      pxy += 0.5 * (ux * Fy + uy * Fx);
    }
    // (1 − ω) Q_i:Π^neq / (2 c_s⁴) = (1 − ω) 4.5 [(cx² − ⅓) Πxx + (cy² − ⅓) Πyy + 2 cx cy Πxy]
    const double keep = 4.5 * (1.0 - om);
    const double trace = (pxx + pyy) / 3.0;
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) {
      const double cu = dot_c(i, ux, uy);
      const double feq = w[i] * (drho + rho * (uu_term + 3.0 * cu + 4.5 * cu * cu));
      const double qp = cx[i] * cx[i] * pxx + cy[i] * cy[i] * pyy + 2.0 * cx[i] * cy[i] * pxy - trace;
      double fi = feq + w[i] * keep * qp;
      if constexpr (HasForce) {
        const double cF = dot_c(i, Fx, Fy);
        fi += 0.5 * w[i] * (3.0 * (cF - uF) + 9.0 * cu * cF);
      }
      f[i] = fi;
    }
  } else {
    const double op = r.omega_plus, om = r.omega_minus;
    // With a force, f^eq± take Guo's source S± (eq 1.5b): b± = (τ± − ½) F/ρ.
    double bpx = 0.0, bpy = 0.0, bmx = 0.0, bmy = 0.0, uu = uu_term;
    if constexpr (HasForce) {
      const double lag_p = r.lag_plus * inv_rho, lag_m = r.lag_minus * inv_rho;
      bpx = lag_p * Fx;
      bpy = lag_p * Fy;
      bmx = lag_m * Fx;
      bmy = lag_m * Fy;
      uu = -1.5 * (ux * (ux + 2.0 * bpx) + uy * (uy + 2.0 * bpy));
    }
    // Rest population: symmetric only.
    {
      const double feq0 = w[0] * (drho + rho * uu);
      f[0] = f[0] - op * (f[0] - feq0);
    }
    // Pairs (i, ī) = (1,3), (2,4), (5,7), (6,8).
    constexpr int pos[4] = {1, 2, 5, 6};
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int i = pos[k], j = opposite[i];
      const double cu = dot_c(i, ux, uy);
      double cq = cu * cu, cv = cu;  // (c·u)(c·u + 2 c·b⁺) and c·(u + b⁻)
      if constexpr (HasForce) {
        cq = cu * (cu + 2.0 * dot_c(i, bpx, bpy));
        cv = cu + dot_c(i, bmx, bmy);
      }
      const double feq_p = w[i] * (drho + rho * (uu + 4.5 * cq));
      const double feq_m = w[i] * rho * 3.0 * cv;
      const double f_p = 0.5 * (f[i] + f[j]), f_m = 0.5 * (f[i] - f[j]);
      const double dp = -op * (f_p - feq_p);
      const double dm = -om * (f_m - feq_m);
      f[i] += dp + dm;
      f[j] += dp - dm;
    }
  }
  return {ux, uy};
}

}  // namespace erythro::fluid::detail
