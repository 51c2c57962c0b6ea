// Fused stream–collide of the transport lattice, pull scheme (docs/transport.md §1):
// node n gathers g_i from n − c_i (post-collision values of the previous step, or the
// boundary rule of its side), collides, and writes its Q post-collision values and C.
// Rows are distributed over OpenMP threads; every node is independent and the mass
// balance is summed per row, then serially over rows, so results are bitwise
// identical for any thread count.
//
// Collision (eqs T2–T4), ω = 1/τ, τ = ½ + D/c_s²:
//   C     = (Σ g_i + q/2) / (1 + k/2),   q_tot = q − k C
//   BGK (T3):  g*_i = g_i − ω (g_i − w_i C (1 + c_i·u/c_s²)) + (1 − ω/2) w_i q_tot (1 + c_i·u/c_s²)
//   TRT (T3'): g*_i = g_i − ω⁺ (g⁺_i − w_i C) − ω⁻ (g⁻_i − w_i C c_i·u/c_s²)
//                     + (1 − ω⁺/2) w_i q_tot + (1 − ω⁻/2) w_i q_tot c_i·u/c_s²,
//              g^±_i = (g_i ± g_ī)/2, ω⁻ = ω (D), ω⁺ = 1/(½ + Λ/(τ − ½)).
// Σ_i g*_i = Σ_i g_i + q_tot exactly for both (Σ w_i c_i = 0, Σ g⁻ = 0), which is what
// closes the mass balance.
#include "transport/transport_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace erythro::transport::detail {
namespace {

// Transport steps of small grids take tens of microseconds: forking threads (and
// waiting for a descheduled worker on a shared machine) costs more than it saves
// below 128² nodes (measured: a 64² D2Q5 run was over 10× slower with two threads on a
// loaded 2-core machine). Larger than the fluid's threshold for that reason.
constexpr std::size_t kThreadingThreshold = 128 * 128;

// Relaxation rates of a uniform D: ω (BGK; ω⁻ of TRT) and ω⁺ (TRT).
struct Rates {
  double omega = 1.0, omega_plus = 1.0;
};

inline Rates rates_for(double D, bool trt, double magic) {
  const double omega = 1.0 / tau_for_diffusivity(D);  // τ⁻ = ½ + D/c_s² (sets D)
  return {omega, trt ? 1.0 / (0.5 + magic / (kInvCs2 * D)) : omega};  // τ⁺ = ½ + Λ/(τ⁻ − ½)
}

// The D2Q5 collision with a per-node diffusivity TENSOR (docs/transport.md eq T8; Yoshida &
// Nagaoka 2010, J Comput Phys 229:7774, relaxation of the flux moment by a matrix; Ginzburg
// 2005, Adv Water Resour 28:1171, link-wise symmetric rates). Moments of the moving pairs:
//   j = (g1 − g3, g2 − g4),  e_x = g1 + g3,  e_y = g2 + g4,  g0 = m − e_x − e_y;
//   j*   = j − Ω (j − C u) + (I − Ω/2) q_tot u,    Ω = (½ I + D/c_s²)⁻¹   (2×2; sets D_ij)
//   e_a* = e_a − ω⁺_a (e_a − C/3) + (1 − ω⁺_a/2) q_tot/3,  ω⁺_a = 1/(½ + Λ/(D_aa/c_s²)),
//   g0*  = m + q_tot − e_x* − e_y*   (mass exactly conserved, as T3').
// With D_xy = 0 and D_xx = D_yy = D this is T3' (unit test TransportTensor.ReducesToScalarTrtWhenIsotropic).
// Returns Σ_i g*_i; g receives the post-collision populations.
[[gnu::always_inline]] inline double collide_tensor(const KernelArgs& a, std::size_t n, double C, double q, double ux,
                                                    double uy, double* g) {
  const double dxx = a.Dxx[n], dyy = a.Dyy[n], dxy = a.Dxy[n];
  const double txx = 0.5 + kInvCs2 * dxx, tyy = 0.5 + kInvCs2 * dyy, txy = kInvCs2 * dxy;  // T = ½ I + D/c_s²
  const double inv_det = 1.0 / (txx * tyy - txy * txy);
  const double oxx = tyy * inv_det, oyy = txx * inv_det, oxy = -txy * inv_det;  // Ω = T⁻¹
  const double m = g[0] + g[1] + g[2] + g[3] + g[4];
  const double jx = g[1] - g[3], jy = g[2] - g[4];
  const double nx = jx - C * ux, ny = jy - C * uy;  // non-equilibrium flux
  const double qx = q * ux, qy = q * uy;
  const double jxs = jx - (oxx * nx + oxy * ny) + qx - 0.5 * (oxx * qx + oxy * qy);
  const double jys = jy - (oxy * nx + oyy * ny) + qy - 0.5 * (oxy * qx + oyy * qy);
  const double opx = 1.0 / (0.5 + a.magic / (kInvCs2 * dxx)), opy = 1.0 / (0.5 + a.magic / (kInvCs2 * dyy));
  const double third = 1.0 / 3.0;
  const double exs = (g[1] + g[3]) - opx * (g[1] + g[3] - third * C) + (1.0 - 0.5 * opx) * third * q;
  const double eys = (g[2] + g[4]) - opy * (g[2] + g[4] - third * C) + (1.0 - 0.5 * opy) * third * q;
  g[0] = m + q - exs - eys;
  g[1] = 0.5 * (exs + jxs);
  g[3] = 0.5 * (exs - jxs);
  g[2] = 0.5 * (eys + jys);
  g[4] = 0.5 * (eys - jys);
  return m + q;
}

// The collision of one node (eqs T2–T4, T3 or T3'): g holds the streamed populations and
// receives the post-collision ones; returns Σ_i g*_i in total and q_tot in q.
template <class S, bool Vel, bool DField, bool React, bool Decay, bool Trt, bool Tensor, bool Axi = false>
[[gnu::always_inline]] inline void collide(const KernelArgs& a, std::size_t n, const Rates& uniform, double* g,
                                           double& total, double& q) {
  constexpr int Q = S::Q;
  double m = 0.0;
#pragma GCC unroll 9
  for (int i = 0; i < Q; ++i) m += g[i];
  double C = m;
  q = 0.0;
  if constexpr (React && Decay) {
    const double k = a.decay[n];
    C = (m + 0.5 * a.source[n]) / (1.0 + 0.5 * k);  // eq T4 with the implicit sink
    q = a.source[n] - k * C;
  } else if constexpr (React) {  // the same with k = 0 (x / 1 = x, s − 0 C = s: the same bits)
    C = m + 0.5 * a.source[n];
    q = a.source[n];
  }
  double ux = 0.0, uy = 0.0;
  if constexpr (Vel) {
    ux = a.ux[n];
    uy = a.uy[n];
  }
  double t = 0.0;
  if constexpr (Tensor) {
    static_assert(S::Q == 5 && Trt, "the diffusivity tensor is D2Q5 TRT only");
    t = collide_tensor(a, n, C, q, ux, uy, g);
    a.C[n] = C;
    total = t;
    return;
  }
  const Rates r = DField ? Rates{a.omega[n], a.omega_plus[n]} : uniform;
  if constexpr (!Trt) {
    const double omega = r.omega;
    const double src_pref = (1.0 - 0.5 * omega) * q;
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) {
      const double shape = Vel ? 1.0 + kInvCs2 * (S::cx[i] * ux + S::cy[i] * uy) : 1.0;
      const double geq = S::w[i] * C * shape;
      double gi = g[i] - omega * (g[i] - geq);
      if constexpr (React) gi += src_pref * S::w[i] * shape;
      g[i] = gi;
      t += gi;
    }
  } else {
    // eq T3': symmetric part relaxes with ω⁺ towards w_i C, antisymmetric with ω⁻ towards w_i C c_i·u/c_s²
    const double om = r.omega, op = r.omega_plus;
    const double src_p = (1.0 - 0.5 * op) * q;
    double src_m = (1.0 - 0.5 * om) * q;
    // Axisymmetric (docs/model.md eq 7.9): the source's antisymmetric part carries the velocity
    // times Λ⁺/Λ⁻, which makes the steady state the conservative cylindrical finite-volume scheme
    // (with 1, the steady flux gains (Λ⁺ − Λ⁻) r q_tot (u + D/r e_r), a point source at the axis).
    if constexpr (Axi) src_m *= DField ? a.source_velocity_scale[n] : a.uniform_source_velocity_scale;
    double out[Q];
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) {
      const int o = S::opposite[i];
      const double cu = Vel ? kInvCs2 * (S::cx[i] * ux + S::cy[i] * uy) : 0.0;
      const double gp = 0.5 * (g[i] + g[o]), gm = 0.5 * (g[i] - g[o]);
      double gi = g[i] - op * (gp - S::w[i] * C) - om * (gm - S::w[i] * C * cu);
      if constexpr (React) gi += S::w[i] * (src_p + src_m * cu);
      out[i] = gi;
      t += gi;
    }
#pragma GCC unroll 9
    for (int i = 0; i < Q; ++i) g[i] = out[i];
  }
  a.C[n] = C;
  total = t;
}

