// [transport] and [hemoglobin] options beyond the species (docs/scenes.md "[transport]"):
// collision, the cells' representation and membrane rule, a uniform velocity of a still
// medium, the [[transport.layers]] bands and the monitor's concentration range, checked and converted
// into the TransportSetup (the lattice-unit conversion itself: T.units, transport_setup.cpp).
#include <array>
#include <cmath>
#include <vector>
#include <string>

#include "scene/units_detail.hpp"
#include "transport/transport_units.hpp"

namespace erythro::scene::detail {
namespace {

std::string layer_key(std::size_t i, const std::string& key) {
  return "transport.layers[" + std::to_string(i) + "]." + key;
}

std::array<double, 2> x_range(const TransportLayerSpec& l, double width_um) {
  return l.x_um.value_or(std::array<double, 2>{0.0, width_um});
}

// Every band of one species must lie inside the domain and not overlap another band of it.
void check_layers(const Scene& s, double width_um, double height_um) {
  const auto& layers = s.transport_layers;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const TransportLayerSpec& a = layers[i];
    if (a.y_um[0] < 0.0 || a.y_um[1] > height_um * (1.0 + 1e-12))
      reject(s, "key '" + layer_key(i, "y_um") + "' = " + vec(a.y_um) + " µm reaches outside the domain (0 … " +
                    num(height_um) + " µm in y)");
    if (a.x_um && ((*a.x_um)[0] < 0.0 || (*a.x_um)[1] > width_um * (1.0 + 1e-12)))
      reject(s, "key '" + layer_key(i, "x_um") + "' = " + vec(*a.x_um) + " µm reaches outside the domain (0 … " +
                    num(width_um) + " µm in x)");
    for (std::size_t j = 0; j < i; ++j) {
      const TransportLayerSpec& b = layers[j];
      const auto xa = x_range(a, width_um), xb = x_range(b, width_um);
      if (a.species == b.species && a.y_um[0] < b.y_um[1] && b.y_um[0] < a.y_um[1] && xa[0] < xb[1] && xb[0] < xa[1])
        reject(s, "key '" + layer_key(i, "y_um") + "' = " + vec(a.y_um) + " µm overlaps " + layer_key(j, "y_um") +
                      " = " + vec(b.y_um) + " µm of the same species \"" + a.species + "\"");
    }
  }
}

}  // namespace

