#include "transport/compartments.hpp"

#include <algorithm>
#include <stdexcept>

#include "transport/reactions.hpp"

namespace erythro::transport {

NoO2Model NoO2Model::arteriole_defaults() {
  NoO2Model m;
  m[Compartment::rbc].no_decay = no_scavenging_rate();  // 1.4e5 M⁻¹s⁻¹ × 20.3 mM
  m[Compartment::endothelium].no_R_max = no_r_max_from_shear(2.4);
  m[Compartment::smooth_muscle].no_decay = 1.0;
  m[Compartment::smooth_muscle].o2_Q_max = 5.0;
  m[Compartment::tissue].no_decay = 1.0;
  m[Compartment::tissue].o2_Q_max = 50.0;
  return m;
}

namespace {
void check_sizes(std::span<const std::uint8_t> ids, const TransportLattice& no, const TransportLattice& o2) {
  if (ids.size() != no.grid().size() || ids.size() != o2.grid().size()) {
    throw std::invalid_argument("compartments: id field size does not match the lattices");
  }
}
const CompartmentProperties& props(const NoO2Model& m, std::uint8_t id) {
  if (id >= kCompartmentCount) throw std::invalid_argument("compartments: unknown compartment id");
  return m.compartments[id];
}
}  // namespace

void apply_diffusivities(const NoO2Model& model, std::span<const std::uint8_t> ids, const TransportUnits& units,
                         TransportLattice& no, TransportLattice& o2) {
  check_sizes(ids, no, o2);
  auto Dno = no.diffusivity();
  auto Do2 = o2.diffusivity();
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const auto& p = props(model, ids[n]);
    Dno[n] = units.diffusivity(p.D_NO);
    Do2[n] = units.diffusivity(p.D_O2);
  }
}

void update_reactions(const NoO2Model& model, std::span<const std::uint8_t> ids, const TransportUnits& units,
                      TransportLattice& no, TransportLattice& o2) {
  check_sizes(ids, no, o2);
  const auto Cno = no.concentration();
  const auto Co2 = o2.concentration();
  auto qno = no.source();
  auto kno = no.decay_rate();
  auto qo2 = o2.source();
  auto ko2 = o2.decay_rate();
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const auto& p = props(model, ids[n]);
    const double P = Co2[n] / model.alpha;
    // R1 as a rate per unit O2 concentration: R_max / (α (P + K_m)); also the EC O2 sink.
    const double eNOS_per_C = p.no_R_max > 0.0 ? p.no_R_max / (model.alpha * (std::max(P, 0.0) + p.Km_eNOS)) : 0.0;
    // R5 likewise: Q_max / (α (P + K_m (1 + C_NO/C_ref))).
    const double mm_per_C =
        p.o2_Q_max > 0.0
            ? p.o2_Q_max / (model.alpha * (std::max(P, 0.0) + p.Km_O2 * (1.0 + std::max(Cno[n], 0.0) / p.C_ref_NO)))
            : 0.0;
    qno[n] = units.source(eNOS_per_C * std::max(Co2[n], 0.0));  // = R1(P) dt
    kno[n] = units.rate(p.no_decay);
    qo2[n] = units.source(p.o2_exchange * model.alpha * p.o2_held_torr);  // the core's exchange (eq 7.11)
    ko2[n] = units.rate(eNOS_per_C + mm_per_C + p.o2_exchange);
  }
}

}  // namespace erythro::transport
