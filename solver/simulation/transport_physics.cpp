#include "simulation/transport_physics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/error.hpp"
#include "simulation/transport_layers.hpp"
#include "transport/compartments.hpp"
#include "transport/hb_kinetics.hpp"
#include "transport/subpixel_diffusivity.hpp"

namespace erythro::sim {
namespace {

// The default lower limit of a species' concentration (no monitor.concentration_range_uM):
// a concentration is never negative; the scheme's undershoot near a steep front stays far
// within 1 % of the concentration scale (the start's largest |C|, the held side values,
// at least 1 µM), while a sink or outward flux that draws more than there is, or a
// growing oscillation, crosses it.
double concentration_floor(const transport::TransportBoundaries& sides, std::span<const double> C) {
  double scale = 1.0;
  for (const double c : C) scale = std::max(scale, std::abs(c));
  for (const transport::Side& side : {sides.left, sides.right, sides.bottom, sides.top})
    if (side.kind == transport::SideKind::fixed_concentration) scale = std::max(scale, std::abs(side.value));
  return -0.01 * scale;
}

}  // namespace

TransportPhysics::TransportPhysics(const scene::TransportSetup& setup, const geometry::Domain& domain,
                                   std::span<const geometry::Polygon> cells)
    : setup_(setup), domain_(domain) {
  if (setup_.hemoglobin) coupling_ = hb_coupling_from(setup_.hb_coupling);
  const std::size_t S = setup_.species.size();
  lattices_.reserve(S);
  base_D_.resize(S);
  base_source_.resize(S);
  corrections_.resize(S);
  for (std::size_t i = 0; i < S; ++i) {
    const scene::SpeciesSetup& sp = setup_.species[i];
    lattices_.emplace_back(domain_.grid, setup_.stencil, sp.boundaries);
    if (setup_.axisymmetric_inner_radius) lattices_.back().set_axisymmetric(*setup_.axisymmetric_inner_radius);
    lattices_.back().set_collision(setup_.collision);
    lattices_.back().set_uniform_diffusivity(sp.diffusivity);
    if (setup_.velocity) lattices_.back().set_uniform_velocity((*setup_.velocity)[0], (*setup_.velocity)[1]);
    apply_species_fields(i);
  }
  place_cells(cells);
  // Initial state: the medium's concentration outside, the cells' inside (by their area
  // fraction on a cut node: φ C_cell + (1 − φ) C_out).
  const std::size_t N = domain_.grid.size();
  initial_amount_.assign(S, 0.0);
  inflow_.assign(S, 0.0);
  floor_.assign(S, 0.0);
  for (std::size_t i = 0; i < S; ++i) {
    const scene::SpeciesSetup& sp = setup_.species[i];
    std::vector<double> c(N, sp.initial);
    for (const CellNodes& cell : nodes_)
      for (const auto& m : cell.mask) c[m.node] = cell.fractional ? m.phi * sp.cell_initial + (1.0 - m.phi) * sp.initial
                                                                  : sp.cell_initial;
    initialize(i, c);
  }
  if (const auto& n = setup_.no_o2) {
    // [no_o2] (docs/model.md §7c): the compartment of each node centre, the reactions from the
    // initial concentrations, and the start again so that they act time-centred (eq T4).
    const Grid& g = domain_.grid;
    compartment_ids_.assign(N, static_cast<std::uint8_t>(transport::Compartment::plasma));
    for (const auto& band : n->bands)
      for (int y = 0; y < g.ny; ++y)
        if (y + 0.5 >= band.y_lo && y + 0.5 < band.y_hi)
          for (int x = 0; x < g.nx; ++x) compartment_ids_[g.index(x, y)] = static_cast<std::uint8_t>(band.compartment);
    update_no_o2_reactions();
    for (const int i : {n->no_species, n->o2_species}) {
      const auto C = lattices_[static_cast<std::size_t>(i)].concentration();
      initialize(static_cast<std::size_t>(i), std::vector<double>(C.begin(), C.end()));
    }
  }
  if (setup_.hemoglobin) {
    // Each cell starts at the given saturation, or in equilibrium with its initial PO2.
    const transport::HbParameters& hb = *setup_.hemoglobin;
    const double P0 = setup_.species[static_cast<std::size_t>(setup_.hemoglobin_species)].cell_initial / hb.alpha;
    const double S0 = setup_.initial_saturation.value_or(transport::hill_saturation(P0, hb.P50, hb.n));
    saturation_.assign(nodes_.size(), S0);
    const transport::TransportLattice& o2 = lattices_[static_cast<std::size_t>(setup_.hemoglobin_species)];
    const bool corrected = setup_.mean_pressure == "source_corrected";
    if (setup_.hb_kinetics == "local") {  // eq H4: a saturation per heme node
      for (const CellNodes& cell : nodes_) {
        local_hb_.emplace_back(cell, S0, row_radius(), domain_.grid.nx);
        if (corrected) local_hb_.back().set_offset_response(o2);
      }
    } else {
      hb_.assign(nodes_.size(), HbCell(S0));
      if (corrected)
        for (std::size_t c = 0; c < nodes_.size(); ++c) hb_[c].set_offset_response(o2, nodes_[c]);
    }
  }
}

// The species' own fields: D, k and q from the species' values and its [[transport.layers]]
// (transport_layers.hpp); fields are allocated only where something is set.
void TransportPhysics::apply_species_fields(std::size_t i) {
  const LayerFields f = layer_fields(setup_, static_cast<int>(i), domain_.grid);
  transport::TransportLattice& lat = lattices_[i];
  base_D_[i] = f.D;
  if (!f.D.empty()) std::copy(f.D.begin(), f.D.end(), lat.diffusivity().begin());
  const bool hb_species = setup_.hemoglobin && static_cast<int>(i) == setup_.hemoglobin_species;
  if (!f.source.empty() || !f.decay.empty() || hb_species) {
    auto q = lat.source();
    base_source_[i] = f.source.empty() ? std::vector<double>(q.size(), 0.0) : f.source;
    std::copy(base_source_[i].begin(), base_source_[i].end(), q.begin());
    if (!f.decay.empty()) std::copy(f.decay.begin(), f.decay.end(), lat.decay_rate().begin());
  }
}

std::span<double> TransportPhysics::base_source(std::size_t i) {
  if (base_source_[i].empty()) base_source_[i].assign(domain_.grid.size(), 0.0);
  return base_source_[i];
}

void TransportPhysics::initialize(std::size_t i, std::span<const double> C) {
  if (!base_source_[i].empty()) {  // the base source (possibly set by the caller) reaches the lattice first
    auto q = lattices_[i].source();
    std::copy(base_source_[i].begin(), base_source_[i].end(), q.begin());
  }
  lattices_[i].initialize(C);
  initial_amount_[i] = lattices_[i].stored_amount();
  inflow_[i] = 0.0;
  floor_[i] = concentration_floor(setup_.species[i].boundaries, C);
}

void TransportPhysics::place_cells(std::span<const geometry::Polygon> cells) {
  cells_.assign(cells.begin(), cells.end());
  nodes_.resize(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c)
    nodes_[c] = cell_nodes(cells[c], domain_, setup_.cell_representation, setup_.heme_weights, row_radius());
  apply_compartments();
  if (setup_.mean_pressure == "source_corrected" && hb_.size() == nodes_.size())
    for (std::size_t c = 0; c < nodes_.size(); ++c)
      hb_[c].set_offset_response(lattices_[static_cast<std::size_t>(setup_.hemoglobin_species)], nodes_[c]);
}

// The cells' interior diffusivity (docs/transport.md §1): ray-cast nodes take the cell's D;
// area-fraction nodes the series rule 1/D = φ/D_in + (1 − φ)/D_out (T9), with the membrane
// rule on top: the node subpixel tensor (T10 on each node, T8) or the face subpixel tensor
// imposed by the face-flux correction (T10 on each face, T11).
void TransportPhysics::apply_compartments() {
  const bool fractional = setup_.cell_representation == "area_fraction";
  const Grid& g = domain_.grid;
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    const scene::SpeciesSetup& sp = setup_.species[i];
    transport::TransportLattice& lat = lattices_[i];
    corrections_[i].reset();
    if (cells_.empty()) continue;
    if (!fractional && sp.cell_diffusivity == sp.diffusivity && base_D_[i].empty()) continue;  // one D: no field
    std::span<double> D = lat.diffusivity();
    if (base_D_[i].empty()) std::fill(D.begin(), D.end(), sp.diffusivity);
    else std::copy(base_D_[i].begin(), base_D_[i].end(), D.begin());
    for (const CellNodes& cell : nodes_)
      for (const auto& m : cell.mask)
        D[m.node] = fractional ? setup_.units.diffusivity(
                                     transport::series_diffusivity(m.phi, sp.cell_diffusivity_um2_s, sp.diffusivity_um2_s))
                               : sp.cell_diffusivity;
    if (setup_.interface == "node_tensor") {
      const auto T = lat.diffusivity_tensor();  // isotropic from D first (cells may have moved)
      std::copy(D.begin(), D.end(), T.xx.begin());
      std::copy(D.begin(), D.end(), T.yy.begin());
      std::fill(T.xy.begin(), T.xy.end(), 0.0);
      for (const auto& cell : cells_)
        transport::set_node_subpixel_tensor(lat, transport::cut_cells(cell, g.nx, g.ny), sp.cell_diffusivity,
                                            sp.diffusivity);
    } else if (setup_.interface == "face_tensor") {
      std::vector<transport::FaceTarget> targets;
      for (const auto& cell : cells_) {
        const auto t = transport::subpixel_face_targets(cell, g.nx, g.ny, sp.cell_diffusivity, sp.diffusivity);
        targets.insert(targets.end(), t.begin(), t.end());
      }
      corrections_[i] = std::make_unique<transport::FaceFluxCorrection>(g, D, targets, row_radius());
      try {
        corrections_[i]->require_stable(lat);  // before running: a clear error, not a diverged run
      } catch (const std::invalid_argument& e) {
        throw InputError("species \"" + sp.name + "\", transport.interface = \"face_tensor\": " + e.what());
      }
    }
  }
}

