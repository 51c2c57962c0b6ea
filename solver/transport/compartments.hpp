#pragma once
// Compartments of the NO/O2 model (docs/transport.md §4.3): a per-node compartment id
// selects the diffusivities and the reaction set of the node.
//   plasma        : diffusion only
//   rbc           : NO scavenging by Hb (first order); O2 release by Hb per cell
//                   (hb_kinetics.hpp, added by the caller after update_reactions)
//   endothelium   : NO production R1, O2 use 1:1 with it
//   smooth_muscle : NO first-order consumption R2, O2 consumption R5
//   tissue        : as smooth muscle with its own constants
//   core          : the RBC core as one homogeneous phase (docs/model.md §7c): first-order NO
//                   scavenging at the core rate (R4) and O2 held near a PO2 by an exchange
//                   k_ex (C − α P_held), implicit
#include <array>
#include <cstdint>
#include <span>

#include "transport/transport_lattice.hpp"
#include "transport/transport_units.hpp"

namespace erythro::transport {

enum class Compartment : std::uint8_t {
  plasma = 0,
  rbc = 1,
  endothelium = 2,
  smooth_muscle = 3,
  tissue = 4,
  core = 5
};
inline constexpr int kCompartmentCount = 6;

struct CompartmentProperties {
  double D_NO = 3300.0;  // µm²/s
  double D_O2 = 2800.0;  // µm²/s
  double no_decay = 0.0;    // first-order NO sink, 1/s (R2, R3)
  double no_R_max = 0.0;    // eNOS maximum production, µM/s (R1; EC only)
  double Km_eNOS = 4.7;     // Torr
  double o2_Q_max = 0.0;    // Michaelis–Menten O2 consumption, µM/s (R5)
  double Km_O2 = 1.0;       // Torr
  double C_ref_NO = 27e-3;  // µM (27 nM)
  double o2_exchange = 0.0;  // k_ex of the core's O2 exchange, 1/s (eq 7.11)
  double o2_held_torr = 0.0; // the PO2 the exchange holds, Torr
};

struct NoO2Model {
  std::array<CompartmentProperties, kCompartmentCount> compartments{};
  double alpha = 1.3;  // O2 solubility, µM/Torr

  CompartmentProperties& operator[](Compartment c) { return compartments[static_cast<std::size_t>(c)]; }
  const CompartmentProperties& operator[](Compartment c) const { return compartments[static_cast<std::size_t>(c)]; }

  // docs/parameters.md (Kim-laboratory arteriole set): RBC scavenging 1.4e5 M⁻¹s⁻¹ × 20.3 mM,
  // EC R_max at τ_w = 2.4 Pa (50 µM/s), SM Q_max 5 µM/s, tissue Q_max 50 µM/s, NO
  // consumption 1 s⁻¹ in SM and tissue.
  static NoO2Model arteriole_defaults();
};

// Sets the per-node diffusivity fields of both lattices from the compartment ids.
void apply_diffusivities(const NoO2Model& model, std::span<const std::uint8_t> ids, const TransportUnits& units,
                         TransportLattice& no, TransportLattice& o2);

// Rewrites source() and decay_rate() of both lattices from their current
// concentrations (µM) and the compartment ids (lattice units through `units`):
//   NO : q = R1(P) in the EC;  k = no_decay (RBC, SM, tissue)          — implicit sink
//   O2 : k = [R1 + R5](P, C_NO) / C_O2, i.e. each O2 sink written as a first-order
//        rate at the current P, applied implicitly to the new C: the O2 concentration
//        cannot turn negative. (The 1:1 EC coupling is then exact at steady state and
//        to O(Δt) in transients.) The core's exchange adds q = k_ex α P_held, k += k_ex.
// Hb release into RBC nodes is added afterwards (distribute_release) by the caller.
void update_reactions(const NoO2Model& model, std::span<const std::uint8_t> ids, const TransportUnits& units,
                      TransportLattice& no, TransportLattice& o2);

}  // namespace erythro::transport
