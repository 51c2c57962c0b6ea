#pragma once
// The Morse potential of RBC aggregation (docs/model.md §4 eq 4.1, thesis eq 13; Liu et al.):
//
//   Φ(r) = D_e [e^{2β(r0−r)} − 2 e^{β(r0−r)}],   Φ'(r) = 2βD_e [e^{β(r0−r)} − e^{2β(r0−r)}]
//
// minimum Φ(r0) = −D_e, repulsive for r < r0, attractive beyond. It is cut off at
// r_c > r0 with a FORCE-SHIFTED form, so that energy AND force are continuous there:
//
//   Φ_s(r) = Φ(r) − Φ(r_c) − (r − r_c) Φ'(r_c)   for r < r_c,   0 beyond.
//
// Without the shift the force would jump by Φ'(r_c) = 2βD_e(e^{−βδ} − e^{−2βδ}),
// δ = r_c − r0 (a 2·e^{−βδ} fraction of the peak attraction βD_e/2), and the discrete
// energy would not be differentiable, so −∇E could not be checked by finite
// differences. The shift moves the minimum slightly (use the shifted form for
// predictions: solver/aggregation/morse_units.hpp does).
//
// e^x is numeric::exp_portable (common/portable_exp.hpp): the pair loop evaluates it in
// vector lanes with the bits of a scalar call.
//
// Units: lattice (h = Δt = ρ0 = 1). In the 2D pair model (cell_contacts.hpp) the
// pair energy of markers m, n is Φ_s(r_mn) ℓ_m ℓ_n, so D_e is an energy per unit depth
// per length², i.e. a PRESSURE (lattice ρ0 h²/Δt²); r0, r_c are lengths (h), β an
// inverse length (1/h). See morse_units.hpp for the physical parameters.
#include <cmath>

#include "common/portable_exp.hpp"

namespace erythro::aggregation {

struct MorseParameters {
  double De = 0.0;      // well depth of the pair density (lattice pressure)
  double r0 = 0.0;      // zero-force separation (h)
  double beta = 0.0;    // decay (1/h)
  double cutoff = 0.0;  // r_c > r0 (h)
};

// Throws std::invalid_argument unless De ≥ 0, r0 > 0, β > 0, r_c > r0 (all finite).
void check(const MorseParameters& p);

// The bare potential and its derivative dΦ/dr (no cut-off).
double morse_energy(const MorseParameters& p, double r);
double morse_derivative(const MorseParameters& p, double r);

// The force-shifted, cut-off potential Φ_s and dΦ_s/dr (zero for r ≥ r_c).
struct ShiftedMorse {
  explicit ShiftedMorse(const MorseParameters& p);
  double energy(double r) const;
  double derivative(double r) const;
  // Both at once (one pair of exponentials); returns false (and zeros) beyond r_c.
  bool evaluate(double r, double& phi, double& dphi) const {
    if (!(r < p_.cutoff)) {
      phi = dphi = 0.0;
      return false;
    }
    const double e1 = numeric::exp_portable(p_.beta * (p_.r0 - r));
    const double e2 = e1 * e1;
    phi = p_.De * (e2 - 2.0 * e1) - phi_c_ - (r - p_.cutoff) * dphi_c_;
    dphi = 2.0 * p_.beta * p_.De * (e1 - e2) - dphi_c_;
    return true;
  }
  const MorseParameters& parameters() const { return p_; }
  double phi_c() const { return phi_c_; }
  double dphi_c() const { return dphi_c_; }

 private:
  MorseParameters p_;
  double phi_c_ = 0.0, dphi_c_ = 0.0;  // Φ(r_c), Φ'(r_c)
};

}  // namespace erythro::aggregation