std::span<const double> TransportPhysics::row_radius() const {
  return lattices_.empty() ? std::span<const double>{} : lattices_.front().row_radius();
}

// Hb–O2 release (docs/transport.md §4.2, eqs H1–H4): per cell, S over Δt_T from the mean PO2
// over its sample weights (hemoglobin.coupling); the O2 released, C_heme (S_old − S_new) per
// unit heme weight, is this step's source on the cell's heme nodes, on top of the base source.
// Local kinetics: the same per heme node, from its own PO2, onto itself.
void TransportPhysics::release_oxygen() {
  const std::size_t o = static_cast<std::size_t>(setup_.hemoglobin_species);
  transport::TransportLattice& o2 = lattices_[o];
  if (!local_hb_.empty()) {  // eq H4: each heme node from its own P, its release on itself
    std::span<double> q = o2.source();
    std::copy(base_source_[o].begin(), base_source_[o].end(), q.begin());
    for (std::size_t c = 0; c < local_hb_.size(); ++c) {
      local_hb_[c].advance(*setup_.hemoglobin, coupling_, o2.concentration(), setup_.time_step_s, q);
      saturation_[c] = local_hb_[c].saturation();
    }
    return;
  }
  std::vector<double> released(nodes_.size(), 0.0);
  for (std::size_t c = 0; c < nodes_.size(); ++c) {
    if (nodes_[c].heme.empty()) continue;
    released[c] = hb_[c].advance(*setup_.hemoglobin, coupling_, o2.concentration(), nodes_[c], setup_.time_step_s);
    saturation_[c] = hb_[c].saturation();
  }
  std::span<double> q = o2.source();
  std::copy(base_source_[o].begin(), base_source_[o].end(), q.begin());
  for (std::size_t c = 0; c < nodes_.size(); ++c)
    for (const auto& w : nodes_[c].heme) q[w.node] += w.phi * released[c];  // w = 1: transport::distribute_release
}