// A row's three sums, Σ q_tot, Σ g* and Σ |g*| over its nodes, each with four interleaved
// partial sums in a fixed order (deterministic: the four are one vector's lanes). One loop
// for the three, so that their three chains of additions overlap; each sum is the one it
// would be alone, the same bits.
struct RowSums {
  double source, amount, scale;
};
inline RowSums row_sums(const double* qtot, const double* total, int len) {
  double q[4] = {0.0, 0.0, 0.0, 0.0}, t[4] = {0.0, 0.0, 0.0, 0.0}, a[4] = {0.0, 0.0, 0.0, 0.0};
  int k = 0;
  for (; k + 4 <= len; k += 4) {
#pragma GCC unroll 4
    for (int j = 0; j < 4; ++j) {
      q[j] += qtot[k + j];
      t[j] += total[k + j];
      a[j] += std::fabs(total[k + j]);
    }
  }
  for (; k < len; ++k) {
    q[0] += qtot[k];
    t[0] += total[k];
    a[0] += std::fabs(total[k]);
  }
  return {(q[0] + q[1]) + (q[2] + q[3]), (t[0] + t[1]) + (t[2] + t[3]), (a[0] + a[1]) + (a[2] + a[3])};
}

// Interior nodes n0 … n0+len−1 of one row: Q restrict source and destination
// streams, no branches, so the loop vectorises along x (as the fluid kernel; named
// pointers rather than arrays, which GCC would not vectorise).
template <class S, bool Vel, bool DField, bool React, bool Decay, bool Trt, bool Tensor, bool Axi>
void interior_span(const KernelArgs& a, const double* const* src, double* const* out, std::size_t n0, int len,
                   const Rates& rates, double* __restrict total, double* __restrict qtot) {
  constexpr int Q = S::Q;
  const double* __restrict s0 = src[0];
  const double* __restrict s1 = src[1];
  const double* __restrict s2 = src[2];
  const double* __restrict s3 = src[3];
  const double* __restrict s4 = src[4];
  const double* __restrict s5 = src[Q > 5 ? 5 : 0];
  const double* __restrict s6 = src[Q > 5 ? 6 : 0];
  const double* __restrict s7 = src[Q > 5 ? 7 : 0];
  const double* __restrict s8 = src[Q > 5 ? 8 : 0];
  double* __restrict o0 = out[0];
  double* __restrict o1 = out[1];
  double* __restrict o2 = out[2];
  double* __restrict o3 = out[3];
  double* __restrict o4 = out[4];
  double* __restrict o5 = out[Q > 5 ? 5 : 0];
  double* __restrict o6 = out[Q > 5 ? 6 : 0];
  double* __restrict o7 = out[Q > 5 ? 7 : 0];
  double* __restrict o8 = out[Q > 5 ? 8 : 0];
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (int k = 0; k < len; ++k) {
    double f[Q];
    f[0] = s0[k];
    f[1] = s1[k];
    f[2] = s2[k];
    f[3] = s3[k];
    f[4] = s4[k];
    if constexpr (Q > 5) {
      f[5 % Q] = s5[k];
      f[6 % Q] = s6[k];
      f[7 % Q] = s7[k];
      f[8 % Q] = s8[k];
    }
    collide<S, Vel, DField, React, Decay, Trt, Tensor, Axi>(a, n0 + static_cast<std::size_t>(k), rates, f, total[k],
                                                            qtot[k]);
    o0[k] = f[0];
    o1[k] = f[1];
    o2[k] = f[2];
    o3[k] = f[3];
    o4[k] = f[4];
    if constexpr (Q > 5) {
      o5[k] = f[5 % Q];
      o6[k] = f[6 % Q];
      o7[k] = f[7 % Q];
      o8[k] = f[8 % Q];
    }
  }
}

