#include "aggregation/morse_units.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace erythro::aggregation {

MorseParameters to_lattice(const MorsePhysical& p, const membrane::LatticeScales& s) {
  auto positive = [](double v, const char* what) {
    if (!std::isfinite(v) || !(v > 0.0)) throw std::invalid_argument(std::string("Morse units: ") + what + " must be > 0, got " + std::to_string(v));
  };
  positive(s.h_m, "the lattice spacing h");
  positive(s.dt_s, "the time step");
  positive(s.rho_kg_m3, "the fluid density");
  if (!std::isfinite(p.De_Pa) || p.De_Pa < 0.0) throw std::invalid_argument("Morse units: D_e must be >= 0, got " + std::to_string(p.De_Pa));
  positive(p.r0_m, "r0");
  positive(p.beta_per_m, "beta");
  positive(p.cutoff_m, "the cut-off");
  if (!(p.cutoff_m > p.r0_m)) {
    throw std::invalid_argument("Morse units: the cut-off (" + std::to_string(p.cutoff_m) + " m) must exceed r0 (" +
                                std::to_string(p.r0_m) + " m)");
  }
  MorseParameters q;
  q.De = membrane::pressure_to_lattice(p.De_Pa, s);  // energy/depth/length² = pressure
  q.r0 = p.r0_m / s.h_m;
  q.beta = p.beta_per_m * s.h_m;
  q.cutoff = p.cutoff_m / s.h_m;
  check(q);
  return q;
}

namespace {

// 2∫_0^U g(u) du by composite Simpson, U = √(r_c² − d²); g is smooth on [0, U].
template <class G>
double half_line(double d, double rc, G g) {
  if (!(d < rc)) return 0.0;
  const double U = std::sqrt(rc * rc - d * d);
  const int n = 4096;  // even
  const double du = U / n;
  double s = g(0.0) + g(U);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * g(i * du);
  return 2.0 * s * du / 3.0;
}

MorseParameters unit_depth(const MorseParameters& p) {
  MorseParameters q = p;
  q.De = 1.0;  // J is per unit D_e
  return q;
}

}  // namespace

double flat_contact_integral(const MorseParameters& p, double d) {
  const ShiftedMorse m(unit_depth(p));
  return half_line(d, p.cutoff, [&](double u) { return m.energy(std::sqrt(d * d + u * u)); });
}

double flat_contact_integral_derivative(const MorseParameters& p, double d) {
  // d/dd ∫φ_s(ρ) du = ∫φ_s'(ρ) d/ρ du (the end-point terms vanish: φ_s(r_c) = 0).
  const ShiftedMorse m(unit_depth(p));
  return half_line(d, p.cutoff, [&](double u) {
    const double rho = std::sqrt(d * d + u * u);
    return m.derivative(rho) * d / rho;
  });
}

FlatContact flat_contact(const MorseParameters& p) {
  check(p);
  const double rc = p.cutoff;
  const int samples = 400;
  double lo = 0.0, hi = 0.0;
  bool found = false;
  double prev_d = rc / samples, prev = flat_contact_integral_derivative(p, prev_d);
  for (int i = 2; i < samples && !found; ++i) {
    const double d = rc * i / samples, v = flat_contact_integral_derivative(p, d);
    if (prev < 0.0 && v >= 0.0) {
      lo = prev_d;
      hi = d;
      found = true;
    }
    prev_d = d;
    prev = v;
  }
  if (!found) throw std::invalid_argument("Morse: no flat-contact equilibrium below the cut-off");
  for (int it = 0; it < 200 && hi - lo > 1e-13 * rc; ++it) {
    const double mid = 0.5 * (lo + hi);
    (flat_contact_integral_derivative(p, mid) < 0.0 ? lo : hi) = mid;
  }
  FlatContact fc;
  fc.gap = 0.5 * (lo + hi);
  fc.integral = flat_contact_integral(p, fc.gap);
  return fc;
}

double pair_density_for(double gamma, const MorseParameters& shape) {
  if (!std::isfinite(gamma) || gamma < 0.0) throw std::invalid_argument("Morse: the surface energy must be >= 0");
  const FlatContact fc = flat_contact(shape);
  return gamma / std::abs(fc.integral);
}

double surface_energy_for_de_star(double de_star) {
  if (!std::isfinite(de_star) || de_star < 0.0) throw std::invalid_argument("Morse: De* must be >= 0");
  return de_star * kDeStarUnit_J_m2;  // docs/model.md eq 4.7
}

double de_star_for_surface_energy(double gamma_J_m2) { return gamma_J_m2 / kDeStarUnit_J_m2; }

double peak_adhesion_stress(double gamma, double beta) { return 0.5 * gamma * beta; }  // docs/model.md eq 4.8

}  // namespace erythro::aggregation
