#pragma once
// What acts between the membranes of different cells: Morse aggregation (morse.hpp,
// docs/model.md §4), short-range repulsion (repulsion.hpp, §4b), or both. Their pair
// densities add up into one potential, so one neighbour search serves both (cell_contacts.hpp).
#include <algorithm>
#include <cstddef>
#include <optional>
#include <stdexcept>

#include "aggregation/morse.hpp"
#include "aggregation/repulsion.hpp"

namespace erythro::aggregation {

struct ContactLaw {
  std::optional<MorseParameters> morse;
  std::optional<RepulsionParameters> repulsion;
};

// Φ_s (eq 4.2) + Φ_r (eq 4.11), each only where it is switched on. With Morse alone the
// result is ShiftedMorse's, bit for bit (nothing is added to it).
class ContactPotential {
 public:
  // Throws std::invalid_argument on bad parameters or when neither part is on.
  explicit ContactPotential(const ContactLaw& law);

  // Both at once; returns false (and zeros) beyond the cut-off of every part.
  bool evaluate(double r, double& phi, double& dphi) const {
    if (morse_ && repulsion_) return evaluate_of<true, true>(r, phi, dphi);
    if (morse_) return evaluate_of<true, false>(r, phi, dphi);
    return evaluate_of<false, true>(r, phi, dphi);
  }
  // The same for k separations r[0 … k−1] (each > 0): phi[i], dphi[i] and on[i] = whether
  // pair i interacts, bit for bit what evaluate(r[i]) gives, in straight loops the
  // compiler vectorises (the exponential is numeric::exp_portable, morse.hpp).
  void evaluate_many(const double* r, std::size_t k, double* phi, double* dphi, unsigned char* on) const {
    if (morse_ && repulsion_) evaluate_many_of<true, true>(r, k, phi, dphi, on);
    else if (morse_) evaluate_many_of<true, false>(r, k, phi, dphi, on);
    else evaluate_many_of<false, true>(r, k, phi, dphi, on);
  }
  // The largest distance at which a pair interacts (max of r_c and d).
  double cutoff() const { return cutoff_; }
  const ContactLaw& law() const { return law_; }
  // The repulsion's parameters when it acts on walls too, else nullptr.
  const RepulsionParameters* wall_repulsion() const {
    return law_.repulsion && law_.repulsion->walls ? &*law_.repulsion : nullptr;
  }

 private:
  // The parts that are on, added: with Morse alone its value unchanged (nothing is added
  // to it), a part beyond its cut-off adds nothing. Branch-free, for evaluate_many.
  template <bool kMorse, bool kRepulsion>
  bool evaluate_of(double r, double& phi, double& dphi) const {
    double pm = 0.0, dpm = 0.0, pr = 0.0, dpr = 0.0;
    bool m_on = false, r_on = false;
    if constexpr (kMorse) m_on = morse_->evaluate(r, pm, dpm);
    if constexpr (kRepulsion) r_on = repulsion_->evaluate(r, pr, dpr);
    phi = r_on ? (m_on ? pm + pr : pr) : pm;
    dphi = r_on ? (m_on ? dpm + dpr : dpr) : dpm;
    return m_on || r_on;
  }
  template <bool kMorse, bool kRepulsion>
  void evaluate_many_of(const double* __restrict r, std::size_t k, double* __restrict phi, double* __restrict dphi,
                        unsigned char* __restrict on) const;

  ContactLaw law_;
  std::optional<ShiftedMorse> morse_;
  std::optional<Repulsion> repulsion_;
  double cutoff_ = 0.0;
};

inline ContactPotential::ContactPotential(const ContactLaw& law) : law_(law) {
  if (!law.morse && !law.repulsion) throw std::invalid_argument("cell contacts: neither Morse nor repulsion is on");
  if (law.morse) {
    morse_.emplace(*law.morse);
    cutoff_ = law.morse->cutoff;
  }
  if (law.repulsion) {
    repulsion_.emplace(*law.repulsion);
    cutoff_ = std::max(cutoff_, law.repulsion->range);
  }
}

// Each lane evaluate_of: the same operations as a single call.
template <bool kMorse, bool kRepulsion>
void ContactPotential::evaluate_many_of(const double* __restrict r, std::size_t k, double* __restrict phi,
                                        double* __restrict dphi, unsigned char* __restrict on) const {
#pragma omp simd
  for (std::size_t i = 0; i < k; ++i) on[i] = evaluate_of<kMorse, kRepulsion>(r[i], phi[i], dphi[i]) ? 1 : 0;
}

}  // namespace erythro::aggregation
