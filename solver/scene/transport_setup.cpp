// [transport], [[species]], [hemoglobin] → lattice units and the set-up checks of the
// transport (docs/scenes.md "[transport]", docs/transport.md §5). Conversions by the
// transport layer's own TransportUnits: D_lat = D Δt_T/h², J_lat = J Δt_T/h.
#include <algorithm>
#include <cmath>
#include <string>

#include "scene/units_detail.hpp"
#include "transport/reactions.hpp"
#include "transport/transport_units.hpp"

namespace erythro::scene::detail {
namespace {

std::string species_key(std::size_t i, const std::string& key) {
  return "species[" + std::to_string(i) + "]." + key;
}

transport::Side make_transport_side(const Scene& s, std::size_t i, int k, bool geometry_periodic,
                                    const transport::TransportUnits& units) {
  static const char* names[] = {"left", "right", "bottom", "top"};
  const SpeciesSpec& sp = s.species[i];
  const std::string kind = sp.side[k].empty() ? (geometry_periodic ? "periodic" : "zero_flux") : sp.side[k];
  const std::string key = species_key(i, names[k]);
  if ((kind == "periodic") != geometry_periodic)
    reject(s, "key '" + key + "' = \"" + kind + "\" does not match [boundaries." + names[k] + "], which is " +
                  (geometry_periodic ? "periodic: the species must be periodic there too"
                                     : "not periodic: a species can be periodic only across a periodic side"));
  transport::Side side;
  if (kind == "periodic") side.kind = transport::SideKind::periodic;
  if (kind == "zero_flux") side.kind = transport::SideKind::zero_flux;
  if (kind == "fixed_concentration") {
    side.kind = transport::SideKind::fixed_concentration;
    side.value = sp.side_value[k];  // µM (concentrations keep their unit)
    if (side.value < 0.0)
      reject(s, "key '" + key + "_value' = " + num(side.value) + " µM must be >= 0 (a concentration)");
  }
  if (kind == "fixed_flux") {
    side.kind = transport::SideKind::fixed_flux;
    side.value = units.flux(sp.side_value[k]);  // µM·µm/s → per unit length per step
  }
  return side;
}

// domain.geometry = "axisymmetric" (docs/model.md §7b): the inner radius in lattice units, the
// axis a zero-flux side of every species, no radial velocity of the medium.
void set_axisymmetric(const Scene& s, TransportSetup& T) {
  T.axisymmetric_inner_radius = s.domain.inner_radius_um / s.domain.spacing_um;
  if (T.stencil != transport::Stencil::d2q5)
    reject(s, "transport.stencil = \"" + s.transport->stencil + "\" with domain.geometry = \"axisymmetric\": only "
              "\"d2q5\" is second order at the axis (D2Q9 measured at order 1.6 on the row next to it, "
              "docs/verification-transport.md)");
  if (s.domain.inner_radius_um == 0.0) {
    for (std::size_t i = 0; i < T.species.size(); ++i)
      if (T.species[i].boundaries.bottom.kind != transport::SideKind::zero_flux)
        reject(s, "key '" + species_key(i, "bottom") + "' = \"" + s.species[i].side[2] +
                      "\": with domain.geometry = \"axisymmetric\" and domain.inner_radius_um = 0 the bottom side "
                      "is the axis, where only \"zero_flux\" (symmetry) is allowed");
  }
  if (s.transport->interface == "node_tensor")
    reject(s, "transport.interface = \"node_tensor\" with domain.geometry = \"axisymmetric\": the node tensor needs the "
              "tensor lattice, which is planar; use \"face_tensor\" (or \"series\")");
  if (const auto& v = s.transport->velocity_um_s; v && (*v)[1] != 0.0)
    reject(s, "transport.velocity_um_s = [" + num((*v)[0]) + ", " + num((*v)[1]) +
                  "] µm/s: an axisymmetric medium moves along its axis only; the radial (second) component must be 0");
}

transport::Compartment compartment_of(const std::string& name) {
  using transport::Compartment;
  if (name == "core") return Compartment::core;
  if (name == "endothelium") return Compartment::endothelium;
  if (name == "smooth_muscle") return Compartment::smooth_muscle;
  if (name == "tissue") return Compartment::tissue;
  return Compartment::plasma;  // the schema admits no other name
}

// [no_o2] (docs/model.md §7c): the compartment model from the scene's values, the core's NO
// rate by R4 from its band and the plasma band(s) above it, the bands in lattice units. The
// reactions of both species come from the model alone: their own sources, sinks and band
// reactions are refused rather than silently replaced.
void set_no_o2(const Scene& s, TransportSetup& T) {
  const NoO2Spec& spec = *s.no_o2;
  NoO2Setup out;
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    if (s.species[i].name == spec.no_species) out.no_species = static_cast<int>(i);
    if (s.species[i].name == spec.o2_species) out.o2_species = static_cast<int>(i);
  }
  if (!s.cells.empty() || !s.cell_populations.empty() || s.hemoglobin)
    reject(s, "[no_o2] is the continuum model (the RBC core as one phase): remove [[cells]], [[cell_populations]] "
              "and [hemoglobin]");
  for (const int i : {out.no_species, out.o2_species}) {
    const SpeciesSpec& sp = s.species[static_cast<std::size_t>(i)];
    if (sp.source_uM_per_s != 0.0 || sp.decay_per_s != 0.0)
      reject(s, "species \"" + sp.name + "\": [no_o2] sets its reactions; remove source_uM_per_s and decay_per_s");
    for (const TransportLayerSpec& l : s.transport_layers)
      if (l.species == sp.name && (l.decay_per_s || l.source_uM_per_s))
        reject(s, "[[transport.layers]] of species \"" + sp.name + "\": [no_o2] sets its reactions; such a band may "
                  "set diffusivity_um2_s only");
  }
  const double h = s.domain.spacing_um, height = s.domain.size_um[1];
  double core_top = -1.0;
  for (std::size_t i = 0; i < s.compartment_layers.size(); ++i) {
    const CompartmentLayerSpec& l = s.compartment_layers[i];
    if (l.y_um[0] < 0.0 || l.y_um[1] > height * (1.0 + 1e-12))
      reject(s, "no_o2.layers[" + std::to_string(i) + "].y_um = " + vec(l.y_um) + " µm must lie inside [0, " +
                    num(height) + "] (domain.size_um[1])");
    // A node belongs to the band holding its centre, so an edge between two lattice faces would
    // move to the nearer face: the band's width would change (the 2.5 µm endothelium at h = 1 µm
    // holds two rows, 2 µm: 20 % less NO made, measured). Edges must lie on faces.
    for (int e = 0; e < 2; ++e) {
      const double rows = l.y_um[static_cast<std::size_t>(e)] / h;
      if (std::abs(rows - std::round(rows)) > 1e-9 * std::max(1.0, std::abs(rows)))
        reject(s, "no_o2.layers[" + std::to_string(i) + "].y_um = " + vec(l.y_um) + " µm: the edge " +
                      num(l.y_um[static_cast<std::size_t>(e)]) + " µm is not a multiple of domain.spacing_um = " +
                      num(h) + " µm (a node takes the compartment at its centre, so the band would be " +
                      num(std::round(rows) * h) + " µm there): choose a spacing that divides every edge");
    }
    for (std::size_t j = 0; j < i; ++j) {
      const auto& o = s.compartment_layers[j].y_um;
      if (l.y_um[0] < o[1] && o[0] < l.y_um[1])
        reject(s, "no_o2.layers[" + std::to_string(i) + "].y_um = " + vec(l.y_um) + " overlaps no_o2.layers[" +
                      std::to_string(j) + "].y_um = " + vec(o));
    }
    const transport::Compartment c = compartment_of(l.compartment);
    if (c == transport::Compartment::core) {
      if (core_top >= 0.0) reject(s, "[[no_o2.layers]]: at most one \"core\" band (the RBC core)");
      core_top = l.y_um[1];
    }
    out.bands.push_back({l.y_um[0] / h, l.y_um[1] / h, c});
  }
  // The cell-free layer: the plasma band(s) directly above the core, up to the next compartment.
  double lumen = core_top;
  for (bool grew = core_top >= 0.0; grew;) {
    grew = false;
    for (const CompartmentLayerSpec& l : s.compartment_layers)
      if (l.compartment == "plasma" && std::abs(l.y_um[0] - lumen) < 1e-9 * h) {
        lumen = l.y_um[1];
        grew = true;
      }
  }
  transport::NoO2Model& m = out.model;
  m = transport::NoO2Model::arteriole_defaults();
  using transport::Compartment;
  m[Compartment::endothelium].no_R_max = transport::no_r_max_from_shear(spec.wall_shear_stress_Pa);
  m[Compartment::smooth_muscle].no_decay = spec.no_consumption_per_s;
  m[Compartment::tissue].no_decay = spec.no_consumption_per_s;
  m[Compartment::smooth_muscle].o2_Q_max = spec.sm_o2_max_consumption_uM_s;
  m[Compartment::tissue].o2_Q_max = spec.tissue_o2_max_consumption_uM_s;
  if (core_top >= 0.0) {
    out.core_radius_um = lumen;
    out.cell_free_layer_um = lumen - core_top;
    m[Compartment::core].no_decay = transport::no_core_scavenging_rate(spec.blood_no_scavenging_per_s, lumen,
                                                                     out.cell_free_layer_um);  // R4
    m[Compartment::core].o2_exchange = spec.core_o2_exchange_per_s;
    m[Compartment::core].o2_held_torr = spec.core_po2_torr;
  }
  T.no_o2 = out;
}

}  // namespace