template <class S, bool Vel, bool DField, bool React, bool Decay, bool Trt, bool Tensor = false, bool Axi = false>
void run(const KernelArgs& a) {
  constexpr int Q = S::Q;
  const Grid g = a.grid;
  const std::size_t N = g.size();
  const Rates rates = rates_for(a.uniform_D, Trt, a.magic);
#pragma omp parallel if (N >= kThreadingThreshold)
  {
    // Per-node Σ g* and q_tot of the current row, summed after the row.
    std::vector<double> total(static_cast<std::size_t>(g.nx)), qtot(static_cast<std::size_t>(g.nx));
#pragma omp for schedule(static)
    for (int y = 0; y < g.ny; ++y) {
      double boundary = 0.0;
      const TransportBoundaries sides = row_sides(a, y);
      auto general = [&](int x) {
        double f[Q];
        for (int i = 0; i < Q; ++i) f[i] = pull<S>(g, sides, a.src, x, y, i, boundary);
        const std::size_t n = g.index(x, y);
        collide<S, Vel, DField, React, Decay, Trt, Tensor, Axi>(a, n, rates, f, total[static_cast<std::size_t>(x)],
                                                                qtot[static_cast<std::size_t>(x)]);
        for (int i = 0; i < Q; ++i) a.dst[i * N + n] = f[i];
      };
      if (y == 0 || y == g.ny - 1 || g.nx < 3) {
        for (int x = 0; x < g.nx; ++x) general(x);
      } else {
        general(0);
        const double* s[Q];
        double* o[Q];
        const std::size_t n0 = g.index(1, y);
        for (int i = 0; i < Q; ++i) {
          s[i] = a.src + i * N + g.index(1 - S::cx[i], y - S::cy[i]);
          o[i] = a.dst + i * N + n0;
        }
        interior_span<S, Vel, DField, React, Decay, Trt, Tensor, Axi>(a, s, o, n0, g.nx - 2, rates, total.data() + 1,
                                                                      qtot.data() + 1);
        general(g.nx - 1);
      }
      const auto r = static_cast<std::size_t>(y);
      const RowSums sums = row_sums(qtot.data(), total.data(), g.nx);
      a.row_source[r] = sums.source;
      a.row_boundary[r] = boundary;
      a.row_amount[r] = sums.amount;
      a.row_scale[r] = sums.scale;
    }
  }
}

