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
#include "common/select_bits.hpp"

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
    bool any = false;
    phi = dphi = 0.0;
    if (morse_) any = morse_->evaluate(r, phi, dphi);
    if (repulsion_) {
      double pr = 0.0, dpr = 0.0;
      if (repulsion_->evaluate(r, pr, dpr)) {
        phi = any ? phi + pr : pr;
        dphi = any ? dphi + dpr : dpr;
        any = true;
      }
    }
    return any;
  }
  // The same for k separations r[0 … k−1] (each > 0): phi[i], dphi[i] and on[i] = whether
  // pair i interacts, bit for bit what evaluate(r[i]) gives, in straight loops the
  // compiler vectorises (the exponential is numeric::exp_portable, morse.hpp).
  // With both parts the repulsion, whose range is a small part of the Morse cut-off, is added
  // in a second pass over the pairs within its range only (its two divisions in every lane
  // were the loop's largest cost).
  void evaluate_many(const double* r, std::size_t k, double* phi, double* dphi, unsigned char* on) const {
    if (morse_ && repulsion_ && repulsion_->parameters().range < morse_->parameters().cutoff) {
      evaluate_many_of<true, false>(r, k, phi, dphi, on);
      add_repulsion_within_range(r, k, phi, dphi, on);
    } else if (morse_ && repulsion_) {
      evaluate_many_of<true, true>(r, k, phi, dphi, on);
    } else if (morse_) {
      evaluate_many_of<true, false>(r, k, phi, dphi, on);
    } else {
      evaluate_many_of<false, true>(r, k, phi, dphi, on);
    }
  }
  // The largest distance at which a pair interacts (max of r_c and d).
  double cutoff() const { return cutoff_; }
  const ContactLaw& law() const { return law_; }
  // The repulsion's parameters when it acts on walls too, else nullptr.
  const RepulsionParameters* wall_repulsion() const {
    return law_.repulsion && law_.repulsion->walls ? &*law_.repulsion : nullptr;
  }

 private:
  template <bool kMorse, bool kRepulsion>
  void evaluate_many_of(const double* __restrict r, std::size_t k, double* __restrict phi, double* __restrict dphi,
                        unsigned char* __restrict on) const;
  void add_repulsion_within_range(const double* __restrict r, std::size_t k, double* __restrict phi,
                                  double* __restrict dphi, unsigned char* __restrict on) const;

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

// Each lane: the parts' formulas of ShiftedMorse::evaluate and Repulsion::evaluate with the
// same operations, combined as evaluate() combines them (a part beyond its cut-off adds
// nothing; the Morse part alone is its value unchanged). Written out rather than calling
// the parts: calling them (made branch-free) kept GCC 12 from vectorising the loop and cost
// 30 % of the contact stage; unit test ContactPotential.EvaluateManyGivesTheBitsOfEvaluate
// holds the two to the same bits. The choices go through numeric::select_bits, so that the loop
// vectorises on AVX2 processors too (common/select_bits.hpp).
template <bool kMorse, bool kRepulsion>
void ContactPotential::evaluate_many_of(const double* __restrict r, std::size_t k, double* __restrict phi,
                                        double* __restrict dphi, unsigned char* __restrict on) const {
  MorseParameters m{};
  double phi_c = 0.0, dphi_c = 0.0;
  if constexpr (kMorse) {
    m = morse_->parameters();
    phi_c = morse_->phi_c();
    dphi_c = morse_->dphi_c();
  }
  double range = 0.0, pressure = 0.0;
  if constexpr (kRepulsion) {
    range = repulsion_->parameters().range;
    pressure = repulsion_->parameters().pressure;
  }
#pragma omp simd
  for (std::size_t i = 0; i < k; ++i) {
    const double ri = r[i];
    double pm = 0.0, dpm = 0.0, pr = 0.0, dpr = 0.0;
    bool m_on = false, r_on = false;
    if constexpr (kMorse) {
      const double e1 = numeric::exp_portable(m.beta * (m.r0 - ri));
      const double e2 = e1 * e1;
      m_on = ri < m.cutoff;
      pm = numeric::select_bits(m_on, m.De * (e2 - 2.0 * e1) - phi_c - (ri - m.cutoff) * dphi_c, 0.0);
      dpm = numeric::select_bits(m_on, 2.0 * m.beta * m.De * (e1 - e2) - dphi_c, 0.0);
    }
    if constexpr (kRepulsion) {
      const double q = range / ri - 1.0;
      r_on = ri < range;
      pr = pressure * q * q;
      dpr = -2.0 * pressure * q * range / (ri * ri);
    }
    phi[i] = numeric::select_bits(r_on, numeric::select_bits(m_on, pm + pr, pr), pm);
    dphi[i] = numeric::select_bits(r_on, numeric::select_bits(m_on, dpm + dpr, dpr), dpm);
    on[i] = static_cast<unsigned char>(m_on | r_on);
  }
}

// After the Morse part alone: the repulsion (Repulsion::evaluate) for the pairs with r < d,
// found block by block and evaluated one by one, combined as evaluate() combines them (Φ_s + Φ_r
// where the Morse part is on, Φ_r alone where it is not).
inline void ContactPotential::add_repulsion_within_range(const double* __restrict r, std::size_t k,
                                                         double* __restrict phi, double* __restrict dphi,
                                                         unsigned char* __restrict on) const {
  const double range = repulsion_->parameters().range;
  constexpr std::size_t kBlock = 32;
  std::size_t near[kBlock];
  for (std::size_t b = 0; b < k; b += kBlock) {
    const std::size_t e = std::min(k, b + kBlock);
    int any = 0;  // most blocks hold no pair within d: a vector test skips them
#pragma omp simd reduction(| : any)
    for (std::size_t i = b; i < e; ++i) any |= r[i] < range ? 1 : 0;
    if (any == 0) continue;
    std::size_t n = 0;
    for (std::size_t i = b; i < e; ++i) {  // branch-free
      near[n] = i;
      n += r[i] < range ? 1 : 0;
    }
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = near[j];
      double pr = 0.0, dpr = 0.0;
      repulsion_->evaluate(r[i], pr, dpr);  // r[i] < d: on
      phi[i] = on[i] ? phi[i] + pr : pr;
      dphi[i] = on[i] ? dphi[i] + dpr : dpr;
      on[i] = 1;
    }
  }
}

}  // namespace erythro::aggregation