TransportSetup derive_transport(const Scene& s, const LatticeSetup& L) {
  const TransportSpec& spec = *s.transport;
  TransportSetup T;
  T.coupling = spec.coupling;
  T.stencil = spec.stencil == "d2q9" ? transport::Stencil::d2q9 : transport::Stencil::d2q5;
  if (spec.coupling == "none") {
    T.time_step_s = L.scales.time_s;  // the run's clock is the transport's
  } else if (spec.coupling == "subcycle") {
    if (spec.fluid_steps_per_step < 1)
      reject(s, "transport.coupling = \"subcycle\" needs transport.fluid_steps_per_step (>= 1): the transport "
                "advances once every that many fluid steps");
    if (spec.time_step_s)
      reject(s, "transport.time_step_s is derived with transport.coupling = \"subcycle\" "
                "(fluid_steps_per_step × the fluid's Δt = " +
                    num(static_cast<double>(spec.fluid_steps_per_step) * L.scales.time_s) + " s): remove it");
    T.fluid_steps_per_step = spec.fluid_steps_per_step;
    T.time_step_s = static_cast<double>(spec.fluid_steps_per_step) * L.scales.time_s;
    T.velocity_scale = static_cast<double>(spec.fluid_steps_per_step);
  } else {
    reject(s, "transport.coupling = \"" + spec.coupling + "\" is not one of \"none\", \"subcycle\"");
  }

  // h from the scene's spacing itself (not from the length scale in m): conversions are then
  // bitwise those of a transport::TransportUnits{spacing_um, Δt_T} built by hand.
  const transport::TransportUnits units{s.domain.spacing_um, T.time_step_s};
  T.units = units;
  const double u_max_um_s = L.has_fluid ? L.expected_max_speed * L.scales.velocity_m_s() * 1e6
                            : spec.velocity_um_s ? std::hypot((*spec.velocity_um_s)[0], (*spec.velocity_um_s)[1])
                                                 : 0.0;
  // The keys behind h, Δt_T and the speed, for the messages: any of them may be the one off.
  const std::string sources =
      std::string(" (h: domain.spacing_um; Δt_T: ") +
      (spec.coupling == "none" ? "transport.time_step_s" : "transport.fluid_steps_per_step × the fluid's Δt") +
      (L.has_fluid              ? "; speed: the fluid's expected max speed"
       : spec.velocity_um_s     ? "; speed: transport.velocity_um_s"
                                : "") +
      ")";
  const bool periodic_side[4] = {L.boundaries.left.type == fluid::SideType::periodic,
                                 L.boundaries.right.type == fluid::SideType::periodic,
                                 L.boundaries.bottom.type == fluid::SideType::periodic,
                                 L.boundaries.top.type == fluid::SideType::periodic};
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    const SpeciesSpec& sp = s.species[i];
    SpeciesSetup out;
    out.name = sp.name;
    const double D_cell = sp.cell_diffusivity_um2_s.value_or(sp.diffusivity_um2_s);
    for (const auto& [key, D] : {std::pair{std::string("diffusivity_um2_s"), sp.diffusivity_um2_s},
                                 std::pair{std::string("cell_diffusivity_um2_s"), D_cell}}) {
      const auto problems = transport::check_transport_units(units, D, 0.0, u_max_um_s);  // k: implicit
      if (!problems.empty()) {
        std::string all;
        for (const auto& p : problems) all += (all.empty() ? "" : "; ") + p;
        reject(s, "key '" + species_key(i, key) + "' = " + num(D) + " µm²/s with h = " + num(units.h_um) +
                      " µm and Δt_T = " + num(units.dt_s) + " s" + sources + ": " + all);
      }
    }
    out.diffusivity = units.diffusivity(sp.diffusivity_um2_s);
    out.cell_diffusivity = units.diffusivity(D_cell);
    out.initial = sp.initial_uM;
    out.cell_initial = sp.cell_initial_uM.value_or(sp.initial_uM);
    out.diffusivity_um2_s = sp.diffusivity_um2_s;
    out.cell_diffusivity_um2_s = D_cell;
    out.source_uM_per_s = sp.source_uM_per_s;
    out.decay_per_s = sp.decay_per_s;
    out.source = units.source(sp.source_uM_per_s);
    out.decay = units.rate(sp.decay_per_s);
    out.boundaries.left = make_transport_side(s, i, 0, periodic_side[0], units);
    out.boundaries.right = make_transport_side(s, i, 1, periodic_side[1], units);
    out.boundaries.bottom = make_transport_side(s, i, 2, periodic_side[2], units);
    out.boundaries.top = make_transport_side(s, i, 3, periodic_side[3], units);
    if (const std::string why = out.boundaries.inconsistency(); !why.empty())
      reject(s, "species[" + std::to_string(i) + "] boundaries: " + why);
    T.species.push_back(out);
  }

  if (s.domain.geometry == "axisymmetric") set_axisymmetric(s, T);
  if (s.no_o2) set_no_o2(s, T);

  if (const auto& hb = s.hemoglobin) {
    transport::HbParameters p;
    p.k_off = hb->k_off_per_s;
    p.C_heme = hb->heme_uM;
    p.alpha = hb->solubility_uM_per_torr;
    p.P50 = hb->p50_torr;
    p.n = hb->hill_n;
    p.M = hb->rate_modifier;
    T.hemoglobin = p;
    for (std::size_t i = 0; i < T.species.size(); ++i)
      if (T.species[i].name == hb->species) T.hemoglobin_species = static_cast<int>(i);
    T.initial_saturation = hb->initial_saturation;
  }
  derive_transport_options(s, L, T);  // transport_options.cpp
  return T;
}

}  // namespace erythro::scene::detail