// The axisymmetric source scaling (Axi) changes only TRT with a source (Vel is always set there).
template <class S, bool Vel, bool DField, bool React, bool Decay>
void with_collision(const KernelArgs& a) {
  if constexpr (React && Vel) {
    if (a.trt && a.row_radius != nullptr) return run<S, Vel, DField, React, Decay, true, false, true>(a);
  }
  return a.trt ? run<S, Vel, DField, React, Decay, true>(a) : run<S, Vel, DField, React, Decay, false>(a);
}

// Reaction: none, a source alone, or a source and a sink.
template <class S, bool Vel, bool DField>
void with_reaction(const KernelArgs& a) {
  if (a.source == nullptr) return with_collision<S, Vel, DField, false, false>(a);
  if (a.decay == nullptr) return with_collision<S, Vel, DField, true, false>(a);
  return with_collision<S, Vel, DField, true, true>(a);
}

// Tensor diffusivity: D2Q5 with TRT only (checked by TransportLattice::step).
template <bool Vel>
void tensor_with_reaction(const KernelArgs& a) {
  if (a.source == nullptr) return run<D2Q5, Vel, true, false, false, true, true>(a);
  if (a.decay == nullptr) return run<D2Q5, Vel, true, true, false, true, true>(a);
  return run<D2Q5, Vel, true, true, true, true, true>(a);
}

void dispatch_tensor(const KernelArgs& a) {
  return a.ux != nullptr ? tensor_with_reaction<true>(a) : tensor_with_reaction<false>(a);
}

template <class S>
void dispatch(const KernelArgs& a) {
  const bool vel = a.ux != nullptr, dfield = a.omega != nullptr;
  if (vel) return dfield ? with_reaction<S, true, true>(a) : with_reaction<S, true, false>(a);
  return dfield ? with_reaction<S, false, true>(a) : with_reaction<S, false, false>(a);
}

}  // namespace

void stream_collide(const KernelArgs& args) {
  if (args.Dxx != nullptr) return dispatch_tensor(args);
  if (args.stencil == Stencil::d2q5) return dispatch<D2Q5>(args);
  return dispatch<D2Q9>(args);
}

void relaxation_rates(std::span<const double> D, bool trt, double magic, std::vector<double>& omega,
                      std::vector<double>& omega_plus) {
  omega.resize(D.size());
  omega_plus.resize(D.size());
  for (std::size_t n = 0; n < D.size(); ++n) {
    const Rates r = rates_for(D[n], trt, magic);  // what the collision computed node by node
    omega[n] = r.omega;
    omega_plus[n] = r.omega_plus;
  }
}

}  // namespace erythro::transport::detail
