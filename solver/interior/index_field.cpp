// The index field I(x) of the thesis (§II.4, eqs 26–27; docs/model.md §5). One update:
//  (1) I = 1 everywhere (only the nodes the previous update changed are reset);
//  (2) per cell, a band pass: each edge visits the nodes of its capsule |d| < w (or, for a
//      smooth polygon, of its wedge between the bisector lines at its ends), so the cost
//      is O(markers), not O(grid); d = shortest signed distance to the polygon's edges;
//      |d| < w → band node, I = min(I, H(d)) (eq 26); free nodes next to an inside band
//      node (w ≤ −d < w + 1) → start candidates;
//  (3) per cell, the interior: flood_fill — a scan-line fill from the first candidate in
//      the 2w × 2w window of a marker (the thesis), replacing I = 1 by 0 and stopping at
//      band nodes, then from every candidate still free (completion); ray_casting — the
//      free nodes inside by the even–odd rule. Then a leak check against the area.
#include "interior/index_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "interior/geometry.hpp"
#include "interior/marks.hpp"
#include "lattice/d2q9.hpp"

namespace erythro::interior {

using detail::kFree;

std::string detail::marker_box(const geometry::Polygon& p) {
  const auto [x0, x1] = std::minmax_element(p.x.begin(), p.x.end());
  const auto [y0, y1] = std::minmax_element(p.y.begin(), p.y.end());
  std::ostringstream s;
  s << "[" << *x0 << ", " << *x1 << "] x [" << *y0 << ", " << *y1 << "]";
  return s.str();
}

std::string_view to_string(Method m) {
  switch (m) {
    case Method::indexless: return "indexless";
    case Method::band_only: return "band_only";
    case Method::flood_fill: return "flood_fill";
    case Method::ray_casting: return "ray_casting";
  }
  return "?";
}

Method parse_method(std::string_view name) {
  for (Method m : {Method::indexless, Method::band_only, Method::flood_fill, Method::ray_casting})
    if (name == to_string(m)) return m;
  throw std::invalid_argument("unknown index-field method '" + std::string(name) +
                              "' (allowed: indexless, band_only, flood_fill, ray_casting)");
}

IndexField::IndexField(const geometry::Domain& domain, IndexFieldOptions options) : domain_(domain), options_(options) {
  if (domain.grid.nx <= 0 || domain.grid.ny <= 0)
    throw std::invalid_argument("IndexField: the grid must have at least one node per axis");
  if (!std::isfinite(options.band_half_width) || options.band_half_width <= 0.0)
    throw std::invalid_argument("IndexField: band_half_width must be positive and finite (lattice units), got " +
                                std::to_string(options.band_half_width));
  const std::size_t n = domain.grid.size();
  index_.assign(n, 1.0);
  mark_.assign(n, kFree);
  owner_.assign(n, -1);
  candidate_.assign(n, 0);
}

const FillReport& IndexField::update(std::span<const geometry::Polygon> cells) {
  // (1) I = 1 everywhere: undo the previous update (its nodes are kept in previous_dirty_
  // for write_changed_relaxation_times).
  for (std::size_t k : dirty_) {
    index_[k] = 1.0;
    mark_[k] = kFree;
    owner_[k] = -1;
    candidate_[k] = 0;
  }
  previous_dirty_.swap(dirty_);
  dirty_.clear();
  report_ = FillReport{};
  report_.cells = static_cast<int>(cells.size());
  if (options_.method == Method::indexless) return report_;

  for (int c = 0; c < report_.cells; ++c) check_polygon(cells[static_cast<std::size_t>(c)], c);
  stats_.assign(cells.size(), CellStats{});
  starts_.clear();
  starts_begin_.assign(1, 0);
  // (2) the bands of every cell first, so that each fill stops at every band.
  for (int c = 0; c < report_.cells; ++c) band_pass(cells[static_cast<std::size_t>(c)], c, stats_[static_cast<std::size_t>(c)]);
  if (options_.method == Method::band_only) return report_;
  // (3) the interiors, then the leak check.
  for (int c = 0; c < report_.cells; ++c) {
    const auto& p = cells[static_cast<std::size_t>(c)];
    auto& s = stats_[static_cast<std::size_t>(c)];
    if (options_.method == Method::flood_fill)
      flood_fill_cell(p, c, s);
    else
      ray_cast_cell(p, c, s);
    report_.interior_nodes += s.filled;
  }
  for (int c = 0; c < report_.cells; ++c)
    check_area(cells[static_cast<std::size_t>(c)], c, stats_[static_cast<std::size_t>(c)]);
  return report_;
}

void IndexField::save_state(StateRecord& r, const std::string& prefix) const {
  r.put(prefix + "index", index_);
  r.put(prefix + "mark", mark_);
  r.put(prefix + "owner", owner_);
  r.put(prefix + "candidate", candidate_);
  r.put(prefix + "dirty", dirty_);
}

void IndexField::restore_state(const StateRecord& r, const std::string& prefix) {
  const std::size_t n = index_.size();
  r.copy_to(prefix + "index", index_);
  auto ints = [&](const char* name, auto& out) {
    const std::vector<double>& v = r.get(prefix + name, n);
    std::transform(v.begin(), v.end(), out.begin(), [](double d) { return static_cast<std::decay_t<decltype(out[0])>>(d); });
  };
  ints("mark", mark_);
  ints("owner", owner_);
  ints("candidate", candidate_);
  dirty_ = r.get_as<std::size_t>(prefix + "dirty");
  previous_dirty_.clear();
}

void IndexField::check_polygon(const geometry::Polygon& p, int cell) const {
  if (p.size() < 3 || p.y.size() != p.x.size())
    throw InputError("interior: cell " + std::to_string(cell) + " has " + std::to_string(p.size()) +
                     " markers; a closed membrane polygon needs at least 3 (and as many y as x)");
  for (std::size_t m = 0; m < p.size(); ++m)
    if (!std::isfinite(p.x[m]) || !std::isfinite(p.y[m]))
      // A diverged membrane, not bad input: std::domain_error, as ImmersedCells reports it
      // (the simulation layer turns it into a divergence diagnosis).
      throw std::domain_error("interior: cell " + std::to_string(cell) + " marker " + std::to_string(m) +
                              " has a non-finite position (" + std::to_string(p.x[m]) + ", " +
                              std::to_string(p.y[m]) + ")");
}

void IndexField::check_area(const geometry::Polygon& p, int cell, const CellStats& stats) {
  // Σ(1 − I) of the cell against its enclosed area (clipped at walls). A valid fill agrees
  // to O(h²) (docs/verification-interior.md); the bound allows a band cut by a wall
  // (0.30 h per unit length, ∫₀^w (1 − H) = w(¼ − 1/π²)) and pinched bands with a margin.
  const double area = std::abs(stats.within_walls ? stats.signed_area : clipped_area(p, domain_));
  const double mismatch = std::abs(stats.band_area + static_cast<double>(stats.filled) - area);
  const double allowed = 0.5 * stats.perimeter + 4.0;
  if (mismatch > report_.max_area_mismatch) {
    report_.max_area_mismatch = mismatch;
    report_.max_area_mismatch_allowed = allowed;
  }
  if (mismatch <= allowed) return;
  std::ostringstream msg;
  msg << "interior: cell " << cell << " (markers in " << detail::marker_box(p) << "): the " << to_string(options_.method)
      << " interior plus band holds " << stats.band_area + static_cast<double>(stats.filled)
      << " h^2 but the polygon encloses " << area << " h^2 (mismatch " << mismatch << " > " << allowed
      << "): the membrane polygon self-intersects, overlaps itself or another cell, or the fill leaked";
  throw FillLeakError(msg.str());
}

void IndexField::write_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const {
  if (tau.size() != index_.size())
    throw std::invalid_argument("IndexField::write_relaxation_times: tau has " + std::to_string(tau.size()) +
                                " entries, the grid " + std::to_string(index_.size()));
  // Eq 27 with ν = μ/ρ0, ρ0 = 1: ν(x) = ν_in + (ν_ex − ν_in) I(x), τ = ½ + 3ν (c_s² = ⅓).
  for (std::size_t k = 0; k < tau.size(); ++k) tau[k] = d2q9::tau_of_viscosity(nu_in + (nu_ex - nu_in) * index_[k]);
}

void IndexField::write_changed_relaxation_times(std::span<double> tau, double nu_in, double nu_ex) const {
  if (tau.size() != index_.size())
    throw std::invalid_argument("IndexField::write_changed_relaxation_times: tau has " + std::to_string(tau.size()) +
                                " entries, the grid " + std::to_string(index_.size()));
  // Every node whose I differs from 1 now, or did after the previous update, is in one of
  // the two lists; every other node has I = 1 in both, so its τ is already ½ + 3ν_ex.
  for (const auto* nodes : {&previous_dirty_, &dirty_})
    for (std::size_t k : *nodes) tau[k] = d2q9::tau_of_viscosity(nu_in + (nu_ex - nu_in) * index_[k]);
}

}  // namespace erythro::interior
