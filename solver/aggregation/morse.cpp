#include "aggregation/morse.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace erythro::aggregation {

void check(const MorseParameters& p) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("Morse parameters: " + what); };
  if (!std::isfinite(p.De) || p.De < 0.0) fail("D_e must be finite and >= 0, got " + std::to_string(p.De));
  if (!std::isfinite(p.r0) || !(p.r0 > 0.0)) fail("r0 must be finite and > 0, got " + std::to_string(p.r0));
  if (!std::isfinite(p.beta) || !(p.beta > 0.0)) fail("beta must be finite and > 0, got " + std::to_string(p.beta));
  if (!std::isfinite(p.cutoff) || !(p.cutoff > p.r0)) {
    fail("the cut-off must be finite and > r0 = " + std::to_string(p.r0) + ", got " + std::to_string(p.cutoff));
  }
}

double morse_energy(const MorseParameters& p, double r) {
  const double e1 = numeric::exp_portable(p.beta * (p.r0 - r));
  return p.De * (e1 * e1 - 2.0 * e1);
}

double morse_derivative(const MorseParameters& p, double r) {
  const double e1 = numeric::exp_portable(p.beta * (p.r0 - r));
  return 2.0 * p.beta * p.De * (e1 - e1 * e1);
}

ShiftedMorse::ShiftedMorse(const MorseParameters& p) : p_(p) {
  check(p);
  phi_c_ = morse_energy(p, p.cutoff);
  dphi_c_ = morse_derivative(p, p.cutoff);
}

double ShiftedMorse::energy(double r) const {
  double phi = 0.0, dphi = 0.0;
  evaluate(r, phi, dphi);
  return phi;
}

double ShiftedMorse::derivative(double r) const {
  double phi = 0.0, dphi = 0.0;
  evaluate(r, phi, dphi);
  return dphi;
}

}  // namespace erythro::aggregation
