#pragma once
// What acts between the membranes of different cells: Morse aggregation (morse.hpp,
// docs/model.md §4), short-range repulsion (repulsion.hpp, §4b), or both. Their pair
// densities add up into one potential, so one neighbour search serves both (cell_contacts.hpp).
#include <algorithm>
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
  // The largest distance at which a pair interacts (max of r_c and d).
  double cutoff() const { return cutoff_; }
  const ContactLaw& law() const { return law_; }
  // The repulsion's parameters when it acts on walls too, else nullptr.
  const RepulsionParameters* wall_repulsion() const {
    return law_.repulsion && law_.repulsion->walls ? &*law_.repulsion : nullptr;
  }

 private:
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

}  // namespace erythro::aggregation
