#pragma once
// The markers of all cells as the contact forces read them (cell_contacts.hpp, pair_lists.hpp).
#include <cstddef>
#include <span>

namespace erythro::aggregation {

// The markers of all cells: positions and the cell ranges, cell c owning markers
// offsets[c] … offsets[c+1] − 1 (offsets.size() = cells + 1, offsets[0] = 0). A cell
// needs ≥ 3 markers.
struct MarkerView {
  std::span<const double> x, y;
  std::span<const std::size_t> offsets;
};

}  // namespace erythro::aggregation
