#include "prediction.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace erythro::vv {

double circle_pair_force(const aggregation::MorseParameters& p, double R1, double R2, double D, int points) {
  const aggregation::ShiftedMorse m(p);
  const double ds1 = 2.0 * std::numbers::pi * R1 / points, ds2 = 2.0 * std::numbers::pi * R2 / points;
  // Circle 1 at the origin, circle 2 at (D, 0). Only the facing arcs can be within r_c.
  std::vector<double> x2, y2;
  for (int j = 0; j < points; ++j) {
    const double t = 2.0 * std::numbers::pi * j / points;
    const double x = D + R2 * std::cos(t), y = R2 * std::sin(t);
    if (x - R1 < p.cutoff) {
      x2.push_back(x);
      y2.push_back(y);
    }
  }
  double f = 0.0;  // −dE/dD = −Σ Φ_s'(ρ) ∂ρ/∂D, ∂ρ/∂D = (x2 − x1)/ρ
  for (int i = 0; i < points; ++i) {
    const double t = 2.0 * std::numbers::pi * i / points;
    const double x1 = R1 * std::cos(t), y1 = R1 * std::sin(t);
    if (D - R2 - x1 > p.cutoff) continue;
    for (std::size_t j = 0; j < x2.size(); ++j) {
      const double dx = x2[j] - x1, dy = y2[j] - y1;
      const double r = std::sqrt(dx * dx + dy * dy);
      if (r < p.cutoff) f -= m.derivative(r) * dx / r;
    }
  }
  return f * ds1 * ds2;
}

double circle_pair_gap(const aggregation::MorseParameters& p, double R1, double R2, int points) {
  // Repulsive (f > 0) at small gaps, attractive (f < 0) further out: the first sign change.
  double lo = 0.1 * p.r0, hi = lo;
  if (!(circle_pair_force(p, R1, R2, R1 + R2 + lo, points) > 0.0)) throw std::runtime_error("no repulsion at r0/10");
  bool found = false;
  for (double d = lo + 0.05; d < p.cutoff; d += 0.05) {
    if (circle_pair_force(p, R1, R2, R1 + R2 + d, points) < 0.0) {
      hi = d;
      found = true;
      break;
    }
    lo = d;
  }
  if (!found) throw std::runtime_error("no equilibrium gap below the cut-off");
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (circle_pair_force(p, R1, R2, R1 + R2 + mid, points) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace erythro::vv
