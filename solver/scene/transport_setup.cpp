// [transport], [[species]], [hemoglobin] → lattice units and the set-up checks of the
// transport (docs/scenes.md "[transport]", docs/transport.md §5). Conversions by the
// transport layer's own TransportUnits: D_lat = D Δt_T/h², J_lat = J Δt_T/h.
#include <algorithm>
#include <cmath>
#include <string>

#include "scene/units_detail.hpp"
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
  if (const auto& v = s.transport->velocity_um_s; v && (*v)[1] != 0.0)
    reject(s, "transport.velocity_um_s = [" + num((*v)[0]) + ", " + num((*v)[1]) +
                  "] µm/s: an axisymmetric medium moves along its axis only; the radial (second) component must be 0");
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
