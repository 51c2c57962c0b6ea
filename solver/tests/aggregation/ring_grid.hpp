#pragma once
// Test geometry of the contact-force tests: 10 × 10 slightly elliptic rings of 30 markers
// (3 000 markers, above CellContacts::kParallelMarkers, so the per-marker passes run in
// parallel), neighbours close enough to interact, ring (i, j) centred at
// (10 + 19 i + 0.3 j, y0 + pitch j + 0.2 i).
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "aggregation/cell_contacts.hpp"

namespace erythro::aggregation::test_support {

struct RingGrid {
  std::vector<double> x, y;
  std::vector<std::size_t> off{0};
  RingGrid(double y0, double pitch) {
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j)
        for (int k = 0; k < 30; ++k) {
          const double a = 2.0 * std::numbers::pi * k / 30.0;
          x.push_back(10.0 + 19.0 * i + 0.3 * j + 9.1 * std::cos(a));
          y.push_back(y0 + pitch * j + 0.2 * i + 9.3 * std::sin(a));
          if (k == 29) off.push_back(x.size());
        }
  }
  MarkerView view() const { return {x, y, off}; }
};

}  // namespace erythro::aggregation::test_support