// [no_o2]: the sources and sinks of NO and O2 from this step's concentrations (R1–R5 and the
// core's exchange, transport::update_reactions; lagged one step, the sinks implicit).
void TransportPhysics::update_no_o2_reactions() {
  const scene::NoO2Setup& n = *setup_.no_o2;
  transport::update_reactions(n.model, compartment_ids_, setup_.units, lattices_[static_cast<std::size_t>(n.no_species)],
                              lattices_[static_cast<std::size_t>(n.o2_species)]);
}

void TransportPhysics::step(std::span<const double> fluid_ux, std::span<const double> fluid_uy) {
  if (setup_.no_o2) update_no_o2_reactions();
  // face-flux corrections from this step's Ĉ, before the sources are rewritten (eq T11)
  for (std::size_t i = 0; i < lattices_.size(); ++i)
    if (corrections_[i]) corrections_[i]->evaluate(lattices_[i]);
  if (setup_.hemoglobin) release_oxygen();
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    if (!corrections_[i]) continue;
    std::span<double> q = lattices_[i].source();
    if (!(setup_.hemoglobin && static_cast<int>(i) == setup_.hemoglobin_species)) {
      if (base_source_[i].empty()) std::fill(q.begin(), q.end(), 0.0);
      else std::copy(base_source_[i].begin(), base_source_[i].end(), q.begin());
    }
    corrections_[i]->add_to(q);
  }
  const bool flow = !fluid_ux.empty();
  if (flow) {
    // u_T = u_F Δt_T/Δt_F (both in their own lattice units, same h).
    ux_.resize(fluid_ux.size());
    uy_.resize(fluid_uy.size());
    for (std::size_t n = 0; n < ux_.size(); ++n) {
      ux_[n] = fluid_ux[n] * setup_.velocity_scale;
      uy_[n] = fluid_uy[n] * setup_.velocity_scale;
    }
  }
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    transport::TransportLattice& lat = lattices_[i];
    if (flow) lat.set_velocity(ux_, uy_);
    lat.step();
    inflow_[i] += lat.mass_balance().boundary_in;
  }
}

