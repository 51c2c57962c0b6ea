#include "membrane/membrane_units.hpp"

#include <stdexcept>

namespace erythro::membrane {

namespace {
void check(const LatticeScales& s) {
  if (!(s.h_m > 0.0) || !(s.dt_s > 0.0) || !(s.rho_kg_m3 > 0.0)) {
    throw std::invalid_argument("membrane units: h, dt and rho must be positive");
  }
}
}  // namespace

double tension_to_lattice(double v, const LatticeScales& s) {
  check(s);
  return v * s.dt_s * s.dt_s / (s.rho_kg_m3 * s.h_m * s.h_m * s.h_m);
}

double bending_to_lattice(double v, const LatticeScales& s) {
  check(s);
  const double h2 = s.h_m * s.h_m;
  return v * s.dt_s * s.dt_s / (s.rho_kg_m3 * h2 * h2 * s.h_m);
}

double pressure_to_lattice(double v, const LatticeScales& s) {
  check(s);
  return v * s.dt_s * s.dt_s / (s.rho_kg_m3 * s.h_m * s.h_m);
}

}  // namespace erythro::membrane