void derive_transport_options(const Scene& s, const LatticeSetup& L, TransportSetup& T) {
  const TransportSpec& spec = *s.transport;
  const transport::TransportUnits& units = T.units;
  T.collision = {spec.collision == "trt" ? transport::Collision::trt : transport::Collision::bgk, spec.trt_magic};
  if (spec.velocity_um_s) {
    if (L.has_fluid)
      reject(s, "transport.velocity_um_s is the advecting velocity of a still medium (transport.coupling = \"none\"); "
                "with a fluid the transport is advected by the flow: remove it");
    T.velocity = std::array<double, 2>{units.velocity((*spec.velocity_um_s)[0]), units.velocity((*spec.velocity_um_s)[1])};
  }
  T.cell_representation = spec.cell_representation;
  T.interface = spec.interface;
  T.layer_mean = spec.layer_mean;
  T.readout = spec.readout;
  if (spec.interface != "series") {
    if (spec.cell_representation != "area_fraction")
      reject(s, "transport.interface = \"" + spec.interface + "\" needs the cut cells of transport.cell_representation = "
                "\"area_fraction\" (it is \"" + spec.cell_representation + "\")");
    if (spec.collision != "trt" || T.stencil != transport::Stencil::d2q5)
      reject(s, "transport.interface = \"" + spec.interface + "\" needs transport.collision = \"trt\" and stencil "
                "\"d2q5\" (docs/transport.md eqs T8, T11)");
    if (spec.interface == "face_tensor" && spec.trt_magic != 0.25)
      reject(s, "transport.interface = \"face_tensor\" needs transport.trt_magic = 0.25 (the face-flux correction "
                "imposes finite-volume fluxes, exact at Λ = 1/4 only, docs/transport.md eq T7); it is " +
                    num(spec.trt_magic));
  }
  if (const auto& hb = s.hemoglobin) {
    T.hb_kinetics = hb->kinetics;
    if (hb->kinetics == "local" && spec.coupling != "none")
      reject(s, "hemoglobin.kinetics = \"local\" keeps a saturation per heme node, so the cells must stay where they "
                "are: it needs transport.coupling = \"none\" (it is \"" + spec.coupling + "\")");
    if (hb->kinetics == "local" && hb->coupling == "cell_implicit_outflow")
      reject(s, "hemoglobin.kinetics = \"local\" with hemoglobin.coupling = \"cell_implicit_outflow\": the outflow "
                "predictor assumes the slow manifold of a whole cell; on one node it was measured unreliable (the "
                "single RBC at h = 0.4 µm: max |ΔS| 0.002, 0.048 and 0.17 at Δt = 16, 10 and 2.5 µs, "
                "docs/validation-deoxygenation.md): use \"cell_implicit\"");
    if (hb->kinetics == "local" && hb->heme_weights != "area_fraction")
      reject(s, "hemoglobin.kinetics = \"local\" gives every heme node its own saturation: it needs "
                "hemoglobin.heme_weights = \"area_fraction\" (it is \"" + hb->heme_weights + "\")");
    T.hb_coupling = hb->coupling;
    T.mean_pressure = hb->mean_pressure;
    T.heme_weights = hb->heme_weights;
    if (hb->mean_pressure == "source_corrected" && hb->coupling != "cell_implicit_outflow")
      reject(s, "hemoglobin.mean_pressure = \"source_corrected\" enters the implicit update of hemoglobin.coupling = "
                "\"cell_implicit_outflow\" only (it is \"" + hb->coupling + "\")");
    if (hb->heme_weights != "area_fraction" && spec.cell_representation != "area_fraction")
      reject(s, "hemoglobin.heme_weights = \"" + hb->heme_weights + "\" needs transport.cell_representation = "
                "\"area_fraction\"");
  }
  const double h = units.h_um;
  check_layers(s, L.grid.nx * h, L.grid.ny * h);
  for (std::size_t i = 0; i < s.transport_layers.size(); ++i) {
    const TransportLayerSpec& l = s.transport_layers[i];
    TransportLayerSetup out;
    for (std::size_t k = 0; k < s.species.size(); ++k)
      if (s.species[k].name == l.species) out.species = static_cast<int>(k);
    const SpeciesSpec& sp = s.species[static_cast<std::size_t>(out.species)];
    out.y_lo = l.y_um[0] / h;
    out.y_hi = l.y_um[1] / h;
    out.full_width = !l.x_um;
    out.x_lo = l.x_um ? (*l.x_um)[0] / h : 0.0;
    out.x_hi = l.x_um ? (*l.x_um)[1] / h : static_cast<double>(L.grid.nx);
    out.diffusivity_um2_s = l.diffusivity_um2_s.value_or(sp.diffusivity_um2_s);
    out.decay_per_s = l.decay_per_s.value_or(sp.decay_per_s);
    out.source_uM_per_s = l.source_uM_per_s.value_or(sp.source_uM_per_s);
    // the first-order sink is implicit (eq T4, unconditionally stable): no limit on k Δt
    const auto problems = transport::check_transport_units(units, out.diffusivity_um2_s, 0.0, 0.0);
    if (!problems.empty()) {
      std::string all;
      for (const auto& p : problems) all += (all.empty() ? "" : "; ") + p;
      reject(s, "[[transport.layers]] entry " + std::to_string(i) + " (species \"" + l.species + "\", y_um = " + vec(l.y_um) +
                    ") with h = " + num(units.h_um) + " µm and Δt_T = " + num(units.dt_s) + " s: " + all);
    }
    T.layers.push_back(out);
  }
  T.concentration_range = s.monitor.concentration_range_uM;
}

void append_transport_option_rows(const TransportSetup& T, std::vector<std::array<std::string, 3>>& rows) {
  const bool trt = T.collision.kind == transport::Collision::trt;
  rows.push_back({"transport options", trt ? "trt, Λ = " + num(T.collision.magic) : std::string("bgk"),
                  "cells " + T.cell_representation + (T.cell_representation == "area_fraction" ? ", " + T.interface : "") +
                      (T.readout == "source_corrected" ? ", readout Ĉ" : "")});
  if (T.hemoglobin)
    rows.push_back({"hemoglobin coupling", T.hb_coupling,
                    "kinetics " + T.hb_kinetics + ", mean P: " + T.mean_pressure + ", heme weights " + T.heme_weights});
  if (T.velocity) rows.push_back({"transport velocity", vec(*T.velocity), "lattice units (still medium)"});
  if (T.axisymmetric_inner_radius)
    rows.push_back({"geometry", "axisymmetric",
                    "x along the axis, y the radius from " + num(*T.axisymmetric_inner_radius) + " h (model.md §7b)"});
  if (const auto& n = T.no_o2) {
    const auto& core = n->model[transport::Compartment::core];
    rows.push_back({"no_o2 compartments", std::to_string(n->bands.size()) + " bands",
                    n->core_radius_um > 0.0 ? "core NO rate " + num(core.no_decay) + " 1/s (R4: R " +
                                                  num(n->core_radius_um) + " µm, cell-free layer " +
                                                  num(n->cell_free_layer_um) + " µm), PO2 " +
                                                  num(core.o2_held_torr) + " Torr"
                                            : std::string("no core")});
  }
  for (std::size_t k = 0; k < T.layers.size(); ++k) {
    const TransportLayerSetup& l = T.layers[k];
    rows.push_back({"layer " + std::to_string(k) + " (" + T.species[static_cast<std::size_t>(l.species)].name + ")",
                    "y " + vec({l.y_lo, l.y_hi}) + " h" + (l.full_width ? "" : ", x " + vec({l.x_lo, l.x_hi}) + " h"),
                    "D " + num(l.diffusivity_um2_s) + " µm²/s, k " + num(l.decay_per_s) + " 1/s, q " +
                        num(l.source_uM_per_s) + " µM/s"});
  }
}

}  // namespace erythro::scene::detail