void TransportPhysics::save_state(StateRecord& r, const std::string& prefix) const {
  for (std::size_t i = 0; i < lattices_.size(); ++i) lattices_[i].save_state(r, prefix + std::to_string(i) + ".");
  r.put_scalar(prefix + "cells", static_cast<double>(cells_.size()));
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    const std::string cell = prefix + "cell_" + std::to_string(c) + ".";
    r.put(cell + "x", cells_[c].x);
    r.put(cell + "y", cells_[c].y);
  }
  for (std::size_t c = 0; c < hb_.size(); ++c) hb_[c].save_state(r, prefix + "cell_" + std::to_string(c) + ".");
  for (std::size_t c = 0; c < local_hb_.size(); ++c) local_hb_[c].save_state(r, prefix + "cell_" + std::to_string(c) + ".");
  r.put(prefix + "saturation", saturation_);
  r.put(prefix + "initial_amount", initial_amount_);
  r.put(prefix + "inflow", inflow_);
  r.put(prefix + "concentration_floor", floor_);
}

void TransportPhysics::restore_state(const StateRecord& r, const std::string& prefix) {
  std::vector<geometry::Polygon> cells(static_cast<std::size_t>(r.scalar(prefix + "cells")));
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string cell = prefix + "cell_" + std::to_string(c) + ".";
    cells[c].x = r.get(cell + "x");
    cells[c].y = r.get(cell + "y");
  }
  place_cells(cells);  // first: it rebuilds what depends on where the cells are
  for (std::size_t i = 0; i < lattices_.size(); ++i) lattices_[i].restore_state(r, prefix + std::to_string(i) + ".");
  for (std::size_t c = 0; c < hb_.size(); ++c) hb_[c].restore_state(r, prefix + "cell_" + std::to_string(c) + ".");
  for (std::size_t c = 0; c < local_hb_.size(); ++c)
    local_hb_[c].restore_state(r, prefix + "cell_" + std::to_string(c) + ".");
  r.copy_to(prefix + "saturation", saturation_);
  r.copy_to(prefix + "initial_amount", initial_amount_);
  r.copy_to(prefix + "inflow", inflow_);
  r.copy_to(prefix + "concentration_floor", floor_);
}

