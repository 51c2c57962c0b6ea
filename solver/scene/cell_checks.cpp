// [membrane] and [[cells]] → lattice units, and the cell set-up checks (units_detail.hpp).
// Moduli: membrane/membrane_units.hpp; stability numbers: membrane/stability.hpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "aggregation/morse_units.hpp"
#include "geometry/grid_polygon.hpp"
#include "lattice/d2q9.hpp"
#include "membrane/membrane_units.hpp"
#include "scene/cell_shape.hpp"
#include "scene/units_detail.hpp"

namespace erythro::scene::detail {
namespace {

// Shortest distance between two markers along axis a, using the nearest periodic image.
double axis_gap(double d, int n, bool periodic) {
  if (periodic) d -= n * std::round(d / n);
  return d;
}

// The smallest distance between a marker of `a` and one of `b` (nearest periodic image) when
// it is below `within`, else +inf. The markers of `b` are binned in squares of side at least
// max(within, h), so each marker of `a` searches the 3 × 3 squares around it: O(markers)
// instead of O(markers²), which for two cells of 1e6 markers each kept `check` busy for hours.
double closest_within(const geometry::Polygon& a, const geometry::Polygon& b, const int n[2], const bool periodic[2],
                      double within) {
  const double side = std::max(within, 1.0);
  long count[2];  // squares across a periodic axis (they wrap round); 0: unbounded
  double width[2];
  for (int k = 0; k < 2; ++k) {
    count[k] = periodic[k] ? std::max(1L, static_cast<long>(std::floor(n[k] / side))) : 0;
    width[k] = periodic[k] ? static_cast<double>(n[k]) / static_cast<double>(count[k]) : side;
  }
  const auto square = [&](double v, int k) {
    if (periodic[k]) v -= n[k] * std::floor(v / n[k]);  // into [0, n)
    return static_cast<long>(std::floor(v / width[k]));
  };
  const auto wrap = [&](long i, int k) { return count[k] ? (i % count[k] + count[k]) % count[k] : i; };
  std::map<std::pair<long, long>, std::vector<std::size_t>> bins;
  for (std::size_t q = 0; q < b.size(); ++q) bins[{square(b.x[q], 0), square(b.y[q], 1)}].push_back(q);
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < a.size(); ++p) {
    const long ix = square(a.x[p], 0), iy = square(a.y[p], 1);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        const auto bin = bins.find({wrap(ix + dx, 0), wrap(iy + dy, 1)});
        if (bin == bins.end()) continue;
        for (const std::size_t q : bin->second)
          closest = std::min(closest, std::hypot(axis_gap(a.x[p] - b.x[q], n[0], periodic[0]),
                                                 axis_gap(a.y[p] - b.y[q], n[1], periodic[1])));
      }
  }
  return closest < within ? closest : std::numeric_limits<double>::infinity();
}

std::string cell_key(std::size_t i, const char* key) { return "cells[" + std::to_string(i) + "]." + key; }

// γ of [aggregation] in J/m² from whichever strength key the scene gives: γ itself, De*
// (docs/model.md eq 4.7: γ = De* × 2.6e−8 J/m²) or D_e (eq 4.6: γ = D_e |J(d*)|, `shape` in SI).
double surface_energy_J_m2(const AggregationSpec& a, const aggregation::MorseParameters& shape) {
  if (a.surface_energy_J_m2) return *a.surface_energy_J_m2;
  if (a.de_star) return aggregation::surface_energy_for_de_star(*a.de_star);
  return *a.pair_density_Pa * std::abs(aggregation::flat_contact(shape).integral);
}

