#pragma once
// Marker configurations for the aggregation cases and the benchmark: random cells
// (fixed seeds) and cells on a lattice at a given area fraction.
#include <cstdint>
#include <vector>

#include "aggregation/cell_contacts.hpp"
#include "geometry/domain.hpp"

namespace erythro::vv {

struct MarkerConfig {
  geometry::Domain domain;
  std::vector<double> x, y;
  std::vector<std::size_t> offsets{0};
  aggregation::MarkerView view() const { return {x, y, offsets}; }
  std::size_t markers() const { return x.size(); }
};

// Appends a closed polygon (counter-clockwise) as one more cell.
void add_cell(MarkerConfig& c, const std::vector<double>& x, const std::vector<double>& y);

// `cells` cells (circles and Evans–Fung sections, radius a ∈ [6, 10], `markers` each,
// random rotation, marker jitter 0.1), centres uniform in the nx × ny box. On periodic
// axes about a third of the cells are stored UNWRAPPED, shifted by ±n (as ImmersedCells
// may hold them), to exercise the minimum image. Cells may overlap.
MarkerConfig random_cells(int cells, int markers, int nx, int ny, bool periodic, std::uint64_t seed);

// k × k cells (circles of radius a, `markers` each) on a square lattice in a periodic box
// sized for the given area fraction (πa² k² / L² = fraction), each jittered by ±1 and
// rotated at random (seeded): the benchmark's "realistic spacing".
MarkerConfig lattice_cells(int k, int markers, double a, double fraction, std::uint64_t seed);

}  // namespace erythro::vv
