#include "membrane/membrane_energy.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/portable_hypot.hpp"

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
    const double ax = std::fabs(dx), ay = std::fabs(dy);
    const double a = ax < ay ? ay : ax, b = ax < ay ? ax : ay;
    outside |= numeric::hypot_fast_range(a, b) ? 0 : 1;
    pull(e, dx, dy, numeric::hypot_fast(a, b));
  }
  if (outside != 0)
    for (std::size_t e = 0; e + 1 < n; ++e) {
      const double dx = x[e + 1] - x[e], dy = y[e + 1] - y[e];
      pull(e, dx, dy, numeric::hypot_portable(dx, dy));
    }
  const double dx = x[0] - x[n - 1], dy = y[0] - y[n - 1];  // the closing edge
  pull(n - 1, dx, dy, numeric::hypot_portable(dx, dy));
}

// Scratch of the edge pass, one per thread (cells run on the threads), grown to the largest cell.
struct EdgeScratch {
  std::vector<double> px, py;
};
EdgeScratch& edge_scratch(std::size_t n) {
  thread_local EdgeScratch s;
  if (s.px.size() < n) {
    s.px.resize(n);
    s.py.resize(n);
  }
  return s;
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
  if (model.bending != 0.0) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t im = (i == 0) ? n - 1 : i - 1, ip = (i + 1 == n) ? 0 : i + 1;
      const double ax = x[i] - x[im], ay = y[i] - y[im], bx = x[ip] - x[i], by = y[ip] - y[i];
      double dtheta = turning_angle(ax, ay, bx, by) - rest.turning[i];
      // Keep the difference in (−π, π] (a rest angle near ±π must not jump by 2π).
      if (dtheta > std::numbers::pi) dtheta -= 2.0 * std::numbers::pi;
      if (dtheta <= -std::numbers::pi) dtheta += 2.0 * std::numbers::pi;
      if constexpr (kEnergy) E.bending += 0.5 * model.bending * dtheta * dtheta / rest.dual[i];
      if constexpr (kForces) {
        const double g = model.bending * dtheta / rest.dual[i];  // ∂E/∂θ_i
        const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
        const double gax = -g * (-ay) / a2, gay = -g * ax / a2;  // −g ∂θ/∂X_{i−1}
        const double gbx = -g * (-by) / b2, gby = -g * bx / b2;  // −g ∂θ/∂X_{i+1}
        fx[im] += gax;
        fy[im] += gay;
        fx[ip] += gbx;
        fy[ip] += gby;
        fx[i] -= gax + gbx;
        fy[i] -= gay + gby;
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
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t im = (i == 0) ? n - 1 : i - 1, ip = (i + 1 == n) ? 0 : i + 1;
        fx[i] -= 0.5 * p * (y[ip] - y[im]);
        fy[i] -= 0.5 * p * (x[im] - x[ip]);
      }
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