// The strength in physical terms (docs/model.md eqs 4.7–4.8): De*, the estimate γβ/2 of the
// largest Morse stress and, in a wall-driven simple shear, its ratio to the viscous stress μγ̇
// of the plasma (fluid.viscosity_cP).
AggregationStrength aggregation_strength(const Scene& s, const LatticeSetup& L, double gamma_J_m2) {
  AggregationStrength st;
  st.surface_energy_J_m2 = gamma_J_m2;
  st.de_star = aggregation::de_star_for_surface_energy(gamma_J_m2);
  st.peak_stress_Pa = aggregation::peak_adhesion_stress(gamma_J_m2, s.aggregation->decay_per_um * 1e6);
  st.shear_rate_per_s = wall_shear_rate_per_s(L);
  if (st.shear_rate_per_s) {
    const double viscous_stress_Pa = s.fluid.viscosity_cP * 1e-3 * *st.shear_rate_per_s;  // μγ̇
    st.adhesion_to_viscous_stress = st.peak_stress_Pa / viscous_stress_Pa;
  }
  return st;
}

}  // namespace

MembraneSetup derive_membrane(const Scene& s, const LatticeSetup& L, bool mechanics) {
  const MembraneSpec spec = s.membrane.value_or(MembraneSpec{});
  MembraneSetup M;
  if (!ib::parse_kernel(spec.kernel, M.kernel))
    reject(s, "membrane.kernel = \"" + spec.kernel + "\" is not one of \"cosine4\", \"peskin4\", \"roma3\", \"linear2\"");
  if (spec.area_correction != "none" && spec.area_correction != "projection")
    reject(s, "membrane.area_correction = \"" + spec.area_correction + "\" is not one of \"none\", \"projection\"");
  M.area_projection = spec.area_correction == "projection";
  membrane::TensionLawType law{};
  if (!membrane::parse_tension_law(spec.law, law))
    reject(s, "membrane.law = \"" + spec.law + "\" is not one of \"neo_hookean\", \"skalak\", \"hookean\"");
  // SI, then the layer's own conversion (membrane_units.hpp): E_s [N/m], E_B [J], k_A [Pa].
  const membrane::LatticeScales ms{L.scales.length_m, L.scales.time_s, L.scales.density_kg_m3};
  M.model.tension.type = law;
  M.model.tension.modulus = membrane::tension_to_lattice(spec.shear_modulus_dyn_cm * membrane::kDynPerCm, ms);
  M.model.tension.skalak_c = spec.skalak_c;
  M.model.bending = membrane::bending_to_lattice(spec.bending_modulus_dyn_cm * membrane::kDynCm, ms);
  M.model.area_modulus = membrane::pressure_to_lattice(spec.area_modulus_Pa, ms);

  // Interior viscosity (eq 27): ν_in/ν_ex = μ_in/μ_ex (one density inside and out).
  M.interior_viscosity = L.viscosity;
  if (spec.interior_viscosity_cP) {
    M.interior_viscosity = L.viscosity * *spec.interior_viscosity_cP / s.fluid.viscosity_cP;
    try {
      M.indicator = interior::parse_method(spec.interior_method);
    } catch (const std::invalid_argument& e) {
      reject(s, std::string("membrane.interior_method: ") + e.what());
    }
    // 0: the interval the validation supports for this flow (k U <= 0.1 h), U the run's expected
    // fastest speed; a guessed speed (a force along a periodic direction) gives no bound: every step.
    M.index_update_interval = spec.index_update_interval != 0 ? spec.index_update_interval
                              : L.speed_is_estimate       ? 1
                                                          : supported_index_interval(L.expected_max_speed);
  }
  M.interior_tau = d2q9::tau_of_viscosity(M.interior_viscosity);
  if (mechanics && M.interior_tau < 0.5 + s.limits.min_tau_margin)
    reject(s, "membrane.interior_viscosity_cP = " + num(spec.interior_viscosity_cP.value_or(0.0)) +
                  " cP gives an interior relaxation time tau = " + num(M.interior_tau) + ", below the limit " +
                  num(0.5 + s.limits.min_tau_margin) + " (limits.min_tau_margin): raise it or raise time.tau");
  if (mechanics && !(M.interior_tau <= s.limits.max_tau))
    reject(s, "membrane.interior_viscosity_cP = " + num(spec.interior_viscosity_cP.value_or(0.0)) +
                  " cP gives an interior relaxation time tau = " + num(M.interior_tau) + ", above the limit " +
                  num(s.limits.max_tau) + " (limits.max_tau): lower it or lower time.tau");
  if (mechanics && spec.interior_viscosity_cP)
    check_trt_tau_minus(s, L, M.interior_tau,
                        "the interior's, membrane.interior_viscosity_cP = " + num(*spec.interior_viscosity_cP) + " cP");

  const double h_um = s.domain.spacing_um;
  const int n[2] = {L.grid.nx, L.grid.ny};
  const bool periodic[2] = {!wall_bounded(s, 0), !wall_bounded(s, 1)};
  // Each placed cell's centre and bounding radius (h): two cells whose bounding circles are
  // at least limits.min_cell_gap apart (nearest images) cannot overlap, so the marker-by-marker
  // check below is skipped for them (a suspension of many cells, [[cell_populations]]).
  std::vector<std::array<double, 3>> bounds;
  for (std::size_t i = 0; i < s.cells.size(); ++i) {
    const CellSpec& c = s.cells[i];
    if (c.markers != 0 && c.markers < 8)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(c.markers) + " must be >= 8");
    // The centre first: the shape placed far outside would lose its markers' spacing to round-off.
    const double centre[2] = {c.center_um[0] / h_um, c.center_um[1] / h_um};
    for (int a = 0; a < 2; ++a)
      if (!(centre[a] >= 0.0 && centre[a] < n[a]))
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm lies outside the domain " +
                      vec(s.domain.size_um) + " µm");
    std::string size_key = cell_key(i, "radius_um"), size_shown = num(c.radius_um) + " µm";
    // The shape centred at the origin, its size divided by `shrink` (the rest shape of a
    // pre-stressed cell: shrink = prestretch).
    const auto make = [&](int count, double shrink = 1.0) { return cell_shape_at_origin(c, count, h_um, shrink); };
    if (c.shape == "ellipse") {
      size_key = cell_key(i, "semi_axes_um");
      size_shown = vec(c.semi_axes_um) + " µm";
    }
    // A membrane in a fluid longer than the domain's diagonal fits in no orientation: say so
    // before its marker count and spacing are computed from a size that is a typo. (A fixed
    // shape in a still medium may cover the whole domain: a uniform cell interior.)
    const double longest_um =
        2.0 * c.scale * (c.shape == "ellipse" ? std::max(c.semi_axes_um[0], c.semi_axes_um[1]) : c.radius_um);
    const double diagonal_um = std::hypot(s.domain.size_um[0], s.domain.size_um[1]);
    if (mechanics && longest_um > diagonal_um)
      reject(s, "cell " + std::to_string(i) + " does not fit in the domain: " + size_key + " = " + size_shown +
                    " (× " + cell_key(i, "scale") + " = " + num(c.scale) + ") spans " + num(longest_um) +
                    " µm, more than the domain's diagonal " + num(diagonal_um) + " µm (domain.size_um = " +
                    vec(s.domain.size_um) + " µm)");
    // markers = 0 (key absent): perimeter / kAutoMarkerSpacing, at least 16; no more than
    // cells.markers allows (the schema's bound, 1e6).
    const double auto_markers = automatic_marker_count(c, h_um);
    if (c.markers == 0 && auto_markers > 1e6)
      reject(s, "cell " + std::to_string(i) + " (" + size_key + " = " + size_shown + ", × " + cell_key(i, "scale") +
                    " = " + num(c.scale) + ") would get " + num(auto_markers) +
                    " markers at the automatic spacing of " + num(kAutoMarkerSpacing) + " h, more than 1e6 (the most " +
                    cell_key(i, "markers") + " allows): make domain.spacing_um larger");
    const int m = c.markers != 0 ? static_cast<int>(c.markers) : std::max(16, static_cast<int>(auto_markers));
    const geometry::Polygon base = make(m);
    CellSetup cell;
    cell.model = M.model;
    if (c.shear_modulus_dyn_cm)
      cell.model.tension.modulus = membrane::tension_to_lattice(*c.shear_modulus_dyn_cm * membrane::kDynPerCm, ms);
    cell.shape = geometry::transformed(base, c.scale, c.angle_deg * std::numbers::pi / 180.0, c.center_um[0] / h_um,
                                       c.center_um[1] / h_um);
    geometry::make_counter_clockwise(cell.shape);
    if (c.prestretch != 1.0) {  // rest shape: placement-free (lengths, angles and area only)
      cell.rest = geometry::transformed(make(m, c.prestretch), c.scale, 0.0, 0.0, 0.0);
      geometry::make_counter_clockwise(cell.rest);
    }
    cell.equivalent_radius = std::sqrt(std::abs(geometry::signed_area(cell.shape)) / std::numbers::pi);
    cell.min_edge = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < cell.shape.size(); ++e) {
      const std::size_t f = (e + 1) % cell.shape.size();
      const double len = std::hypot(cell.shape.x[f] - cell.shape.x[e], cell.shape.y[f] - cell.shape.y[e]);
      cell.min_edge = std::min(cell.min_edge, len);
      cell.max_edge = std::max(cell.max_edge, len);
    }
    if (cell.equivalent_radius < kMinCellRadius)
      reject(s, "resolution too coarse: cell " + std::to_string(i) + " has " + size_key + " = " + size_shown +
                    " (× " + cell_key(i, "scale") + " = " + num(c.scale) + "), an equivalent radius √(A/π) of " +
                    num(cell.equivalent_radius) + " h, below " + num(kMinCellRadius) +
                    " h: enlarge the cell or make domain.spacing_um <= " +
                    num(h_um * cell.equivalent_radius / kMinCellRadius) + " µm");
    // Marker spacing matters for a membrane in a fluid (leaks, stiffness); a fixed shape in a
    // still medium is only a polygon (e.g. 800 markers for exact area fractions).
    const double max_spacing = s.limits.max_marker_spacing;
    if (mechanics && cell.max_edge > max_spacing)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(m) + " is too few: markers are up to " +
                    num(cell.max_edge) + " h apart, more than " + num(max_spacing) +
                    " h (limits.max_marker_spacing; fluid leaks between markers): use markers >= " +
                    num(std::ceil(m * cell.max_edge / max_spacing)));
    if (mechanics && cell.min_edge < kMinMarkerSpacing)
      reject(s, "key '" + cell_key(i, "markers") + "' = " + std::to_string(m) + " is too many: markers are as close as " +
                    num(cell.min_edge) + " h, less than " + num(kMinMarkerSpacing) +
                    " h (over-resolved membrane, stiff and noisy): use markers <= " +
                    num(std::floor(m * cell.min_edge / kMinMarkerSpacing)));
    for (int a = 0; a < 2; ++a) {
      if (periodic[a]) continue;
      const auto& coords = a == 0 ? cell.shape.x : cell.shape.y;
      const auto [lo, hi] = std::minmax_element(coords.begin(), coords.end());
      // axisymmetric: the section straddles the axis (the bottom side) by construction
      const bool on_axis = a == 1 && s.domain.geometry == "axisymmetric";
      const double gap = on_axis ? n[a] - *hi : std::min(*lo, n[a] - *hi);
      if (gap < s.limits.min_cell_gap)
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm places cell " +
                      std::to_string(i) + " " + num(gap) + " h from the " +
                      (a == 0 ? "left/right" : "bottom/top") + " wall, closer than " + num(s.limits.min_cell_gap) +
                      " h (limits.min_cell_gap; overlaps the wall): move it inward or shrink it");
    }
    double reach = 0.0;
    for (std::size_t p = 0; p < cell.shape.size(); ++p)
      reach = std::max(reach, std::hypot(cell.shape.x[p] - centre[0], cell.shape.y[p] - centre[1]));
    for (std::size_t j = 0; j < M.cells.size(); ++j) {
      const double apart = std::hypot(axis_gap(centre[0] - bounds[j][0], n[0], periodic[0]),
                                      axis_gap(centre[1] - bounds[j][1], n[1], periodic[1]));
      if (apart - reach - bounds[j][2] >= s.limits.min_cell_gap) continue;
      const geometry::Polygon& o = M.cells[j].shape;
      const double closest = closest_within(cell.shape, o, n, periodic, s.limits.min_cell_gap);
      // One inside the other (even–odd rule: a negative signed distance).
      const bool nested = geometry::signed_distance(o, cell.shape.x[0], cell.shape.y[0]) < 0.0 ||
                          geometry::signed_distance(cell.shape, o.x[0], o.y[0]) < 0.0;
      if (nested || closest < s.limits.min_cell_gap)
        reject(s, "key '" + cell_key(i, "center_um") + "' = " + vec(c.center_um) + " µm makes cell " +
                      std::to_string(i) + " overlap cell " + std::to_string(j) + " (" + cell_key(j, "center_um") +
                      " = " + vec(s.cells[j].center_um) + " µm): " +
                      (nested ? std::string("one lies inside the other")
                              : "their markers are " + num(closest) + " h apart, closer than " +
                                    num(s.limits.min_cell_gap) + " h (limits.min_cell_gap)") +
                      "; move them apart");
    }
    bounds.push_back({centre[0], centre[1], reach});
    M.cells.push_back(std::move(cell));
  }

  if (s.aggregation) {
    if (!mechanics)
      reject(s, "[aggregation] moves cells, but transport.coupling = \"none\" builds no fluid: remove [aggregation]");
    const AggregationSpec& a = *s.aggregation;
    aggregation::MorsePhysical p;
    p.r0_m = a.zero_force_distance_um * 1e-6;
    p.beta_per_m = a.decay_per_um * 1e6;
    p.cutoff_m = a.cutoff_um.value_or(a.zero_force_distance_um + 5.0 / a.decay_per_um) * 1e-6;
    try {
      // γ (given, or De* × 2.6e−8 J/m²) is fitted through the flat contact
      // (aggregation/morse_units.hpp: D_e = γ/|J(d*)|, docs/model.md eq 4.6); SI throughout,
      // then the layer's own conversion.
      const aggregation::MorseParameters shape{1.0, p.r0_m, p.beta_per_m, p.cutoff_m};
      const double gamma_J_m2 = surface_energy_J_m2(a, shape);
      p.De_Pa = a.pair_density_Pa ? *a.pair_density_Pa : aggregation::pair_density_for(gamma_J_m2, shape);
      M.aggregation = aggregation::to_lattice(p, ms);
      M.aggregation_flat_gap = aggregation::flat_contact(*M.aggregation).gap;
      M.aggregation_strength = aggregation_strength(s, L, gamma_J_m2);
    } catch (const std::invalid_argument& e) {
      reject(s, "[aggregation] with aggregation.zero_force_distance_um = " + num(a.zero_force_distance_um) +
                    " µm, aggregation.decay_per_um = " + num(a.decay_per_um) + " /µm, aggregation.cutoff_um = " +
                    num(p.cutoff_m * 1e6) + " µm: " + e.what());
    }
    for (int axis = 0; axis < 2; ++axis)
      if (periodic[axis] && M.aggregation->cutoff >= 0.5 * n[axis])
        reject(s, "aggregation.cutoff_um = " + num(p.cutoff_m * 1e6) + " µm is not below half the periodic domain (" +
                      num(0.5 * n[axis] * h_um) + " µm): the minimum-image separation would be ambiguous");
  }

  if (s.repulsion) {
    if (!mechanics)
      reject(s, "[repulsion] moves cells, but transport.coupling = \"none\" builds no fluid: remove [repulsion]");
    const RepulsionSpec& r = *s.repulsion;
    const double range_h = r.range_um ? *r.range_um / h_um : 2.0;
    const std::string range_text =
        r.range_um ? "repulsion.range_um = " + num(*r.range_um) + " µm" : "repulsion.range_um (default 2 h)";
    if (range_h < 1.0)
      reject(s, range_text + " is below domain.spacing_um = " + num(h_um) +
                    " µm: a marker could slip between two markers of another cell; allowed: >= " + num(h_um) + " µm");
    for (int axis = 0; axis < 2; ++axis)
      if (periodic[axis] && range_h >= 0.5 * n[axis])
        reject(s, range_text + " is not below half the periodic domain (" + num(0.5 * n[axis] * h_um) +
                      " µm): the minimum-image separation would be ambiguous");
    const double pressure_lattice = membrane::pressure_to_lattice(r.pressure_Pa, ms);
    M.repulsion = aggregation::RepulsionParameters{pressure_lattice, range_h, r.walls};
  }

  if (!mechanics) return M;  // fixed shapes in a still medium: no membrane update to keep stable

  // Explicit-update stability (membrane/stability.hpp): Π = modulus Δt²/(ρ0 h^k) < limit.
  // The stiffest membrane limits the step (cells may override the shear modulus).
  std::size_t stiffest = 0;
  for (std::size_t i = 1; i < M.cells.size(); ++i)
    if (M.cells[i].model.tension.modulus > M.cells[stiffest].model.tension.modulus) stiffest = i;
  const bool cell_override = !M.cells.empty() && s.cells[stiffest].shear_modulus_dyn_cm.has_value();
  membrane::StabilityInput in;
  in.kernel = M.kernel;
  in.model = M.cells.empty() ? M.model : M.cells[stiffest].model;
  in.viscosity = L.viscosity;
  in.density = 1.0;
  in.max_stretch = 1.0;  // cells start at their rest shape, or pre-stressed (cells.prestretch)
  for (const CellSpec& c : s.cells) in.max_stretch = std::max(in.max_stretch, c.prestretch);
  M.stability = membrane::estimate_stability(in);
  if (!M.stability.acceptable()) {
    const auto& e = M.stability;
    const std::string shear_key =
        cell_override ? cell_key(stiffest, "shear_modulus_dyn_cm") : std::string("membrane.shear_modulus_dyn_cm");
    const double shear_shown = cell_override ? *s.cells[stiffest].shear_modulus_dyn_cm : spec.shear_modulus_dyn_cm;
    struct Term {
      const char* key;
      std::string shown;
      const char* number;
      double value, limit;
    };
    const Term terms[] = {
        {shear_key.c_str(), num(shear_shown) + " dyn/cm", "Π_T = (dT/dλ) Δt²/(ρ0 h³)", e.tension_number,
         e.tension_limit},
        {"membrane.bending_modulus_dyn_cm", num(spec.bending_modulus_dyn_cm) + " dyn·cm", "Π_B = E_B Δt²/(ρ0 h⁵)",
         e.bending_number, e.bending_limit},
        {"membrane.area_modulus_Pa", num(spec.area_modulus_Pa) + " Pa", "Π_A = k_A Δt²/(ρ0 h²)", e.area_number,
         e.area_limit}};
    const Term* worst = &terms[0];
    for (const Term& t : terms)
      if (t.value / t.limit > worst->value / worst->limit) worst = &t;
    const double factor = std::sqrt(worst->limit / worst->value);
    const std::string why = "key '" + std::string(worst->key) + "' = " + worst->shown +
                  " is outside the membrane's stability limit: " + worst->number + " = " + num(worst->value) +
                  " exceeds " + num(worst->limit) + " (explicit immersed-boundary update, " +
                  std::string(ib::to_string(M.kernel)) + " kernel, membrane::estimate_stability, " +
                  "docs/verification-ib-membrane.md); lower " + worst->key + " by a factor " +
                  num(1.0 / (factor * factor)) + ", or shrink the time step by a factor " + num(1.0 / factor) + " (" +
                  (s.time.tau ? "time.tau <= " + num(0.5 + (L.collision.tau - 0.5) * factor)
                              : "time.step_s <= " + num(L.scales.time_s * factor) + " s") +
                  ") or refine domain.spacing_um";
    if (s.limits.membrane_stability != "warn") reject(s, why);
    // limits.membrane_stability = "warn": run it anyway (e.g. to find where it diverges).
    M.stability.warning += (M.stability.warning.empty() ? "" : "; ") + why + " (limits.membrane_stability = \"warn\")";
  }
  return M;
}

}  // namespace erythro::scene::detail

namespace erythro::scene {

long supported_index_interval(double fastest_speed_lattice) {
  if (!(fastest_speed_lattice > 0.0)) return 1;
  return std::max(1L, static_cast<long>(std::floor(0.1 / fastest_speed_lattice)));
}

}  // namespace erythro::scene
