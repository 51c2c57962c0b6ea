#include "membrane/membrane_energy.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/portable_hypot.hpp"
#include "common/select_bits.hpp"

namespace erythro::membrane {

namespace {

void check_sizes(const RestShape& rest, std::size_t a, std::size_t b) {
  if (a != rest.size() || b != rest.size()) {
    throw std::invalid_argument("membrane energy: marker arrays do not match the rest shape");
  }
}

// Edge pass of the tension forces: pull_e = (T(λ_e)/ℓ_e)(dx_e, dy_e), the pull of edge e on its
// first end (and minus it on its second), every edge on its own (eqs 3.7, 3.7a). The lengths
// come from hypot_portable's branch-free kernel in a loop that vectorises; should any edge lie
// outside the kernel's common range (coincident markers, say), every edge is done again with
// hypot_portable itself, so the result is always hypot_portable's, bit for bit.
template <TensionLawType kLaw>
void edge_pulls(const TensionLaw& law, const RestShape& rest, const double* x, const double* y, std::size_t n,
                double* px, double* py) {
  auto pull = [&](std::size_t e, double dx, double dy, double l) {
    const double T = tension_of<kLaw>(law, l / rest.length[e]) / l;  // T · t_e = (T/ℓ)(dx, dy)
    px[e] = T * dx;
    py[e] = T * dy;
  };
  int outside = 0;
  for (std::size_t e = 0; e + 1 < n; ++e) {
    const double dx = x[e + 1] - x[e], dy = y[e + 1] - y[e];
    pull(e, dx, dy, numeric::hypot_fast_flagged(dx, dy, outside));
  }
  if (outside != 0)
    for (std::size_t e = 0; e + 1 < n; ++e) {
      const double dx = x[e + 1] - x[e], dy = y[e + 1] - y[e];
      pull(e, dx, dy, numeric::hypot_portable(dx, dy));
    }
  const double dx = x[0] - x[n - 1], dy = y[0] - y[n - 1];  // the closing edge
  pull(n - 1, dx, dy, numeric::hypot_portable(dx, dy));
}

// Scratch of the edge and vertex passes, one per thread (cells run on the threads), grown to the
// largest cell: the edge pulls (px, py), then the bending's pulls on each vertex's two neighbours.
struct EdgeScratch {
  std::vector<double> px, py, qx, qy;
};
EdgeScratch& edge_scratch(std::size_t n) {
  thread_local EdgeScratch s;
  if (s.px.size() < n) {
    s.px.resize(n);
    s.py.resize(n);
    s.qx.resize(n);
    s.qy.resize(n);
  }
  return s;
}

// Vertex i of the bending energy (eq 3.6, 3.6a), with a = X_i − X_{i−1}, b = X_{i+1} − X_i, E_B the
// bending modulus, θ0 and D̄ the vertex's rest angle and dual length, g = ∂E_B/∂θ_i: the pulls
// −g ∂θ_i/∂X_{i−1} → (pax, pay) and −g ∂θ_i/∂X_{i+1} → (pbx, pby); returns the vertex's energy term.
// θ_i − θ0_i is kept in (−π, π] (a rest angle near ±π must not jump by 2π).
[[gnu::always_inline]] inline double bend_vertex(double E_B, double theta0, double dual, double ax, double ay,
                                                 double bx, double by, double& pax, double& pay, double& pbx,
                                                 double& pby) {
  // The wrap as selects through the bits (common/select_bits.hpp): the loop over the vertices then
  // vectorises on AVX2 hosts too, with the bits of the two `if`s.
  double dtheta = turning_angle(ax, ay, bx, by) - theta0;
  dtheta = numeric::select_bits(dtheta > std::numbers::pi, dtheta - 2.0 * std::numbers::pi, dtheta);
  dtheta = numeric::select_bits(dtheta <= -std::numbers::pi, dtheta + 2.0 * std::numbers::pi, dtheta);
  const double g = E_B * dtheta / dual;  // ∂E/∂θ_i
  const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
  pax = -g * (-ay) / a2;
  pay = -g * ax / a2;
  pbx = -g * (-by) / b2;
  pby = -g * bx / b2;
  return 0.5 * E_B * dtheta * dtheta / dual;
}

// Vertex pass of the bending forces (n ≥ 3): each vertex's pulls on its two neighbours on their
// own, in a loop that vectorises (the inline atan2 of eq 3.6a; every array restrict, so the
// compiler needs no overlap checks).
void bending_vertex_pass(double E_B, const double* __restrict theta0, const double* __restrict dual,
                         const double* __restrict x, const double* __restrict y, std::size_t n, double* __restrict pax,
                         double* __restrict pay, double* __restrict pbx, double* __restrict pby) {
  bend_vertex(E_B, theta0[0], dual[0], x[0] - x[n - 1], y[0] - y[n - 1], x[1] - x[0], y[1] - y[0], pax[0], pay[0],
              pbx[0], pby[0]);
  for (std::size_t i = 1; i + 1 < n; ++i)
    bend_vertex(E_B, theta0[i], dual[i], x[i] - x[i - 1], y[i] - y[i - 1], x[i + 1] - x[i], y[i + 1] - y[i], pax[i],
                pay[i], pbx[i], pby[i]);
  bend_vertex(E_B, theta0[n - 1], dual[n - 1], x[n - 1] - x[n - 2], y[n - 1] - y[n - 2], x[0] - x[n - 1],
              y[0] - y[n - 1], pax[n - 1], pay[n - 1], pbx[n - 1], pby[n - 1]);
}

// The bending forces by passes (n ≥ 3): the vertex pass, then a node pass that adds the pulls to
// every marker in the order the one loop over the vertices adds them (vertex i − 1's pull, then
// minus vertex i's two, then vertex i + 1's; markers 0 and n − 1 in that loop's order), so the
// same bits as that loop.
void add_bending_by_passes(const MembraneModel& model, const RestShape& rest, const double* x, const double* y,
                           std::size_t n, EdgeScratch& s, double* fx, double* fy) {
  double* pax = s.px.data();
  double* pay = s.py.data();
  double* pbx = s.qx.data();
  double* pby = s.qy.data();
  bending_vertex_pass(model.bending, rest.turning.data(), rest.dual.data(), x, y, n, pax, pay, pbx, pby);
  fx[0] = ((fx[0] - (pax[0] + pbx[0])) + pax[1]) + pbx[n - 1];
  fy[0] = ((fy[0] - (pay[0] + pby[0])) + pay[1]) + pby[n - 1];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    fx[i] = ((fx[i] + pbx[i - 1]) - (pax[i] + pbx[i])) + pax[i + 1];
    fy[i] = ((fy[i] + pby[i - 1]) - (pay[i] + pby[i])) + pay[i + 1];
  }
  fx[n - 1] = ((fx[n - 1] + pax[0]) + pbx[n - 2]) - (pax[n - 1] + pbx[n - 1]);
  fy[n - 1] = ((fy[n - 1] + pay[0]) + pby[n - 2]) - (pay[n - 1] + pby[n - 1]);
}

// One pass computing the energy (kEnergy) and/or adding −∂E/∂X (kForces).
template <bool kForces, bool kEnergy = true>
Energy evaluate(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                std::span<const double> y, double* fx, double* fy) {
  const std::size_t n = rest.size();
  Energy E;
  // Tension: E_T = Σ L_e W(ℓ_e/L_e); −∂E_T/∂X_{e+1} = −T t_e, −∂E_T/∂X_e = +T t_e.
  if constexpr (kEnergy) {
    for (std::size_t e = 0; e < n; ++e) {
      const std::size_t f = (e + 1 == n) ? 0 : e + 1;
      const double l = numeric::hypot_portable(x[f] - x[e], y[f] - y[e]);
      E.tension += rest.length[e] * model.tension.energy(l / rest.length[e]);
    }
  }
  if constexpr (kForces) {
    if (n > 0) {
      EdgeScratch& s = edge_scratch(n);
      double* px = s.px.data();
      double* py = s.py.data();
      switch (model.tension.type) {
        case TensionLawType::neo_hookean:
          edge_pulls<TensionLawType::neo_hookean>(model.tension, rest, x.data(), y.data(), n, px, py);
          break;
        case TensionLawType::skalak:
          edge_pulls<TensionLawType::skalak>(model.tension, rest, x.data(), y.data(), n, px, py);
          break;
        case TensionLawType::hookean:
          edge_pulls<TensionLawType::hookean>(model.tension, rest, x.data(), y.data(), n, px, py);
          break;
      }
      // Node pass, in the order a single loop over the edges adds them: marker i (≥ 1) first
      // loses edge i − 1's pull, then gains edge i's; marker 0 gains edge 0's, then loses the
      // last edge's. The same sums, so the same bits, as the one-loop form.
      fx[0] = (fx[0] + px[0]) - px[n - 1];
      fy[0] = (fy[0] + py[0]) - py[n - 1];
      for (std::size_t i = 1; i < n; ++i) {
        fx[i] = (fx[i] - px[i - 1]) + px[i];
        fy[i] = (fy[i] - py[i - 1]) + py[i];
      }
    }
  }
  // Bending: E_B = ½ E_B Σ (θ_i − θ0_i)² / D̄_i; with a = X_i − X_{i−1}, b = X_{i+1} − X_i,
  // ∂θ/∂X_{i+1} = b⊥/|b|², ∂θ/∂X_{i−1} = a⊥/|a|², ∂θ/∂X_i = −(both), v⊥ = (−v_y, v_x).
  // Forces alone: the vertex and node passes; with the energy, the one loop (the same forces).
  if (model.bending != 0.0) {
    if (kForces && !kEnergy && n >= 3) {
      add_bending_by_passes(model, rest, x.data(), y.data(), n, edge_scratch(n), fx, fy);
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t im = (i == 0) ? n - 1 : i - 1, ip = (i + 1 == n) ? 0 : i + 1;
        double gax, gay, gbx, gby;
        const double e = bend_vertex(model.bending, rest.turning[i], rest.dual[i], x[i] - x[im], y[i] - y[im],
                                     x[ip] - x[i], y[ip] - y[i], gax, gay, gbx, gby);
        if constexpr (kEnergy) E.bending += e;
        if constexpr (kForces) {
          fx[im] += gax;
          fy[im] += gay;
          fx[ip] += gbx;
          fy[ip] += gby;
          fx[i] -= gax + gbx;
          fy[i] -= gay + gby;
        }
      }
    }
  }
  // Area: A = ½ Σ (x_i y_{i+1} − x_{i+1} y_i) (relative to marker 0 against cancellation),
  // ∂A/∂x_i = ½(y_{i+1} − y_{i−1}), ∂A/∂y_i = ½(x_{i−1} − x_{i+1}).
  if (model.area_modulus != 0.0) {
    const double ox = x[0], oy = y[0];
    double A2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1 == n) ? 0 : i + 1;
      A2 += (x[i] - ox) * (y[j] - oy) - (x[j] - ox) * (y[i] - oy);
    }
    const double dA = 0.5 * A2 - rest.area;
    if constexpr (kEnergy) E.area = 0.5 * model.area_modulus * dA * dA / rest.area;
    if constexpr (kForces) {
      const double p = model.area_modulus * dA / rest.area;  // pressure-like −∂E/∂A
      auto area_pull = [&](std::size_t i, std::size_t im, std::size_t ip) {
        fx[i] -= 0.5 * p * (y[ip] - y[im]);
        fy[i] -= 0.5 * p * (x[im] - x[ip]);
      };
      // The two closing markers apart, so that the loop between them reads its neighbours
      // without wrapped indices and vectorises (each marker's own arithmetic: the same bits).
      area_pull(0, n - 1, n > 1 ? 1 : 0);
      for (std::size_t i = 1; i + 1 < n; ++i) area_pull(i, i - 1, i + 1);
      if (n > 1) area_pull(n - 1, n - 2, 0);
    }
  }
  return E;
}

}  // namespace

Energy membrane_energy(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                       std::span<const double> y) {
  check_sizes(rest, x.size(), y.size());
  return evaluate<false>(model, rest, x, y, nullptr, nullptr);
}

Energy add_membrane_forces(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                           std::span<const double> y, std::span<double> fx, std::span<double> fy) {
  check_sizes(rest, x.size(), y.size());
  check_sizes(rest, fx.size(), fy.size());
  return evaluate<true>(model, rest, x, y, fx.data(), fy.data());
}

void add_membrane_forces_only(const MembraneModel& model, const RestShape& rest, std::span<const double> x,
                              std::span<const double> y, std::span<double> fx, std::span<double> fy) {
  check_sizes(rest, x.size(), y.size());
  check_sizes(rest, fx.size(), fy.size());
  evaluate<true, false>(model, rest, x, y, fx.data(), fy.data());
}

}  // namespace erythro::membrane