std::span<const double> TransportPhysics::readout(std::size_t i) const {
  const transport::TransportLattice& lat = lattices_[i];
  if (setup_.readout != "source_corrected") return lat.concentration();
  // one buffer per species: the observers hold every species' span at once
  readout_.resize(lattices_.size());
  std::vector<double>& out = readout_[i];
  out.resize(lat.grid().size());
  for (std::size_t n = 0; n < out.size(); ++n) out[n] = lat.source_corrected_concentration(n);
  return out;
}

double TransportPhysics::released(std::size_t c) const {
  if (!local_hb_.empty()) return local_hb_[c].released(setup_.hemoglobin->C_heme);
  return setup_.hemoglobin->C_heme * (hb_[c].initial_saturation() - hb_[c].saturation()) * nodes_[c].heme_volume;
}

double TransportPhysics::face_correction_gain(std::size_t i) const {
  return corrections_[i] ? corrections_[i]->lagged_gain(lattices_[i]) : 0.0;
}

double TransportPhysics::max_relative_residual() const {
  double r = 0.0;
  for (const auto& lat : lattices_) r = std::max(r, std::abs(lat.mass_balance().relative_residual()));
  return r;
}

HealthReport TransportPhysics::check_health() const {
  for (std::size_t i = 0; i < lattices_.size(); ++i) {
    const bool range_set = setup_.concentration_range.has_value();
    HealthReport h = lattices_[i].check_health(
        range_set ? *setup_.concentration_range
                  : std::array<double, 2>{floor_[i], std::numeric_limits<double>::infinity()});
    if (!h.healthy && h.quantity == "concentration" && !std::isnan(h.limit))
      h.hint = range_set ? "outside monitor.concentration_range_uM"
                         : "below the floor of -1 % of the start's concentration scale (a concentration is never "
                           "negative; monitor.concentration_range_uM sets another range): a sink, a zero-order "
                           "consumption or an outward fixed flux draws more than there is, or the scheme is unstable";
    // Eq T5 holds to round-off (~1e-16 (nodes)^½ of Σ|g|); far above it the lattice has lost
    // amount it cannot account for: a defect or an overflow, never physics.
    const double residual = lattices_[i].mass_balance().relative_residual();
    if (h.healthy && !(residual <= kMaxRelativeResidual))
      h = {false, "mass-balance residual", -1, -1, residual, kMaxRelativeResidual, 0.0,
           "relative to the stored amount (eq T5 holds to round-off): the step lost or created amount it cannot "
           "account for"};
    if (!h.healthy) {
      h.quantity = setup_.species[i].name + " " + h.quantity;
      return h;
    }
  }
  for (std::size_t c = 0; c < saturation_.size(); ++c)
    if (!(saturation_[c] >= 0.0 && saturation_[c] <= 1.0)) {
      const double limit = std::isfinite(saturation_[c]) ? (saturation_[c] < 0.0 ? 0.0 : 1.0)
                                                          : std::numeric_limits<double>::quiet_NaN();
      return {false, "cell " + std::to_string(c) + " saturation", -1, -1, saturation_[c], limit, 0.0, {}};
    }
  return {};
}

}  // namespace erythro::sim
